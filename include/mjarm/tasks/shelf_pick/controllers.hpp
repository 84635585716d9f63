#pragma once
/// @file
/// The controllers of the shelf pick, built with the gains tuned for each robot (the figures in
/// docs/tasks.md were measured with exactly these).

#include <memory>
#include <string_view>

#include "mjarm/control/controller.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/tasks/shelf_pick/plan.hpp"

namespace mjarm {

/// Builds the shelf-pick controller called @p name ("ct", "osc", "task-pd", "accel") for
/// @p chain on @p robot: a position task on planar2, a pose task on the panda, torque commands.
/// @p gain_scale s multiplies the tuned tracking stiffness by s and its damping by √s (the
/// damping ratio kept; the null-space posture gains stay). The controller keeps a copy of
/// @p chain.
/// @throws Error for an unknown name (listing the choices) or a scale not positive and finite.
std::unique_ptr<Controller> make_shelf_pick_controller(std::string_view name, const Chain& chain,
                                                       const ShelfPickRobot& robot,
                                                       double gain_scale = 1.0);

}  // namespace mjarm
