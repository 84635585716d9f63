#include "mjarm/tasks/arm_reach.hpp"

#include <algorithm>
#include <limits>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/kinematics/workspace.hpp"
#include "mjarm/random.hpp"

namespace mjarm {

ArmReach arm_reach(const Chain& chain, int samples, std::uint64_t seed) {
  if (samples < 1)
    throw Error("arm_reach: samples must be ≥ 1, got " + std::to_string(samples));
  ChainKinematics kin(chain);
  ArmReach reach;
  kin.update(chain.center());
  // the most proximal joint that moves the frame
  for (int i = 0; i < chain.size(); ++i) {
    if (kin.moves_frame(i)) {
      reach.p_WS = kin.anchor(i);
      break;
    }
  }
  JointSampler sampler(chain);
  Random rng(seed);
  Eigen::VectorXd q(chain.size());
  reach.min_distance = std::numeric_limits<double>::infinity();
  for (int k = 0; k < samples; ++k) {
    sampler.sample(rng, q);
    const double d = (kin.update(q).p - reach.p_WS).norm();
    reach.min_distance = std::min(reach.min_distance, d);
    reach.max_distance = std::max(reach.max_distance, d);
  }
  reach.samples = samples;
  return reach;
}

}  // namespace mjarm
