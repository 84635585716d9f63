// `mjarm render`: a still PNG from the command line, headless with no display and software GL,
// and the exit codes of bad input (2: the command line, 1: the command failed).

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "mjarm/render/png.hpp"
#include "render_test_support.hpp"

namespace mjarm {
namespace {

namespace fs = std::filesystem;

test::ProcessRun render(std::vector<std::string> args, std::vector<std::string> env = {}) {
  args.insert(args.begin(), {MJARM_CLI, "render"});
  return test::run_process(std::move(args), std::move(env));
}

TEST(CliRender, WritesAPngAndDescribesItAsJson) {
  const fs::path out = test::scratch() / "cli.png";
  const auto run = render({"panda", "--keyframe", "home", "--size", "200x150", "--out",
                           out.string(), "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto doc = nlohmann::json::parse(run.out);
  EXPECT_EQ(doc["model"], "panda");
  EXPECT_EQ(doc["configuration"], "keyframe 'home'");
  EXPECT_EQ(doc["camera"]["kind"], "free");
  EXPECT_EQ(doc["width"], 200);
  const Image image = read_png(out);
  EXPECT_EQ(image.width, 200);
  EXPECT_EQ(image.height, 150);
  EXPECT_GT(test::pixel_stats(image).grey_stddev, 10.0);
}

TEST(CliRender, HeadlessWithoutDisplayOrGpu) {
  // no DISPLAY, no WAYLAND_DISPLAY, software rasteriser forced: what a CI box or server has
  const fs::path out = test::scratch() / "headless.png";
  const char* path = std::getenv("PATH");
  const char* asan = std::getenv("ASAN_OPTIONS");  // a sanitized build's settings carry over
  const auto run = render({"panda", "--q", "0", "-0.5", "0", "-2", "0", "1.6", "0.8",
                           "--follow", "attachment_site", "--distance", "0.9", "--out",
                           out.string()},
                          {std::string("PATH=") + (path != nullptr ? path : "/usr/bin:/bin"),
                           "LIBGL_ALWAYS_SOFTWARE=1", "MJARM_MODELS=" MJARM_MODELS_DIR,
                           std::string("ASAN_OPTIONS=") + (asan != nullptr ? asan : "")});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("llvmpipe"), std::string::npos) << run.out;
  const auto stats = test::pixel_stats(read_png(out));
  EXPECT_GT(stats.grey_stddev, 10.0);
  EXPECT_LT(stats.dark_share, 0.05);
}

TEST(CliRender, UnknownCameraFailsWithTheList) {
  const auto run = render({"panda", "--camera", "top", "--out",
                           (test::scratch() / "never.png").string()});
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("camera 'top' not found in model 'panda'; cameras: (none)"),
            std::string::npos)
      << run.err;
}

TEST(CliRender, UnwritableOutputFails) {
  const auto run = render({"panda", "--size", "64x48", "--out",
                           (test::scratch() / "missing_dir" / "x.png").string()});
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("No such file or directory"), std::string::npos) << run.err;
}

TEST(CliRender, BadCommandLinesExitTwo) {
  const std::string out = (test::scratch() / "bad.png").string();
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"panda", "--size", "0x0", "--out", out},
           {"panda", "--size", "640", "--out", out},
           {"panda", "--size", "-640x480", "--out", out},
           {"panda"},                                            // no --out
           {"panda", "--q", "1", "2", "3", "4", "5", "6", "7", "8", "--out", out},  // > nq
           {"panda", "--camera", "x", "--lookat", "0", "0", "0", "--out", out},
           {"panda", "--elevation", "nan", "--out", out}}) {
    const auto run = render(args);
    std::string line;
    for (const auto& a : args) line += a + " ";
    EXPECT_EQ(run.exit_code, 2) << line << "\n" << run.err;
  }
  EXPECT_EQ(render({"--help"}).exit_code, 0);
}

}  // namespace
}  // namespace mjarm
