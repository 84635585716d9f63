// Pinocchio against mjarm in C++: forward kinematics, frame Jacobian, inverse dynamics (RNEA) and
// the joint-space inertia (CRBA) on the same arm, at the same configurations, both in this one
// process, compiled with the same compiler, flags and Eigen (Pinocchio's algorithms are
// header-only templates; its headers come from the `pin` wheel).
//
// Run by bench/peers/pinocchio_side_by_side.py, which writes the input (--input=PATH, JSON): per
// robot, the bundled model's name and frame, the Pinocchio model that pin.buildModelFromMJCF made
// from the same MJCF (joint by joint: parent, type, placement, inertia, armature; the frame's
// parent joint and placement; gravity) and the configurations (q, v, a). This program rebuilds
// that model, checks that both libraries agree on every configuration before timing (pose,
// world-aligned Jacobian, τ, M: largest absolute difference, written into the benchmark
// context as "agreement/<robot>"; exits 1 above --tolerance), then times per call, cycling the
// configurations in order (one iteration = one configuration):
//   fk           mjarm: ChainKinematics::update(q)
//                Pinocchio: forwardKinematics(q) + updateFramePlacement(frame)
//   fk_jacobian  mjarm: update(q) + jacobian(world_aligned)
//                Pinocchio: computeFrameJacobian(q, frame, LOCAL_WORLD_ALIGNED) (computes the
//                poses on the frame's support itself)
//   rnea         mjarm: q, v into qpos, qvel; mj_kinematics, mj_comPos, mj_makeM, mj_comVel,
//                mj_rne (bias) — the MuJoCo stages ChainDynamics reads —, then
//                ChainDynamics::inverse_dynamics (τ = M·q̈ + h)
//                Pinocchio: rnea(q, v, a)
//   crba         mjarm: q into qpos; mj_kinematics, mj_comPos, mj_makeM, ChainDynamics::update
//                (which reads M, and h, g, J, J̇q̇ with it)
//                Pinocchio: crba(q) (Convention::LOCAL, the default; upper triangle)
//   rnea_state, crba_state  mjarm only: inverse_dynamics, resp. update, on a state MuJoCo has
//                already computed (what a controller pays inside a simulation step)
// Run: bench_peers_pinocchio --input=PATH [Google Benchmark flags]

#include <benchmark/benchmark.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <pinocchio/algorithm/crba.hpp>
#include <pinocchio/algorithm/frames.hpp>
#include <pinocchio/algorithm/jacobian.hpp>
#include <pinocchio/algorithm/kinematics.hpp>
#include <pinocchio/algorithm/rnea.hpp>
#include <pinocchio/multibody.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "mjarm/dynamics/chain_dynamics.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"

