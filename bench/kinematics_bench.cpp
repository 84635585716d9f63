// Forward kinematics and frame Jacobian: mjarm's ChainKinematics against MuJoCo's own pipeline.
//
// Protocol (also printed at start-up and in every benchmark's label):
// - Scenes: the bundled panda (7 DoF, site attachment_site) and ur5e (6 DoF, attachment_site),
//   each as shipped and with 50 extra free-floating boxes. The boxes are added here: the bundled
//   XML text gets a <worldbody> with 50 <body><freejoint/><geom type="box"/></body> inserted
//   before its first <include>, so the boxes come first in body and qpos order (the arm's qpos
//   addresses shift by 350); keyframes are dropped (their qpos no longer fits).
// - Inputs: 1024 configurations drawn once per scene with JointSampler (uniform within the joint
//   limits, std::mt19937_64 seed 2024), cycled in order; one iteration = one configuration.
// - Cases, each timed for ours and for MuJoCo in the same process:
//     FK      ours: ChainKinematics::update(q)
//             MuJoCo: Chain::scatter(q → qpos) + mj_kinematics
//     Jac     at one configuration already propagated (the cost does not depend on q's values)
//             ours: ChainKinematics::jacobian (6×n, world-aligned)
//             MuJoCo: mj_jacSite (3×nv + 3×nv, needs mj_kinematics + mj_comPos done)
//     FK+Jac  ours: update(q) + jacobian
//             MuJoCo: scatter + mj_kinematics + mj_comPos + mj_jacSite
// - Before timing, both are checked to agree (pose and Jacobian columns to 1e-10) on 64 of the
//   configurations; the program aborts otherwise.
// - After the runs, a summary prints CPU time per call and the ratio ours / MuJoCo per case, and
//   ours with 50 boxes / ours as shipped (scene-size independence).
// Run: build-<you>/bench_kinematics [--benchmark_min_time=0.5]

#include <benchmark/benchmark.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/kinematics/workspace.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"

namespace {

constexpr int kConfigurations = 1024;
constexpr int kExtraBodies = 50;
constexpr std::uint64_t kSeed = 2024;

/// The bundled model's XML with @p extra free boxes inserted and its keyframes removed.
std::string scene_xml(const std::string& model, int extra) {
  std::ifstream in(std::string(MJARM_MODELS_DIR) + "/" + model + ".xml");
  std::stringstream text;
  text << in.rdbuf();
  std::string xml =
      std::regex_replace(text.str(), std::regex("<keyframe>[\\s\\S]*?</keyframe>"), "");
  std::string boxes = "<worldbody>\n";
  for (int i = 0; i < extra; ++i) {
    // a 10 × 5 grid of boxes beside the arm, out of its way
    char body[256];
    std::snprintf(body, sizeof(body),
                  "  <body name=\"box%d\" pos=\"%.2f %.2f 0.5\"><freejoint/>"
                  "<geom type=\"box\" size=\"0.02 0.02 0.02\"/></body>\n",
                  i, 1.5 + 0.1 * (i % 10), -0.25 + 0.1 * (i / 10));
    boxes += body;
  }
  boxes += "</worldbody>\n";
  // before the arm's own bodies when it includes them, else at the end of the model
  std::size_t at = xml.find("<include");
  if (at == std::string::npos) at = xml.rfind("</mujoco>");
  xml.insert(at, boxes);
  return xml;
}

/// One scene: the robot, ours, MuJoCo's data, and the shared configurations.
struct Scene {
  std::string label;
  mjarm::Robot robot;
  mjarm::Chain chain;
  mjarm::ChainKinematics kin;
  mjarm::DataPtr data;
  int site = 0;
  std::vector<Eigen::VectorXd> qs;
  mjarm::Matrix6Xd J;
  std::vector<double> jacp, jacr;

  Scene(std::string name, mjarm::Robot r, const std::string& frame)
      : label(std::move(name)),
        robot(std::move(r)),
        chain(robot, frame),
        kin(chain),
        data(robot.make_data()),
        site(robot.site(frame)),
        J(6, chain.size()),
        jacp(3 * robot.nv()),
        jacr(3 * robot.nv()) {
    const mjarm::JointSampler sampler(chain);
    std::mt19937_64 rng(kSeed);
    qs.assign(kConfigurations, Eigen::VectorXd(chain.size()));
    for (auto& q : qs) sampler.sample(rng, q);
  }

