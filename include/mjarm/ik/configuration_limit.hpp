#pragma once
/// @file
/// Joint limits with a margin for the differential-IK QP: every joint keeps `margin` from its
/// limits, approaching that inner limit no faster than `gain` times the remaining gap per step:
///
///     gain·(lower + margin − q)/dt ≤ v ≤ gain·(upper − margin − q)/dt.
///
/// A box tightening (no general rows): `DiffIk` keeps its box QP with it alone.

#include <Eigen/Core>

#include "mjarm/fields.hpp"
#include "mjarm/ik/diff_ik_constraint.hpp"
#include "mjarm/model/chain.hpp"

namespace mjarm {

/// How far from its limits each joint stays, and how fast it may close in.
struct ConfigurationLimitOptions {
  double margin = 0.0;  ///< kept from each limit [rad or m] (≥ 0, < half of every range)
  double gain = 0.5;    ///< fraction of the remaining gap one step may close, (0, 1]
};

constexpr auto declared_fields(const ConfigurationLimitOptions*) {
  using S = ConfigurationLimitOptions;
  return declare<S>(
      "configuration limit",
      field("margin", &S::margin, "rad or m", Range::non_negative(), "kept from each joint limit"),
      field("gain", &S::gain, "", Range::open_closed(0.0, 1.0),
            "fraction of the remaining gap one step may close"));
}

/// The margin box of a chain's differential IK (see the file comment). Starting inside the
/// margin, a joint is pushed back out as fast as the caller's hard box allows.
class ConfigurationLimit final : public DiffIkConstraint {
 public:
  /// @throws Error for an invalid option or a joint whose range is not wider than 2·margin
  /// (naming the joint).
  ConfigurationLimit(const Chain& chain, const ConfigurationLimitOptions& options);

  const ConfigurationLimitOptions& options() const noexcept { return options_; }

  int variables() const noexcept override { return static_cast<int>(lower_.size()); }
  int max_rows() const noexcept override { return 0; }
  int rows(const Eigen::Ref<const Eigen::VectorXd>& q, double dt, Eigen::Ref<Eigen::MatrixXd> C,
           Eigen::Ref<Eigen::VectorXd> b) noexcept override;
  void tighten_box(const Eigen::Ref<const Eigen::VectorXd>& q, double dt,
                   Eigen::Ref<Eigen::VectorXd> lo,
                   Eigen::Ref<Eigen::VectorXd> hi) const noexcept override;

 private:
  ConfigurationLimitOptions options_;
  Eigen::VectorXd lower_, upper_;  // the limits moved in by the margin
};

}  // namespace mjarm
