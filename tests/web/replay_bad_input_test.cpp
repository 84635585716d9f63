// The replay page's bad input (docs/replay.md "Bad input"): a run too long for the size cap is
// decimated and says so, a model whose mesh files are gone is drawn with boxes and warned about, a
// truncated, binary, foreign or diverged recording is a clear error (or an honest early end) that
// leaves no half-written file; through the library and the CLI.

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/cli_runner.hpp"
#include "mjarm/error.hpp"
#include "mjarm/plot/recording.hpp"
#include "mjarm/web/replay_html.hpp"
#include "support/error_message.hpp"
#include "web/replay_test_support.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// a falling cube and a swinging link that shows two meshes read from files (one of them given a
// size of its own)
constexpr const char* kMeshModel = R"(
<mujoco model="meshes">
  <option timestep="0.002"/>
  <compiler meshdir="meshes"/>
  <asset>
    <mesh name="wedge" file="wedge.obj"/>
    <mesh file="fin.obj"/>
  </asset>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 0.1"/>
    <body name="cube" pos="0.3 0 0.3">
      <freejoint name="cube_free"/>
      <geom name="cube_box" type="box" size="0.03 0.03 0.03"/>
    </body>
    <body name="link" pos="-0.2 0 0.5">
      <joint name="hinge" type="hinge" axis="0 1 0" damping="0.01"/>
      <geom name="rod" type="capsule" fromto="0 0 0 0 0 -0.2" size="0.01"/>
      <geom name="wedge_geom" type="mesh" mesh="wedge" pos="0 0 -0.2"/>
      <geom name="fin_geom" type="mesh" mesh="fin" size="0.01 0.02 0.03"/>
      <site name="tip" pos="0 0 -0.2"/>
    </body>
  </worldbody>
  <actuator>
    <motor name="swing" joint="hinge" gear="1" ctrllimited="true" ctrlrange="-1 1"/>
  </actuator>
</mujoco>)";

constexpr const char* kTetrahedron =
    "v 0 0 0\nv 0.05 0 0\nv 0 0.05 0\nv 0 0 0.05\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

