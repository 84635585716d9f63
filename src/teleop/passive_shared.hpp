#pragma once
// What the user's loop and the passive viewer's window thread share (private to src/teleop):
// everything behind one mutex, held by `sync` for a copy and by the window thread for a swap.

#include <mujoco/mujoco.h>

#include <array>
#include <atomic>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "mjarm/model/robot.hpp"
#include "mjarm/teleop/passive_viewer.hpp"
#include "mjarm/teleop/viewer.hpp"
#include "viewer_driver.hpp"

namespace mjarm::detail {

/// Lines a figure of the passive viewer draws at most (actuators, the loop's plots).
inline constexpr int kPassiveFigureLines = 8;

/// The figures' values at one sync.
struct FigureSample {
  double time = 0.0;                                  ///< simulated time [s]
  float contact = 0.0f;                               ///< total normal contact force [N]
  int contacts = 0;                                   ///< contacts (ncon)
  std::array<float, kPassiveFigureLines> actuator{};  ///< force / limit [%]
  std::array<float, kPassiveFigureLines> plots{};     ///< the loop's plot lines
};

/// An actuator the figure shows: its force (`actuator_force`, before the gear) against its limit
/// (`forcerange`, or for a motor the control range times the gain).
struct LimitedActuator {
  int id = 0;
  double limit = 0.0;  ///< [N or N·m], > 0
};

/// The first `kPassiveFigureLines` actuators of @p m with a force limit.
std::vector<LimitedActuator> limited_actuators(const mjModel& m);

/// The figures' values of @p d: time, total normal contact force, each of @p actuators' force
/// in percent of its limit, and @p plots.
FigureSample figure_sample(const mjModel& m, const mjData& d,
                           const std::vector<LimitedActuator>& actuators,
                           const std::array<double, kPassiveFigureLines>& plots);

struct PassiveShared {
  PassiveShared(const Robot& robot, const PassiveViewerOptions& options);

  const Robot robot;
  const PassiveViewerOptions options;
  const std::vector<LimitedActuator> actuators;
  std::mutex mutex;
  // guarded by mutex ↓
  DataPtr incoming;                   // the newest synced state
  bool fresh = false;                 // incoming holds a state the window has not taken yet
  std::vector<mjvGeom> markers;       // the markers synced with it
  std::vector<FigureSample> samples;  // ring of samples not taken yet
  std::size_t sample_start = 0, sample_count = 0;
  std::vector<std::string> plot_names;  // the loop's plot lines, in order of first use
  mjvPerturb pert{};                    // the window's selection and drag
  int applied_body = 0;        // the body whose xfrc_applied row the last sync wrote (0: none)
  std::exception_ptr failure;  // the window thread's error, raised once by sync or close
  ViewerReport report;         // written when the window thread ends
  std::int64_t syncs = 0;
  // ↑
  std::atomic<bool> running{false};
  std::atomic<bool> close_requested{false};

  void push(const FigureSample& sample);
};

/// The driver of the passive viewer's window (passive_driver.cpp).
std::unique_ptr<ViewerDriver> make_passive_driver(std::shared_ptr<PassiveShared> shared);

}  // namespace mjarm::detail
