// `mjarm models` and `mjarm info MODEL`: what a model holds.

#include <iostream>
#include <memory>

#include "commands.hpp"
#include "output.hpp"

namespace mjarm::cli {

namespace {

std::string unit_of(JointType type) { return type == JointType::slide ? "m" : "rad"; }

// MJCF's names of MuJoCo's integrators (mjtIntegrator)
std::string integrator_name(int integrator) {
  switch (integrator) {
    case mjINT_EULER: return "Euler";
    case mjINT_RK4: return "RK4";
    case mjINT_IMPLICIT: return "implicit";
    case mjINT_IMPLICITFAST: return "implicitfast";
    case mjINT_DISCRETE: return "discrete";
    default: return "integrator " + std::to_string(integrator);
  }
}

std::string joint_name(const Robot& robot, const std::optional<int>& joint) {
  return joint ? robot.joint_info(*joint).name : "—";
}

std::vector<std::string> named_only(const std::vector<std::string>& names) {
  std::vector<std::string> result;
  for (const auto& name : names) result.push_back(name.empty() ? "(unnamed)" : name);
  return result;
}

void print_list(std::ostream& os, const std::string& title, const std::vector<std::string>& names) {
  os << title << " (" << names.size() << "): " << join(named_only(names)) << '\n';
}

void list_models(bool json) {
  const auto names = Robot::bundled_names();
  if (json) {
    print_json({{"models_dir", Robot::models_dir().string()}, {"models", names}});
    return;
  }
  std::cout << "bundled models in " << Robot::models_dir().string() << ":\n";
  for (const auto& name : names) std::cout << "  " << name << '\n';
}

}  // namespace

Json model_json(const Robot& robot) {
  const mjModel& m = robot.model();
  Json doc;
  doc["name"] = robot.name();
  doc["source"] = robot.source();
  doc["nq"] = robot.nq();
  doc["nv"] = robot.nv();
  doc["nu"] = robot.nu();
  doc["bodies"] = robot.body_names();
  doc["joints"] = Json::array();
  for (const auto& joint : robot.joints()) {
    Json j{{"name", joint.name},
           {"type", to_string(joint.type)},
           {"qpos_address", joint.qpos_address},
           {"dof_address", joint.dof_address},
           {"body", robot.body_names().at(static_cast<std::size_t>(joint.body))},
           {"limited", joint.limited}};
    j["range"] = joint.limited ? Json::array({joint.lower, joint.upper}) : Json(nullptr);
    doc["joints"].push_back(std::move(j));
  }
  doc["actuators"] = Json::array();
  for (const auto& actuator : robot.actuators()) {
    Json a{{"name", actuator.name}, {"kind", to_string(actuator.kind)}, {"gear", actuator.gear}};
    a["joint"] = actuator.joint ? Json(joint_name(robot, actuator.joint)) : Json(nullptr);
    a["ctrlrange"] = actuator.ctrl_limited ? Json::array({actuator.ctrl_lower, actuator.ctrl_upper})
                                           : Json(nullptr);
    a["forcerange"] = actuator.force_limited
                          ? Json::array({actuator.force_lower, actuator.force_upper})
                          : Json(nullptr);
    doc["actuators"].push_back(std::move(a));
  }
  doc["sites"] = robot.site_names();
  doc["sensors"] = Json::array();
  for (const auto& sensor : robot.sensors()) {
    doc["sensors"].push_back({{"name", sensor.name},
                              {"type", sensor.type},
                              {"address", sensor.address},
                              {"dimension", sensor.dimension}});
  }
  doc["cameras"] = robot.camera_names();
  doc["keyframes"] = robot.keyframe_names();
  doc["timestep"] = m.opt.timestep;
  doc["integrator"] = integrator_name(m.opt.integrator);
  doc["warnings"] = robot.load_warnings();
  return doc;
}

void print_model_summary(std::ostream& os, const Robot& robot) {
  const mjModel& m = robot.model();
  print_fields(os, {{"model", robot.name()},
                    {"source", robot.source()},
                    {"sizes", "nq " + std::to_string(m.nq) + ", nv " + std::to_string(m.nv) +
                                  ", nu " + std::to_string(m.nu) + ", bodies " +
                                  std::to_string(m.nbody) + ", geoms " + std::to_string(m.ngeom)},
                    {"timestep", compact(m.opt.timestep) + " s"},
                    {"integrator", integrator_name(m.opt.integrator)}});

  const auto joints = robot.joints();
  os << "\njoints (" << joints.size() << ")\n";
  Table joint_table({{"#"},
                     {"name", Table::Align::left},
                     {"type", Table::Align::left},
                     {"lower"},
                     {"upper"},
                     {"unit", Table::Align::left},
                     {"qpos"},
                     {"dof"}});
  for (const auto& joint : joints) {
    const bool scalar = joint.type == JointType::hinge || joint.type == JointType::slide;
    joint_table.add_row({std::to_string(joint.id), joint.name, to_string(joint.type),
                         !scalar         ? "—"
                         : joint.limited ? fixed(joint.lower)
                                         : "-inf",
                         !scalar         ? "—"
                         : joint.limited ? fixed(joint.upper)
                                         : "inf",
                         scalar ? unit_of(joint.type) : "", std::to_string(joint.qpos_address),
                         std::to_string(joint.dof_address)});
  }
  joint_table.print(os);

  const auto actuators = robot.actuators();
  os << "\nactuators (" << actuators.size() << ")\n";
  if (!actuators.empty()) {
    Table actuator_table({{"#"},
                          {"name", Table::Align::left},
                          {"kind", Table::Align::left},
                          {"joint", Table::Align::left},
                          {"ctrlrange", Table::Align::left},
                          {"forcerange [N or N·m]", Table::Align::left},
                          {"gear"}});
    for (const auto& a : actuators) {
      actuator_table.add_row(
          {std::to_string(a.id), a.name, to_string(a.kind), joint_name(robot, a.joint),
           a.ctrl_limited ? "[" + fixed(a.ctrl_lower) + ", " + fixed(a.ctrl_upper) + "]"
                          : "unlimited",
           a.force_limited ? "[" + fixed(a.force_lower, 1) + ", " + fixed(a.force_upper, 1) + "]"
                           : "unlimited",
           compact(a.gear)});
    }
    actuator_table.print(os);
  }
}

Command add_models_command(CLI::App& root) {
  auto json = std::make_shared<bool>(false);
  CLI::App* app = root.add_subcommand("models", "list the bundled models");
  add_json_flag(*app, *json);
  return {app, [json] { list_models(*json); }};
}

Command add_info_command(CLI::App& root) {
  struct Options {
    std::string model;
    bool list = false;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* app = root.add_subcommand(
      "info", "describe a model: sizes, joints, actuators, sites, sensors, cameras, keyframes");
  add_model_argument(*app, options->model);
  app->add_flag("--list", options->list,
                "list the bundled models instead (same as `mjarm models`)");
  add_json_flag(*app, options->json);

  return {app, [options] {
            if (options->list) return list_models(options->json);
            if (options->model.empty()) throw UsageError("info: MODEL is required (or --list)");
            const Robot robot = load_model(options->model);
            if (options->json) return print_json(model_json(robot));

            std::ostream& os = std::cout;
            print_model_summary(os, robot);
            os << '\n';
            print_list(os, "bodies", robot.body_names());
            print_list(os, "sites", robot.site_names());

            const auto sensors = robot.sensors();
            os << "sensors (" << sensors.size() << ")";
            if (sensors.empty()) {
              os << ": (none)\n";
            } else {
              os << '\n';
              Table table({{"#"},
                           {"name", Table::Align::left},
                           {"type", Table::Align::left},
                           {"address"},
                           {"dimension"}});
              for (const auto& s : sensors) {
                table.add_row({std::to_string(s.id), s.name, s.type, std::to_string(s.address),
                               std::to_string(s.dimension)});
              }
              table.print(os);
            }
            print_list(os, "cameras", robot.camera_names());
            print_list(os, "keyframes", robot.keyframe_names());
            const auto& warnings = robot.load_warnings();
            os << "load warnings (" << warnings.size() << ")"
               << (warnings.empty() ? ": (none)" : ":") << '\n';
            for (const auto& w : warnings) os << "  - " << w << '\n';
          }};
}

}  // namespace mjarm::cli
