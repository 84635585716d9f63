#include "mjarm/control/task_error.hpp"

#include "mjarm/lie/so3.hpp"

namespace mjarm {

Vector6d task_error(const Pose& X_WE, const Pose& X_WD) noexcept {
  Vector6d e;
  e.head<3>() = X_WD.p - X_WE.p;
  e.tail<3>() = so3::log(X_WD.R * X_WE.R.transpose());
  return e;
}

}  // namespace mjarm
