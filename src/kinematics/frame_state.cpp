#include "mjarm/kinematics/frame_state.hpp"

#include <string>
#include <vector>

#include "mjarm/error.hpp"

namespace mjarm {

Pose frame_pose(const mjModel& m, const mjData& d, const FrameRef& frame) {
  const bool site = frame.kind == FrameKind::site;
  const int count = site ? m.nsite : m.nbody;
  if (frame.id < 0 || frame.id >= count) {
    throw Error(std::string(site ? "site" : "body") + " id " + std::to_string(frame.id) + " ('" +
                frame.name + "') is out of range: the model has " + std::to_string(count) +
                (site ? " sites" : " bodies"));
  }
  const double* pos = site ? d.site_xpos + 3 * frame.id : d.xpos + 3 * frame.id;
  const double* mat = site ? d.site_xmat + 9 * frame.id : d.xmat + 9 * frame.id;
  Pose X_WF;
  X_WF.p = Eigen::Map<const Eigen::Vector3d>(pos);
  // mujoco stores 3x3 matrices row-major
  X_WF.R = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(mat);
  return X_WF;
}

void mujoco_frame_jacobian(const Chain& chain, const mjData& d, Eigen::Ref<Matrix6Xd> J) {
  const int n = chain.size();
  if (J.cols() != n) {
    throw Error("jacobian output has " + std::to_string(J.cols()) + " columns, the chain to '" +
                chain.frame().name + "' has " + std::to_string(n) + " joints");
  }
  const mjModel& m = chain.robot().model();
  const FrameRef& frame = chain.frame();
  // one scratch buffer per thread: grows to the largest model met, then never allocates again
  thread_local std::vector<double> scratch;
  if (scratch.size() < static_cast<std::size_t>(6 * m.nv)) scratch.resize(6 * m.nv);
  double* jacp = scratch.data();
  double* jacr = scratch.data() + 3 * m.nv;
  if (frame.kind == FrameKind::site) {
    mj_jacSite(&m, &d, jacp, jacr, frame.id);
  } else {
    mj_jacBody(&m, &d, jacp, jacr, frame.id);
  }
  // mujoco's 3 x nv blocks are row-major; keep the chain's dof columns, linear rows first
  for (int i = 0; i < n; ++i) {
    const int dof = chain.dof_address(i);
    for (int r = 0; r < 3; ++r) {
      J(r, i) = jacp[r * m.nv + dof];
      J(3 + r, i) = jacr[r * m.nv + dof];
    }
  }
}

Pose forward_kinematics(const Chain& chain, const Eigen::VectorXd& q) {
  chain.check(q, "q");
  ChainKinematics kin(chain);
  return kin.update(q);
}

}  // namespace mjarm
