#pragma once
/// @file
/// `RobotContacts`: which of MuJoCo's contacts count as the robot touching something — a contact
/// with a geom moved by the chain, between two geoms whose pair is not allowed to touch. Shared
/// by the configuration checks and the sampling-based planner's validity checker, so that both
/// judge a state alike.

#include <mujoco/mujoco.h>

#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/model/chain.hpp"

namespace mjarm {

/// The deepest counted contact of a state.
struct RobotContact {
  int geom1 = -1;  ///< a geom of the robot (−1: no contact counted)
  int geom2 = -1;  ///< the geom it touches
  double distance = std::numeric_limits<double>::infinity();  ///< signed distance [m]
  bool found() const noexcept { return geom1 >= 0; }
};

/// The contact filter of one chain. "The robot" is every geom on a body moved by a chain joint;
/// MuJoCo's own filters (contype/conaffinity, its parent–child exclusion, which lets adjacent
/// links touch) apply before this one. Allowed pairs are symmetric.
class RobotContacts {
 public:
  explicit RobotContacts(const Chain& chain);

  /// Lets geoms @p geom1 and @p geom2 touch (ids; out-of-range ids are ignored).
  void allow(int geom1, int geom2);
  /// Lets @p first and @p second touch: each the name of a geom, of a body (every geom of the
  /// body), or of both (models often name a link's body and its main geom alike).
  /// @throws Error naming the name that is neither, with the closest geom and body names.
  void allow(std::string_view first, std::string_view second);

  /// True when geom @p geom is on a body the chain moves.
  bool moving(int geom) const noexcept { return moving_[geom] != 0; }
  /// True when a contact between the two geoms counts.
  bool counts(int geom1, int geom2) const noexcept;
  /// The deepest contact of @p data (after MuJoCo's collision detection) that counts and is
  /// closer than @p margin [m]. Allocates nothing.
  RobotContact deepest(const mjData& data, double margin) const noexcept;

  /// "geom 'link3_c'" (or "geom #12" when unnamed).
  std::string geom_name(int geom) const;

 private:
  Robot robot_;  // keeps the model alive
  int ngeom_;
  std::vector<char> moving_;   // per geom
  std::vector<char> allowed_;  // ngeom × ngeom, symmetric
};

}  // namespace mjarm
