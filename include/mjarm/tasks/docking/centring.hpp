#pragma once
/// @file
/// Centring in the bore (`BoreCentring`, `DockingCentringOptions`): once the peg is down in the
/// bore, a slow lateral probe finds the wall and the reference moves to the axis one clearance
/// from it. docs/docking.md "Centring in the bore".

#include <Eigen/Core>

#include "mjarm/fields.hpp"

namespace mjarm {

/// A released peg stays laterally where the chamfer hands it to the bore, touching a wall: the
/// one on the side it slid from, or, carried across by its speed, the opposite one (6 mm
/// offsets). Either way its centre is one radial clearance c from the axis, within tens of
/// micrometres of the lateral criterion. Its excursion d = (I − u·uᵀ)·(p_tip − p_ref) from the
/// reference shows that a contact moved it and along which line the axis lies, not on which side.
/// So, once the tip is `start_depth` below the believed top face (past the chamfer's foot), the
/// peg at rest sideways (‖ḋ‖ ≤ `settle_speed`: one that crosses the bore is still moving there)
/// and ‖d‖ ≥ `min_excursion`, the lateral release is disarmed and the reference, starting on the
/// tip, probes along d/‖d‖ at `probe_speed`: the wall ahead stops the peg, the reference runs ahead
/// of it, and a lag of `contact_lag` (the lateral spring then pressing with K·lag, a fraction of a
/// newton) marks the wall. The reference then moves over `duration` (smoothstep) to one clearance
/// back from the tip there: the axis believed from the contact. A probe that travels
/// `probe_travel` without a wall moves back to where it started. The release is armed again at
/// the hold (the bottom's preload then releases it as before). A peg that met nothing is not
/// moved.
struct DockingCentringOptions {
  bool enabled = true;
  double start_depth = 0.015;    ///< the tip below the believed top face [m]
  double min_excursion = 1e-4;   ///< lateral excursion that shows a contact moved the peg [m]
  double settle_speed = 0.001;   ///< the tip's lateral speed below which it is at rest [m/s]
  double latest_depth = 0.035;   ///< no centring starts deeper (time left for it) [m]
  double probe_speed = 0.002;    ///< lateral speed of the probe [m/s]
  double probe_ramp = 0.25;      ///< the probe's speed ramps in over this [s]
  double contact_lag = 2.5e-4;   ///< the reference ahead of the tip that marks the wall [m]
  double probe_travel = 0.0015;  ///< the longest probe (≥ two clearances) [m]
  double duration = 0.3;         ///< the move to the axis [s]
};

constexpr auto declared_fields(const DockingCentringOptions*) {
  using S = DockingCentringOptions;
  return declare<S>(
      "docking centring",
      field("enabled", &S::enabled, "centre the peg in the bore by a lateral probe"),
      field("start_depth", &S::start_depth, "m", Range::positive(),
            "the tip below the believed top face when the centring starts (past the chamfer)"),
      field("min_excursion", &S::min_excursion, "m", Range::positive(),
            "lateral excursion from the reference that shows a contact moved the peg"),
      field("settle_speed", &S::settle_speed, "m/s", Range::positive(),
            "the tip's lateral speed below which the peg is at rest sideways"),
      field("latest_depth", &S::latest_depth, "m", Range::positive(),
            "no centring starts deeper than this below the believed top face"),
      field("probe_speed", &S::probe_speed, "m/s", Range::positive(),
            "lateral speed of the probe for the wall"),
      field("probe_ramp", &S::probe_ramp, "s", Range::positive(),
            "the probe's speed ramps in over this (smoothstep)"),
      field("contact_lag", &S::contact_lag, "m", Range::positive(),
            "the reference ahead of the tip that marks the wall"),
      field("probe_travel", &S::probe_travel, "m", Range::positive(),
            "the longest probe (at least two radial clearances)"),
      field("duration", &S::duration, "s", Range::positive(), "the move to the believed axis"));
}

/// The centring's lateral shift of the reference, one insertion at a time. Positions are
/// relative to the uncentred reference p_ref; all lateral (in the believed socket's plane).
class BoreCentring {
 public:
  /// @param clearance c, the radial clearance at a bore face [m]
  BoreCentring(const DockingCentringOptions& options, double clearance) noexcept
      : options_(options), clearance_(clearance) {}

  /// Forgets the last centring (a new insertion).
  void reset() noexcept;
  /// At @p depth below the believed top face (tip @p p_tip, reference @p p_ref, insertion
  /// direction @p u, time @p t), every tick of the insertion: starts the probe once, between
  /// `start_depth` and `latest_depth` with the tip at rest sideways. True on the tick the probe
  /// starts (the caller then disarms the release).
  bool decide(double depth, const Eigen::Vector3d& p_tip, const Eigen::Vector3d& p_ref,
              const Eigen::Vector3d& u, double t) noexcept;
  /// Every tick after the start: watches the probe for the wall (or its end) and starts the move.
  void update(const Eigen::Vector3d& p_tip, const Eigen::Vector3d& p_ref, double t) noexcept;
  /// True once a centring has started in this insertion.
  bool active() const noexcept { return stage_ != Stage::idle; }
  /// True once the probe met the wall.
  bool found_wall() const noexcept { return found_; }
  /// The lateral shift of the reference at @p t [m] and its rate [m/s] (zero when not active).
  Eigen::Vector3d shift(double t) const noexcept;
  Eigen::Vector3d shift_rate(double t) const noexcept;
  /// The lateral excursion d when the centring started [m] (zero: none).
  const Eigen::Vector3d& excursion() const noexcept { return from_; }
  /// How far the probe has gone at @p t [m] and its speed [m/s].
  double probe_travel(double t) const noexcept;
  double probe_speed(double t) const noexcept;
  /// The shift it moves to: the axis believed from the wall (or back to the start) [m].
  const Eigen::Vector3d& target() const noexcept { return target_; }

 private:
  enum class Stage { idle, probing, moving };
  DockingCentringOptions options_;
  double clearance_;
  Eigen::Vector3d u_ = Eigen::Vector3d::UnitZ();
  bool decided_ = false;
  double last_t_ = -1.0;                              // the previous tick [s] (< 0: none)
  Eigen::Vector3d last_d_ = Eigen::Vector3d::Zero();  // d at the previous tick
  bool found_ = false;
  Stage stage_ = Stage::idle;
  double start_ = 0.0;                                   // the probe's start [s]
  double move_start_ = 0.0;                              // the move's start [s]
  Eigen::Vector3d from_ = Eigen::Vector3d::Zero();       // d, where the probe starts
  Eigen::Vector3d direction_ = Eigen::Vector3d::Zero();  // d/‖d‖
  Eigen::Vector3d move_from_ = Eigen::Vector3d::Zero();  // the probe's end
  Eigen::Vector3d target_ = Eigen::Vector3d::Zero();
};

}  // namespace mjarm
