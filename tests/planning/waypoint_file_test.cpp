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
  const WaypointPath path =
      parse_waypoints_csv("x,y,z\n# comment\n0.4,0,0.5\n\n0.3, 0.1, 0.4, 1, 0, 0, 0\n");
  ASSERT_EQ(path.waypoints.size(), 2u);
  Eigen::Matrix3d R = Eigen::Matrix3d::Zero();
  R(0, 1) = R(1, 0) = 1.0;
  R(2, 2) = -1.0;
  const std::vector<Pose> poses = path.poses(R);
  EXPECT_EQ(poses[0].R, R);
  EXPECT_TRUE(poses[1].R.isApprox(Eigen::Matrix3d::Identity()));
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
              parse_waypoints_csv("x,y,z\n0.1,0.2\n", "f.csv");
            }).find("line 2: expected 3 columns"),
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

TEST(WaypointFile, LoadPicksTheFormatByExtension) {
  const std::string json = ::testing::TempDir() + "planning_waypoints.json";
  const std::string csv = ::testing::TempDir() + "planning_waypoints.csv";
  std::ofstream(json) << R"({"waypoints": [{"position": [0.1, 0.2, 0.3]}]})";
  std::ofstream(csv) << "0.1,0.2,0.3\n0.2,0.2,0.3\n";
  EXPECT_EQ(load_waypoints(json).waypoints.size(), 1u);
  EXPECT_EQ(load_waypoints(csv).waypoints.size(), 2u);
  std::remove(json.c_str());
  std::remove(csv.c_str());
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
