#pragma once
/// @file
/// The collision hook of the local IK solvers: geoms that must not touch, checked on an owned
/// scratch `mjData` (never the caller's) with `mj_kinematics` followed by MuJoCo's
/// `mj_geomDistance` for explicit pairs and `mj_collision` for "geom against anything".

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"

namespace mjarm {

/// Which geoms must stay apart during a solve, and what a solver does when a step breaks that.
/// A step that puts a watched geom in contact is rolled back and halved, `max_halvings` times;
/// then the solve stops with `IkStatus::not_converged` at the last contact-free iterate.
struct CollisionSpec {
  /// Geom pairs (names) that must not touch each other. Checked directly, whatever the model's
  /// contype/conaffinity/exclude filters say.
  std::vector<std::pair<std::string, std::string>> pairs;
  /// Geoms (names) that must not touch any other geom. Candidates come from `mj_collision`, so
  /// the model's filters apply and detection reaches only as far as the model's geom margins.
  std::vector<std::string> geoms;
  /// Two geoms are in contact when their signed distance is below this [m] (≥ 0).
  double margin = 0.0;
  /// Halvings of a rejected step before the solve stops (≥ 0).
  int max_halvings = 4;

  /// True when nothing is watched (the hook is off).
  bool empty() const noexcept { return pairs.empty() && geoms.empty(); }
};

constexpr auto declared_fields(const CollisionSpec*) {
  using S = CollisionSpec;
  return declare<S>("collision",
                    field("pairs", &S::pairs, "geom name pairs that must not touch each other"),
                    field("geoms", &S::geoms, "geoms (names) that must not touch any other geom"),
                    field("margin", &S::margin, "m", Range::non_negative(),
                          "geoms closer than this are in contact"),
                    field("max_halvings", &S::max_halvings, "", Range::at_least(0),
                          "halvings of a step that touches before the solve stops"));
}

/// Contact checks of a chain's configurations against a `CollisionSpec`, on its own scratch
/// `mjData`. Joints outside the chain hold the configuration given by `set_fixed_qpos` (the
/// model's qpos0 by default). `in_contact` allocates nothing.
class CollisionGuard {
 public:
  /// Resolves the geom names.
  /// @throws Error naming an unknown geom (with close names), a pair of a geom with itself, a
  /// negative or non-finite margin, or negative max_halvings.
  CollisionGuard(const Chain& chain, const CollisionSpec& spec);

  const CollisionSpec& spec() const noexcept { return spec_; }

  /// Sets the joints that are not in the chain (full qpos, nq entries).
  /// @throws Error when the size is not nq or a value is not finite.
  void set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos);

  /// True when, at chain configuration @p q (n, unchecked), a watched pair or a watched geom is
  /// in contact (signed distance < margin).
  bool in_contact(const Eigen::Ref<const Eigen::VectorXd>& q) noexcept;

  /// The watched contacts at @p q as text ("geom 'a' – geom 'b' (distance -0.003 m)"), empty
  /// when there are none. Allocates; meant for messages.
  std::string describe_contacts(const Eigen::Ref<const Eigen::VectorXd>& q);

 private:
  /// Signed distance of the closest contact of geoms g1, g2 below the margin, or +inf.
  double pair_distance(int g1, int g2) noexcept;
  void place(const Eigen::Ref<const Eigen::VectorXd>& q) noexcept;

  Chain chain_;
  CollisionSpec spec_;
  std::vector<std::pair<int, int>> pair_ids_;
  std::vector<char> watched_;  // per geom: must not touch anything
  bool any_watched_ = false;
  DataPtr data_;
  Eigen::VectorXd fixed_qpos_;
};

}  // namespace mjarm
