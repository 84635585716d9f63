// lie room: Pose, SO(3)/SE(3) exp/log, Adjoint, ad, wrench transforms, dexp family, pose errors.
#include <cmath>

#include "bindings.hpp"
#include "mjarm/ik/targets.hpp"
#include "mjarm/lie/pose_error.hpp"
#include "mjarm/lie/rotation.hpp"
#include "mjarm/lie/se3.hpp"
#include "mjarm/lie/se3_jacobian.hpp"
#include "mjarm/lie/so3.hpp"
#include "mjarm/lie/so3_jacobian.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm::python {

namespace {

/// Every number a Lie or pose function takes from Python is finite: exp(NaN) would return a NaN
/// pose without a word (the C++ kernels are plain arithmetic, NaN in, NaN out).
template <class M>
M finite(M value, const char* name) {
  for (Eigen::Index i = 0; i < value.size(); ++i) {
    if (std::isfinite(value.data()[i])) continue;
    // column-major storage: report the entry as (row, column) for a matrix
    const Eigen::Index row = i % value.rows(), col = i / value.rows();
    throw Error(std::string(name) + " holds " + number_text(value.data()[i]) + " at " +
                (value.cols() == 1 ? "entry " + std::to_string(row)
                                   : "(" + std::to_string(row) + ", " + std::to_string(col) + ")") +
                "; expected finite numbers");
  }
  return value;
}

using V3 = Eigen::Vector3d;
using V6 = Vector6d;

V3 v3(py::handle o, const char* n) { return finite(to_fixed<3>(o, n), n); }
V6 v6(py::handle o, const char* n) { return finite(to_fixed<6>(o, n), n); }
Eigen::Matrix3d m3(py::handle o, const char* n) { return finite(to_fixed_matrix<3, 3>(o, n), n); }
Eigen::Matrix4d m4(py::handle o, const char* n) { return finite(to_fixed_matrix<4, 4>(o, n), n); }
Eigen::Vector4d v4(py::handle o, const char* n) { return finite(to_fixed<4>(o, n), n); }

}  // namespace

Pose to_pose(py::handle object, const char* name) {
  if (py::isinstance<Pose>(object)) return object.cast<Pose>();
  if (object.is_none()) {
    throw py::type_error(std::string(name) + ": expected a Pose or a 4x4 matrix, got None");
  }
  return Pose::from_matrix(m4(object, name));
}

