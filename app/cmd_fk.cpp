// `mjarm fk MODEL --site S --q …`: the pose of a frame, and optionally its Jacobian.

#include <iostream>
#include <memory>
#include <numbers>

#include "commands.hpp"
#include "mjarm/lie/rotation.hpp"
#include "output.hpp"

namespace mjarm::cli {

namespace {

constexpr double kDegrees = 180.0 / std::numbers::pi;
const std::vector<std::string> kTwistRows = {"vx", "vy", "vz", "ωx", "ωy", "ωz"};

std::string unit_of(const Robot& robot, int joint) {
  return robot.joint_info(joint).type == JointType::slide ? "m" : "rad";
}

Matrix6Xd jacobian_of(const ChainKinematics& kin) {
  Matrix6Xd J(6, kin.chain().size());
  kin.jacobian(J, JacobianFrame::world_aligned);
  return J;
}

}  // namespace

Json pose_json(const ChainKinematics& kin, const Configuration& config, bool with_jacobian) {
  const Chain& chain = kin.chain();
  const Pose& X_WE = kin.pose();
  Json doc;
  doc["model"] = chain.robot().name();
  doc["frame"] = {{"kind", chain.frame().kind == FrameKind::site ? "site" : "body"},
                  {"name", chain.frame().name}};
  doc["configuration"] = config.source;
  doc["joints"] = chain.joint_names();
  doc["q"] = vector_json(config.q);
  doc["within_limits"] = chain.within_limits(config.q);
  doc["position"] = vector_json(X_WE.p);
  doc["rotation"] = matrix_json(X_WE.R);
  doc["quaternion_wxyz"] = vector_json(quaternion_from_rotation(X_WE.R));
  doc["rpy"] = vector_json(rpy_from_rotation(X_WE.R));
  if (with_jacobian) {
    doc["jacobian"] = {{"frame", "world_aligned"},
                       {"rows", std::vector<std::string>{"vx", "vy", "vz", "wx", "wy", "wz"}},
                       {"columns", chain.joint_names()},
                       {"data", matrix_json(jacobian_of(kin))}};
  }
  return doc;
}

void print_pose(std::ostream& os, const ChainKinematics& kin, const Configuration& config,
                bool with_jacobian) {
  const Chain& chain = kin.chain();
  const Robot& robot = chain.robot();
  const Pose& X_WE = kin.pose();
  print_fields(os,
               {{"model", robot.name()},
                {"frame", std::string(chain.frame().kind == FrameKind::site ? "site '" : "body '") +
                              chain.frame().name + "'"},
                {"configuration", config.source}});

  os << "\njoint values\n";
  Table joints({{"joint", Table::Align::left},
                {"value"},
                {"unit", Table::Align::left},
                {"[deg]"},
                {"range", Table::Align::left},
                {"", Table::Align::left}});
  for (int i = 0; i < chain.size(); ++i) {
    const bool slide = unit_of(robot, chain.joint_id(i)) == "m";
    const double lower = chain.lower()[i], upper = chain.upper()[i];
    const bool inside = config.q[i] >= lower && config.q[i] <= upper;
    joints.add_row({chain.joint_names()[static_cast<std::size_t>(i)], fixed(config.q[i], 4),
                    slide ? "m" : "rad", slide ? "" : fixed(config.q[i] * kDegrees, 2),
                    "[" + fixed(lower) + ", " + fixed(upper) + "]",
                    inside ? "" : "outside the range"});
  }
  joints.print(os);

  const Eigen::Vector4d quat = quaternion_from_rotation(X_WE.R);
  const Eigen::Vector3d rpy = rpy_from_rotation(X_WE.R);
  os << "\npose of the frame in the world (X_WE)\n";
  print_fields(os,
               {{"position [m]", vector_text(X_WE.p, 4)},
                {"quaternion (w x y z)", vector_text(quat, 6)},
                {"roll pitch yaw [rad]", vector_text(rpy, 4)},
                {"roll pitch yaw [deg]", vector_text(rpy * kDegrees, 2)}},
               2);
  os << "  rotation R_WE\n";
  for (int r = 0; r < 3; ++r) {
    os << "    " << (r == 0 ? "⎡" : r == 1 ? "⎢" : "⎣");
    for (int c = 0; c < 3; ++c) {
      const std::string cell = fixed(X_WE.R(r, c), 6);
      os << std::string(10 - cell.size(), ' ') << cell;
    }
    os << (r == 0 ? " ⎤" : r == 1 ? " ⎥" : " ⎦") << '\n';
  }

  if (with_jacobian) {
    os << "\nJacobian, world-aligned (rows [v; ω], columns joints): v [m/s], ω [rad/s] per unit "
          "q̇\n";
    const Matrix6Xd J = jacobian_of(kin);
    std::vector<Table::Column> columns{{"", Table::Align::left}};
    for (const auto& name : chain.joint_names()) columns.push_back({name});
    Table table(columns);
    for (int r = 0; r < 6; ++r) {
      std::vector<std::string> row{kTwistRows[static_cast<std::size_t>(r)]};
      for (int c = 0; c < J.cols(); ++c) row.push_back(fixed(J(r, c), 4));
      table.add_row(std::move(row));
    }
    table.print(os);
  }
}

Command add_fk_command(CLI::App& root) {
  struct Options {
    std::string model;
    std::string site;
    std::vector<double> q;
    std::string key;
    bool allow_outside_range = false;
    bool jacobian = false;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* app =
      root.add_subcommand("fk", "forward kinematics: the pose of a site at a configuration");
  add_model_argument(*app, options->model)->required();
  add_site_option(*app, options->site);
  auto* q = app->add_option("--q", options->q,
                            "joint values of the chain to the site, root first [rad or m]; "
                            "default: the model's qpos0")
                ->check(finite_number())
                ->expected(1, -1);
  app->add_option("--key", options->key, "take the configuration from this keyframe (e.g. home)")
      ->excludes(q);
  add_allow_outside_range_flag(*app, options->allow_outside_range);
  app->add_flag("--jacobian", options->jacobian,
                "also print the 6×n world-aligned Jacobian [v; ω]");
  add_json_flag(*app, options->json);

  return {app, [options] {
            const Robot robot = load_model(options->model);
            const Chain chain(robot, resolve_site(robot, options->site));
            const Configuration config = resolve_configuration(
                chain, options->q, options->key, "--q", options->allow_outside_range);
            ChainKinematics kin(chain);
            kin.set_fixed_qpos(config.qpos);
            kin.update(config.q);
            if (options->json) return print_json(pose_json(kin, config, options->jacobian));
            print_pose(std::cout, kin, config, options->jacobian);
          }};
}

}  // namespace mjarm::cli