namespace {

using Json = nlohmann::json;

Eigen::VectorXd vector_of(const Json& j) {
  const std::vector<double> v = j.get<std::vector<double>>();
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

Eigen::Matrix3d matrix3_of(const Json& j) {  // 9 values, row-major
  const std::vector<double> v = j.get<std::vector<double>>();
  if (v.size() != 9) throw std::runtime_error("expected 9 values for a 3x3 matrix");
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(v.data());
}

pinocchio::SE3 placement_of(const Json& j) {
  return pinocchio::SE3(matrix3_of(j.at("R")), Eigen::Vector3d(vector_of(j.at("p"))));
}

pinocchio::JointModel joint_of(const Json& j) {
  const std::string type = j.at("type");
  if (type == "JointModelRX") return pinocchio::JointModelRX();
  if (type == "JointModelRY") return pinocchio::JointModelRY();
  if (type == "JointModelRZ") return pinocchio::JointModelRZ();
  if (type == "JointModelRevoluteUnaligned")
    return pinocchio::JointModelRevoluteUnaligned(Eigen::Vector3d(vector_of(j.at("axis"))));
  throw std::runtime_error("joint '" + j.at("name").get<std::string>() + "': type " + type +
                           " is not one this benchmark rebuilds (RX, RY, RZ, RevoluteUnaligned)");
}

/// One robot in both libraries, with the shared configurations.
struct Robot {
  std::string name;
  mjarm::Robot robot;
  mjarm::Chain chain;
  mjarm::ChainKinematics kin;
  mjarm::ChainDynamics dyn;
  mjarm::DataPtr data;
  mjarm::Matrix6Xd J;
  Eigen::VectorXd tau;
  pinocchio::Model model;
  std::unique_ptr<pinocchio::Data> pdata;
  pinocchio::FrameIndex frame = 0;
  pinocchio::Data::Matrix6x pJ;
  std::vector<Eigen::VectorXd> q, v, a;

  explicit Robot(const Json& j)
      : name(j.at("name")),
        robot(mjarm::Robot::bundled(name)),
        chain(robot, j.at("frame").get<std::string>()),
        kin(chain),
        dyn(chain),
        data(robot.make_data()),
        J(6, chain.size()),
        tau(chain.size()) {
    model.gravity.linear(vector_of(j.at("gravity")));
    for (const Json& joint : j.at("joints")) {
      const auto id = model.addJoint(joint.at("parent").get<pinocchio::JointIndex>(),
                                     joint_of(joint), placement_of(joint),
                                     joint.at("name").get<std::string>());
      model.appendBodyToJoint(id, pinocchio::Inertia(joint.at("mass").get<double>(),
                                                     vector_of(joint.at("lever")),
                                                     matrix3_of(joint.at("inertia"))));
      model.armature[model.idx_vs[id]] = joint.at("armature").get<double>();
    }
    frame = model.addFrame(pinocchio::Frame(j.at("frame").get<std::string>(),
                                            j.at("frame_joint").get<pinocchio::JointIndex>(),
                                            placement_of(j.at("frame_placement")),
                                            pinocchio::OP_FRAME));
    pdata = std::make_unique<pinocchio::Data>(model);
    pJ = pinocchio::Data::Matrix6x::Zero(6, model.nv);
    for (const Json& x : j.at("q")) q.push_back(vector_of(x));
    for (const Json& x : j.at("v")) v.push_back(vector_of(x));
    for (const Json& x : j.at("a")) a.push_back(vector_of(x));
    if (model.nv != chain.size() || robot.nv() != chain.size() || q.empty() ||
        q.size() != v.size() || q.size() != a.size() || q[0].size() != chain.size())
      throw std::runtime_error(name + ": the Pinocchio model, the chain and the configurations "
                               "must all have the chain's " + std::to_string(chain.size()) +
                               " joints (an arm alone in its model)");
  }

  // --- mjarm ---
  void set_state(const Eigen::VectorXd& qi, const Eigen::VectorXd* vi) {
    chain.scatter(qi, data->qpos);
    if (vi)
      for (int k = 0; k < chain.size(); ++k) data->qvel[chain.dof_address(k)] = (*vi)[k];
  }
  void mjarm_rnea(std::size_t i) {
    const mjModel& m = robot.model();
    set_state(q[i], &v[i]);
    mj_kinematics(&m, data.get());
    mj_comPos(&m, data.get());
    mj_makeM(&m, data.get());
    mj_comVel(&m, data.get());
    mj_rne(&m, data.get(), 0, data->qfrc_bias);
    dyn.inverse_dynamics(*data, a[i], tau);
  }
  void mjarm_crba(std::size_t i) {
    const mjModel& m = robot.model();
    set_state(q[i], nullptr);
    mj_kinematics(&m, data.get());
    mj_comPos(&m, data.get());
    mj_makeM(&m, data.get());
    dyn.update(*data);
  }

  /// Largest absolute differences over every configuration: pose, Jacobian, τ, M.
  std::vector<double> agreement() {
    std::vector<double> worst(4, 0.0);
    for (std::size_t i = 0; i < q.size(); ++i) {
      const mjarm::Pose& X = kin.update(q[i]);
      kin.jacobian(J);
      pinocchio::forwardKinematics(model, *pdata, q[i]);
      const pinocchio::SE3& pX = pinocchio::updateFramePlacement(model, *pdata, frame);
      worst[0] = std::max({worst[0], (X.p - pX.translation()).cwiseAbs().maxCoeff(),
                           (X.R - pX.rotation()).cwiseAbs().maxCoeff()});
      pinocchio::computeFrameJacobian(model, *pdata, q[i], frame, pinocchio::LOCAL_WORLD_ALIGNED, pJ);
      worst[1] = std::max(worst[1], (J - pJ).cwiseAbs().maxCoeff());
      mjarm_rnea(i);
      pinocchio::rnea(model, *pdata, q[i], v[i], a[i]);
      worst[2] = std::max(worst[2], (tau - pdata->tau).cwiseAbs().maxCoeff());
      mjarm_crba(i);
      pinocchio::crba(model, *pdata, q[i]);
      pdata->M.triangularView<Eigen::StrictlyLower>() = pdata->M.transpose();
      worst[3] = std::max(worst[3], (dyn.mass_matrix() - pdata->M).cwiseAbs().maxCoeff());
    }
    return worst;
  }
};

std::vector<std::unique_ptr<Robot>> g_robots;

template <typename F>
void run(benchmark::State& state, const Robot& r, F&& call) {
  std::size_t i = 0;
  for (auto _ : state) {
    call(i);
    if (++i == r.q.size()) i = 0;
  }
}

void register_robot(Robot& r) {
  Robot* p = &r;
  const auto add = [&](const std::string& op, const std::string& lib, auto fn) {
    benchmark::RegisterBenchmark((r.name + "/" + op + "/" + lib).c_str(),
                                 [p, fn](benchmark::State& s) { run(s, *p, [&](std::size_t i) {
                                   fn(*p, i);
                                 }); });
  };
  add("fk", "mjarm", [](Robot& x, std::size_t i) {
    benchmark::DoNotOptimize(x.kin.update(x.q[i]));
  });
  add("fk", "pinocchio", [](Robot& x, std::size_t i) {
    pinocchio::forwardKinematics(x.model, *x.pdata, x.q[i]);
    benchmark::DoNotOptimize(pinocchio::updateFramePlacement(x.model, *x.pdata, x.frame));
  });
  add("fk_jacobian", "mjarm", [](Robot& x, std::size_t i) {
    x.kin.update(x.q[i]);
    x.kin.jacobian(x.J);
    benchmark::DoNotOptimize(x.J.data());
  });
  add("fk_jacobian", "pinocchio", [](Robot& x, std::size_t i) {
    pinocchio::computeFrameJacobian(x.model, *x.pdata, x.q[i], x.frame,
                                    pinocchio::LOCAL_WORLD_ALIGNED, x.pJ);
    benchmark::DoNotOptimize(x.pJ.data());
  });
  add("rnea", "mjarm", [](Robot& x, std::size_t i) {
    x.mjarm_rnea(i);
    benchmark::DoNotOptimize(x.tau.data());
  });
  add("rnea", "pinocchio", [](Robot& x, std::size_t i) {
    benchmark::DoNotOptimize(pinocchio::rnea(x.model, *x.pdata, x.q[i], x.v[i], x.a[i]).data());
  });
  add("crba", "mjarm", [](Robot& x, std::size_t i) {
    x.mjarm_crba(i);
    benchmark::DoNotOptimize(x.dyn.mass_matrix().data());
  });
  add("crba", "pinocchio", [](Robot& x, std::size_t i) {
    benchmark::DoNotOptimize(pinocchio::crba(x.model, *x.pdata, x.q[i]).data());
  });
  // on a state already computed (whichever the cases before left; the cost does not depend on
  // the values)
  add("rnea_state", "mjarm", [](Robot& x, std::size_t i) {
    x.dyn.inverse_dynamics(*x.data, x.a[i], x.tau);
    benchmark::DoNotOptimize(x.tau.data());
  });
  add("crba_state", "mjarm", [](Robot& x, std::size_t) {
    x.dyn.update(*x.data);
    benchmark::DoNotOptimize(x.dyn.mass_matrix().data());
  });
}

}  // namespace

int main(int argc, char** argv) {
  std::string input;
  double tolerance = 1e-10;
  std::vector<char*> rest;
  for (int k = 0; k < argc; ++k) {
    const std::string arg = argv[k];
    if (arg.rfind("--input=", 0) == 0)
      input = arg.substr(8);
    else if (arg.rfind("--tolerance=", 0) == 0)
      tolerance = std::stod(arg.substr(12));
    else
      rest.push_back(argv[k]);
  }
  int rest_argc = static_cast<int>(rest.size());
  benchmark::Initialize(&rest_argc, rest.data());
  if (input.empty() || benchmark::ReportUnrecognizedArguments(rest_argc, rest.data())) {
    std::fprintf(stderr, "usage: %s --input=PATH [--tolerance=1e-10] [Google Benchmark flags]\n"
                 "(the input is written by bench/peers/pinocchio_side_by_side.py)\n", argv[0]);
    return 2;
  }
  try {
    std::ifstream in(input);
    if (!in) throw std::runtime_error("cannot read the input file " + input);
    const Json j = Json::parse(in);
    benchmark::AddCustomContext("pinocchio", PINOCCHIO_VERSION);
    benchmark::AddCustomContext("mujoco", mj_versionString());
    bool agree = true;
    for (const Json& robot : j.at("robots")) {
      g_robots.push_back(std::make_unique<Robot>(robot));
      Robot& r = *g_robots.back();
      const std::vector<double> worst = r.agreement();
      agree = agree && *std::max_element(worst.begin(), worst.end()) <= tolerance;
      std::ostringstream text;
      text.precision(3);
      text << "{\"configurations\": " << r.q.size() << ", \"pose\": " << worst[0]
           << ", \"jacobian\": " << worst[1] << ", \"rnea\": " << worst[2]
           << ", \"crba\": " << worst[3] << "}";
      benchmark::AddCustomContext("agreement/" + r.name, text.str());
      if (!agree) {
        std::fprintf(stderr, "%s: mjarm and Pinocchio disagree beyond %g: %s\n", r.name.c_str(),
                     tolerance, text.str().c_str());
        return 1;
      }
      r.mjarm_rnea(0);  // a computed state for the *_state cases
      register_robot(r);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_peers_pinocchio: %s\n", e.what());
    return 2;
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
