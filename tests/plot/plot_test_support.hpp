#pragma once
// Recordings for the plot tests, made by the real Simulation and Recorder, and PNG checks.

#include <filesystem>
#include <string>
#include <vector>

#include "mjarm/render/png.hpp"
#include "mjarm/sim/recorder.hpp"
#include "mjarm/sim/simulation.hpp"
#include "sim/sim_test_support.hpp"

namespace mjarm::test {

// A 1 kg block on a slide above a floor, pushed down by a ±50 N motor: the PD command asks for
// more than 50 N, so the motor saturates and the floor carries 50 N + m·g.
constexpr const char* kPressModel = R"(
<mujoco model="press">
  <option timestep="0.002"/>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 0.1"/>
    <body name="block" pos="0 0 0.2">
      <joint name="slide" type="slide" axis="0 0 1" limited="true" range="-0.5 0.5"/>
      <geom name="block" type="box" size="0.05 0.05 0.05" mass="1"/>
      <site name="tip" pos="0 0 -0.05"/>
    </body>
  </worldbody>
  <actuator>
    <motor name="press" joint="slide" gear="1" ctrllimited="true" ctrlrange="-50 50"/>
  </actuator>
</mujoco>)";

// Records 0.6 s of the press (a reference below the floor from the start) with two phases and a
// result event into @p dir.
inline void record_press(const std::filesystem::path& dir) {
  const Robot robot = Robot::from_string(kPressModel);
  const Chain chain(robot, "tip");
  SimulationOptions options;
  options.control_period = 0.004;
  Simulation sim(robot, options);
  PdTorque pd(chain, 2000.0, 40.0, false);
  sim.add_controller(pd);
  Recorder recorder(sim, dir);
  Reference reference;
  reference.joint.q = Eigen::VectorXd::Constant(1, -0.3);  // 0.1 m below the floor
  reference.task.X_WE.p = Eigen::Vector3d(0.0, 0.0, 0.0);
  ConstantReferenceSource source(reference);
  recorder.event(0.0, "phase", "descend");
  RunResult run = sim.run(source, 0.3, &recorder);
  recorder.event(sim.time(), "phase", "press");
  run = sim.run(source, 0.3, &recorder);
  recorder.event(sim.time(), "result", "pressed, with \"quotes\", and commas");
  recorder.finalize(run);
}

struct PixelStats {
  int width = 0, height = 0;
  double variance = 0.0;      // of the grey level (0 … 255)
  double ink_fraction = 0.0;  // pixels that are not near-white
};

inline PixelStats pixel_stats(const std::filesystem::path& png) {
  const Image image = read_png(png);
  PixelStats s;
  s.width = image.width;
  s.height = image.height;
  double sum = 0.0, sum2 = 0.0;
  std::size_t ink = 0;
  for (std::size_t i = 0; i < image.pixels(); ++i) {
    const double g = (image.rgb[3 * i] + image.rgb[3 * i + 1] + image.rgb[3 * i + 2]) / 3.0;
    sum += g;
    sum2 += g * g;
    ink += g < 200.0 ? 1 : 0;
  }
  const double n = static_cast<double>(image.pixels());
  s.variance = sum2 / n - (sum / n) * (sum / n);
  s.ink_fraction = static_cast<double>(ink) / n;
  return s;
}

// Text that runs `touch PWNEDk` if any part of it reaches gnuplot as a command: newlines, both
// quotes, a backtick, $(), a trailing backslash and `system` (issue 16, item 3).
inline std::string injection_text() {
  return "x\nsystem \"touch PWNED1\"\n'\nsystem 'touch PWNED2'\n`touch PWNED3`$(touch PWNED4)"
         "\"; system \"touch PWNED5\"; \"\\\nsystem \"touch PWNED6\"";
}

// Files under @p dir whose name starts with PWNED (what `touch` would have made).
inline std::vector<std::filesystem::path> pwned_files(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> found;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
    if (entry.path().filename().string().rfind("PWNED", 0) == 0)  // the folders hold the word
      found.push_back(entry.path());
  return found;
}

inline void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

}  // namespace mjarm::test
