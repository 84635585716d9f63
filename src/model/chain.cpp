#include "mjarm/model/chain.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mjarm/error.hpp"
#include "mjarm/model/names.hpp"

namespace mjarm {
namespace {

int frame_body(const mjModel& m, const FrameRef& frame) {
  return frame.kind == FrameKind::site ? m.site_bodyid[frame.id] : frame.id;
}

}  // namespace

FrameRef find_frame(const Robot& robot, std::string_view name) {
  const mjModel& m = robot.model();
  if (const int site = try_find_object(m, mjOBJ_SITE, name); site >= 0)
    return {FrameKind::site, site, std::string(name)};
  if (const int body = try_find_object(m, mjOBJ_BODY, name); body >= 0)
    return {FrameKind::body, body, std::string(name)};
  std::vector<std::string> candidates = object_names(m, mjOBJ_SITE);
  const auto bodies = object_names(m, mjOBJ_BODY);
  candidates.insert(candidates.end(), bodies.begin(), bodies.end());
  std::string message = "frame '" + std::string(name) +
                        "' is neither a site nor a body of model '" + robot.name() + "'";
  const auto close = closest_names(name, candidates, 5);
  if (!close.empty()) {
    message += "; closest: ";
    for (std::size_t i = 0; i < close.size(); ++i) message += (i ? ", " : "") + close[i];
  }
  throw Error(message);
}

Chain::Chain(const Robot& robot, std::string_view frame)
    : robot_(robot), frame_(find_frame(robot, frame)) {
  const mjModel& m = robot_.model();
  // walk from the frame's body to the world, collecting movable joints, then reverse
  std::vector<int> path;
  for (int body = frame_body(m, frame_); body > 0; body = m.body_parentid[body]) {
    for (int j = m.body_jntadr[body] + m.body_jntnum[body] - 1; j >= m.body_jntadr[body]; --j) {
      if (m.jnt_type[j] == mjJNT_HINGE || m.jnt_type[j] == mjJNT_SLIDE) path.push_back(j);
    }
  }
  if (path.empty()) {
    throw Error("frame '" + frame_.name + "' of model '" + robot_.name() +
                "' has no hinge or slide joint between it and the world");
  }
  std::reverse(path.begin(), path.end());
  for (int j : path) add_joint(j);
  finish();
}

Chain::Chain(const Robot& robot, const std::vector<std::string>& joints, std::string_view frame)
    : robot_(robot), frame_(find_frame(robot, frame)) {
  if (joints.empty()) throw Error("a chain needs at least one joint");
  for (const auto& name : joints) {
    const int id = robot_.joint(name);
    if (std::find(joints_.begin(), joints_.end(), id) != joints_.end())
      throw Error("joint '" + name + "' appears twice in the chain");
    const int type = robot_.model().jnt_type[id];
    if (type != mjJNT_HINGE && type != mjJNT_SLIDE) {
      throw Error("joint '" + name + "' is a " + to_string(static_cast<JointType>(type)) +
                  " joint; a chain moves hinge and slide joints only");
    }
    add_joint(id);
  }
  finish();
}

std::vector<int> Chain::unmoved_path_joints() const {
  const mjModel& m = robot_.model();
  std::vector<int> unmoved;
  for (int body = frame_body(m, frame_); body > 0; body = m.body_parentid[body]) {
    for (int j = m.body_jntadr[body] + m.body_jntnum[body] - 1; j >= m.body_jntadr[body]; --j)
      if (std::find(joints_.begin(), joints_.end(), j) == joints_.end()) unmoved.push_back(j);
  }
  std::reverse(unmoved.begin(), unmoved.end());
  return unmoved;
}

void Chain::add_joint(int id) {
  const mjModel& m = robot_.model();
  joints_.push_back(id);
  const char* name = mj_id2name(&m, mjOBJ_JOINT, id);
  names_.emplace_back(name ? name : "joint" + std::to_string(id));
  qpos_addresses_.push_back(m.jnt_qposadr[id]);
  dof_addresses_.push_back(m.jnt_dofadr[id]);
  std::optional<int> actuator;
  for (int a = 0; a < m.nu && !actuator; ++a) {
    if (m.actuator_trntype[a] == mjTRN_JOINT && m.actuator_trnid[2 * a] == id) actuator = a;
  }
  actuators_.push_back(actuator);
}

void Chain::finish() {
  const mjModel& m = robot_.model();
  const int n = size();
  lower_.resize(n);
  upper_.resize(n);
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i) {
    const int j = joints_[i];
    const bool limited = m.jnt_limited[j] != 0;
    lower_[i] = limited ? m.jnt_range[2 * j] : -inf;
    upper_[i] = limited ? m.jnt_range[2 * j + 1] : inf;
  }
}

Eigen::VectorXd Chain::center() const {
  Eigen::VectorXd c(size());
  for (int i = 0; i < size(); ++i)
    c[i] =
        std::isfinite(lower_[i]) && std::isfinite(upper_[i]) ? 0.5 * (lower_[i] + upper_[i]) : 0.0;
  return c;
}

bool Chain::within_limits(const Eigen::Ref<const Eigen::VectorXd>& q, double tolerance) const {
  if (q.size() != size()) return false;
  for (int i = 0; i < size(); ++i)
    if (!(q[i] >= lower_[i] - tolerance && q[i] <= upper_[i] + tolerance)) return false;
  return true;
}

Eigen::VectorXd Chain::clamp(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  return q.cwiseMax(lower_).cwiseMin(upper_);
}

void Chain::check(const Eigen::Ref<const Eigen::VectorXd>& q, std::string_view what) const {
  if (q.size() != size()) {
    throw Error(std::string(what) + " has " + std::to_string(q.size()) +
                " values but the chain to '" + frame_.name + "' of model '" + robot_.name() +
                "' has " + std::to_string(size()) + " joints");
  }
  for (int i = 0; i < size(); ++i) {
    if (!std::isfinite(q[i]))
      throw Error(std::string(what) + " value for joint '" + names_[i] + "' is not finite");
  }
}

void Chain::check_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos, std::string_view what) const {
  const int nq = robot_.nq();
  if (qpos.size() != nq) {
    throw Error(std::string(what) + " has " + std::to_string(qpos.size()) + " values, model '" +
                robot_.name() + "' has nq = " + std::to_string(nq));
  }
  if (!qpos.allFinite()) throw Error(std::string(what) + " holds a non-finite value");
}

Eigen::VectorXd Chain::gather(const double* qpos) const {
  Eigen::VectorXd q(size());
  for (int i = 0; i < size(); ++i) q[i] = qpos[qpos_addresses_[i]];
  return q;
}

void Chain::scatter(const Eigen::Ref<const Eigen::VectorXd>& q, double* qpos) const noexcept {
  for (int i = 0; i < size(); ++i) qpos[qpos_addresses_[i]] = q[i];
}

}  // namespace mjarm
