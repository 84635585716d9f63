#include "mjarm/kinematics/constraint_summary.hpp"

#include <algorithm>
#include <cmath>

namespace mjarm {

ConstraintSummary constraint_summary(const mjData& d) noexcept {
  ConstraintSummary s;
  s.rows = d.nefc;
  s.contacts = d.ncon;
  s.islands = d.nisland;
  for (int i = 0; i < d.nefc; ++i) {
    switch (d.efc_type[i]) {
      case mjCNSTR_EQUALITY:
        ++s.equality;
        break;
      case mjCNSTR_FRICTION_DOF:
      case mjCNSTR_FRICTION_TENDON:
        ++s.friction;
        break;
      case mjCNSTR_LIMIT_JOINT:
      case mjCNSTR_LIMIT_TENDON:
        ++s.limit;
        break;
      default:
        ++s.contact;
    }
    if (d.efc_state[i] != mjCNSTRSTATE_SATISFIED) ++s.active;
    s.max_force = std::max(s.max_force, std::abs(d.efc_force[i]));
  }
  // islands off (or none found): the solver's statistics sit in slot 0
  const int islands = std::max(1, std::min(d.nisland, mjNISLAND));
  for (int k = 0; k < islands; ++k) s.solver_iterations += d.solver_niter[k];
  const int last = std::min(d.solver_niter[0], mjNSOLVER) - 1;
  if (last >= 0) {
    s.solver_improvement = d.solver[last].improvement;
    s.solver_gradient = d.solver[last].gradient;
  }
  return s;
}

}  // namespace mjarm