  std::string description() const {
    const mjModel& m = robot.model();
    return "nbody=" + std::to_string(m.nbody) + " nv=" + std::to_string(m.nv) + ", " +
           std::to_string(kConfigurations) + " seeded q cycled";
  }

  void mujoco_fk(const Eigen::VectorXd& q) {
    chain.scatter(q, data->qpos);
    mj_kinematics(&robot.model(), data.get());
  }
  void mujoco_fk_jacobian(const Eigen::VectorXd& q) {
    mujoco_fk(q);
    mj_comPos(&robot.model(), data.get());
    mj_jacSite(&robot.model(), data.get(), jacp.data(), jacr.data(), site);
  }

  /// Aborts unless ours and MuJoCo agree on pose and Jacobian.
  void verify() {
    const int nv = robot.nv();
    for (int k = 0; k < 64; ++k) {
      const mjarm::Pose& X = kin.update(qs[k]);
      kin.jacobian(J);
      mujoco_fk_jacobian(qs[k]);
      double error = 0.0;
      for (int i = 0; i < 3; ++i) {
        error = std::max(error, std::abs(X.p[i] - data->site_xpos[3 * site + i]));
        for (int j = 0; j < 3; ++j)
          error = std::max(error, std::abs(X.R(i, j) - data->site_xmat[9 * site + 3 * i + j]));
        for (int c = 0; c < chain.size(); ++c) {
          const int dof = chain.dof_address(c);
          error = std::max(error, std::abs(J(i, c) - jacp[i * nv + dof]));
          error = std::max(error, std::abs(J(3 + i, c) - jacr[i * nv + dof]));
        }
      }
      if (error > 1e-10) {
        std::fprintf(stderr, "%s: ours and MuJoCo disagree by %g at configuration %d\n",
                     label.c_str(), error, k);
        std::abort();
      }
    }
  }
};

std::vector<std::unique_ptr<Scene>> make_scenes() {
  std::vector<std::unique_ptr<Scene>> scenes;
  for (const std::string model : {"panda", "ur5e"}) {
    scenes.push_back(
        std::make_unique<Scene>(model, mjarm::Robot::bundled(model), "attachment_site"));
    scenes.push_back(std::make_unique<Scene>(
        model + "+50boxes",
        mjarm::Robot::from_string(scene_xml(model, kExtraBodies), MJARM_MODELS_DIR),
        "attachment_site"));
  }
  for (auto& scene : scenes) scene->verify();
  return scenes;
}

void register_benchmarks(Scene& s) {
  const std::string info = s.description();
  benchmark::RegisterBenchmark((s.label + "/FK/ours").c_str(), [&s, info](benchmark::State& state) {
    std::size_t i = 0;
    for (auto _ : state) {
      benchmark::DoNotOptimize(s.kin.update(s.qs[i]).p.data());
      i = (i + 1) % kConfigurations;
    }
    state.SetLabel("ours: update(q); " + info);
  });
  benchmark::RegisterBenchmark((s.label + "/FK/mujoco").c_str(),
                               [&s, info](benchmark::State& state) {
                                 std::size_t i = 0;
                                 for (auto _ : state) {
                                   s.mujoco_fk(s.qs[i]);
                                   benchmark::DoNotOptimize(s.data->site_xpos);
                                   i = (i + 1) % kConfigurations;
                                 }
                                 state.SetLabel("mujoco: scatter+mj_kinematics; " + info);
                               });
  benchmark::RegisterBenchmark((s.label + "/Jac/ours").c_str(),
                               [&s, info](benchmark::State& state) {
                                 s.kin.update(s.qs[0]);
                                 for (auto _ : state) {
                                   s.kin.jacobian(s.J);
                                   benchmark::DoNotOptimize(s.J.data());
                                   benchmark::ClobberMemory();
                                 }
                                 state.SetLabel("ours: jacobian() at q[0]; " + info);
                               });
  benchmark::RegisterBenchmark(
      (s.label + "/Jac/mujoco").c_str(), [&s, info](benchmark::State& state) {
        s.mujoco_fk_jacobian(s.qs[0]);
        for (auto _ : state) {
          mj_jacSite(&s.robot.model(), s.data.get(), s.jacp.data(), s.jacr.data(), s.site);
          benchmark::DoNotOptimize(s.jacp.data());
          benchmark::ClobberMemory();
        }
        state.SetLabel("mujoco: mj_jacSite at q[0]; " + info);
      });
  benchmark::RegisterBenchmark((s.label + "/FK+Jac/ours").c_str(),
                               [&s, info](benchmark::State& state) {
                                 std::size_t i = 0;
                                 for (auto _ : state) {
                                   s.kin.update(s.qs[i]);
                                   s.kin.jacobian(s.J);
                                   benchmark::DoNotOptimize(s.J.data());
                                   benchmark::ClobberMemory();
                                   i = (i + 1) % kConfigurations;
                                 }
                                 state.SetLabel("ours: update(q)+jacobian(); " + info);
                               });
  benchmark::RegisterBenchmark(
      (s.label + "/FK+Jac/mujoco").c_str(), [&s, info](benchmark::State& state) {
        std::size_t i = 0;
        for (auto _ : state) {
          s.mujoco_fk_jacobian(s.qs[i]);
          benchmark::DoNotOptimize(s.jacp.data());
          benchmark::ClobberMemory();
          i = (i + 1) % kConfigurations;
        }
        state.SetLabel("mujoco: scatter+mj_kinematics+mj_comPos+mj_jacSite; " + info);
      });
}

/// Prints the usual console table and keeps each run's CPU time per iteration [ns].
class SummaryReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      if (run.run_type != Run::RT_Iteration || run.error_occurred) continue;
      const double ns = run.GetAdjustedCPUTime() *
                        benchmark::GetTimeUnitMultiplier(benchmark::kNanosecond) /
                        benchmark::GetTimeUnitMultiplier(run.time_unit);
      cpu_ns_[run.benchmark_name()] = ns;
    }
  }
  double ns(const std::string& name) const {
    const auto it = cpu_ns_.find(name);
    return it == cpu_ns_.end() ? std::nan("") : it->second;
  }

 private:
  std::map<std::string, double> cpu_ns_;
};

