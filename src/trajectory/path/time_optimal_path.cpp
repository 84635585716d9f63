#include "mjarm/trajectory/path/time_optimal_path.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"
#include "trajectory/path/reachability.hpp"

namespace mjarm {

namespace {

void require_path_limits(const Eigen::VectorXd& limits, Eigen::Index n, const char* what) {
  if (limits.size() != n)
    throw Error(std::string("time-optimal path: ") + what + " has " +
                std::to_string(limits.size()) + " entries, the path has " + std::to_string(n) +
                " joints");
  for (Eigen::Index j = 0; j < n; ++j)
    if (!(limits[j] > 0.0) || !std::isfinite(limits[j]))
      throw Error(std::string("time-optimal path: ") + what + "[" + std::to_string(j) +
                  "] must be positive and finite, got " + number_text(limits[j]));
}

// the forward pass takes a u this far outside its feasible interval as rounding (relative to
// the interval's scale); beyond it the grid problem is declared infeasible
constexpr double kForwardSlack = 1e-7;

}  // namespace

TimeOptimalPath::TimeOptimalPath(const JointPath& path, const Eigen::VectorXd& max_velocity,
                                 const Eigen::VectorXd& max_acceleration,
                                 const ToppOptions& options)
    : path_(path), max_velocity_(max_velocity), max_acceleration_(max_acceleration) {
  check_fields(options);
  require_path_limits(max_velocity, path.dofs(), "max_velocity");
  require_path_limits(max_acceleration, path.dofs(), "max_acceleration");
  const int N = options.grid_intervals;
  grid_ = Eigen::VectorXd::LinSpaced(N + 1, 0.0, path.length());
  grid_[N] = path.length();
  x_ = Eigen::VectorXd::Zero(N + 1);
  u_ = Eigen::VectorXd::Zero(N);
  times_ = Eigen::VectorXd::Zero(N + 1);
  controllable_ = Eigen::Matrix2Xd::Zero(2, N + 1);
  parameterize();
}

void TimeOptimalPath::parameterize() {
  const Eigen::Index n = dofs();
  const int N = static_cast<int>(grid_.size()) - 1;
  // q′ and q″ at every grid point
  Eigen::MatrixXd d1(n, N + 1), d2(n, N + 1);
  Eigen::VectorXd q(n);
  for (int i = 0; i <= N; ++i) path_.evaluate(grid_[i], q, d1.col(i), d2.col(i));
  // velocity: q′_j² x ≤ v_j²  ⇒  x ≤ min_j (v_j/q′_j)²
  Eigen::VectorXd x_velocity(N + 1);
  for (int i = 0; i <= N; ++i) {
    double bound = std::numeric_limits<double>::infinity();
    for (Eigen::Index j = 0; j < n; ++j) {
      const double w = std::abs(d1(j, i));
      if (w > 0.0) bound = std::min(bound, (max_velocity_[j] / w) * (max_velocity_[j] / w));
    }
    x_velocity[i] = bound;
  }
  topp::StepRows rows(static_cast<int>(4 * n));
  const auto fill_rows = [&](int i) {
    const double delta = grid_[i + 1] - grid_[i];
    rows.count = 0;
    for (Eigen::Index j = 0; j < n; ++j) {
      const double scale = 1.0 / max_acceleration_[j];  // rows in units of the limit
      rows.add_two_sided(d1(j, i) * scale, d2(j, i) * scale, -1.0, 1.0);  // collocation at s_i
      // at s_{i+1}: q′·u + q″·(x + 2Δu)
      rows.add_two_sided((d1(j, i + 1) + 2.0 * delta * d2(j, i + 1)) * scale, d2(j, i + 1) * scale,
                         -1.0, 1.0);
    }
    return delta;
  };

  // backward pass: K_N = {0}, K_i = Q(K_{i+1}) within the velocity bound
  status_ = ToppStatus::infeasible;
  topp::XInterval next{0.0, 0.0};
  controllable_.col(N) << 0.0, 0.0;
  for (int i = N - 1; i >= 0; --i) {
    const double delta = fill_rows(i);
    topp::XInterval k = topp::controllable_interval(rows, delta, next, 0.0, x_velocity[i]);
    if (k.empty()) return;
    controllable_.col(i) << k.lo, k.hi;
    next = k;
  }
  if (controllable_(0, 0) > 0.0) return;  // the start at rest is not controllable

  // forward pass: the greatest u that keeps x_{i+1} in K_{i+1}
  x_[0] = 0.0;
  for (int i = 0; i < N; ++i) {
    const double delta = fill_rows(i);
    const topp::XInterval target{controllable_(0, i + 1), controllable_(1, i + 1)};
    const topp::XInterval u = topp::feasible_controls(rows, delta, target, x_[i]);
    const double scale = 1.0 + std::abs(u.lo) + std::abs(u.hi);
    if (!(u.hi >= u.lo - kForwardSlack * scale)) return;  // also NaN
    double x_next = x_[i] + 2.0 * delta * u.hi;
    x_next = std::clamp(x_next, std::max(0.0, target.lo), target.hi);
    x_[i + 1] = x_next;
    u_[i] = (x_next - x_[i]) / (2.0 * delta);
  }
  for (int i = 0; i < N; ++i) {
    // ṡ is linear in time on a step: Δt = 2Δ/(ṡ_i + ṡ_{i+1})
    const double rate = std::sqrt(x_[i]) + std::sqrt(x_[i + 1]);
    if (!(rate > 0.0)) {
      x_.setZero();
      u_.setZero();
      times_.setZero();
      return;
    }
    times_[i + 1] = times_[i] + 2.0 * (grid_[i + 1] - grid_[i]) / rate;
  }
  if (!std::isfinite(times_[N])) {
    times_.setZero();
    return;
  }
  status_ = ToppStatus::solved;
}

TimeOptimalPath::PathState TimeOptimalPath::path_state(double t) const noexcept {
  PathState state;
  const int N = static_cast<int>(grid_.size()) - 1;
  if (!(t > 0.0) || !solved()) return state;  // also NaN
  if (t >= duration()) {
    state.s = grid_[N];
    return state;
  }
  const double* begin = times_.data();
  const int i = static_cast<int>(std::upper_bound(begin + 1, begin + N, t) - begin) - 1;
  const double tau = t - times_[i];
  const double v0 = std::sqrt(x_[i]);
  state.dds = u_[i];
  state.ds = std::max(0.0, v0 + u_[i] * tau);
  state.s = std::min(grid_[i] + tau * (v0 + 0.5 * u_[i] * tau), grid_[i + 1]);
  return state;
}

void TimeOptimalPath::at(double t, TrajectorySample& sample) const {
  if (sample.size() != dofs()) sample.resize(dofs());
  const PathState p = path_state(t);
  path_.evaluate(p.s, sample.position, sample.velocity, sample.acceleration, sample.jerk);
  // chain rule on q(s(t)), s̈ constant on a step: q⃛ = q‴ṡ³ + 3q″ṡs̈
  sample.jerk = sample.jerk * (p.ds * p.ds * p.ds) + (3.0 * p.ds * p.dds) * sample.acceleration;
  sample.acceleration = sample.acceleration * (p.ds * p.ds) + p.dds * sample.velocity;
  sample.velocity *= p.ds;
}

TimeOptimalPath parameterize(const JointPath& path, const Eigen::VectorXd& max_velocity,
                             const Eigen::VectorXd& max_acceleration, const ToppOptions& options) {
  return TimeOptimalPath(path, max_velocity, max_acceleration, options);
}

}  // namespace mjarm
