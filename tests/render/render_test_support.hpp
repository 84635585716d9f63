#pragma once
// Shared pieces of the render tests: scenes, pixel statistics, a scratch folder and a way to run
// programs (the CLI, ffprobe) without a shell.

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

}  // namespace mjarm::test
