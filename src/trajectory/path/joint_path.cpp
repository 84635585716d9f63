#include "mjarm/trajectory/path/joint_path.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

namespace {

void require_path_output(Eigen::Index size, Eigen::Index n, const char* what) {
  if (size != n)
    throw Error(std::string("joint path: ") + what + " has " + std::to_string(size) +
                " entries, expected " + std::to_string(n));
}

}  // namespace

JointPath::JointPath(const std::vector<Eigen::VectorXd>& waypoints) {
  if (waypoints.size() < 2)
    throw Error("joint path: needs at least 2 waypoints, got " + std::to_string(waypoints.size()));
  const Eigen::Index n = waypoints.front().size();
  if (n == 0) throw Error("joint path: waypoint 0 has no joints");
  const int count = static_cast<int>(waypoints.size());
  const int pieces = count - 1;
  waypoints_.resize(n, count);
  for (int k = 0; k < count; ++k) {
    if (waypoints[k].size() != n)
      throw Error("joint path: waypoint " + std::to_string(k) + " has " +
                  std::to_string(waypoints[k].size()) + " joints, waypoint 0 has " +
                  std::to_string(n));
    for (Eigen::Index j = 0; j < n; ++j)
      if (!std::isfinite(waypoints[k][j]))
        throw Error("joint path: waypoint " + std::to_string(k) + " joint " + std::to_string(j) +
                    " is not finite (" + number_text(waypoints[k][j]) + ")");
    waypoints_.col(k) = waypoints[k];
  }
  knots_.resize(count);
  knots_[0] = 0.0;
  for (int k = 1; k < count; ++k) {
    const double chord = (waypoints_.col(k) - waypoints_.col(k - 1)).norm();
    // a chord this short relative to where it lies has no usable direction
    const double scale = 1.0 + waypoints_.col(k).cwiseAbs().maxCoeff();
    if (!(chord > 1e-12 * scale))
      throw Error("joint path: waypoints " + std::to_string(k - 1) + " and " + std::to_string(k) +
                  " are the same (chord length " + number_text(chord) +
                  "); consecutive waypoints must differ");
    knots_[k] = knots_[k - 1] + chord;
  }

  // natural spline: second derivatives M_k with M_0 = M_K = 0 and, at interior knots,
  // h_{k−1}M_{k−1} + 2(h_{k−1} + h_k)M_k + h_k M_{k+1} = 6(slope_k − slope_{k−1});
  // the tridiagonal system by the Thomas algorithm, every joint at once
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, count);
  if (pieces > 1) {
    const int m = pieces - 1;  // unknowns M_1 … M_{K−1}
    Eigen::VectorXd diag(m), upper(m);
    Eigen::MatrixXd rhs(n, m);
    for (int r = 0; r < m; ++r) {
      const int k = r + 1;
      const double h0 = knots_[k] - knots_[k - 1], h1 = knots_[k + 1] - knots_[k];
      diag[r] = 2.0 * (h0 + h1);
      upper[r] = h1;
      rhs.col(r) = 6.0 * ((waypoints_.col(k + 1) - waypoints_.col(k)) / h1 -
                          (waypoints_.col(k) - waypoints_.col(k - 1)) / h0);
    }
    for (int r = 1; r < m; ++r) {
      const double lower = knots_[r + 1] - knots_[r];  // h_{k−1} of row r (k = r + 1)
      const double w = lower / diag[r - 1];
      diag[r] -= w * upper[r - 1];
      rhs.col(r) -= w * rhs.col(r - 1);
    }
    M.col(m) = rhs.col(m - 1) / diag[m - 1];
    for (int r = m - 2; r >= 0; --r)
      M.col(r + 1) = (rhs.col(r) - upper[r] * M.col(r + 2)) / diag[r];
  }
  c0_.resize(n, pieces);
  c1_.resize(n, pieces);
  c2_.resize(n, pieces);
  c3_.resize(n, pieces);
  for (int k = 0; k < pieces; ++k) {
    const double h = knots_[k + 1] - knots_[k];
    c0_.col(k) = waypoints_.col(k);
    c1_.col(k) =
        (waypoints_.col(k + 1) - waypoints_.col(k)) / h - h * (2.0 * M.col(k) + M.col(k + 1)) / 6.0;
    c2_.col(k) = 0.5 * M.col(k);
    c3_.col(k) = (M.col(k + 1) - M.col(k)) / (6.0 * h);
  }
}

int JointPath::piece_at(double s) const noexcept {
  const double* begin = knots_.data();
  const double* end = begin + knots_.size();
  // the last knot s_k ≤ s, among s_0 … s_{K−1}
  const double* it = std::upper_bound(begin + 1, end - 1, s);
  return static_cast<int>(it - begin) - 1;
}

void JointPath::evaluate(double s, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> dq,
                         Eigen::Ref<Eigen::VectorXd> ddq) const {
  const Eigen::Index n = dofs();
  require_path_output(q.size(), n, "q");
  require_path_output(dq.size(), n, "q′");
  require_path_output(ddq.size(), n, "q″");
  if (!(s > 0.0)) s = 0.0;  // also NaN
  s = std::min(s, length());
  const int k = piece_at(s);
  const double t = s - knots_[k];
  q = c0_.col(k) + t * (c1_.col(k) + t * (c2_.col(k) + t * c3_.col(k)));
  dq = c1_.col(k) + t * (2.0 * c2_.col(k) + 3.0 * t * c3_.col(k));
  ddq = 2.0 * c2_.col(k) + 6.0 * t * c3_.col(k);
}

void JointPath::evaluate(double s, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> dq,
                         Eigen::Ref<Eigen::VectorXd> ddq, Eigen::Ref<Eigen::VectorXd> dddq) const {
  require_path_output(dddq.size(), dofs(), "q‴");
  evaluate(s, q, dq, ddq);
  if (!(s > 0.0)) s = 0.0;
  dddq = 6.0 * c3_.col(std::min(piece_at(s), static_cast<int>(c3_.cols()) - 1));
}

}  // namespace mjarm
