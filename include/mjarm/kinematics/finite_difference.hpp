#pragma once
/// @file
/// Central finite-difference Jacobians of any user function: R^n → R^m (vector, matrix or
/// scalar valued), R → anything (a derivative), and pose valued R^n → SE(3) (a 6×n twist
/// Jacobian through the SE(3) log, linear rows first, in the frames `ChainKinematics` uses).
///
/// Accuracy. Column i is (f(x + h·e_i) − f(x − h·e_i)) / Δ with Δ = (x_i + h) − (x_i − h) the
/// step actually taken in floating point. The truncation error is h²/6·|f'''| and the rounding
/// error about ε·|f|/h (ε = 2.2e-16), so with the default h = 1e-6 a function of unit scale
/// (metres, radians) gets its derivative to about 1e-10 absolute. Against the analytic Jacobians
/// of the bundled arms the largest entry error is 2e-10 to 2e-9 (examples/07_finite_differences,
/// docs/kinematics.md). The pose variant is second order as well.
///
/// Allocation. With a `FiniteDifferenceWorkspace` sized for (n, m) and a preallocated output, the
/// functions allocate nothing themselves (the user function may, e.g. when it returns an
/// `Eigen::VectorXd`; return fixed-size types or write into the output argument to avoid it).

#include <Eigen/Core>
#include <type_traits>
#include <utility>

#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/lie/types.hpp"

