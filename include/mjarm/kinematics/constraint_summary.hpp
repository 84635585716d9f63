#pragma once
/// @file
/// What MuJoCo's constraint solver had to do in one step, in a few numbers: how many constraint
/// rows of each kind, how many were active, the largest force, and how the solver ended.

#include <mujoco/mujoco.h>

#include "mjarm/fields.hpp"

namespace mjarm {

/// The constraint rows of an `mjData` (after mj_forward or a step), by kind.
struct ConstraintSummary {
  int rows = 0;                     ///< nefc
  int equality = 0;                 ///< equality rows (welds, connects, joint couplings)
  int friction = 0;                 ///< dof and tendon friction-loss rows
  int limit = 0;                    ///< joint and tendon limit rows
  int contact = 0;                  ///< contact rows (each contact has 1 to 6 or a pyramid's edges)
  int contacts = 0;                 ///< contacts (ncon)
  int active = 0;                   ///< rows whose state is not "satisfied" (they push or hold)
  double max_force = 0.0;           ///< largest |efc_force| [N or N·m]
  int islands = 0;                  ///< constraint islands
  int solver_iterations = 0;        ///< iterations of the solver, summed over the islands
  double solver_improvement = 0.0;  ///< the last iteration's cost reduction (island 0)
  double solver_gradient = 0.0;     ///< the last iteration's gradient norm (island 0)
};

constexpr auto declared_fields(const ConstraintSummary*) {
  using S = ConstraintSummary;
  return declare<S>(
      "constraints", field("rows", &S::rows, "", "constraint rows (nefc)"),
      field("equality", &S::equality, "", "equality rows"),
      field("friction", &S::friction, "", "dof and tendon friction-loss rows"),
      field("limit", &S::limit, "", "joint and tendon limit rows"),
      field("contact", &S::contact, "", "contact rows"),
      field("contacts", &S::contacts, "", "contacts (ncon)"),
      field("active", &S::active, "", "rows not satisfied: they push or hold"),
      field("max_force", &S::max_force, "N or N·m", "largest |efc_force|"),
      field("islands", &S::islands, "", "constraint islands"),
      field("solver_iterations", &S::solver_iterations, "", "summed over the islands"),
      field("solver_improvement", &S::solver_improvement, "",
            "the last iteration's cost reduction (island 0)"),
      field("solver_gradient", &S::solver_gradient, "",
            "the last iteration's gradient norm (island 0)"));
}

/// The summary of @p d's constraint rows. Allocates nothing.
ConstraintSummary constraint_summary(const mjData& d) noexcept;

}  // namespace mjarm
