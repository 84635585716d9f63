#pragma once
/// @file
/// The compliant docking as a scenario (`run_docking`, docs/docking.md): its parameters,
/// declared.

#include "mjarm/fields.hpp"
#include "mjarm/scenarios/declared_scenario.hpp"
#include "mjarm/tasks/docking/docking.hpp"

namespace mjarm {

/// What a docking can be run with; the defaults are `DockingOptions`'. It draws nothing: the
/// same parameters give the same run.
struct DockingParameters {
  DockingControllerOptions controller = DockingOptions{}.controller;
  DockingOffset offset = DockingOptions{}.offset;
  DockingMotion motion = DockingOptions{}.motion;
  DockingCriteria criteria = DockingOptions{}.criteria;
  bool joint_friction = DockingOptions{}.joint_friction;
  DockingGeometry geometry = DockingOptions{}.geometry;
  double max_acceleration = DockingOptions{}.max_acceleration;
};

constexpr auto declared_fields(const DockingParameters*) {
  using S = DockingParameters;
  return declare<S>(
      "docking", field("controller", &S::controller, "the law, its force source and gains"),
      field("offset", &S::offset, "the error of the believed socket pose"),
      field("motion", &S::motion, "reference shape and timing, preload"),
      field("criteria", &S::criteria, "when the peg counts as seated"),
      field("joint_friction", &S::joint_friction, "the variant with Franka joint friction"),
      field("geometry", &S::geometry, "the peg and the socket: sizes, friction, collision"),
      field("max_acceleration", &S::max_acceleration, "rad/s²", Range::positive(),
            "divergence bound on |joint acceleration|"));
}

/// The docking's options for @p p (no recording, no video, no samples kept).
DockingOptions docking_options(const DockingParameters& p);
/// Sets the fields of @p options that @p p covers; the others (scene, recording, video,
/// samples) are kept.
void apply(const DockingParameters& p, DockingOptions& options);
/// The parameters @p options stand for.
DockingParameters docking_parameters(const DockingOptions& options);

/// The docking of the registry.
const DeclaredScenario<DockingParameters>& docking_scenario();

}  // namespace mjarm
