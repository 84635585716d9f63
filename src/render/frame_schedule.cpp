#include "mjarm/render/frame_schedule.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

FrameSchedule::FrameSchedule(double fps, double start_time) : fps_(fps), start_(start_time) {
  if (!std::isfinite(fps) || !(fps > 0.0))
    throw Error("video frame rate must be a finite number > 0 frames/s, got " +
                number_text(fps));
  if (!std::isfinite(start_time))
    throw Error("frame schedule start time must be finite, got " + number_text(start_time));
}

int FrameSchedule::frames_due(double time) noexcept {
  constexpr double kSlack = 1e-9;  // [s]
  if (!std::isfinite(time) || time + kSlack < start_) return 0;
  // frames 0 … reached are due by now; computed from the index, so no drift accumulates
  const double reached = std::floor((time + kSlack - start_) * fps_);
  if (!(reached < static_cast<double>(std::numeric_limits<std::int64_t>::max() / 2))) return 0;
  const std::int64_t total = static_cast<std::int64_t>(reached) + 1;
  const std::int64_t due = total - frames_;
  if (due <= 0) return 0;
  const int count = due > std::numeric_limits<int>::max() ? std::numeric_limits<int>::max()
                                                          : static_cast<int>(due);
  frames_ += count;
  return count;
}

double FrameSchedule::next_time() const noexcept {
  return start_ + static_cast<double>(frames_) / fps_;
}

}  // namespace mjarm