namespace mjarm {

/// Default step h of the central differences, in the units of x (rad or m): 1e-6.
inline constexpr double kFiniteDifferenceStep = 1e-6;

/// Buffers reused across finite-difference calls: the perturbed argument (n) and one value of
/// the function (m, only for functions that write their value into an output argument).
struct FiniteDifferenceWorkspace {
  FiniteDifferenceWorkspace() = default;
  /// Sized for @p inputs arguments and @p outputs values: later calls with these sizes
  /// allocate nothing.
  FiniteDifferenceWorkspace(Eigen::Index inputs, Eigen::Index outputs) : x(inputs), y(outputs) {}
  Eigen::VectorXd x;  ///< x with one entry moved (n)
  Eigen::VectorXd y;  ///< f(x − h·e_i) for output-argument functions (m)
};

namespace detail {

/// @throws Error when @p step is not finite and positive.
void check_finite_difference_step(double step);
/// @throws Error when @p x holds NaN/inf.
void check_finite_difference_point(const Eigen::Ref<const Eigen::VectorXd>& x);
/// @throws Error when the output (@p rows × @p cols) is not @p expected_rows × n (any rows > 0
/// when @p expected_rows is 0); @p what names the output.
void check_finite_difference_shape(Eigen::Index rows, Eigen::Index cols, Eigen::Index n,
                                   Eigen::Index expected_rows, const char* what);
/// @throws Error when the step vanishes at x_i (|x_i| so large that x_i ± h rounds to x_i).
void check_finite_difference_spacing(double delta, Eigen::Index i, double xi, double step);
/// @throws Error when a function value has @p got entries instead of @p expected.
void check_finite_difference_value_size(Eigen::Index got, Eigen::Index expected);
/// One column of a pose Jacobian from the poses at x ± h·e_i, divided by the step @p delta.
void pose_difference(const Pose& X_plus, const Pose& X_minus, double delta, JacobianFrame frame,
                     Eigen::Ref<Vector6d> column) noexcept;

/// Number of entries of a function value: 1 for a scalar, size() for an Eigen object.
template <class T>
Eigen::Index value_size(const T& y) {
  if constexpr (std::is_arithmetic_v<T>) {
    return 1;
  } else {
    return y.size();
  }
}

/// (a − b)/delta written into @p column: scalars, or Eigen objects flattened column-major.
template <class T>
void write_difference(const T& a, const T& b, double delta, Eigen::Ref<Eigen::VectorXd> column) {
  if constexpr (std::is_arithmetic_v<T>) {
    column[0] = (static_cast<double>(a) - static_cast<double>(b)) / delta;
  } else {
    column = (a.reshaped() - b.reshaped()).template cast<double>() / delta;
  }
}

/// The plain value of f(x): scalars as they are, Eigen expressions evaluated.
template <class T>
auto evaluated(T&& y) {
  if constexpr (std::is_arithmetic_v<std::decay_t<T>>) {
    return static_cast<double>(y);
  } else {
    return y.eval();
  }
}

}  // namespace detail

/// Central-difference Jacobian J = ∂f/∂x (m × n) of a function R^n → R^m at @p x.
///
/// @p f takes `const Eigen::VectorXd& x` (n entries) and either
/// - returns its value: a scalar (m = 1) or any Eigen vector or matrix (flattened column-major
///   into m entries, so a matrix-valued f gives column i = vec(∂f/∂x_i)); or
/// - writes it into a second argument `Eigen::Ref<Eigen::VectorXd> y` (m entries).
/// @param x point of evaluation (n entries, finite)
/// @param J output, m × n, preallocated by the caller
/// @param workspace reused buffers; sized on first use (no allocation once sized for n and m)
/// @param step h, finite and > 0, in the units of x
/// @throws Error on a non-finite x or step, a J that is not m × n, a value of the wrong size, or
/// a step that vanishes next to a large x_i.
template <class F>
void finite_difference_jacobian(F&& f, const Eigen::Ref<const Eigen::VectorXd>& x,
                                Eigen::Ref<Eigen::MatrixXd> J, FiniteDifferenceWorkspace& workspace,
                                double step = kFiniteDifferenceStep) {
  detail::check_finite_difference_step(step);
  detail::check_finite_difference_point(x);
  detail::check_finite_difference_shape(J.rows(), J.cols(), x.size(), 0, "Jacobian");
  if (workspace.x.size() != x.size()) workspace.x.resize(x.size());
  workspace.x = x;
  constexpr bool writes_output =
      std::is_invocable_v<F&, const Eigen::VectorXd&, Eigen::Ref<Eigen::VectorXd>>;
  if constexpr (writes_output) {
    if (workspace.y.size() != J.rows()) workspace.y.resize(J.rows());
  }
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    const double plus = x[i] + step, minus = x[i] - step;
    const double delta = plus - minus;
    detail::check_finite_difference_spacing(delta, i, x[i], step);
    if constexpr (writes_output) {
      workspace.x[i] = plus;
      f(std::as_const(workspace.x), J.col(i));
      workspace.x[i] = minus;
      f(std::as_const(workspace.x), Eigen::Ref<Eigen::VectorXd>(workspace.y));
      J.col(i) = (J.col(i) - workspace.y) / delta;
    } else {
      workspace.x[i] = plus;
      const auto y_plus = detail::evaluated(f(std::as_const(workspace.x)));
      workspace.x[i] = minus;
      const auto y_minus = detail::evaluated(f(std::as_const(workspace.x)));
      detail::check_finite_difference_value_size(detail::value_size(y_plus), J.rows());
      detail::check_finite_difference_value_size(detail::value_size(y_minus), J.rows());
      detail::write_difference(y_plus, y_minus, delta, J.col(i));
    }
    workspace.x[i] = x[i];
  }
}

/// Central-difference Jacobian of a value-returning @p f (scalar or Eigen, as above) at @p x,
/// for one-off use: evaluates f(x) once for m and allocates the m × n result.
/// @throws Error as the preallocated form.
template <class F>
Eigen::MatrixXd finite_difference_jacobian(F&& f, const Eigen::Ref<const Eigen::VectorXd>& x,
                                           double step = kFiniteDifferenceStep) {
  static_assert(std::is_invocable_v<F&, const Eigen::VectorXd&>,
                "the one-off form needs f(x) returning its value; pass a preallocated J for "
                "f(x, y)");
  detail::check_finite_difference_step(step);
  FiniteDifferenceWorkspace workspace;
  workspace.x = x;
  const Eigen::Index m = detail::value_size(detail::evaluated(f(std::as_const(workspace.x))));
  Eigen::MatrixXd J(m, x.size());
  finite_difference_jacobian(f, x, J, workspace, step);
  return J;
}

