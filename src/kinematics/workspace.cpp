#include "mjarm/kinematics/workspace.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "mjarm/file_writer.hpp"
#include "mjarm/error.hpp"
#include "mjarm/random.hpp"

namespace mjarm {

JointSampler::JointSampler(const Chain& chain) : lower_(chain.lower()), upper_(chain.upper()) {
  for (int i = 0; i < chain.size(); ++i) {
    if (!std::isfinite(lower_[i]) || !std::isfinite(upper_[i])) {
      lower_[i] = -std::numbers::pi;
      upper_[i] = std::numbers::pi;
    }
  }
}

void JointSampler::sample(Random& rng, Eigen::Ref<Eigen::VectorXd> q) const noexcept {
  for (Eigen::Index i = 0; i < lower_.size(); ++i) q[i] = uniform(rng, lower_[i], upper_[i]);
}

namespace {

/// Index of the chain joint closest to the world on the frame's path.
int base_joint(const ChainKinematics& kin) {
  int best = -1;
  for (int i = 0; i < kin.chain().size(); ++i) {
    if (!kin.moves_frame(i)) continue;
    if (best < 0 || kin.chain().joint_id(i) < kin.chain().joint_id(best)) best = i;
  }
  return best;
}

}  // namespace

WorkspaceResult sample_workspace(const Chain& chain, const WorkspaceOptions& options) {
  check_fields(options);
  if (options.keep_points && options.samples > kMaxKeptWorkspacePoints) {
    throw Error(
        "workspace sampling: keeping " + std::to_string(options.samples) + " points would take " +
        std::to_string(options.samples / (std::size_t{1} << 20) * sizeof(WorkspacePoint)) +
        " MiB; at most " + std::to_string(kMaxKeptWorkspacePoints) + " points (" +
        std::to_string(kMaxKeptWorkspacePoints * sizeof(WorkspacePoint) >> 20) + " MiB) are kept");
  }
  Manipulability measure(chain, options.manipulability);
  ChainKinematics& kin = measure.kinematics();
  const JointSampler sampler(chain);
  Random rng(options.seed);
  const int n = chain.size();

  WorkspaceResult result;
  result.samples = options.samples;
  result.seed = options.seed;
  // the base: most proximal moving joint's anchor at the centre configuration
  kin.update(chain.center());
  const int base = base_joint(kin);
  result.p_WB = base >= 0 ? kin.anchor(base) : kin.pose().p;
  if (options.keep_points) result.points.resize(options.samples);

  result.lower.setConstant(std::numeric_limits<double>::infinity());
  result.upper.setConstant(-std::numeric_limits<double>::infinity());
  result.min_manipulability = std::numeric_limits<double>::infinity();
  result.max_manipulability = -std::numeric_limits<double>::infinity();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double w_sum = 0.0;
  Eigen::VectorXd q(n);
  const std::size_t total = options.samples;
  // every 1 % of the work, and at least every 1000 samples: a long run still shows it moving
  const std::size_t report_every = std::clamp<std::size_t>((total + 99) / 100, 1, 1000);
  constexpr std::size_t kStopEvery = 1000;

  const auto start = std::chrono::steady_clock::now();
  std::size_t done = 0;
  for (std::size_t s = 0; s < total; ++s) {
    if (options.stop && s % kStopEvery == 0 && options.stop()) {
      result.status = SamplingStatus::interrupted;
      break;
    }
    sampler.sample(rng, q);
    double w = 0.0;
    if (options.compute_manipulability) {
      w = measure.evaluate(q).manipulability;
    } else {
      kin.update(q);
    }
    const Eigen::Vector3d& p = kin.pose().p;
    result.lower = result.lower.cwiseMin(p);
    result.upper = result.upper.cwiseMax(p);
    sum += p;
    result.max_reach_from_base = std::max(result.max_reach_from_base, (p - result.p_WB).norm());
    result.max_reach_from_origin = std::max(result.max_reach_from_origin, p.norm());
    result.min_manipulability = std::min(result.min_manipulability, w);
    result.max_manipulability = std::max(result.max_manipulability, w);
    w_sum += w;
    if (options.keep_points) result.points[s] = WorkspacePoint{p, w};
    done = s + 1;
    if (options.progress && ((s + 1) % report_every == 0 || s + 1 == total)) {
      options.progress(s + 1, total);
    }
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.samples = done;
  if (options.keep_points) result.points.resize(done);
  if (done == 0) {
    // stopped before the first sample: no statistics to give
    result.lower.setZero();
    result.upper.setZero();
    result.min_manipulability = result.max_manipulability = 0.0;
    return result;
  }
  result.centroid = sum / static_cast<double>(done);
  result.mean_manipulability = w_sum / static_cast<double>(done);
  return result;
}

void WorkspaceResult::write_csv(const std::filesystem::path& path) const {
  // a new file beside the target, renamed over it once complete: never a truncated CSV
  FileWriter out(path, FileWriter::Mode::replace, "the workspace CSV");
  out.write("x,y,z,manipulability\n");
  char row[4 * 26 + 4];  // four %.17g numbers (at most 24 characters each) and separators
  for (const WorkspacePoint& point : points) {
    const int n = std::snprintf(row, sizeof(row), "%.17g,%.17g,%.17g,%.17g\n", point.p_WE.x(),
                                point.p_WE.y(), point.p_WE.z(), point.manipulability);
    if (!out.write(row, static_cast<std::size_t>(n))) break;  // the failure is reported below
  }
  out.commit();
}

}  // namespace mjarm
