#include "mjarm/dynamics/momentum_observer.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <string>

#include "mjarm/error.hpp"

namespace mjarm {
namespace {

using Vec3Map = Eigen::Map<const Eigen::Vector3d>;

// spatial momentum [angular; linear] of one body about the com-frame origin, from MuJoCo's
// cinert (I_xx I_yy I_zz I_xy I_xz I_yz, m·c, m) and cvel [ω; v]:
// angular = I·ω + m·c × v, linear = m·v + ω × m·c
void body_momentum(const double* inert, const double* vel, double* out) {
  Eigen::Matrix3d I;
  I << inert[0], inert[3], inert[4], inert[3], inert[1], inert[5], inert[4], inert[5], inert[2];
  const Vec3Map mc(inert + 6);
  const Vec3Map w(vel);
  const Vec3Map v(vel + 3);
  Eigen::Map<Eigen::Vector3d> angular(out);
  Eigen::Map<Eigen::Vector3d> linear(out + 3);
  angular = I * w + mc.cross(v);
  linear = inert[9] * v + w.cross(mc);
}

}  // namespace

void coriolis_transpose_velocity(const Chain& chain, const mjData& d, double* body_momentum_work,
                                 Eigen::Ref<Eigen::VectorXd> out) noexcept {
  const mjModel& m = chain.robot().model();
  // each body's momentum, then children added into parents (bodies are stored parents first)
  for (int b = 0; b < m.nbody; ++b)
    body_momentum(d.cinert + 10 * b, d.cvel + 6 * b, body_momentum_work + 6 * b);
  for (int b = m.nbody - 1; b > 0; --b) {
    const int parent = m.body_parentid[b];
    for (int k = 0; k < 6; ++k) body_momentum_work[6 * parent + k] += body_momentum_work[6 * b + k];
  }
  // (Cᵀq̇)_i = Ṡ_i · H_i: d/dt (S_i·H_i) = Ṡ_i·H_i + S_i·Ḣ_i and S_i·Ḣ_i = τ_i − g_i
  for (int i = 0; i < chain.size(); ++i) {
    const int dof = chain.dof_address(i);
    const int body = m.dof_bodyid[dof];
    double sum = 0.0;
    for (int k = 0; k < 6; ++k) sum += d.cdof_dot[6 * dof + k] * body_momentum_work[6 * body + k];
    out[i] = sum;
  }
}

void mass_derivative_velocity(const Chain& chain, const mjData& d, mjData& scratch, double* work,
                              Eigen::Ref<Eigen::VectorXd> out) noexcept {
  const mjModel& m = chain.robot().model();
  const int n = chain.size();
  double speed = 0.0;
  for (int i = 0; i < n; ++i) speed = std::max(speed, std::abs(d.qvel[chain.dof_address(i)]));
  if (speed == 0.0) {
    out.setZero();
    return;
  }
  const double eps = 1e-5 / speed;
  double* v = work;               // nv: q̇ on the chain dofs, zero elsewhere
  double* product = work + m.nv;  // nv: M·v
  std::fill(v, v + m.nv, 0.0);
  for (int i = 0; i < n; ++i) v[chain.dof_address(i)] = d.qvel[chain.dof_address(i)];
  out.setZero();
  for (const double sign : {1.0, -1.0}) {
    mju_copy(scratch.qpos, d.qpos, m.nq);
    for (int i = 0; i < n; ++i)
      scratch.qpos[chain.qpos_address(i)] += sign * eps * v[chain.dof_address(i)];
    mj_kinematics(&m, &scratch);
    mj_comPos(&m, &scratch);
    mj_crb(&m, &scratch);
    mj_mulM(&m, &scratch, product, v);
    for (int i = 0; i < n; ++i) out[i] += sign * product[chain.dof_address(i)];
  }
  out /= 2.0 * eps;
}

struct MomentumObserver::Solver {
  Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt;
};

MomentumObserver::MomentumObserver(const Chain& chain, const FrictionFeedForward& friction,
                                   MomentumObserverOptions options)
    : chain_(chain),
      friction_(friction),
      options_(options),
      n_(chain.size()),
      solver_(make_workspace<Solver>()) {
  check_fields(options_);
  if (friction_.size() != n_) {
    throw Error("momentum observer: the friction model has " + std::to_string(friction_.size()) +
                " dofs, the chain " + std::to_string(n_));
  }
  const mjModel& m = chain_.robot().model();
  for (Channel* c : {&all_, &contact_}) {
    c->p_hat = Eigen::VectorXd::Zero(n_);
    c->integral = Eigen::VectorXd::Zero(n_);
    c->r = Eigen::VectorXd::Zero(n_);
  }
  for (Eigen::VectorXd* v : {&p_, &beta_, &ctv_, &mdv_, &e_, &input_, &passive_})
    *v = Eigen::VectorXd::Zero(n_);
  if (options_.coriolis == CoriolisMethod::directional_difference) {
    scratch_ = chain_.robot().make_data();
    work_.assign(static_cast<std::size_t>(2 * m.nv), 0.0);
  } else {
    work_.assign(static_cast<std::size_t>(6 * m.nbody), 0.0);
  }
  JJt_.setIdentity();
  solver_->ldlt.compute(JJt_);
}

MomentumObserver::MomentumObserver(const Chain& chain, MomentumObserverOptions options)
    : MomentumObserver(chain, FrictionFeedForward(chain), options) {}

MomentumObserver::~MomentumObserver() = default;
MomentumObserver::MomentumObserver(MomentumObserver&& other) noexcept = default;
MomentumObserver& MomentumObserver::operator=(MomentumObserver&& other) noexcept = default;

void MomentumObserver::reset() noexcept {
  started_ = false;
  for (Channel* c : {&all_, &contact_}) {
    c->integral.setZero();
    c->r.setZero();
  }
  wrench_.setZero();
  contact_wrench_.setZero();
}

void MomentumObserver::step_channel(Channel& c, const Eigen::VectorXd& input, double dt) noexcept {
  const double limit = options_.integral_limit;
  e_ = p_ - c.p_hat;
  c.integral = (c.integral + dt * e_).cwiseMax(-limit).cwiseMin(limit);
  c.r = options_.kp * e_ + options_.ki * c.integral;
  c.p_hat += dt * (input - beta_ + c.r);
}

ObserverStatus MomentumObserver::update(const mjData& d, const ChainDynamics& dynamics,
                                        const Eigen::Ref<const Eigen::VectorXd>& tau,
                                        double dt) noexcept {
  if (!(dt > 0.0) || !std::isfinite(dt) || tau.size() != n_ || !tau.allFinite())
    return ObserverStatus::bad_input;

  // p = M·q̇ and β = g − Cᵀ·q̇
  const Eigen::VectorXd& qd = dynamics.qd();
  p_.noalias() = dynamics.mass_matrix() * qd;
  if (options_.coriolis == CoriolisMethod::subtree_momentum) {
    coriolis_transpose_velocity(chain_, d, work_.data(), ctv_);
  } else {
    mass_derivative_velocity(chain_, d, *scratch_, work_.data(), mdv_);
    ctv_ = mdv_ - (dynamics.bias() - dynamics.gravity());
  }
  beta_ = dynamics.gravity() - ctv_;
  if (!p_.allFinite() || !beta_.allFinite()) return ObserverStatus::non_finite;
  if (!started_) {
    all_.p_hat = p_;
    contact_.p_hat = p_;
    started_ = true;
  }

  // both channels: r sees every disturbance, r_c has the modelled friction and damping as input
  input_ = tau;
  step_channel(all_, input_, dt);
  friction_.model_force(qd, passive_);
  input_ += passive_;
  step_channel(contact_, input_, dt);

  // F̂ = (J·Jᵀ + εI)⁻¹·J·r
  const Matrix6Xd& J = dynamics.jacobian();
  JJt_.noalias() = J * J.transpose();
  JJt_.diagonal().array() += options_.wrench_damping;
  solver_->ldlt.compute(JJt_);
  wrench_.noalias() = J * all_.r;
  wrench_ = solver_->ldlt.solve(wrench_);
  contact_wrench_.noalias() = J * contact_.r;
  contact_wrench_ = solver_->ldlt.solve(contact_wrench_);
  return ObserverStatus::ok;
}

}  // namespace mjarm
