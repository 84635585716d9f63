#include "mjarm/planning/waypoint_file.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/model/user_file.hpp"
#include "support/error_message.hpp"
#include "support/files.hpp"
#include "support/unreadable_paths.hpp"

namespace mjarm {
namespace {

using test::error_of;

TEST(WaypointFile, JsonPositionsAndOrientations) {
  const WaypointPath path = parse_waypoints_json(R"({"frame": "attachment_site",
      "orientation": [0, 1, 0, 0],
      "waypoints": [{"position": [0.4, 0, 0.5]},
                    {"position": [0.4, 0.1, 0.5], "quaternion": [2, 0, 0, 0]}]})");
  ASSERT_EQ(path.waypoints.size(), 2u);
  EXPECT_EQ(*path.frame, "attachment_site");
  const std::vector<Pose> poses = path.poses(Eigen::Matrix3d::Identity());
  EXPECT_TRUE(poses[0].R.isApprox(Eigen::Vector3d(1, -1, -1).asDiagonal().toDenseMatrix()));
  EXPECT_TRUE(poses[1].R.isApprox(Eigen::Matrix3d::Identity()));  // normalised
  EXPECT_EQ(poses[1].p, Eigen::Vector3d(0.4, 0.1, 0.5));
}

TEST(WaypointFile, CsvWithAndWithoutHeaderUsesTheDefaultOrientation) {
  Eigen::Matrix3d R = Eigen::Matrix3d::Zero();
  R(0, 1) = R(1, 0) = 1.0;
  R(2, 2) = -1.0;
  // without a header, rows of 3 and 7 columns mix
  WaypointPath path = parse_waypoints_csv("# comment\n0.4,0,0.5\n\n0.3, 0.1, 0.4, 1, 0, 0, 0\n");
  ASSERT_EQ(path.waypoints.size(), 2u);
  std::vector<Pose> poses = path.poses(R);
  EXPECT_EQ(poses[0].R, R);
  EXPECT_TRUE(poses[1].R.isApprox(Eigen::Matrix3d::Identity()));
  // a header's names in any case
  path = parse_waypoints_csv("x,y,z\n# comment\n0.4,0,0.5\n");
  ASSERT_EQ(path.waypoints.size(), 1u);
  EXPECT_EQ(path.poses(R)[0].R, R);
  path = parse_waypoints_csv("X, Y, Z, QW, QX, QY, QZ\n0.3, 0.1, 0.4, 1, 0, 0, 0\n");
  ASSERT_EQ(path.waypoints.size(), 1u);
  EXPECT_TRUE(path.poses(R)[0].R.isApprox(Eigen::Matrix3d::Identity()));
}

// issue 29: a 2 000 000-row CSV ran for 97 s and failed blaming "very slow velocities"
TEST(WaypointFile, AFileOfMoreWaypointsThanTheBoundIsRefused) {
  std::string csv = "x,y,z\n", json = R"({"waypoints": [)";
  for (std::size_t k = 0; k <= kMaxWaypoints; ++k) {
    csv += "0.4,0.0,0.5\n";
    json += std::string(k ? "," : "") + R"({"position": [0.4, 0.0, 0.5]})";
  }
  json += "]}";
  EXPECT_NE(error_of([&] { parse_waypoints_csv(csv, "big.csv"); })
                .find("waypoints big.csv line 10002: a waypoint beyond the 10000 a file may hold"),
            std::string::npos);
  EXPECT_NE(error_of([&] { parse_waypoints_json(json, "big.json"); })
                .find("waypoints big.json: 10001 waypoints, more than the 10000 a file may hold"),
            std::string::npos);
  // at the bound a file reads
  csv.erase(csv.rfind("0.4,0.0,0.5\n"));
  EXPECT_EQ(parse_waypoints_csv(csv, "big.csv").waypoints.size(), kMaxWaypoints);
}

TEST(WaypointFile, BadFilesAreClearErrors) {
  EXPECT_NE(error_of([] {
              parse_waypoints_csv("0.4,nan,0.5\n", "f.csv");
            }).find("f.csv line 1: 'nan' is not a finite number"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              parse_waypoints_csv("0.1,0.2\n", "f.csv");
            }).find("line 1: expected 3 columns"),
            std::string::npos);
  EXPECT_NE(error_of([] { parse_waypoints_csv("x,y,z\n", "f.csv"); }).find("holds no waypoint"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              parse_waypoints_json(R"({"waypoints": []})", "f.json");
            }).find("holds no waypoint"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              parse_waypoints_json(R"({"waypoints": [{"position": [NaN, 0, 0]}]})");
            }).find("not valid JSON"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              parse_waypoints_json(R"({"waypoints": [{"position": [1, 0]}]})");
            }).find("waypoint 0 \"position\" must be an array of 3 numbers"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              parse_waypoints_json(
                  R"({"waypoints": [{"position": [1, 0, 0], "quaternion": [0, 0, 0, 0]}]})");
            }).find("must not be zero"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              load_waypoints("/nonexistent/path.json");
            }).find("waypoint file '/nonexistent/path.json' does not exist"),
            std::string::npos);
}

