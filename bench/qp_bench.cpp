// DenseQp and BoxQp timings.
//
// Protocol (also printed in each benchmark's label):
//   sizes n/m = 7/42, 14/100, 30/200: n variables, m two-sided general rows l ≤ Cx ≤ u, plus
//   simple bounds lb ≤ x ≤ ub on every variable; no equality rows.
//   16 seeded random problems per size: H = MᵀM/n + I (M Gaussian; well conditioned), g ~ N(0, 3²),
//   unit-norm Gaussian rows with limits −1.5(0.5 + U) ≤ Cx ≤ 1.5(0.5 + U), bounds alike
//   (U uniform on [0, 1]; x = 0 is strictly feasible); the "active" counter reports how many
//   constraints are active at the solution (about 60 % of n: 4.6 of 7, 7.9 of 14, 18.7 of 30),
//   "iters" the Goldfarb–Idnani steps per solve.
//   cold: set_hessian (so the Cholesky factorization is timed) + solve(QpStart::cold).
//   warm: each iteration alternates between the base problem and a copy with g, l, u, lb, ub
//   perturbed by 1 % (additive Gaussian, 0.01 × their typical magnitude); set_gradient +
//   set_inequality_limits + set_bounds + solve(QpStart::warm) from the other copy's solution.
//   box (BoxQp vs DenseQp on the differential-IK problem, include/mjarm/ik/diff_ik.hpp): n = 7,
//   bounds only. 16 seeded problems H = JᵀJ + 1e-6·I (J 6×7 Gaussian, σ = 0.5: a pose task),
//   g = −Jᵀ·50·e (e ~ N(0, 0.03²): the error removed in one 0.02 s step), bounds ±v_max with
//   v_max = 2.175 (joints 0–3) and 2.61 rad/s (4–6), the panda's speed limits, so the box is
//   active on several joints; each has a second copy with J and e perturbed by 5 %.
//   cold: set_hessian + set_gradient + set_bounds + solve(cold). warm: the same alternating
//   between the two copies, solve(warm) (what DiffIk::step does every control step).
//   Timed per solve, problems cycled round-robin. Run e.g.
//     bench_qp --benchmark_min_time=0.2

#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <random>
#include <string>
#include <vector>

#include "mjarm/qp/box_qp.hpp"
#include "mjarm/qp/dense_qp.hpp"

