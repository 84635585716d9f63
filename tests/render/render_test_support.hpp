#pragma once
// Shared pieces of the render tests: scenes, pixel statistics, a scratch folder and a way to run
// programs (the CLI, ffprobe) without a shell, the video tests' pattern and ffprobe check.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "executable_on_path.hpp"
#include "mjarm/error.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/render/image.hpp"
#include "support/error_message.hpp"
#include "support/files.hpp"

extern char** environ;

namespace mjarm::test {

namespace fs = std::filesystem;

/// The bundled scene without any robot: floor, lights and sky of models/common/scene.xml.
inline Robot empty_scene() {
  return Robot::from_string(R"(<mujoco model="empty"><include file="common/scene.xml"/></mujoco>)",
                            MJARM_MODELS_DIR);
}

/// The bundled panda at its "home" keyframe, kinematics computed.
inline DataPtr panda_home(const Robot& panda) {
  DataPtr d = panda.make_data();
  const std::vector<double> home = panda.keyframe_qpos("home");
  for (int i = 0; i < panda.nq(); ++i) d->qpos[i] = home[static_cast<std::size_t>(i)];
  mj_forward(&panda.model(), d.get());
  return d;
}

/// Per-channel mean and the standard deviation of grey levels (0…255) of an image.
struct PixelStats {
  double mean[3] = {0, 0, 0};
  double grey_stddev = 0.0;
  double dark_share = 0.0;  ///< share of pixels with every channel < 8
};

inline PixelStats pixel_stats(const Image& image) {
  PixelStats s;
  double sum = 0.0, sum2 = 0.0;
  std::size_t dark = 0;
  for (std::size_t p = 0; p < image.pixels(); ++p) {
    const std::uint8_t* px = image.rgb.data() + 3 * p;
    for (int c = 0; c < 3; ++c) s.mean[c] += px[c];
    const double grey = (px[0] + px[1] + px[2]) / 3.0;
    sum += grey;
    sum2 += grey * grey;
    if (px[0] < 8 && px[1] < 8 && px[2] < 8) ++dark;
  }
  const double n = static_cast<double>(image.pixels());
  for (double& m : s.mean) m /= n;
  s.grey_stddev = std::sqrt(std::max(0.0, sum2 / n - (sum / n) * (sum / n)));
  s.dark_share = static_cast<double>(dark) / n;
  return s;
}

/// Same size and the same bytes, pixel for pixel.
inline bool same(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height && a.rgb == b.rgb;
}

/// True where two images differ by more than @p threshold (sum of |Δ| over r, g, b).
inline std::vector<bool> changed_pixels(const Image& a, const Image& b, int threshold = 30) {
  std::vector<bool> changed(a.pixels(), false);
  for (std::size_t p = 0; p < a.pixels(); ++p) {
    int d = 0;
    for (int c = 0; c < 3; ++c) d += std::abs(a.rgb[3 * p + c] - b.rgb[3 * p + c]);
    changed[p] = d > threshold;
  }
  return changed;
}

/// What a program did.
struct ProcessRun {
  int exit_code = -1;
  bool signaled = false;
  std::string out;
  std::string err;
};

/// Runs @p argv (argv[0] is the executable path) with environment @p env (the test's own when
/// empty), capturing stdout and stderr through files.
inline ProcessRun run_process(std::vector<std::string> argv, std::vector<std::string> env = {}) {
  static int counter = 0;
  const std::string tag = std::to_string(++counter);
  const fs::path out = scratch() / ("stdout" + tag);
  const fs::path err = scratch() / ("stderr" + tag);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::vector<char*> args;
  for (auto& a : argv) args.push_back(a.data());
  args.push_back(nullptr);
  std::vector<char*> envp;
  for (auto& e : env) envp.push_back(e.data());
  envp.push_back(nullptr);
  pid_t pid = 0;
  ProcessRun run;
  const int spawned = posix_spawn(&pid, argv[0].c_str(), &actions, nullptr, args.data(),
                                  env.empty() ? environ : envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) {
    run.err = "cannot start " + argv[0];
    return run;
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  run.signaled = WIFSIGNALED(status);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = slurp(out);
  run.err = slurp(err);
  return run;
}

// ---- videos: a moving test pattern, ffprobe's view of a file, a hostile file name

// a frame with a square that moves with k, so the encoder has something to do
inline Image moving_square(int w, int h, int k) {
  Image image(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = image.at(x, y);
      const bool square = x >= 2 * k && x < 2 * k + 12 && y >= 10 && y < 22;
      p[0] = square ? 230 : 20;
      p[1] = static_cast<std::uint8_t>(4 * y);
      p[2] = static_cast<std::uint8_t>(3 * x);
    }
  }
  return image;
}

struct Probe {
  int frames = -1;
  int width = 0;
  int height = 0;
  std::string codec;
};

// ffprobe decodes every frame and reports the count; -1 when the file is not a valid video
inline Probe probe(const fs::path& video) {
  const std::string ffprobe = executable_on_path("ffprobe");
  EXPECT_FALSE(ffprobe.empty()) << "ffprobe (Debian package ffmpeg) is needed by this test";
  const auto run = run_process({ffprobe, "-v", "error", "-count_frames", "-select_streams", "v:0",
                                "-show_entries", "stream=nb_read_frames,width,height,codec_name",
                                "-of", "default=noprint_wrappers=1", video.string()});
  Probe p;
  if (run.exit_code != 0) return p;
  std::istringstream lines(run.out);
  std::string line;
  while (std::getline(lines, line)) {
    const auto eq = line.find('=');
    if (eq == std::string::npos) continue;
    const std::string key = line.substr(0, eq), value = line.substr(eq + 1);
    if (key == "nb_read_frames") p.frames = std::atoi(value.c_str());
    if (key == "width") p.width = std::atoi(value.c_str());
    if (key == "height") p.height = std::atoi(value.c_str());
    if (key == "codec_name") p.codec = value;
  }
  return p;
}

inline bool has_moov_atom(const fs::path& video) {
  return slurp(video).find("moov") != std::string::npos;
}

// issue 16, item 3: the video path reaches ffmpeg's command line as one argv entry, never
// through a shell nor read as an option or a protocol: every byte of the name is kept
inline std::string hostile_video_name() {
  return "-y:v\n'`touch PWNED1`$(touch PWNED2)\"; system \"touch PWNED3\" %d \\.mp4";
}

}  // namespace mjarm::test
