#include "mjarm/trajectory/quintic.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"
#include "polynomial.hpp"

namespace mjarm {

namespace {

void require_finite_state(const Quintic::State& s, const char* which) {
  if (!std::isfinite(s.p) || !std::isfinite(s.v) || !std::isfinite(s.a))
    throw Error(std::string("quintic: the ") + which +
                " state must be finite, got p = " + number_text(s.p) +
                ", v = " + number_text(s.v) + ", a = " + number_text(s.a));
}

// c₀ … c₅ of the quintic from s0 to s1 in T > 0 (formulas in quintic.hpp)
std::array<double, 6> quintic_coefficients(const Quintic::State& s0, const Quintic::State& s1,
                                           double T) {
  const double h = s1.p - s0.p;
  const double T2 = T * T, T3 = T2 * T;
  return {s0.p,
          s0.v,
          0.5 * s0.a,
          (20.0 * h - (8.0 * s1.v + 12.0 * s0.v) * T - (3.0 * s0.a - s1.a) * T2) / (2.0 * T3),
          (-30.0 * h + (14.0 * s1.v + 16.0 * s0.v) * T + (3.0 * s0.a - 2.0 * s1.a) * T2) /
              (2.0 * T3 * T),
          (12.0 * h - 6.0 * (s1.v + s0.v) * T + (s1.a - s0.a) * T2) / (2.0 * T3 * T2)};
}

// p, v, a, j of coefficients c at t (no clamping)
Quintic::Sample evaluate_quintic(const double* c, double t) noexcept {
  Quintic::Sample out;
  out.p = c[0] + t * (c[1] + t * (c[2] + t * (c[3] + t * (c[4] + t * c[5]))));
  out.v = c[1] + t * (2.0 * c[2] + t * (3.0 * c[3] + t * (4.0 * c[4] + t * 5.0 * c[5])));
  out.a = 2.0 * c[2] + t * (6.0 * c[3] + t * (12.0 * c[4] + t * 20.0 * c[5]));
  out.j = 6.0 * c[3] + t * (24.0 * c[4] + t * 60.0 * c[5]);
  return out;
}

// t clamped to [0, T] (NaN → 0) and whether t itself lies in [0, T]
double clamp_quintic_time(double t, double T, bool& inside) noexcept {
  inside = t >= 0.0 && t <= T;
  if (t >= T) return T;
  return t > 0.0 ? t : 0.0;
}

// max |p(t)| over [0, T] for a polynomial in t: at the roots of p′ and at the ends
double quintic_peak_abs(const polynomial::Poly& p, double T) {
  double peak =
      std::max(std::abs(polynomial::evaluate(p, 0.0)), std::abs(polynomial::evaluate(p, T)));
  for (double t : polynomial::real_roots(polynomial::derivative(p), 0.0, T))
    peak = std::max(peak, std::abs(polynomial::evaluate(p, t)));
  return peak;
}

void require_quintic_size(Eigen::Index expected, Eigen::Index got, const char* what) {
  if (got != expected)
    throw Error(std::string("quintic trajectory: ") + what + " must have " +
                std::to_string(expected) + " entries, got " + std::to_string(got));
}

}  // namespace

Quintic::Quintic(const State& start, const State& end, double duration) : duration_(duration) {
  require_finite_state(start, "start");
  require_finite_state(end, "end");
  if (!(duration >= 0.0) || !std::isfinite(duration))
    throw Error("quintic: duration must be ≥ 0 and finite, got " + number_text(duration) + " s");
  if (duration == 0.0) {
    if (start.p != end.p || start.v != end.v)
      throw Error(
          "quintic: a zero duration needs equal start and end positions and velocities "
          "(got p " +
          number_text(start.p) + " → " + number_text(end.p) + ", v " +
          number_text(start.v) + " → " + number_text(end.v) + ")");
    c_ = {end.p, end.v, 0.5 * end.a, 0.0, 0.0, 0.0};
    return;
  }
  c_ = quintic_coefficients(start, end, duration);
  // a duration far outside the scale of the boundary values overflows the coefficients (or
  // their evaluation): refuse it rather than return NaN later
  const double T = duration;
  const double scale = std::abs(start.p) + std::abs(end.p) +
                       (std::abs(start.v) + std::abs(end.v)) * T +
                       (std::abs(start.a) + std::abs(end.a)) * T * T;
  const Sample e = evaluate_quintic(c_.data(), T);
  const bool finite =
      std::all_of(c_.begin(), c_.end(), [](double c) { return std::isfinite(c); }) &&
      std::isfinite(scale) && std::isfinite(e.p) && std::isfinite(e.v) && std::isfinite(e.a) &&
      std::isfinite(e.j);
  if (!finite || std::abs(e.p - end.p) > 1e-9 * scale + 1e-300)
    throw Error("quintic: the duration " + number_text(T) +
                " s is out of scale with the boundary values (p " + number_text(start.p) +
                " → " + number_text(end.p) +
                "): its polynomial cannot be evaluated in double precision");
}

Quintic::Sample Quintic::at(double t) const noexcept {
  bool inside = false;
  Sample out = evaluate_quintic(c_.data(), clamp_quintic_time(t, duration_, inside));
  if (!inside) out.j = 0.0;
  return out;
}

Quintic::Peaks Quintic::peaks() const {
  const polynomial::Poly p(c_.begin(), c_.end());
  const polynomial::Poly v = polynomial::derivative(p);
  const polynomial::Poly a = polynomial::derivative(v);
  Peaks out;
  out.velocity = quintic_peak_abs(v, duration_);
  out.acceleration = quintic_peak_abs(a, duration_);
  out.jerk = duration_ > 0.0 ? quintic_peak_abs(polynomial::derivative(a), duration_) : 0.0;
  return out;
}

QuinticTrajectory::QuinticTrajectory(const State& start, const State& end, double duration)
    : duration_(duration) {
  const Eigen::Index n = start.q.size();
  if (n == 0) throw Error("quintic trajectory: no joints (start q is empty)");
  require_quintic_size(n, start.qd.size(), "start qd");
  require_quintic_size(n, start.qdd.size(), "start qdd");
  require_quintic_size(n, end.q.size(), "end q");
  require_quintic_size(n, end.qd.size(), "end qd");
  require_quintic_size(n, end.qdd.size(), "end qdd");
  coefficients_.resize(n, 6);
  for (Eigen::Index i = 0; i < n; ++i) {
    try {
      const Quintic joint({start.q[i], start.qd[i], start.qdd[i]},
                          {end.q[i], end.qd[i], end.qdd[i]}, duration);
      for (int k = 0; k < 6; ++k) coefficients_(i, k) = joint.coefficients()[k];
    } catch (const Error& e) {
      throw Error("quintic trajectory, joint " + std::to_string(i) + ": " + e.what());
    }
  }
}

QuinticTrajectory QuinticTrajectory::to_rest(const State& start, const Eigen::VectorXd& goal,
                                             double duration) {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(goal.size());
  return QuinticTrajectory(start, {goal, zero, zero}, duration);
}

Quintic QuinticTrajectory::joint(Eigen::Index i) const {
  if (i < 0 || i >= size())
    throw Error("quintic trajectory: joint " + std::to_string(i) + " out of range (0 … " +
                std::to_string(size() - 1) + ")");
  // rebuild the scalar quintic from its boundary values (the same formulas give it back)
  const Eigen::Matrix<double, 1, 6> row = coefficients_.row(i);
  const Quintic::Sample a = evaluate_quintic(row.data(), 0.0);
  const Quintic::Sample b = evaluate_quintic(row.data(), duration_);
  return Quintic({a.p, a.v, a.a}, {b.p, b.v, b.a}, duration_);
}

void QuinticTrajectory::at(double t, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> qd,
                           Eigen::Ref<Eigen::VectorXd> qdd) const {
  const Eigen::Index n = size();
  require_quintic_size(n, q.size(), "q");
  require_quintic_size(n, qd.size(), "qd");
  require_quintic_size(n, qdd.size(), "qdd");
  bool inside = false;
  const double tc = clamp_quintic_time(t, duration_, inside);
  const auto& c = coefficients_;
  q = c.col(0) +
      tc * (c.col(1) + tc * (c.col(2) + tc * (c.col(3) + tc * (c.col(4) + tc * c.col(5)))));
  qd = c.col(1) +
       tc * (2.0 * c.col(2) + tc * (3.0 * c.col(3) + tc * (4.0 * c.col(4) + tc * 5.0 * c.col(5))));
  qdd = 2.0 * c.col(2) + tc * (6.0 * c.col(3) + tc * (12.0 * c.col(4) + tc * 20.0 * c.col(5)));
}

void QuinticTrajectory::at(double t, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> qd,
                           Eigen::Ref<Eigen::VectorXd> qdd,
                           Eigen::Ref<Eigen::VectorXd> qddd) const {
  at(t, q, qd, qdd);
  require_quintic_size(size(), qddd.size(), "qddd");
  bool inside = false;
  const double tc = clamp_quintic_time(t, duration_, inside);
  if (!inside) {
    qddd.setZero();
    return;
  }
  const auto& c = coefficients_;
  qddd = 6.0 * c.col(3) + tc * (24.0 * c.col(4) + tc * 60.0 * c.col(5));
}

void Quintic::at(double t, TrajectorySample& sample) const {
  sample.resize(1);
  const Sample s = at(t);
  sample.position[0] = s.p;
  sample.velocity[0] = s.v;
  sample.acceleration[0] = s.a;
  sample.jerk[0] = s.j;
}

void QuinticTrajectory::at(double t, TrajectorySample& sample) const {
  sample.resize(dofs());
  at(t, sample.position, sample.velocity, sample.acceleration, sample.jerk);
}

}  // namespace mjarm
