#pragma once
// `FigureSeries` (private to src/teleop): the last seconds of a few lines of samples, thinned to
// a fixed number of points, and laid into a MuJoCo figure (`mjvFigure`) with x as time before
// the newest sample. The passive viewer's figures (contact force, actuator forces, the loop's
// plots) are three of them.

#include <mujoco/mujoco.h>

#include <span>
#include <string>
#include <vector>

namespace mjarm::detail {

class FigureSeries {
 public:
  /// Up to @p lines lines (≤ mjMAXLINE) over the last @p seconds (> 0) of time, at most
  /// @p points (≤ mjMAXLINEPNT) points per line.
  FigureSeries(int lines, double seconds, int points = 500);

  /// Adds the values at time @p t (one per line; missing lines keep no point). A sample closer
  /// than seconds / points to the previous kept one is skipped; a time before it starts the
  /// series again (a reset of the loop). Returns whether the sample was kept. Allocation-free.
  bool add(double t, std::span<const float> values);
  void clear() noexcept;

  int size() const noexcept { return count_; }
  /// The newest kept time (NaN when empty).
  double last_time() const noexcept;

  /// Writes the lines into @p figure: x = t − newest time ∈ [−seconds, 0], y the values, the
  /// x range fixed to the span; line names from @p names (as many lines as names).
  void fill(mjvFigure& figure, std::span<const std::string> names) const;

 private:
  int lines_;
  double seconds_;
  int points_;
  std::vector<double> times_;  // ring of points_ times
  std::vector<float> values_;  // ring of points_ × lines_ values
  int start_ = 0;              // oldest sample
  int count_ = 0;
};

}  // namespace mjarm::detail