/// Central-difference derivative df/dt of a function of one real variable at @p t:
/// (f(t + h) − f(t − h)) / Δ, of the same type as f's value (a scalar or a plain Eigen object).
/// @throws Error on a non-finite t or step, or a step that vanishes next to a large t.
template <class F>
auto finite_difference_derivative(F&& f, double t, double step = kFiniteDifferenceStep) {
  detail::check_finite_difference_step(step);
  detail::check_finite_difference_point(Eigen::Matrix<double, 1, 1>(t));
  const double plus = t + step, minus = t - step;
  const double delta = plus - minus;
  detail::check_finite_difference_spacing(delta, 0, t, step);
  const auto y_plus = detail::evaluated(f(plus));
  const auto y_minus = detail::evaluated(f(minus));
  if constexpr (std::is_arithmetic_v<std::decay_t<decltype(y_plus)>>) {
    return (y_plus - y_minus) / delta;
  } else {
    return ((y_plus - y_minus) / delta).eval();
  }
}

/// Central-difference twist Jacobian (6 × n, linear rows first) of a pose-valued function
/// x ↦ X_WE(x) at @p x, in the same frames as `ChainKinematics::jacobian` (column i, with
/// X₊ = X_WE(x + h·e_i), X₋ = X_WE(x − h·e_i)):
/// - `world`: the spatial twist log(X₊·X₋⁻¹)/Δ (SE(3) log);
/// - `local`: the body twist log(X₋⁻¹·X₊)/Δ (SE(3) log), in E's axes;
/// - `world_aligned`: [ṗ_WE; ω_WE], the world twist with its linear part taken at E's origin:
///   (p₊ − p₋)/Δ and the rotation part log(R₊·R₋ᵀ)/Δ.
/// Each is second order in h (the O(h²) terms of the two logs cancel).
/// @p f takes `const Eigen::VectorXd& x` and returns a `Pose` (a reference, such as
/// `ChainKinematics::update`'s, is copied before the next call).
/// @throws Error on a non-finite x or step, a J that is not 6 × n, or a vanishing step.
template <class F>
void finite_difference_pose_jacobian(F&& f, const Eigen::Ref<const Eigen::VectorXd>& x,
                                     Eigen::Ref<Matrix6Xd> J, FiniteDifferenceWorkspace& workspace,
                                     JacobianFrame frame = JacobianFrame::world_aligned,
                                     double step = kFiniteDifferenceStep) {
  detail::check_finite_difference_step(step);
  detail::check_finite_difference_point(x);
  detail::check_finite_difference_shape(J.rows(), J.cols(), x.size(), 6, "pose Jacobian");
  if (workspace.x.size() != x.size()) workspace.x.resize(x.size());
  workspace.x = x;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    const double plus = x[i] + step, minus = x[i] - step;
    const double delta = plus - minus;
    detail::check_finite_difference_spacing(delta, i, x[i], step);
    workspace.x[i] = plus;
    const Pose X_plus = f(std::as_const(workspace.x));
    workspace.x[i] = minus;
    const Pose X_minus = f(std::as_const(workspace.x));
    workspace.x[i] = x[i];
    detail::pose_difference(X_plus, X_minus, delta, frame, J.col(i));
  }
}

/// One-off form of `finite_difference_pose_jacobian`: allocates the 6 × n result.
template <class F>
Matrix6Xd finite_difference_pose_jacobian(F&& f, const Eigen::Ref<const Eigen::VectorXd>& x,
                                          JacobianFrame frame = JacobianFrame::world_aligned,
                                          double step = kFiniteDifferenceStep) {
  Matrix6Xd J(6, x.size());
  FiniteDifferenceWorkspace workspace;
  finite_difference_pose_jacobian(f, x, J, workspace, frame, step);
  return J;
}

}  // namespace mjarm