void print_summary(const SummaryReporter& r, const std::vector<std::unique_ptr<Scene>>& scenes) {
  std::printf("\nsummary: CPU time per call [ns], ratio ours / MuJoCo (< 1: ours is faster)\n");
  std::printf("  %-18s %-7s %10s %10s %8s\n", "scene", "case", "ours", "mujoco", "ratio");
  for (const auto& s : scenes) {
    for (const std::string c : {"FK", "Jac", "FK+Jac"}) {
      const double ours = r.ns(s->label + "/" + c + "/ours");
      const double theirs = r.ns(s->label + "/" + c + "/mujoco");
      if (std::isnan(ours) || std::isnan(theirs)) continue;
      std::printf("  %-18s %-7s %10.1f %10.1f %8.3f\n", s->label.c_str(), c.c_str(), ours, theirs,
                  ours / theirs);
    }
  }
  std::printf("scene-size independence: ours with %d extra free bodies / ours as shipped\n",
              kExtraBodies);
  for (const std::string model : {"panda", "ur5e"}) {
    for (const std::string c : {"FK", "Jac", "FK+Jac"}) {
      const double plain = r.ns(model + "/" + c + "/ours");
      const double big = r.ns(model + "+50boxes/" + c + "/ours");
      if (std::isnan(plain) || std::isnan(big)) continue;
      std::printf("  %-18s %-7s %8.3f   (MuJoCo: %.3f)\n", model.c_str(), c.c_str(), big / plain,
                  r.ns(model + "+50boxes/" + c + "/mujoco") / r.ns(model + "/" + c + "/mujoco"));
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  std::printf(
      "protocol: %d configurations per scene (JointSampler, mt19937_64 seed %llu), cycled, one per "
      "iteration;\n  FK = ours update(q) vs scatter+mj_kinematics; Jac = ours jacobian() vs "
      "mj_jacSite at a "
      "propagated q;\n  FK+Jac = ours update+jacobian vs "
      "scatter+mj_kinematics+mj_comPos+mj_jacSite; "
      "'+50boxes' adds %d free bodies.\n",
      kConfigurations, static_cast<unsigned long long>(kSeed), kExtraBodies);
  const auto scenes = make_scenes();
  std::printf("verified: ours and MuJoCo agree to 1e-10 on 64 configurations of every scene\n\n");
  for (const auto& scene : scenes) register_benchmarks(*scene);
  SummaryReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  print_summary(reporter, scenes);
  benchmark::Shutdown();
  return 0;
}