namespace {

using mjarm::qp::BoxQp;
using mjarm::qp::DenseQp;
using mjarm::qp::QpStart;
using mjarm::qp::QpStatus;

struct Instance {
  Eigen::MatrixXd H, C;
  Eigen::VectorXd g[2], l[2], u[2], lb[2], ub[2];  // [0] base, [1] perturbed by 1 %
};

std::vector<Instance> make_instances(int n, int m, int count) {
  std::mt19937 rng(12345 + n);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  auto gauss = [&](int rows, int cols) {
    return Eigen::MatrixXd(Eigen::MatrixXd::NullaryExpr(rows, cols, [&] { return normal(rng); }));
  };
  const double width = 1.5, g_scale = 3.0, delta = 0.01;
  std::vector<Instance> out(count);
  for (Instance& in : out) {
    const Eigen::MatrixXd M = gauss(n, n);
    in.H = M.transpose() * M / n + Eigen::MatrixXd::Identity(n, n);
    in.C = gauss(m, n);
    in.C.rowwise().normalize();
    in.g[0] = g_scale * gauss(n, 1);
    in.l[0].resize(m);
    in.u[0].resize(m);
    for (int i = 0; i < m; ++i) {
      in.l[0][i] = -width * (0.5 + uni(rng));
      in.u[0][i] = width * (0.5 + uni(rng));
    }
    in.lb[0].resize(n);
    in.ub[0].resize(n);
    for (int j = 0; j < n; ++j) {
      in.lb[0][j] = -width * (0.5 + uni(rng));
      in.ub[0][j] = width * (0.5 + uni(rng));
    }
    in.g[1] = in.g[0] + delta * g_scale * gauss(n, 1);
    in.l[1] = in.l[0] + delta * width * gauss(m, 1);
    in.u[1] = in.u[0] + delta * width * gauss(m, 1);
    in.lb[1] = in.lb[0] + delta * width * gauss(n, 1);
    in.ub[1] = in.ub[0] + delta * width * gauss(n, 1);
  }
  return out;
}

std::vector<DenseQp> make_solvers(const std::vector<Instance>& instances, int n, int m) {
  std::vector<DenseQp> solvers;
  solvers.reserve(instances.size());
  for (const Instance& in : instances) {
    solvers.emplace_back(n, 0, m);
    DenseQp& qp = solvers.back();
    qp.set_hessian(in.H);
    qp.set_gradient(in.g[0]);
    qp.set_inequalities(in.C, in.l[0], in.u[0]);
    qp.set_bounds(in.lb[0], in.ub[0]);
  }
  return solvers;
}

std::string label(int n, int m, const char* mode) {
  return "n=" + std::to_string(n) + " m=" + std::to_string(m) +
         " two-sided rows + bounds; 16 seeded problems H=M'M/n+I, g=3N(0,1), unit rows, limits "
         "+-1.5(0.5+U); " +
         mode;
}

void BM_QpCold(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), m = static_cast<int>(state.range(1));
  const std::vector<Instance> instances = make_instances(n, m, 16);
  std::vector<DenseQp> solvers = make_solvers(instances, n, m);
  size_t k = 0;
  double iterations = 0.0, active = 0.0, failures = 0.0, solves = 0.0;
  for (auto _ : state) {
    DenseQp& qp = solvers[k];
    qp.set_hessian(instances[k].H);  // marks H stale: the Cholesky factor is part of the timing
    const auto& r = qp.solve(QpStart::cold);
    benchmark::DoNotOptimize(r.x.data());
    iterations += r.iterations;
    active += qp.active_count();
    failures += r.status != QpStatus::solved;
    solves += 1.0;
    k = (k + 1) % solvers.size();
  }
  state.counters["iters"] = iterations / solves;
  state.counters["active"] = active / solves;
  state.counters["failed"] = failures;
  state.SetLabel(label(n, m, "cold start incl. Cholesky"));
}

void BM_QpWarm(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), m = static_cast<int>(state.range(1));
  const std::vector<Instance> instances = make_instances(n, m, 16);
  std::vector<DenseQp> solvers = make_solvers(instances, n, m);
  for (DenseQp& qp : solvers) qp.solve(QpStart::cold);
  std::vector<int> side(solvers.size(), 0);
  size_t k = 0;
  double iterations = 0.0, active = 0.0, failures = 0.0, solves = 0.0;
  for (auto _ : state) {
    DenseQp& qp = solvers[k];
    const Instance& in = instances[k];
    const int s = side[k] = 1 - side[k];  // alternate base and 1 % perturbed copy
    qp.set_gradient(in.g[s]);
    qp.set_inequality_limits(in.l[s], in.u[s]);
    qp.set_bounds(in.lb[s], in.ub[s]);
    const auto& r = qp.solve(QpStart::warm);
    benchmark::DoNotOptimize(r.x.data());
    iterations += r.iterations;
    active += qp.active_count();
    failures += r.status != QpStatus::solved;
    solves += 1.0;
    k = (k + 1) % solvers.size();
  }
  state.counters["iters"] = iterations / solves;
  state.counters["active"] = active / solves;
  state.counters["failed"] = failures;
  state.SetLabel(label(n, m, "warm start after 1% change of g and limits"));
}

BENCHMARK(BM_QpCold)->Args({7, 42})->Args({14, 100})->Args({30, 200})->Unit(
    benchmark::kMicrosecond);
BENCHMARK(BM_QpWarm)->Args({7, 42})->Args({14, 100})->Args({30, 200})->Unit(
    benchmark::kMicrosecond);

// ---- BoxQp vs DenseQp on differential-IK problems ----

