// The `mjarm._mjarm` extension: one module, one `bind_<room>` per room of the library. Every name
// stays flat (`mjarm.PoseIk`) and is also reachable through its room (`mjarm.ik.PoseIk`).
#include <stdexcept>
#include <string>

#include "bindings.hpp"

namespace py = pybind11;

namespace {

/// Runs @p bind on @p m and makes submodule @p room of the names it defined: those new in the
/// module's namespace, or bound to another object than before (a name a room rebinds then shows
/// in two rooms, which the tests refuse). The membership follows the bindings, never a list.
void bind_room(py::module_& m, py::list& rooms, const char* room, const char* doc,
               void (*bind)(py::module_&)) {
  const py::dict before = m.attr("__dict__").attr("copy")();
  bind(m);
  if (py::hasattr(m, room))
    throw std::logic_error(std::string("mjarm: the room '") + room +
                           "' is also a name of the module");
  py::module_ sub = m.def_submodule(room, doc);
  for (auto [name, value] : py::dict(m.attr("__dict__"))) {
    const auto key = py::str(name).cast<std::string>();
    if (key.starts_with("_") || sub.is(value)) continue;
    if (!before.contains(name) || before[name].ptr() != value.ptr()) sub.attr(name) = value;
  }
  rooms.append(room);
}

}  // namespace

PYBIND11_MODULE(_mjarm, m) {
  m.doc() =
      "mjarm: robot arms in MuJoCo (C++20 library) from Python. Vectors and matrices are "
      "float64 NumPy arrays; twists and wrenches are linear first [v; w]; bad input raises "
      "mjarm.Error (a ValueError) with the library's message. Calls take the user's "
      "mujoco.MjModel and mujoco.MjData too, without a copy. Every name is also in its room's "
      "namespace: mjarm.ik.PoseIk is mjarm.PoseIk.";
  // one MuJoCo library, shared with the mujoco package, of the version mjarm was compiled with
  mjarm::python::check_shared_mujoco();
  mjarm::install_mujoco_handlers();
  // mjarm::Error keeps its message and is a ValueError: bad input at an API boundary
  py::register_exception<mjarm::Error>(m, "Error", PyExc_ValueError).attr("__doc__") =
      "Bad input at an API boundary (unknown name, wrong size, non-finite value, unloadable "
      "model); the message is the library's, naming the thing and what was expected.";
  using namespace mjarm::python;
  py::list rooms;
  bind_room(m, rooms, "model", "Models, chains and frames: Robot, Chain, Data.", bind_model);
  bind_room(m, rooms, "lie", "Rotations, poses, twists: SO(3) and SE(3).", bind_lie);
  bind_room(m, rooms, "kinematics", "Forward kinematics, Jacobians, manipulability, workspace.",
            bind_kinematics);
  bind_room(m, rooms, "ik",
            "Inverse kinematics: position, pose, multi-target, differential, "
            "global.",
            bind_ik);
  bind_room(m, rooms, "dynamics", "Rigid-body and task-space dynamics, friction, observers.",
            bind_dynamics);
  bind_room(m, rooms, "control", "Controllers and their references.", bind_control);
  bind_room(m, rooms, "sim", "The simulation loop, its faults and its recorder.", bind_sim);
  bind_room(m, rooms, "state", "Named state, contacts and constraint forces.", bind_state);
  bind_room(m, rooms, "trajectory", "Time scalings, profiles and interpolations.", bind_trajectory);
  bind_room(m, rooms, "planning", "Waypoint planning and joint splines.", bind_planning);
  bind_room(m, rooms, "scene", "Scenes built from a description.", bind_scene);
  bind_room(m, rooms, "tasks", "Tasks: shelf pick, pick and place, docking.", bind_tasks);
  bind_room(m, rooms, "render", "Offscreen rendering and video.", bind_render);
  bind_room(m, rooms, "teleop", "The passive viewer: a window on the user's own loop.",
            bind_teleop);
  bind_room(m, rooms, "web", "Replay pages: a recording in one HTML file for any browser.",
            bind_web);
  bind_room(m, rooms, "env", "Reinforcement-learning environments.", bind_env);
  // `mjarm.scenarios()` is the registry's own function, so its room takes the singular
  bind_room(m, rooms, "scenario", "The scenario registry: scenarios, runs and their outcomes.",
            bind_scenarios);
  m.attr("_rooms") = py::tuple(rooms);
}
