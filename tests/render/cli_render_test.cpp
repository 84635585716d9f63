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
  const auto run =
      render({"panda", "--keyframe", "home", "--size", "200x150", "--out", out.string(), "--json"});
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
  const auto run = render({"panda", "--q", "0", "-0.5", "0", "-2", "0", "1.6", "0.8", "--follow",
                           "attachment_site", "--distance", "0.9", "--out", out.string()},
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
  const auto run =
      render({"panda", "--camera", "top", "--out", (test::scratch() / "never.png").string()});
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("camera 'top' not found in model 'panda'; cameras: (none)"),
            std::string::npos)
      << run.err;
}

TEST(CliRender, UnwritableOutputFailsBeforeRendering) {
  // checked with the command line (exit 2), before the model loads or OpenGL starts
  const auto run = render(
      {"panda", "--size", "64x48", "--out", (test::scratch() / "missing_dir" / "x.png").string()});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("--out: the folder"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("does not exist"), std::string::npos) << run.err;
  const auto proc = render({"panda", "--size", "64x48", "--out", "/proc/x.png"});
  EXPECT_EQ(proc.exit_code, 2);
  EXPECT_NE(proc.err.find("--out: cannot create '/proc/x.png'"), std::string::npos) << proc.err;
}

TEST(CliRender, SizesBeyondTheBufferLimitsAreRefusedNamingThem) {
  // 16384² passes the size syntax but is 4 GiB per buffer at the model's 4 samples: refused when
  // the renderer is made, naming the limits, and nothing is written
  const fs::path out = test::scratch() / "huge.png";
  const auto run = render({"panda", "--size", "16384x16384", "--out", out.string()});
  EXPECT_EQ(run.exit_code, 1) << run.err;
  for (const char* text :
       {"render size 16384×16384 is too large", "4 samples per pixel",
        "4096 MiB, the limit is 1024 MiB", "GL_MAX_RENDERBUFFER_SIZE", "GL_MAX_VIEWPORT_DIMS"})
    EXPECT_NE(run.err.find(text), std::string::npos) << text << " not in: " << run.err;
  EXPECT_EQ(run.err.find("framebuffer is not complete"), std::string::npos) << run.err;
  EXPECT_TRUE(run.out.empty()) << run.out;
  EXPECT_FALSE(fs::exists(out));
  // a long thin picture within every limit still renders
  const auto thin = render({"panda", "--size", "4096x8", "--out", out.string()});
  EXPECT_EQ(thin.exit_code, 0) << thin.err;
  EXPECT_EQ(read_png(out).width, 4096);
}

TEST(CliRender, BadCommandLinesExitTwo) {
  const std::string out = (test::scratch() / "bad.png").string();
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"panda", "--size", "0x0", "--out", out},
           {"panda", "--size", "640", "--out", out},
           {"panda", "--size", "-640x480", "--out", out},
           {"panda"},                                                               // no --out
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
