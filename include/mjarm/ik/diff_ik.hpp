#pragma once
/// @file
/// Differential inverse kinematics as a quadratic program: one control step's joint velocity.
///
/// Each step solves, for the joint velocity v (n, rad/s or m/s),
///
///     minimize    Σ_k ‖W_k^½ (A_k v − (α_k/dt)·e_k)‖² + λ‖v‖²
///     subject to  lo ≤ v ≤ hi       (and C·v ≥ b with constraint rows, below)
///
/// with one term per task k (α_k ∈ (0, 1] its gain: the fraction of the error removed per step):
/// - pose:     e = log(X_EW·X_WT) (body log error, frame E, m and rad),
///             A = Jlog(e)·J_E (J_E the local Jacobian), so that A·v = −ė exactly to first order;
/// - position: e = p_WT − p_WE (world axes, m), A = rows 0..2 of J_{E[W]};
/// - posture:  e = q_ref − q (n), A = I.
/// The box [lo, hi] intersects, per joint i,
///   position limits after integration: (lower_i − q_i)/dt ≤ v_i ≤ (upper_i − q_i)/dt,
///   velocity limits:                   |v_i| ≤ v_max_i,
///   the step bound:                    |v_i|·dt ≤ max_step.
/// The next configuration is q⁺ = q + v·dt, clipped into [lower, upper] to remove round-off, so
/// q⁺ is within the limits EXACTLY whenever q is.
///
/// Starting outside the limits (q_i < lower_i or q_i > upper_i): the position bound then forces
/// v_i to bring the joint back. If the velocity limit or step bound cannot bring it all the way
/// back in one step, joint i moves towards its range at the largest allowed speed
/// (v_i = v_max_i, resp. −v_max_i) and is not clipped; `DiffIkStep::pulled_back` reports it.
/// With no velocity limit and no step bound every joint is back inside after one step.
///
/// The QP (n variables, box constraints only) is solved by qp::BoxQp, warm-started from the
/// previous step's bound pattern; it is sized at construction and `step()` allocates nothing.
///
/// Inequality constraints (`add_constraint`: collision avoidance, configuration limits with a
/// margin, a manipulability barrier — diff_ik_constraint.hpp) add rows C·v ≥ b and/or tighten
/// the box. Once a constraint with rows is added the QP is solved by qp::DenseQp (general
/// inequalities and the same box), sized when the constraint is added; without one, BoxQp
/// gives today's results bit for bit.

#include <Eigen/Core>
#include <limits>
#include <memory>
#include <string_view>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/ik/diff_ik_constraint.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/lie/types.hpp"
#include "mjarm/qp/box_qp.hpp"
#include "mjarm/qp/dense_qp.hpp"