void bind_lie(py::module_& m) {
  py::class_<Pose>(m, "Pose",
                   "Pose X_AB of a frame B in a frame A: x_A = R x_B + p. R is 3x3 "
                   "(orthonormal), p is (3,) [m]. Compose with *, invert with inverse().")
      .def(py::init<>(), "The identity.")
      .def(py::init([](py::handle R, py::handle p) {
             Pose X;
             X.R = m3(R, "R");
             X.p = v3(p, "p");
             return X;
           }),
           py::arg("R"), py::arg("p"))
      .def_property(
          "R", [](const Pose& X) { return Eigen::Matrix3d(X.R); },
          [](Pose& X, py::handle R) { X.R = m3(R, "R"); }, "rotation R_AB (3, 3)")
      .def_property(
          "p", [](const Pose& X) { return Eigen::Vector3d(X.p); },
          [](Pose& X, py::handle p) { X.p = v3(p, "p"); }, "translation p_AB (3,) [m]")
      .def_static("identity", &Pose::identity)
      .def_static(
          "from_matrix",
          [](py::handle M) { return Pose::from_matrix(m4(M, "M")); },
          py::arg("M"), "From a 4x4 homogeneous matrix [R p; 0 1].")
      .def_static(
          "from_quaternion",
          [](py::handle p, py::handle q) {
            return Pose::from_quaternion(v3(p, "p"), v4(q, "q_wxyz"));
          },
          py::arg("p"), py::arg("q_wxyz"), "From a position [m] and a quaternion (w, x, y, z).")
      .def_static(
          "from_rpy",
          [](py::handle p, py::handle rpy) { return Pose::from_rpy(v3(p, "p"), v3(rpy, "rpy")); },
          py::arg("p"), py::arg("rpy"),
          "From a position [m] and roll-pitch-yaw [rad], R = Rz Ry Rx.")
      .def("matrix", &Pose::matrix, "4x4 homogeneous matrix")
      .def("inverse", &Pose::inverse)
      .def(
          "act", [](const Pose& X, py::handle x) { return X.act(v3(x, "point")); },
          py::arg("point"), "R point + p")
      .def(
          "rotate", [](const Pose& X, py::handle v) { return X.rotate(v3(v, "vector")); },
          py::arg("vector"), "R vector")
      .def(
          "quaternion", [](const Pose& X) { return quaternion_from_rotation(X.R); },
          "(w, x, y, z), w >= 0")
      .def(
          "rpy", [](const Pose& X) { return rpy_from_rotation(X.R); }, "(roll, pitch, yaw) [rad]")
      .def("__mul__", [](const Pose& a, const Pose& b) { return a * b; })
      .def("is_approx", &Pose::is_approx, py::arg("other"), py::arg("tolerance") = 1e-12)
      .def("copy", [](const Pose& X) { return X; })
      .def("__copy__", [](const Pose& X) { return X; })
      .def(
          "__deepcopy__", [](const Pose& X, py::dict) { return X; }, py::arg("memo"))
      .def("__repr__", [](const Pose& X) {
        return "Pose(p=" + py::repr(py::cast(Eigen::Vector3d(X.p))).cast<std::string>() +
               ", rpy=" + py::repr(py::cast(rpy_from_rotation(X.R))).cast<std::string>() + ")";
      });

  m.def(
      "rotation_from_quaternion",
      [](py::handle q) { return rotation_from_quaternion(v4(q, "q_wxyz")); },
      py::arg("q_wxyz"));
  m.def(
      "quaternion_from_rotation", [](py::handle R) { return quaternion_from_rotation(m3(R, "R")); },
      py::arg("R"));
  m.def(
      "rotation_from_rpy", [](py::handle rpy) { return rotation_from_rpy(v3(rpy, "rpy")); },
      py::arg("rpy"));
  m.def(
      "rpy_from_rotation", [](py::handle R) { return rpy_from_rotation(m3(R, "R")); },
      py::arg("R"));
  m.def(
      "wrap_to_pi",
      [](py::handle angle) -> py::object {
        if (py::isinstance<py::float_>(angle) || py::isinstance<py::int_>(angle))
          return py::float_(wrap_to_pi(angle.cast<double>()));
        Eigen::VectorXd v = to_vector(angle, "angle");
        for (double& x : v) x = wrap_to_pi(x);
        return py::cast(v);
      },
      py::arg("angle"),
      "The angle (a number or an array) wrapped into [-pi, pi]: the nearest equivalent angle.");
  m.def(
      "log_error",
      [](py::handle a, py::handle b) { return log_error(to_pose(a, "X_WE"), to_pose(b, "X_WT")); },
      py::arg("X_WE"), py::arg("X_WT"), "Body pose error log(X_EW X_WT) = [v; w] (6,), in E.");
  m.def(
      "log_error_world_aligned",
      [](py::handle a, py::handle b) {
        return log_error_world_aligned(to_pose(a, "X_WE"), to_pose(b, "X_WT"));
      },
      py::arg("X_WE"), py::arg("X_WT"), "The body error with world axes (6,).");
  m.def(
      "log_error_jacobian", [](py::handle e) { return log_error_jacobian(v6(e, "e_E")); },
      py::arg("e_E"), "Jlog of the body error (6, 6).");
  m.def(
      "log_error_world_aligned_jacobian",
      [](py::handle e) { return log_error_world_aligned_jacobian(v6(e, "e_W")); }, py::arg("e_W"));
  m.def(
      "frame_errors",
      [](py::handle a, py::handle b) {
        const FrameErrors e = frame_errors(to_pose(a, "X_WE"), to_pose(b, "X_WT"));
        return py::make_tuple(e.position, e.orientation);
      },
      py::arg("X_WE"), py::arg("X_WT"), "(position error [m], rotation angle [rad])");

  auto so3 = m.def_submodule("so3", "The rotation group SO(3): rotation vectors w (3,) [rad].");
  so3.def(
      "hat", [](py::handle w) { return so3::hat(v3(w, "w")); }, py::arg("w"));
  so3.def(
      "vee", [](py::handle W) { return so3::vee(m3(W, "W")); }, py::arg("W"));
  so3.def(
      "exp", [](py::handle w) { return so3::exp(v3(w, "w")); }, py::arg("w"), "Rodrigues");
  so3.def(
      "log", [](py::handle R) { return so3::log(m3(R, "R")); }, py::arg("R"),
      "principal branch, |w| <= pi");
  so3.def(
      "angle", [](py::handle R) { return so3::angle(m3(R, "R")); }, py::arg("R"));
  so3.def(
      "left_jacobian", [](py::handle w) { return so3::left_jacobian(v3(w, "w")); }, py::arg("w"));
  so3.def(
      "right_jacobian", [](py::handle w) { return so3::right_jacobian(v3(w, "w")); }, py::arg("w"));
  so3.def(
      "left_jacobian_inverse", [](py::handle w) { return so3::left_jacobian_inverse(v3(w, "w")); },
      py::arg("w"), "|w| < 2 pi");
  so3.def(
      "right_jacobian_inverse",
      [](py::handle w) { return so3::right_jacobian_inverse(v3(w, "w")); }, py::arg("w"));
  so3.def(
      "left_jacobian_derivative",
      [](py::handle w, py::handle wd) {
        return so3::left_jacobian_derivative(v3(w, "w"), v3(wd, "w_dot"));
      },
      py::arg("w"), py::arg("w_dot"));
  so3.def(
      "right_jacobian_derivative",
      [](py::handle w, py::handle wd) {
        return so3::right_jacobian_derivative(v3(w, "w"), v3(wd, "w_dot"));
      },
      py::arg("w"), py::arg("w_dot"));
  so3.def(
      "left_jacobian_inverse_derivative",
      [](py::handle w, py::handle wd) {
        return so3::left_jacobian_inverse_derivative(v3(w, "w"), v3(wd, "w_dot"));
      },
      py::arg("w"), py::arg("w_dot"));
  so3.def(
      "right_jacobian_inverse_derivative",
      [](py::handle w, py::handle wd) {
        return so3::right_jacobian_inverse_derivative(v3(w, "w"), v3(wd, "w_dot"));
      },
      py::arg("w"), py::arg("w_dot"));

  auto se3 = m.def_submodule(
      "se3", "The rigid-motion group SE(3): twists xi = [v; w] (6,), linear first.");
  se3.def(
      "hat", [](py::handle x) { return se3::hat(v6(x, "xi")); }, py::arg("xi"));
  se3.def(
      "vee", [](py::handle X) { return se3::vee(m4(X, "xi_hat")); },
      py::arg("xi_hat"));
  se3.def(
      "exp", [](py::handle x) { return se3::exp(v6(x, "xi")); }, py::arg("xi"), "-> Pose");
  se3.def(
      "log", [](py::handle X) { return se3::log(to_pose(X, "X")); }, py::arg("X"), "-> (6,)");
  se3.def(
      "adjoint", [](py::handle X) { return se3::adjoint(to_pose(X, "X_AB")); }, py::arg("X_AB"),
      "Ad = [R, p^R; 0, R] (6, 6)");
  se3.def(
      "ad", [](py::handle x) { return se3::ad(v6(x, "xi")); }, py::arg("xi"),
      "ad = [w^, v^; 0, w^]");
  se3.def(
      "coadjoint", [](py::handle X) { return se3::coadjoint(to_pose(X, "X_AB")); }, py::arg("X_AB"),
      "Ad^-T for wrenches (6, 6)");
  se3.def(
      "transform_twist",
      [](py::handle X, py::handle V) {
        return se3::transform_twist(to_pose(X, "X_AB"), v6(V, "V_B"));
      },
      py::arg("X_AB"), py::arg("V_B"));
  se3.def(
      "transform_wrench",
      [](py::handle X, py::handle F) {
        return se3::transform_wrench(to_pose(X, "X_AB"), v6(F, "F_B"));
      },
      py::arg("X_AB"), py::arg("F_B"));
  se3.def(
      "q_block", [](py::handle v, py::handle w) { return se3::q_block(v3(v, "v"), v3(w, "w")); },
      py::arg("v"), py::arg("w"));
  se3.def(
      "left_jacobian", [](py::handle x) { return se3::left_jacobian(v6(x, "xi")); }, py::arg("xi"));
  se3.def(
      "right_jacobian", [](py::handle x) { return se3::right_jacobian(v6(x, "xi")); },
      py::arg("xi"));
  se3.def(
      "left_jacobian_inverse", [](py::handle x) { return se3::left_jacobian_inverse(v6(x, "xi")); },
      py::arg("xi"));
  se3.def(
      "right_jacobian_inverse",
      [](py::handle x) { return se3::right_jacobian_inverse(v6(x, "xi")); }, py::arg("xi"));
  se3.def(
      "left_jacobian_derivative",
      [](py::handle x, py::handle xd) {
        return se3::left_jacobian_derivative(v6(x, "xi"), v6(xd, "xi_dot"));
      },
      py::arg("xi"), py::arg("xi_dot"));
  se3.def(
      "right_jacobian_derivative",
      [](py::handle x, py::handle xd) {
        return se3::right_jacobian_derivative(v6(x, "xi"), v6(xd, "xi_dot"));
      },
      py::arg("xi"), py::arg("xi_dot"));
  se3.def(
      "left_jacobian_inverse_derivative",
      [](py::handle x, py::handle xd) {
        return se3::left_jacobian_inverse_derivative(v6(x, "xi"), v6(xd, "xi_dot"));
      },
      py::arg("xi"), py::arg("xi_dot"));
  se3.def(
      "right_jacobian_inverse_derivative",
      [](py::handle x, py::handle xd) {
        return se3::right_jacobian_inverse_derivative(v6(x, "xi"), v6(xd, "xi_dot"));
      },
      py::arg("xi"), py::arg("xi_dot"));
}

}  // namespace mjarm::python