void write_text(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

class ReplayBadInput : public ::testing::Test {
 protected:
  // "whole/": the model with its meshes, and 6 s recorded on it (3000 state rows); "gone/": the
  // same model file without its meshes folder
  static void SetUpTestSuite() {
    root_ = new mjarm::test::TempDir("replay_bad_input");
    write_text(whole_model(), kMeshModel);
    write_text(root_->path() / "whole" / "meshes" / "wedge.obj", kTetrahedron);
    write_text(root_->path() / "whole" / "meshes" / "fin.obj", kTetrahedron);
    write_text(gone_model(), kMeshModel);
    mjarm::test::record_swing(mjarm::Robot::from_file(whole_model()), recording(), 6.0);
  }
  static void TearDownTestSuite() {
    delete root_;
    root_ = nullptr;
  }
  static fs::path whole_model() { return root_->path() / "whole" / "robot.xml"; }
  static fs::path gone_model() { return root_->path() / "gone" / "robot.xml"; }
  static fs::path recording() { return root_->path() / "rec"; }
  static fs::path out(const std::string& name) { return root_->path() / name; }

  // a copy of the recording whose @p file is edited by @p edit
  static fs::path variant(const std::string& name, const std::string& file,
                          const std::function<std::string(std::string)>& edit) {
    const fs::path dir = out(name);
    fs::create_directories(dir);
    for (const auto& entry : fs::directory_iterator(recording()))
      fs::copy_file(entry.path(), dir / entry.path().filename(),
                    fs::copy_options::overwrite_existing);
    write_text(dir / file, edit(mjarm::test::slurp_file(dir / file)));
    return dir;
  }

  static mjarm::ReplayHtmlReport replay(const fs::path& rec, const fs::path& html,
                                        const mjarm::ReplayHtmlOptions& options = {}) {
    const mjarm::plot::Recording loaded =
        mjarm::plot::Recording::load(rec, mjarm::plot::TableRows::header_only);
    return mjarm::write_replay_html(mjarm::Robot::from_file(whole_model()), loaded, html, options);
  }

 private:
  static mjarm::test::TempDir* root_;
};
mjarm::test::TempDir* ReplayBadInput::root_ = nullptr;

TEST_F(ReplayBadInput, ALongRunIsDecimatedToTheSizeCapAndThePageSaysSo) {
  mjarm::ReplayHtmlOptions options;
  options.rate = 1000.0;  // above the recording's 500 rows per second: every row
  const mjarm::ReplayHtmlReport all = replay(recording(), out("all.html"), options);
  EXPECT_EQ(all.state_rows, 3000);
  EXPECT_EQ(all.frames, 3000);
  EXPECT_FALSE(all.decimated);
  EXPECT_TRUE(all.decimation.empty());
  EXPECT_GT(all.bytes, 1'000'000u) << "too small a run to test the cap with";
  EXPECT_EQ(mjarm::test::data_block(out("all.html"))["decimation"], "");

  options.max_mb = 1.0;
  const mjarm::ReplayHtmlReport capped = replay(recording(), out("capped.html"), options);
  EXPECT_TRUE(capped.decimated);
  EXPECT_LE(capped.bytes, 1'000'000u);
  EXPECT_EQ(capped.bytes, fs::file_size(out("capped.html")));
  EXPECT_LT(capped.frames, 3000);
  EXPECT_GT(capped.frames, 100);
  EXPECT_LT(capped.rate, 500.0);
  EXPECT_NE(capped.decimation.find("decimated to fit 1.0 MB"), std::string::npos)
      << capped.decimation;
  EXPECT_NE(capped.decimation.find(" frames of 3,000 state rows"), std::string::npos)
      << capped.decimation;

  // the page says it, and its frames, plots and overlays all obey the cap
  const json data = mjarm::test::data_block(out("capped.html"));
  EXPECT_EQ(data["decimation"], capped.decimation);
  EXPECT_LT(data["rate"].get<double>(), 1000.0);
  const std::vector<float> time = mjarm::test::unbase64_floats(data["frames"]["time"]);
  ASSERT_EQ(time.size(), static_cast<std::size_t>(capped.frames));
  EXPECT_EQ(mjarm::test::unbase64_floats(data["plot_time"]).size(), time.size());
  for (const json& plot : data["plots"])
    for (const json& series : plot["series"])
      EXPECT_EQ(mjarm::test::unbase64_floats(series["values"]).size(), time.size());
  EXPECT_EQ(mjarm::test::unbase64_floats(data["overlays"]["tool"]).size(), time.size() * 7);
  EXPECT_EQ(mjarm::test::unbase64(data["overlays"]["contacts"]["offsets"]).size(),
            (time.size() + 1) * 4);
  // every frame is still a recorded row: the cube's position is its free joint's qpos there
  const mjarm::plot::Recording rec = mjarm::plot::Recording::load(recording());
  const std::vector<double> t = rec.state().numbers("t");
  const std::vector<double> x = rec.state().numbers("q.cube_free.2");
  const std::vector<float> pos = mjarm::test::unbase64_floats(data["frames"]["pos"]);
  const std::size_t nbody = data["bodies"].size();
  const std::size_t cube = 1;
  ASSERT_EQ(data["bodies"][cube]["name"], "cube");
  std::size_t row = 0;
  for (std::size_t f = 0; f < time.size(); ++f) {
    while (row + 1 < t.size() && std::abs(t[row] - time[f]) > 1e-6) ++row;
    ASSERT_NEAR(t[row], time[f], 1e-6) << "frame " << f << " is no recorded row";
    EXPECT_NEAR(pos[(f * nbody + cube) * 3 + 2], x[row], 1e-6) << "frame " << f;
  }
  EXPECT_NEAR(time.back(), t.back(), 1e-6) << "the last row is kept";
}

TEST_F(ReplayBadInput, MissingMeshesAreDrawnAsBoxesWithOneWarningEach) {
  // without the option the load fails naming the file, as before
  EXPECT_NE(mjarm::test::error_of([] { mjarm::Robot::from_file(gone_model()); }).find("wedge.obj"),
            std::string::npos);
  const mjarm::Robot robot =
      mjarm::Robot::from_file(gone_model(), {.missing_meshes_as_boxes = true});
  ASSERT_EQ(robot.missing_meshes().size(), 2u);
  const std::string all = robot.missing_meshes()[0] + robot.missing_meshes()[1];
  EXPECT_NE(all.find("'wedge.obj' not found"), std::string::npos) << all;
  EXPECT_NE(all.find("'fin.obj' not found"), std::string::npos) << all;
  EXPECT_NE(all.find("drawn as a box"), std::string::npos) << all;
  const mjModel& m = robot.model();
  const mjarm::Robot whole = mjarm::Robot::from_file(whole_model());
  EXPECT_EQ(m.nq, whole.model().nq);  // the recording's qpos still fits
  EXPECT_EQ(m.nmesh, 0);
  const int wedge = mj_name2id(&m, mjOBJ_GEOM, "wedge_geom");
  const int fin = mj_name2id(&m, mjOBJ_GEOM, "fin_geom");
  EXPECT_EQ(m.geom_type[wedge], mjGEOM_BOX);
  EXPECT_EQ(m.geom_type[fin], mjGEOM_BOX);
  for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(m.geom_size[3 * wedge + k], 0.025);
  EXPECT_DOUBLE_EQ(m.geom_size[3 * fin + 2], 0.03);  // its own size

  const mjarm::plot::Recording rec =
      mjarm::plot::Recording::load(recording(), mjarm::plot::TableRows::header_only);
  const mjarm::ReplayHtmlReport report = mjarm::write_replay_html(robot, rec, out("boxes.html"));
  EXPECT_EQ(report.warnings, robot.missing_meshes());
  EXPECT_EQ(report.meshes, 0);
  const json data = mjarm::test::data_block(out("boxes.html"));
  EXPECT_EQ(data["warnings"].get<std::vector<std::string>>(), robot.missing_meshes());
  int boxes = 0;
  for (const json& g : data["geoms"]) boxes += g["type"] == "box" ? 1 : 0;
  EXPECT_EQ(boxes, 3);  // the cube and the two meshes'
}

TEST_F(ReplayBadInput, ATruncatedBinaryOrForeignRecordingIsAClearErrorAndWritesNothing) {
  const fs::path html = out("bad.html");
  write_text(html, "an older page");
  auto refused = [&](const fs::path& rec, const std::string& expected) {
    const std::string message = mjarm::test::error_of([&] { replay(rec, html); });
    EXPECT_NE(message.find(expected), std::string::npos) << message;
    EXPECT_EQ(mjarm::test::slurp_file(html), "an older page") << "the older file is kept whole";
  };
  // cut in the middle of a row
  auto cut = [](std::string text) {
    std::size_t at = text.size() / 2;
    while (text[at - 1] == '\n' || text[at] == '\n') ++at;
    return text.substr(0, at);
  };
  refused(variant("cut_state", "state.csv", cut), "state.csv' ");
  refused(variant("cut_state", "state.csv", cut), "truncated");
  refused(variant("cut_task", "task.csv", cut), "task.csv' ");
  // a binary file in its place
  refused(
      variant("binary", "state.csv", [](std::string) { return std::string("PK\3\4\0\0bin", 9); }),
      "NUL byte");
  // a CSV of other columns
  refused(variant("foreign", "state.csv", [](std::string) { return std::string("a,b\n1,2\n"); }),
          "does not match the recording");
  // rows but no qpos in the first: nothing to replay
  auto nan_from = [](std::size_t first_row) {
    return [first_row](std::string text) {
      // q.hinge's cells from row first_row on (the header is line 1) become "nan"
      std::vector<std::string> lines;
      std::size_t start = 0;
      while (start < text.size()) {
        const std::size_t end = text.find('\n', start);
        lines.push_back(text.substr(start, end - start));
        start = end + 1;
      }
      std::vector<std::string> header;
      for (std::size_t a = 0, b; a <= lines[0].size(); a = b + 1) {
        b = std::min(lines[0].find(',', a), lines[0].size());
        header.push_back(lines[0].substr(a, b - a));
      }
      const auto column = static_cast<std::size_t>(
          std::find(header.begin(), header.end(), "q.hinge") - header.begin());
      std::string out = lines[0] + "\n";
      for (std::size_t r = 1; r < lines.size(); ++r) {
        std::vector<std::string> cells;
        for (std::size_t a = 0, b; a <= lines[r].size(); a = b + 1) {
          b = std::min(lines[r].find(',', a), lines[r].size());
          cells.push_back(lines[r].substr(a, b - a));
        }
        if (r >= first_row) cells[column] = "nan";
        for (std::size_t c = 0; c < cells.size(); ++c) out += (c ? "," : "") + cells[c];
        out += "\n";
      }
      return out;
    };
  };
  refused(variant("nan_first", "state.csv", nan_from(1)), "in the first row");
  // time going back
  refused(variant("back", "state.csv",
                  [](std::string text) {
                    const std::size_t second = text.find('\n') + 1;
                    const std::size_t third = text.find('\n', second) + 1;
                    return text.substr(0, second) +
                           text.substr(third, text.find('\n', third) + 1 - third) +
                           text.substr(second);
                  }),
          "goes back in time");
  fs::remove(html);

  // a run that diverged at 4 s: the replay ends before it, and says so
  const mjarm::ReplayHtmlReport report =
      replay(variant("diverged", "state.csv", nan_from(2001)), out("diverged.html"));
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("q.hinge is nan at t = 4"), std::string::npos)
      << report.warnings[0];
  EXPECT_LT(report.end_time, 4.0);
  EXPECT_GT(report.end_time, 3.9);
  EXPECT_EQ(mjarm::test::data_block(out("diverged.html"))["warnings"][0], report.warnings[0]);
}

