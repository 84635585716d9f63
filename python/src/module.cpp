// The `mjarm._mjarm` extension: one module, one `bind_<room>` per room of the library.
#include "bindings.hpp"

namespace py = pybind11;

PYBIND11_MODULE(_mjarm, m) {
  m.doc() =
      "mjarm: robot arms in MuJoCo (C++20 library) from Python. Vectors and matrices are "
      "float64 NumPy arrays; twists and wrenches are linear first [v; w]; bad input raises "
      "mjarm.Error (a ValueError) with the library's message. Calls take the user's "
      "mujoco.MjModel and mujoco.MjData too, without a copy.";
  // one MuJoCo library, shared with the mujoco package, of the version mjarm was compiled with
  mjarm::python::check_shared_mujoco();
  mjarm::install_mujoco_handlers();
  // mjarm::Error keeps its message and is a ValueError: bad input at an API boundary
  py::register_exception<mjarm::Error>(m, "Error", PyExc_ValueError).attr("__doc__") =
      "Bad input at an API boundary (unknown name, wrong size, non-finite value, unloadable "
      "model); the message is the library's, naming the thing and what was expected.";
  mjarm::python::bind_model(m);
  mjarm::python::bind_lie(m);
  mjarm::python::bind_kinematics(m);
  mjarm::python::bind_ik(m);
  mjarm::python::bind_dynamics(m);
  mjarm::python::bind_control(m);
  mjarm::python::bind_sim(m);
  mjarm::python::bind_state(m);
  mjarm::python::bind_trajectory(m);
  mjarm::python::bind_planning(m);
  mjarm::python::bind_scene(m);
  mjarm::python::bind_tasks(m);
  mjarm::python::bind_render(m);
  mjarm::python::bind_teleop(m);
  mjarm::python::bind_env(m);
  mjarm::python::bind_scenarios(m);
}
