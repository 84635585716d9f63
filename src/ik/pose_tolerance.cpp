#include "mjarm/ik/pose_tolerance.hpp"

#include <cmath>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/lie/so3.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

Vector6d target_frame_error(const Pose& X_WE, const Pose& X_WT) noexcept {
  Vector6d e_T;
  e_T.head<3>().noalias() = X_WT.R.transpose() * (X_WE.p - X_WT.p);
  e_T.tail<3>() = so3::log(X_WT.R.transpose() * X_WE.R);
  return e_T;
}

bool within_tolerance(const Vector6d& e_T, const PoseTolerance& tolerance) noexcept {
  // written as "all ≤" so that a NaN component fails the test
  for (int i = 0; i < 6; ++i) {
    if (!(std::abs(e_T[i]) <= tolerance.bound[i])) return false;
  }
  return true;
}

void check_tolerance(const PoseTolerance& tolerance) {
  static const char* const kNames[6] = {"x", "y", "z", "roll", "pitch", "yaw"};
  for (int i = 0; i < 6; ++i) {
    const double b = tolerance.bound[i];
    if (!std::isfinite(b) || b <= 0.0) {
      throw Error(std::string("pose tolerance on ") + kNames[i] +
                  " must be finite and positive, got " + number_text(b));
    }
  }
}

}  // namespace mjarm
