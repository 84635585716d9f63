#include "figure_series.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "mjarm/error.hpp"

namespace mjarm::detail {

FigureSeries::FigureSeries(int lines, double seconds, int points)
    : lines_(lines), seconds_(seconds), points_(points) {
  if (lines < 1 || lines > mjMAXLINE || points < 2 || points > mjMAXLINEPNT || !(seconds > 0.0) ||
      !std::isfinite(seconds)) {
    throw Error("figure: 1…" + std::to_string(mjMAXLINE) + " lines, 2…" +
                std::to_string(mjMAXLINEPNT) + " points and a positive span, got " +
                std::to_string(lines) + " lines, " + std::to_string(points) + " points, " +
                std::to_string(seconds) + " s");
  }
  times_.resize(static_cast<std::size_t>(points));
  values_.resize(static_cast<std::size_t>(points) * static_cast<std::size_t>(lines));
}

double FigureSeries::last_time() const noexcept {
  if (count_ == 0) return std::numeric_limits<double>::quiet_NaN();
  return times_[static_cast<std::size_t>((start_ + count_ - 1) % points_)];
}

void FigureSeries::clear() noexcept {
  start_ = 0;
  count_ = 0;
}

bool FigureSeries::add(double t, std::span<const float> values) {
  if (!std::isfinite(t)) return false;
  if (count_ > 0) {
    const double last = last_time();
    if (t < last)
      clear();  // the loop went back in time: a new run
    else if (t - last < (1.0 - 1e-9) * seconds_ / points_)
      return false;  // (rounding of t)
  }
  int slot = (start_ + count_) % points_;
  if (count_ == points_) {
    start_ = (start_ + 1) % points_;  // the oldest point falls out
  } else {
    ++count_;
  }
  times_[static_cast<std::size_t>(slot)] = t;
  float* row = values_.data() + static_cast<std::size_t>(slot) * static_cast<std::size_t>(lines_);
  for (int i = 0; i < lines_; ++i)
    row[i] = i < static_cast<int>(values.size()) ? values[static_cast<std::size_t>(i)] : 0.0f;
  return true;
}

void FigureSeries::fill(mjvFigure& figure, std::span<const std::string> names) const {
  const int shown = std::min(lines_, static_cast<int>(names.size()));
  const double newest = last_time();
  for (int i = 0; i < mjMAXLINE; ++i) figure.linepnt[i] = 0;
  for (int i = 0; i < shown; ++i) {
    std::strncpy(figure.linename[i], names[static_cast<std::size_t>(i)].c_str(),
                 sizeof(figure.linename[i]) - 1);
    figure.linename[i][sizeof(figure.linename[i]) - 1] = '\0';
    int n = 0;
    for (int k = 0; k < count_; ++k) {
      const int slot = (start_ + k) % points_;
      const double age = times_[static_cast<std::size_t>(slot)] - newest;
      if (age < -seconds_) continue;
      figure.linedata[i][2 * n] = static_cast<float>(age);
      figure.linedata[i][2 * n + 1] =
          values_[static_cast<std::size_t>(slot) * static_cast<std::size_t>(lines_) +
                  static_cast<std::size_t>(i)];
      ++n;
    }
    figure.linepnt[i] = n;
  }
  figure.range[0][0] = static_cast<float>(-seconds_);
  figure.range[0][1] = 0.0f;
}

}  // namespace mjarm::detail