namespace mjarm {

/// Constants of a `DiffIk`, fixed at construction.
struct DiffIkOptions {
  double dt = 0.01;  ///< control period [s] (> 0)
  /// λ of the regularisation λ‖v‖² (> 0), on the scale of the task weights: it keeps the QP
  /// strictly convex and bounds v near singularities.
  double damping = 1e-6;
  /// Joint velocity limits v_max (n entries, rad/s or m/s, > 0, +∞ allowed); empty = none.
  Eigen::VectorXd velocity_limit;
  /// Largest |Δq_i| = |v_i|·dt per step [rad or m] (> 0, +∞ = none).
  double max_step = std::numeric_limits<double>::infinity();
};

constexpr auto declared_fields(const DiffIkOptions*) {
  using S = DiffIkOptions;
  return declare<S>(
      "differential IK", field("dt", &S::dt, "s", Range::positive(), "control period"),
      field("damping", &S::damping, "", Range::positive(), "λ of the regularisation λ‖v‖²"),
      field("velocity_limit", &S::velocity_limit, "rad/s or m/s", Range::positive().or_infinity(),
            "joint velocity limits (n entries; empty: none)"),
      field("max_step", &S::max_step, "rad or m", Range::positive().or_infinity(),
            "largest |Δq_i| per step; +inf: none"));
}

/// @throws Error naming the offending option (n = number of chain joints).
void check(const DiffIkOptions& options, int n);

/// What a `DiffIk` task asks for.
enum class DiffIkTaskKind {
  pose,      ///< a frame's full pose (6 rows, body log error)
  position,  ///< a frame's origin (3 rows, world axes)
  posture    ///< a joint configuration (n rows)
};

constexpr auto declared_names(const DiffIkTaskKind*) {
  using K = DiffIkTaskKind;
  return std::array{EnumName{K::pose, "pose", "a frame's full pose (6 rows)"},
                    EnumName{K::position, "position", "a frame's origin (3 rows)"},
                    EnumName{K::posture, "posture", "a joint configuration (n rows)"}};
}

/// The outcome of one `DiffIk::step()`, owned by the solver (valid until the next step).
struct DiffIkStep {
  Eigen::VectorXd v;       ///< joint velocity (n) [rad/s or m/s], within the box
  Eigen::VectorXd q_next;  ///< q + v·dt clipped into the limits (n) [rad or m]
  /// Status of the QP: solved in practice without constraint rows; `infeasible` when the rows
  /// and the box have no common point (v is then the box's point closest to rest).
  qp::QpStatus qp_status = qp::QpStatus::solved;
  /// Iterations of the QP solver: qp::BoxQp's reduced solves (each adding a bound, releasing
  /// one or confirming the answer; 1 when the warm-started bound pattern is the solution), or,
  /// with constraint rows, qp::DenseQp's Goldfarb–Idnani steps (additions and drops).
  int qp_iterations = 0;
  bool pulled_back = false;  ///< a joint was outside its limits by more than one step can undo
  /// General inequality rows active in this step (0 without row constraints).
  int constraint_rows = 0;
};

/// Differential-IK QP for the joints of one chain, with any number of weighted tasks on frames
/// moved by those joints. Construct, add tasks, then call `step()` once per control period.
class DiffIk {
 public:
  /// @throws Error for invalid options.
  explicit DiffIk(const Chain& chain, const DiffIkOptions& options = {});
  ~DiffIk();
  DiffIk(DiffIk&&) noexcept;
  DiffIk& operator=(DiffIk&&) noexcept;

  const Chain& chain() const noexcept { return chain_; }
  const DiffIkOptions& options() const noexcept { return options_; }

  /// Adds a pose task on @p frame (site or body name; empty = the chain's frame). Its target is
  /// the frame's pose at the chain's centre configuration until `set_target` is called.
  /// @param position_weight weight of the three position rows [1/m²] (> 0)
  /// @param orientation_weight weight of the three orientation rows [1/rad²] (> 0)
  /// @param gain fraction of the error removed per step, (0, 1]
  /// @return the task's index
  /// @throws Error for an unknown frame or invalid weights/gain
  int add_pose_task(std::string_view frame = {}, double position_weight = 1.0,
                    double orientation_weight = 1.0, double gain = 1.0);
  /// Adds a position task on @p frame (empty = the chain's frame); weight [1/m²] (> 0).
  /// @throws Error for an unknown frame or invalid weight/gain
  int add_position_task(std::string_view frame = {}, double weight = 1.0, double gain = 1.0);
  /// Adds a posture task pulling towards @p q_ref (n) with @p weight [1/rad²] (≥ 0).
  /// @throws Error for a wrong size, NaN, or invalid weight/gain
  int add_posture_task(const Eigen::Ref<const Eigen::VectorXd>& q_ref, double weight = 1e-3,
                       double gain = 1.0);