TEST_F(ReplayBadInput, TheCliSaysWhatItDecimatedAndWarnsOfEachMissingMesh) {
  const fs::path html = out("cli.html");
  const mjarm::test::CliRun json_run =
      mjarm::test::run_cli({"replay-html", recording().string(), "-o", html.string(), "--model",
                            gone_model().string(), "--rate", "1000", "--max-mb", "1", "--json"});
  ASSERT_EQ(json_run.exit_code, 0) << json_run.err;
  const json doc = json::parse(json_run.out);
  EXPECT_TRUE(doc["decimated"].get<bool>());
  EXPECT_NE(doc["decimation"].get<std::string>().find("decimated to fit 1.0 MB"),
            std::string::npos);
  EXPECT_LE(doc["bytes"].get<std::uintmax_t>(), 1'000'000u);
  ASSERT_EQ(doc["warnings"].size(), 2u);
  EXPECT_NE(json_run.err.find("warning: mesh 'wedge'"), std::string::npos) << json_run.err;

  const mjarm::test::CliRun text_run =
      mjarm::test::run_cli({"replay-html", recording().string(), "-o", html.string(), "--model",
                            whole_model().string(), "--rate", "1000", "--max-mb", "1"});
  ASSERT_EQ(text_run.exit_code, 0) << text_run.err;
  EXPECT_NE(text_run.out.find("decimated to fit 1.0 MB"), std::string::npos) << text_run.out;
  EXPECT_EQ(text_run.err.find("mesh '"), std::string::npos) << text_run.err;

  const mjarm::test::CliRun small = mjarm::test::run_cli(
      {"replay-html", recording().string(), "-o", html.string(), "--max-mb", "0.5"});
  EXPECT_EQ(small.exit_code, 2) << small.err;
}

}  // namespace
