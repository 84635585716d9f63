#include "mjarm/ik/diff_ik.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/lie/pose_error.hpp"
#include "mjarm/number_text.hpp"
#include "validate_pose.hpp"

namespace mjarm {

/// One weighted task of the QP.
struct DiffIk::Task {
  DiffIkTaskKind kind = DiffIkTaskKind::pose;
  std::unique_ptr<ChainKinematics> kin;  // frame tasks only
  Pose X_WT;
  Vector6d row_weight = Vector6d::Ones();  // frame tasks (position uses the first 3)
  double weight = 1.0;                     // posture
  double gain = 1.0;
  Eigen::VectorXd q_ref;  // posture
  Eigen::VectorXd error;  // 6, 3 or n
};

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

void check_gain(double gain) {
  if (!std::isfinite(gain) || gain <= 0.0 || gain > 1.0) {
    throw Error("differential IK: task gain must be in (0, 1], got " + number_text(gain));
  }
}

// H += Aᵀ·(W·A) on the lower triangle, which is all the QP reads (A, WA: the first R rows of
// 6×n matrices; one fixed-size dot of two columns per entry)
template <int R>
void add_lower_gram(Eigen::MatrixXd& H, const Matrix6Xd& A, const Matrix6Xd& WA, int n) {
  for (int j = 0; j < n; ++j) {
    const Eigen::Matrix<double, R, 1> wa_j = WA.col(j).template head<R>();
    for (int i = j; i < n; ++i) H(i, j) += A.col(i).template head<R>().dot(wa_j);
  }
}

void check_weight(double weight, bool allow_zero, const char* what) {
  if (!std::isfinite(weight) || weight < 0.0 || (!allow_zero && weight == 0.0)) {
    throw Error(std::string("differential IK: ") + what + " must be finite and " +
                (allow_zero ? "non-negative" : "positive") + ", got " + number_text(weight));
  }
}

}  // namespace

void check(const DiffIkOptions& options, int n) {
  check_fields(options);
  const Eigen::Index size = options.velocity_limit.size();
  if (size != 0 && size != n) {
    throw Error("differential IK: velocity_limit has " + std::to_string(size) +
                " entries, the chain has " + std::to_string(n) + " joints (or leave it empty)");
  }
}

DiffIk::DiffIk(const Chain& chain, const DiffIkOptions& options)
    : chain_(chain), options_(options), qp_(chain.size()) {
  const int n = chain_.size();
  check(options_, n);
  step_.v = Eigen::VectorXd::Zero(n);
  step_.q_next = Eigen::VectorXd::Zero(n);
  H_ = Eigen::MatrixXd::Zero(n, n);
  g_ = Eigen::VectorXd::Zero(n);
  lo_ = Eigen::VectorXd::Zero(n);
  hi_ = Eigen::VectorXd::Zero(n);
  // the velocity box shared by every step: velocity limits ∩ step bound
  const double step_speed = options_.max_step / options_.dt;
  v_max_ = Eigen::VectorXd::Constant(n, step_speed);
  if (options_.velocity_limit.size() == n) v_max_ = v_max_.cwiseMin(options_.velocity_limit);
  v_min_ = -v_max_;
  J_ = Matrix6Xd::Zero(6, n);
  A_ = Matrix6Xd::Zero(6, n);
}

DiffIk::~DiffIk() = default;
DiffIk::DiffIk(DiffIk&&) noexcept = default;
DiffIk& DiffIk::operator=(DiffIk&&) noexcept = default;

DiffIk::Task& DiffIk::task_at(int task, const char* what) {
  if (task < 0 || task >= task_count()) {
    throw Error(std::string("DiffIk::") + what + ": no task " + std::to_string(task) + " (" +
                std::to_string(task_count()) + " tasks)");
  }
  return *tasks_[task];
}

const DiffIk::Task& DiffIk::task_at(int task, const char* what) const {
  return const_cast<DiffIk*>(this)->task_at(task, what);
}

int DiffIk::add_frame_task(DiffIkTaskKind kind, std::string_view frame, double w_p, double w_o,
                           double gain) {
  check_weight(w_p, false, "position weight");
  check_weight(w_o, false, "orientation weight");
  check_gain(gain);
  auto task = std::make_unique<Task>();
  task->kind = kind;
  // the task's frame moved by this chain's joints (zero columns for joints off its path)
  task->kin =
      frame.empty()
          ? std::make_unique<ChainKinematics>(chain_)
          : std::make_unique<ChainKinematics>(Chain(chain_.robot(), chain_.joint_names(), frame));
  task->X_WT = task->kin->update(chain_.center());
  task->row_weight << w_p, w_p, w_p, w_o, w_o, w_o;
  task->gain = gain;
  task->error = Eigen::VectorXd::Zero(kind == DiffIkTaskKind::pose ? 6 : 3);
  tasks_.push_back(std::move(task));
  return task_count() - 1;
}

int DiffIk::add_pose_task(std::string_view frame, double position_weight, double orientation_weight,
                          double gain) {
  return add_frame_task(DiffIkTaskKind::pose, frame, position_weight, orientation_weight, gain);
}