  /// Sets the target pose X_WT of a pose task (a position task uses X_WT.p).
  /// @throws Error for a bad index, a posture task, or a non-finite / non-rotation target
  void set_target(int task, const Pose& X_WT);
  /// Sets the target position p_WT [m] of a position or pose task (a pose task keeps R_WT).
  /// @throws Error for a bad index, a posture task, or a non-finite target
  void set_target(int task, const Eigen::Vector3d& p_WT);
  /// Sets the reference configuration of a posture task (n).
  /// @throws Error for a bad index, a frame task, a wrong size or NaN
  void set_posture(int task, const Eigen::Ref<const Eigen::VectorXd>& q_ref);
  /// Changes a task's weight (all rows; ≥ 0, a pose task gets the same on both parts).
  /// @throws Error for a bad index or a negative / non-finite weight
  void set_weight(int task, double weight);
  /// Sets the joints outside the chain that move the tasks' frames (full qpos, nq entries).
  /// @throws Error for a wrong size or NaN
  void set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos);

  /// Adds an inequality constraint (rows and/or a box tightening) evaluated at every step's q.
  /// The first constraint with rows switches the solver to qp::DenseQp; each addition resizes
  /// it (allocates), `step()` still allocates nothing. `set_fixed_qpos` passes its qpos on to
  /// the constraints added before it.
  /// @return the constraint's index
  /// @throws Error for a null constraint or one over a different number of joints
  int add_constraint(std::unique_ptr<DiffIkConstraint> constraint);
  /// Number of constraints added.
  int constraint_count() const noexcept { return static_cast<int>(constraints_.size()); }
  /// Constraint @p index. @throws Error for a bad index
  DiffIkConstraint& constraint(int index);
  /// The general rows of the last `step()`: C (m × n, m the sum of `max_rows()`) and b (m), the
  /// QP having held C·v ≥ b. Unused rows are zero with b = −∞.
  const Eigen::MatrixXd& constraint_matrix() const noexcept { return C_; }
  const Eigen::VectorXd& constraint_lower() const noexcept { return c_lo_; }

  /// Number of tasks added.
  int task_count() const noexcept { return static_cast<int>(tasks_.size()); }
  /// Kind of task @p task. @throws Error for a bad index
  DiffIkTaskKind task_kind(int task) const;
  /// The task's error e_k at the q of the last `step()` (6 pose, 3 position, n posture; units
  /// of the task). @throws Error for a bad index
  const Eigen::VectorXd& task_error(int task) const;
  /// The kinematics of frame task @p task, which `step()` updates at its q. A caller that needs
  /// the task frame's pose or Jacobian at the q of the coming step may update it here: `step()`
  /// then reuses that work (`ChainKinematics::update` skips the q it has just computed).
  /// @throws Error for a bad index or a posture task
  ChainKinematics& task_kinematics(int task);

  /// One step from configuration @p q (n): solves the QP and returns v and q⁺ = q + v·dt.
  /// Allocates nothing.
  /// @throws Error when q has the wrong size or holds NaN/inf
  const DiffIkStep& step(const Eigen::Ref<const Eigen::VectorXd>& q);

  /// The result of the last `step()`.
  const DiffIkStep& last_step() const noexcept { return step_; }

  /// Forgets the QP's working set kept for warm starts: the next `step()` starts cold, so that
  /// a sequence of steps does not depend on what was solved before it (bit for bit).
  void reset_warm_start() noexcept;

 private:
  struct Task;
  Task& task_at(int task, const char* what);
  const Task& task_at(int task, const char* what) const;
  int add_frame_task(DiffIkTaskKind kind, std::string_view frame, double w_p, double w_o,
                     double gain);

  Chain chain_;
  DiffIkOptions options_;
  std::vector<std::unique_ptr<Task>> tasks_;
  std::vector<std::unique_ptr<DiffIkConstraint>> constraints_;
  qp::BoxQp qp_;
  std::unique_ptr<qp::DenseQp> dense_;  // once a constraint has rows
  Eigen::MatrixXd C_;                   // general rows C·v ≥ c_lo_ (≤ c_hi_ = +∞)
  Eigen::VectorXd c_lo_, c_hi_;
  DiffIkStep step_;
  // workspace
  Eigen::MatrixXd H_;
  Eigen::VectorXd g_, lo_, hi_, v_min_, v_max_;
  Matrix6Xd J_, A_;
};

}  // namespace mjarm