struct BoxInstance {
  Eigen::MatrixXd H[2];
  Eigen::VectorXd g[2];
  Eigen::VectorXd lb, ub;
};

std::vector<BoxInstance> make_box_instances(int count) {
  constexpr int n = 7;
  std::mt19937 rng(777);
  std::normal_distribution<double> normal(0.0, 1.0);
  auto gauss = [&](int rows, int cols, double sigma) {
    return Eigen::MatrixXd(
        Eigen::MatrixXd::NullaryExpr(rows, cols, [&] { return sigma * normal(rng); }));
  };
  std::vector<BoxInstance> out(count);
  for (BoxInstance& in : out) {
    const Eigen::MatrixXd J = gauss(6, n, 0.5);
    const Eigen::VectorXd e = gauss(6, 1, 0.03);
    for (int s = 0; s < 2; ++s) {
      const Eigen::MatrixXd Js = s == 0 ? J : Eigen::MatrixXd(J + 0.05 * gauss(6, n, 0.5));
      const Eigen::VectorXd es = s == 0 ? e : Eigen::VectorXd(e + 0.05 * gauss(6, 1, 0.03));
      in.H[s] = Js.transpose() * Js + 1e-6 * Eigen::MatrixXd::Identity(n, n);
      in.g[s] = -Js.transpose() * (50.0 * es);
    }
    in.ub.resize(n);
    for (int j = 0; j < n; ++j) in.ub[j] = j < 4 ? 2.175 : 2.61;
    in.lb = -in.ub;
  }
  return out;
}

template <class Solver>
Solver make_box_solver();
template <>
BoxQp make_box_solver<BoxQp>() {
  return BoxQp(7);
}
template <>
DenseQp make_box_solver<DenseQp>() {
  return DenseQp(7, 0, 0);
}

int active_at(const Eigen::VectorXd& x, const BoxInstance& in) {
  int count = 0;
  for (int j = 0; j < 7; ++j) count += x[j] - in.lb[j] < 1e-9 || in.ub[j] - x[j] < 1e-9;
  return count;
}

template <class Solver>
void BM_BoxDiffIk(benchmark::State& state) {
  const bool warm = state.range(0) != 0;
  const std::vector<BoxInstance> instances = make_box_instances(16);
  std::vector<Solver> solvers;
  for (size_t k = 0; k < instances.size(); ++k) solvers.push_back(make_box_solver<Solver>());
  std::vector<int> side(solvers.size(), 0);
  size_t k = 0;
  double iterations = 0.0, active = 0.0, failures = 0.0, solves = 0.0;
  for (auto _ : state) {
    Solver& qp = solvers[k];
    const BoxInstance& in = instances[k];
    const int s = side[k] = 1 - side[k];
    qp.set_hessian(in.H[s]);
    qp.set_gradient(in.g[s]);
    qp.set_bounds(in.lb, in.ub);
    const auto& r = qp.solve(warm ? QpStart::warm : QpStart::cold);
    benchmark::DoNotOptimize(r.x.data());
    iterations += r.iterations;
    active += active_at(r.x, in);
    failures += r.status != QpStatus::solved;
    solves += 1.0;
    k = (k + 1) % solvers.size();
  }
  state.counters["iters"] = iterations / solves;
  state.counters["active"] = active / solves;
  state.counters["failed"] = failures;
  state.SetLabel(
      std::string("n=7 box only, DiffIk-like H=J'J+1e-6 I, g=-J'50e, panda speed box; ") +
      (warm ? "warm, alternating two copies (5 % apart)" : "cold") +
      ", set_hessian+set_gradient+set_bounds+solve");
}

BENCHMARK(BM_BoxDiffIk<BoxQp>)->Arg(0)->Arg(1)->Unit(benchmark::kNanosecond);
BENCHMARK(BM_BoxDiffIk<DenseQp>)->Arg(0)->Arg(1)->Unit(benchmark::kNanosecond);

}  // namespace
