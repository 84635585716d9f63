#pragma once
/// @file
/// `run_docking_grid`: the docking run over a matrix of believed-socket offsets (by default the
/// issue's 27: X, Y ∈ {−6, 0, 6} mm × yaw ∈ {−15, 0, 15}°), in parallel threads sharing one
/// compiled scene, with progress reports and a clean stop on Ctrl-C. docs/docking.md.

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "mjarm/tasks/docking/docking.hpp"

namespace mjarm {

/// The matrix and how to run it.
struct DockingGridOptions {
  /// Everything but the offset (law, force source, friction, motion, criteria, gains). Its
  /// scene, when set, is shared by every run; its record and video must be empty.
  DockingOptions base;
  std::vector<double> x{-0.006, 0.0, 0.006};  ///< dx values [m]
  std::vector<double> y{-0.006, 0.0, 0.006};  ///< dy values [m]
  std::vector<double> yaw{-15.0 * 3.14159265358979323846 / 180.0, 0.0,
                          15.0 * 3.14159265358979323846 / 180.0};  ///< dyaw values [rad]
  int jobs = 0;  ///< worker threads (≥ 0; 0: one per hardware thread, at most the run count)
  /// An explicit list of offsets (the capture map's polar grid); when not empty, x, y and yaw
  /// are ignored.
  std::vector<DockingOffset> offsets;
};

/// One run of the matrix.
struct DockingGridRun {
  DockingOffset offset;
  DockingOutcome outcome = DockingOutcome::not_seated;
  DockingMetrics metrics;
  std::string message;  ///< the run's own account (RunResult::message)
  int searches = 0;     ///< misses detected
  double search_time = 0.0;  ///< time spent searching [s]
  double seat_time = 0.0;    ///< first time at the bottom [s] (NaN: never)
};

/// The matrix's outcome.
struct DockingGridResult {
  std::string controller;  ///< "cic", "hqp-ac", "se3"
  ForceSource source = ForceSource::sensor;
  bool joint_friction = false;
  int planned = 0;           ///< runs in the matrix
  bool interrupted = false;  ///< Ctrl-C/SIGTERM: `runs` holds the runs that completed
  /// The completed runs, in matrix order (x slowest, then y, then yaw; or the list's order).
  std::vector<DockingGridRun> runs;
  // summary of the completed runs
  int seated = 0;
  double max_peak_force = 0.0;         ///< [N]
  double max_peak_axial_force = 0.0;   ///< [N]
  double max_peak_axial_moment = 0.0;  ///< [N·m]
  double max_lateral = 0.0;            ///< worst final-window lateral error [m]
  double max_tilt = 0.0;               ///< [rad]
  double min_steady_axial_force = 0.0, max_steady_axial_force = 0.0;  ///< [N]
  double max_position_rms = 0.0;                                      ///< [m]
  double max_orientation_rms = 0.0;                                   ///< [rad]
  std::map<std::string, int> failures;  ///< reason → runs that failed on it
};

/// Called from the calling thread as runs complete: (done, planned).
using DockingGridProgress = std::function<void(int done, int planned)>;

/// Runs the matrix in `jobs` threads (the scene compiled once and shared: its model is
/// immutable, each run owns its simulation data). An interrupt (mjarm/interrupt.hpp) stops every
/// running simulation at its next tick; the runs it cut short are not counted.
/// @throws Error for bad options (an empty or non-finite axis, jobs < 0, a record or video path
///         in the base options, or what `run_docking` refuses — raised before any run when the
///         first offset's plan fails, else the first error of a worker after all stopped).
DockingGridResult run_docking_grid(const DockingGridOptions& options,
                                   const DockingGridProgress& progress = {});

}  // namespace mjarm
