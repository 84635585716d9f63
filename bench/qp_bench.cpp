// DenseQp timings.
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
//   Timed per solve, problems cycled round-robin. Run e.g.
//     bench_qp --benchmark_min_time=0.2

#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <random>
#include <string>
#include <vector>

#include "mjarm/qp/dense_qp.hpp"

namespace {

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

}  // namespace