// issue 29, item 1: "quaternoin" was skipped, and the waypoint took the path's orientation
// (plan exited 0 with the tool 45° away from the one asked for)
TEST(WaypointFile, UnknownOrRepeatedJsonKeysNameTheLineAndTheClosestKey) {
  const auto error_in = [](const std::string& text) {
    return error_of([&] { parse_waypoints_json(text, "'wp.json'"); });
  };
  std::string message = error_in(R"({"orientation": [0, 1, 0, 0],
    "waypoints": [{"position": [0.45, 0.0, 0.50]},
                  {"position": [0.45, 0.2, 0.40], "quaternoin": [0, 0.92, 0.38, 0]}]})");
  EXPECT_NE(message.find("waypoints 'wp.json' line 3: unknown key 'quaternoin' in waypoint 1; "
                         "closest: quaternion; keys: position, quaternion"),
            std::string::npos)
      << message;
  message = error_in(R"({"frame": "tool",
    "orientaton": [0, 1, 0, 0], "waypoints": [{"position": [0.45, 0.0, 0.50]}]})");
  EXPECT_NE(message.find("line 2: unknown key 'orientaton' in the file; closest: orientation"),
            std::string::npos)
      << message;
  // any extra key, the first one in the text
  message = error_in(R"({"waypoints": [{"position": [1, 0, 0],
      "speed": 2, "a": 1}]})");
  EXPECT_NE(message.find("line 2: unknown key 'speed' in waypoint 0"), std::string::npos)
      << message;
  // a key twice: JSON keeps the last one without a word
  message = error_in(R"({"waypoints": [{"position": [1, 0, 0],
                                         "position": [2, 0, 0]}]})");
  EXPECT_NE(message.find("line 2: key 'position' appears twice in one object"), std::string::npos)
      << message;
  // a key with '/' or '~' is found at its line too
  message = error_in("{\"waypoints\": [{\"position\": [1, 0, 0]}],\n\"a/~b\": 1}");
  EXPECT_NE(message.find("line 2: unknown key 'a/~b' in the file"), std::string::npos) << message;
  // nesting is bounded before the keys' places are kept
  message = error_in("{\"waypoints\": " + std::string(200, '[') + std::string(200, ']') + "}");
  EXPECT_NE(message.find("line 1: nested more than 100 levels deep"), std::string::npos)
      << message;
}

// issue 29, item 1 in CSV: a header in another order ("qx,qy,qz,qw") was skipped and its rows
// read as w, x, y, z; an unknown column name or a row wider than the header was not noticed
TEST(WaypointFile, ACsvHeaderNamesKnownColumnsInTheirOrder) {
  const auto error_in = [](const std::string& text) {
    return error_of([&] { parse_waypoints_csv(text, "'wp.csv'"); });
  };
  std::string message = error_in("x,y,zz\n0.45,0,0.5\n");
  EXPECT_NE(message.find("waypoints 'wp.csv' line 1: unknown column 'zz' in the header; closest: "
                         "z; columns: x, y, z, qw, qx, qy, qz"),
            std::string::npos)
      << message;
  message = error_in("x,y,z,qx,qy,qz,qw\n0.45,0,0.5,0,0,0,1\n");
  EXPECT_NE(message.find("line 1: the header names the columns x, y, z, qx, qy, qz, qw; expected "
                         "x, y, z or x, y, z, qw, qx, qy, qz, in that order"),
            std::string::npos)
      << message;
  message = error_in("x,y,z\n0.45,0,0.5\n0.45,0,0.5,0,1,0,0\n");
  EXPECT_NE(message.find("line 3: 7 values, but the header (line 1) names 3 columns"),
            std::string::npos)
      << message;
  message = error_in("x,y,z,qw,qx,qy,qz\n0.45,0,0.5\n");
  EXPECT_NE(message.find("line 2: 3 values, but the header (line 1) names 7 columns"),
            std::string::npos)
      << message;
}

TEST(WaypointFile, LoadPicksTheFormatByExtension) {
  const std::string json = ::testing::TempDir() + "planning_waypoints.json";
  const std::string csv = ::testing::TempDir() + "planning_waypoints.csv";
  std::ofstream(json) << R"({"waypoints": [{"position": [0.1, 0.2, 0.3]}]})";
  std::ofstream(csv) << "0.1,0.2,0.3\n0.2,0.2,0.3\n";
  EXPECT_EQ(load_waypoints(json).waypoints.size(), 1u);
  EXPECT_EQ(load_waypoints(csv).waypoints.size(), 2u);
  std::remove(json.c_str());
  std::remove(csv.c_str());
  // the extension in any case (".JSON" was read as CSV: "'{\"waypoints\"…' is not a number")
  const auto upper = test::scratch() / "waypoints.JSON";
  std::ofstream(upper) << R"({"waypoints": [{"position": [0.1, 0.2, 0.3]}]})";
  EXPECT_EQ(load_waypoints(upper).waypoints.size(), 1u);
}

// issue 16, item 7: the waypoint file is a user file like a model: a FIFO blocked for ever,
// /dev/zero grew without bound, and a symbolic link loop or a folder had no reason given
TEST(WaypointFile, OnlyRegularFilesOfBoundedSizeAreRead) {
  for (const char* extension : {".json", ".csv"}) {
    for (const test::UnreadablePath& bad : test::unreadable_paths(
             test::scratch() / "waypoint_files", "waypoints", extension, kMaxTextFileBytes + 1)) {
      const std::string message = test::error_without_blocking(
          bad.path, [](const std::filesystem::path& p) { load_waypoints(p); });
      EXPECT_NE(message.find("waypoint file '" + bad.path.string() + "'"), std::string::npos)
          << message;
      EXPECT_NE(message.find(bad.expected), std::string::npos) << message;
    }
  }
}

}  // namespace
}  // namespace mjarm