int DiffIk::add_position_task(std::string_view frame, double weight, double gain) {
  return add_frame_task(DiffIkTaskKind::position, frame, weight, weight, gain);
}

int DiffIk::add_posture_task(const Eigen::Ref<const Eigen::VectorXd>& q_ref, double weight,
                             double gain) {
  chain_.check(q_ref, "posture reference");
  check_weight(weight, true, "posture weight");
  check_gain(gain);
  auto task = std::make_unique<Task>();
  task->kind = DiffIkTaskKind::posture;
  task->weight = weight;
  task->gain = gain;
  task->q_ref = q_ref;
  task->error = Eigen::VectorXd::Zero(chain_.size());
  tasks_.push_back(std::move(task));
  return task_count() - 1;
}

void DiffIk::set_target(int task, const Pose& X_WT) {
  Task& t = task_at(task, "set_target");
  if (t.kind == DiffIkTaskKind::posture) throw Error("DiffIk::set_target: task is a posture task");
  detail::validate_pose(X_WT, "DiffIk target pose");
  t.X_WT = X_WT;
}

void DiffIk::set_target(int task, const Eigen::Vector3d& p_WT) {
  Task& t = task_at(task, "set_target");
  if (t.kind == DiffIkTaskKind::posture) throw Error("DiffIk::set_target: task is a posture task");
  detail::validate_position(p_WT, "DiffIk target position");
  t.X_WT.p = p_WT;
}

void DiffIk::set_posture(int task, const Eigen::Ref<const Eigen::VectorXd>& q_ref) {
  Task& t = task_at(task, "set_posture");
  if (t.kind != DiffIkTaskKind::posture) throw Error("DiffIk::set_posture: task is a frame task");
  chain_.check(q_ref, "posture reference");
  t.q_ref = q_ref;
}

void DiffIk::set_weight(int task, double weight) {
  Task& t = task_at(task, "set_weight");
  check_weight(weight, true, "weight");
  t.weight = weight;
  t.row_weight.setConstant(weight);
}

void DiffIk::set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos) {
  for (auto& t : tasks_) {
    if (t->kin) t->kin->set_fixed_qpos(qpos);
  }
  for (auto& c : constraints_) c->set_fixed_qpos(qpos);
}

int DiffIk::add_constraint(std::unique_ptr<DiffIkConstraint> constraint) {
  if (!constraint) throw Error("DiffIk::add_constraint: the constraint is null");
  const int n = chain_.size();
  if (constraint->variables() != n) {
    throw Error("DiffIk::add_constraint: the constraint is over " +
                std::to_string(constraint->variables()) + " joints, the chain has " +
                std::to_string(n));
  }
  constraints_.push_back(std::move(constraint));
  int rows = 0;
  for (const auto& c : constraints_) rows += c->max_rows();
  if (rows > 0) {
    dense_ = std::make_unique<qp::DenseQp>(n, 0, rows);
    C_ = Eigen::MatrixXd::Zero(rows, n);
    c_lo_ = Eigen::VectorXd::Constant(rows, -kInf);
    c_hi_ = Eigen::VectorXd::Constant(rows, kInf);
  }
  return constraint_count() - 1;
}

DiffIkConstraint& DiffIk::constraint(int index) {
  if (index < 0 || index >= constraint_count()) {
    throw Error("DiffIk::constraint: no constraint " + std::to_string(index) + " (" +
                std::to_string(constraint_count()) + " constraints)");
  }
  return *constraints_[index];
}

DiffIkTaskKind DiffIk::task_kind(int task) const { return task_at(task, "task_kind").kind; }

const Eigen::VectorXd& DiffIk::task_error(int task) const {
  return task_at(task, "task_error").error;
}

ChainKinematics& DiffIk::task_kinematics(int task) {
  Task& t = task_at(task, "task_kinematics");
  if (!t.kin) throw Error("DiffIk::task_kinematics: task is a posture task");
  return *t.kin;
}

