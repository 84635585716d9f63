#include "mjarm/plot/recording.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "mjarm/error.hpp"
#include "mjarm/plot/plots.hpp"
#include "plot/plot_test_support.hpp"

namespace mjarm::plot {
namespace {

namespace fs = std::filesystem;

std::string load_error(const fs::path& dir) {
  try {
    Recording::load(dir);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

// the press recording, made once for this file's tests
const fs::path& press_recording() {
  static test::TempDir dir("plot-recording");
  static const bool made = (test::record_press(dir.path() / "rec"), true);
  (void)made;
  static const fs::path path = dir.path() / "rec";
  return path;
}

// a copy of the press recording whose @p file is replaced by @p text
fs::path damaged_copy(const test::TempDir& dir, const std::string& file, const std::string& text) {
  const fs::path copy = dir.path() / "damaged";
  fs::copy(press_recording(), copy, fs::copy_options::recursive);
  test::write_file(copy / file, text);
  return copy;
}

TEST(Recording, LoadsWhatTheRecorderWrote) {
  const Recording r = Recording::load(press_recording());
  EXPECT_EQ(r.model(), "press");
  EXPECT_EQ(r.status(), "duration_reached");
  EXPECT_EQ(r.frame(), "tip");
  EXPECT_EQ(r.controllers(), std::vector<std::string>{"test-pd"});
  EXPECT_NEAR(r.end_time(), 0.6, 1e-9);
  EXPECT_EQ(r.task().rows(), 150u);   // 0.6 s at 4 ms
  EXPECT_EQ(r.state().rows(), 300u);  // every 2 ms step
  ASSERT_EQ(r.actuators().size(), 1u);
  EXPECT_EQ(r.actuators()[0].name, "press");
  EXPECT_EQ(r.actuators()[0].joint, "slide");
  ASSERT_TRUE(r.actuators()[0].force_range.has_value());
  EXPECT_EQ(r.actuators()[0].force_range->second, 50.0);
  const std::vector<RecordedEvent> phases = r.events_of("phase");
  ASSERT_EQ(phases.size(), 2u);
  EXPECT_EQ(phases[1].message, "press");
  EXPECT_NEAR(phases[1].t, 0.3, 1e-9);
  ASSERT_EQ(r.events().size(), 3u);
  EXPECT_EQ(r.events()[2].message, "pressed, with \"quotes\", and commas");
  // physics: pressed down by the saturated motor, the floor carries 50 N + m·g at the end
  const std::vector<double> force = r.state().numbers("contact.normal_force");
  EXPECT_NEAR(force.back(), 50.0 + 9.81, 0.5);
}

TEST(Recording, AMissingOrNonDirectoryRecordingIsNamed) {
  test::TempDir dir("plot-missing");
  const std::string missing = load_error(dir.path() / "nothing");
  EXPECT_NE(missing.find("nothing' does not exist"), std::string::npos) << missing;
  test::write_file(dir.path() / "file.txt", "x");
  const std::string file = load_error(dir.path() / "file.txt");
  EXPECT_NE(file.find("is not a directory"), std::string::npos) << file;
  // a symbolic link loop is named as such, not as a missing folder
  std::filesystem::create_symlink("loop_b", dir.path() / "loop_a");
  std::filesystem::create_symlink("loop_a", dir.path() / "loop_b");
  const std::string loop = load_error(dir.path() / "loop_a");
  EXPECT_NE(loop.find("symbolic link loop"), std::string::npos) << loop;
}

TEST(Recording, AMissingFileIsNamed) {
  for (const char* name : {"summary.json", "state.csv", "task.csv", "events.csv"}) {
    test::TempDir dir("plot-nofile");
    const fs::path copy = dir.path() / "rec";
    fs::copy(press_recording(), copy, fs::copy_options::recursive);
    fs::remove(copy / name);
    const std::string message = load_error(copy);
    EXPECT_NE(message.find(std::string("has no ") + name), std::string::npos) << message;
  }
}

TEST(Recording, AnEmptyRecordingIsRefused) {
  test::TempDir dir("plot-empty");
  {
    const Robot robot = Robot::from_string(test::kPressModel);
    Simulation sim(robot, SimulationOptions{});
    Recorder recorder(sim, dir.path());
    recorder.finalize("aborted");  // headers, no rows
  }
  const std::string message = load_error(dir.path());
  EXPECT_NE(message.find("is empty: task.csv has no rows"), std::string::npos) << message;
}

TEST(Recording, AMissingColumnNamesTheFileAndTheColumn) {
  test::TempDir dir("plot-nocolumn");
  // an older recording: state.csv without the contact columns
  const fs::path copy =
      damaged_copy(dir, "state.csv", "t,q.slide,v.slide,ctrl.press,force.press\n0,0,0,0,0\n");
  const Recording r = Recording::load(copy);
  try {
    make_plots(r, dir.path() / "out");
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("state.csv' has no column 'contact.normal_force'"), std::string::npos)
        << message;
  }
  // nothing was drawn or written
  EXPECT_FALSE(fs::exists(dir.path() / "out"));
}

TEST(Recording, ADamagedFileIsNamed) {
  test::TempDir dir("plot-damaged");
  const std::string ragged = load_error(damaged_copy(dir, "task.csv", "t,err.vx\n0,1\n0.1\n"));
  EXPECT_NE(ragged.find("task.csv' line 3"), std::string::npos) << ragged;
  test::TempDir dir2("plot-badjson");
  const std::string json = load_error(damaged_copy(dir2, "summary.json", "{\"model\": "));
  EXPECT_NE(json.find("summary.json': not valid JSON"), std::string::npos) << json;
}

// issue 29, item 1 for the summary plot reads: a key twice was read as its last value, a gear
// or force range of the wrong type as 1 or none (the torque figure then scaled by 1)
TEST(Recording, ASummaryValueOfTheWrongTypeOrAKeyTwiceIsNamed) {
  const auto with = [](const char* name, const std::string& summary) {
    test::TempDir dir(name);
    return load_error(damaged_copy(dir, "summary.json", summary));
  };
  std::string message = with("plot-gear", R"({"actuators": [{"name": "a", "gear": "2"}]})");
  EXPECT_NE(message.find("summary.json': key 'gear' holds string \"2\", expected a number"),
            std::string::npos)
      << message;
  message = with("plot-range", R"({"actuators": [{"name": "a", "force_range": [87]}]})");
  EXPECT_NE(message.find("key 'force_range' holds [87], expected [lower, upper]"),
            std::string::npos)
      << message;
  message = with("plot-twice", "{\"model\": \"a\",\n \"model\": \"b\"}");
  EXPECT_NE(message.find("summary.json' line 2: key 'model' appears twice"), std::string::npos)
      << message;
  // keys the recorder writes that plot does not read are fine
  EXPECT_EQ(with("plot-unread", R"({"model": "a", "invocation": ["mjarm", "run"]})"), "no error");
}

// issue 29, item 1 ("unknown keys are an error with the closest name, in every file mjarm
// reads"): a misspelt key of a summary edited by hand was ignored (a "gera" left the gear at 1)
TEST(Recording, AnUnknownSummaryKeyIsNamedWithTheClosest) {
  const auto with = [](const char* name, const std::string& summary) {
    test::TempDir dir(name);
    return load_error(damaged_copy(dir, "summary.json", summary));
  };
  std::string message = with("plot-gera", "{\"actuators\": [{\"name\": \"a\",\n \"gera\": 2}]}");
  EXPECT_NE(message.find("summary.json' line 2: unknown key 'gera' in actuators entry 0; "
                         "closest: gear"),
            std::string::npos)
      << message;
  message = with("plot-modle", R"({"modle": "panda"})");
  EXPECT_NE(message.find("unknown key 'modle' in the summary; closest: model"), std::string::npos)
      << message;
  message = with("plot-ctrl", R"({"controllers": [{"nmae": "pd"}]})");
  EXPECT_NE(message.find("unknown key 'nmae' in controllers entry 0; closest: name"),
            std::string::npos)
      << message;
}

}  // namespace
}  // namespace mjarm::plot