const DiffIkStep& DiffIk::step(const Eigen::Ref<const Eigen::VectorXd>& q) {
  chain_.check(q, "q");
  const int n = chain_.size();
  const double inv_dt = 1.0 / options_.dt;

  // cost: ½vᵀHv + gᵀv with H = Σ AᵀWA + λI (lower triangle only), g = −Σ AᵀW(α/dt)e
  H_.setZero();
  H_.diagonal().setConstant(options_.damping);
  g_.setZero();
  for (auto& task : tasks_) {
    Task& t = *task;
    const double rate = t.gain * inv_dt;
    if (t.kind == DiffIkTaskKind::posture) {
      t.error = t.q_ref - q;
      H_.diagonal().array() += t.weight;
      g_.noalias() -= (t.weight * rate) * t.error;
      continue;
    }
    const Pose& X_WE = t.kin->update(q);
    if (t.kind == DiffIkTaskKind::pose) {
      const Vector6d e = log_error(X_WE, t.X_WT);
      t.error = e;
      // A = Jlog(e)·J_E with the local Jacobian J_E = blockdiag(R_WEᵀ, R_WEᵀ)·J_{E[W]}
      // (ė = −Jlog(e)·V_E: the rows that make A·v track the error rate exactly), formed as the
      // fixed-size 6×6 B = Jlog(e)·blockdiag(R_WEᵀ, R_WEᵀ) times each column of J_{E[W]}
      t.kin->jacobian(J_, JacobianFrame::world_aligned);
      const Eigen::Matrix3d R_EW = X_WE.R.transpose();
      const Matrix6d Jlog = log_error_jacobian(e);
      Matrix6d B;
      B.leftCols<3>().noalias() = Jlog.leftCols<3>() * R_EW;
      B.rightCols<3>().noalias() = Jlog.rightCols<3>() * R_EW;
      for (int c = 0; c < n; ++c) {
        A_.col(c).noalias() = B * J_.col(c);
        J_.col(c) = t.row_weight.cwiseProduct(A_.col(c));  // J_ now holds W·A
      }
      add_lower_gram<6>(H_, A_, J_, n);
      const Vector6d We = rate * e;
      for (int c = 0; c < n; ++c) g_[c] -= J_.col(c).dot(We);
    } else {
      const Eigen::Vector3d e = t.X_WT.p - X_WE.p;
      t.error = e;
      t.kin->jacobian(J_, JacobianFrame::world_aligned);
      A_.topRows<3>() = t.row_weight.head<3>().asDiagonal() * J_.topRows<3>();  // W·J
      add_lower_gram<3>(H_, J_, A_, n);
      const Eigen::Vector3d We = rate * e;
      for (int c = 0; c < n; ++c) g_[c] -= A_.col(c).head<3>().dot(We);
    }
  }

  // box: position limits after integration ∩ velocity limits ∩ step bound
  const Eigen::VectorXd& lower = chain_.lower();
  const Eigen::VectorXd& upper = chain_.upper();
  step_.pulled_back = false;
  for (int i = 0; i < n; ++i) {
    const double lo = std::max((lower[i] - q[i]) * inv_dt, v_min_[i]);
    const double hi = std::min((upper[i] - q[i]) * inv_dt, v_max_[i]);
    if (lo <= hi) {
      lo_[i] = lo;
      hi_[i] = hi;
    } else {
      // outside the range by more than one step can undo: head back at the largest speed
      step_.pulled_back = true;
      lo_[i] = hi_[i] = q[i] < lower[i] ? v_max_[i] : v_min_[i];
    }
  }

  // the constraints' box tightenings stay inside the hard box and never empty it
  for (auto& c : constraints_) c->tighten_box(q, options_.dt, lo_, hi_);

  bool usable = false;
  step_.constraint_rows = 0;
  if (dense_) {
    // general rows, one block per constraint; a block's unused rows are zero with b = −∞
    int offset = 0;
    for (auto& c : constraints_) {
      const int m = c->max_rows();
      if (m == 0) continue;
      const int k = c->rows(q, options_.dt, C_.middleRows(offset, m), c_lo_.segment(offset, m));
      C_.middleRows(offset + k, m - k).setZero();
      c_lo_.segment(offset + k, m - k).setConstant(-kInf);
      step_.constraint_rows += k;
      offset += m;
    }
    dense_->set_hessian(H_);
    dense_->set_gradient(g_);
    dense_->set_inequalities(C_, c_lo_, c_hi_);
    dense_->set_bounds(lo_, hi_);
    const qp::QpResult& r = dense_->solve(qp::QpStart::warm);
    step_.qp_status = r.status;
    step_.qp_iterations = r.iterations;
    usable = r.status == qp::QpStatus::solved && r.x.allFinite();
    if (usable) step_.v = r.x.cwiseMax(lo_).cwiseMin(hi_);
  } else {
    qp_.set_hessian(H_);
    qp_.set_gradient(g_);
    qp_.set_bounds(lo_, hi_);
    const qp::BoxQpResult& r = qp_.solve(qp::QpStart::warm);
    step_.qp_status = r.status;
    step_.qp_iterations = r.iterations;
    usable = r.x.allFinite();
    if (usable) step_.v = r.x.cwiseMax(lo_).cwiseMin(hi_);
  }
  if (!usable) {
    // box QP: never expected (H ≻ 0, box non-empty); dense QP: the rows cannot all hold (e.g.
    // a pair already inside min_distance that the velocity box cannot push out in one step).
    // The closest point of the box to rest is safe; qp_status says what happened.
    step_.v = Eigen::VectorXd::Zero(n).cwiseMax(lo_).cwiseMin(hi_);
  }

  // integrate, then clip to kill round-off (joints being pulled back stay unclipped)
  for (int i = 0; i < n; ++i) {
    double next = q[i] + step_.v[i] * options_.dt;
    const bool inside_reachable =
        (lower[i] - q[i]) * inv_dt <= hi_[i] && (upper[i] - q[i]) * inv_dt >= lo_[i];
    if (inside_reachable) next = std::clamp(next, lower[i], upper[i]);
    step_.q_next[i] = next;
  }
  return step_;
}

void DiffIk::reset_warm_start() noexcept {
  qp_.reset_warm_start();
  if (dense_) dense_->reset_warm_start();
}

}  // namespace mjarm
