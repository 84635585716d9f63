#include "mjarm/kinematics/singularity.hpp"

#include <algorithm>

#include "mjarm/error.hpp"
#include "mjarm/kinematics/workspace.hpp"
#include "mjarm/random.hpp"

namespace mjarm {
namespace {

SingularityEntry measure(SingularityClassifier& classifier, std::string name,
                         const Eigen::VectorXd& q) {
  SingularityClassification c = classifier.classify(q);
  const Manipulability& m = classifier.manipulability();
  const ManipulabilityResult& r = m.result();
  SingularityEntry e;
  e.name = std::move(name);
  e.q = q;
  e.singular_values = m.singular_values();
  e.sigma_min = r.sigma_min;
  e.condition_number = r.condition_number;
  e.manipulability = r.manipulability;
  e.status = r.status;
  e.below_sigma_min = c.below_sigma_min;
  e.above_condition_number = c.above_condition_number;
  e.kinds = std::move(c.kinds);
  e.null_direction = std::move(c.null_direction);
  e.geometry = c.geometry;
  return e;
}

}  // namespace

std::vector<NamedConfiguration> standard_configurations(const Chain& chain) {
  const mjModel& m = chain.robot().model();
  std::vector<NamedConfiguration> configurations;
  configurations.push_back({"qpos0", chain.gather(m.qpos0)});
  configurations.push_back({"center", chain.center()});
  for (int k = 0; k < m.nkey; ++k) {
    const char* key_name = mj_id2name(&m, mjOBJ_KEY, k);
    const std::string name =
        key_name != nullptr && key_name[0] != '\0' ? key_name : "keyframe " + std::to_string(k);
    configurations.push_back({name, chain.gather(m.key_qpos + k * m.nq)});
  }
  return configurations;
}

SingularityReport singularity_report(const Chain& chain,
                                     const std::vector<NamedConfiguration>& extra,
                                     const ManipulabilityOptions& options,
                                     const SingularityThresholds& thresholds) {
  // check the caller's configurations first, naming each
  for (const NamedConfiguration& c : extra) chain.check(c.q, "configuration '" + c.name + "'");
  SingularityClassifier classifier(chain, options, thresholds);
  SingularityReport report;
  report.options = options;
  report.thresholds = thresholds;
  for (const NamedConfiguration& c : standard_configurations(chain)) {
    report.entries.push_back(measure(classifier, c.name, c.q));
  }
  for (const NamedConfiguration& c : extra)
    report.entries.push_back(measure(classifier, c.name, c.q));
  return report;
}

SingularityScan scan_singularities(const Chain& chain, std::size_t samples, std::uint64_t seed,
                                   std::size_t keep_worst, const ManipulabilityOptions& options,
                                   const SingularityThresholds& thresholds,
                                   const ProgressCallback& progress, const StopRequest& stop) {
  if (samples == 0) throw Error("singularity scan needs at least one sample, got 0");
  SingularityClassifier classifier(chain, options, thresholds);
  Manipulability& m = classifier.manipulability();
  const JointSampler sampler(chain);
  Random rng(seed);
  SingularityScan scan;
  scan.options = options;
  scan.thresholds = thresholds;
  scan.samples = samples;
  scan.seed = seed;

  // keep the worst as a max-heap on σmin (its top is the best of the worst, evicted first);
  // ties break on the sample index so the result does not depend on heap internals
  struct Candidate {
    double sigma_min;
    std::size_t index;
    Eigen::VectorXd q;
  };
  const auto less = [](const Candidate& a, const Candidate& b) {
    return a.sigma_min < b.sigma_min || (a.sigma_min == b.sigma_min && a.index < b.index);
  };
  std::vector<Candidate> heap;
  heap.reserve(keep_worst + 1);
  Eigen::VectorXd q(chain.size());
  // every 1 % of the work, and at least every 1000 samples: a long run still shows it moving
  const std::size_t report_every = std::clamp<std::size_t>((samples + 99) / 100, 1, 1000);
  for (std::size_t s = 0; s < samples; ++s) {
    if (stop && s % 1000 == 0 && stop()) {
      scan.status = SamplingStatus::interrupted;
      scan.samples = s;
      break;
    }
    if (progress && s > 0 && s % report_every == 0) progress(s, samples);
    sampler.sample(rng, q);
    const ManipulabilityResult& r = m.evaluate(q);
    if (r.status == SingularityStatus::singular) ++scan.singular_count;
    if (r.status == SingularityStatus::near_singular) ++scan.near_singular_count;
    if (r.sigma_min < thresholds.sigma_min || r.condition_number > thresholds.condition_number) {
      ++scan.flagged_count;
    }
    if (keep_worst == 0) continue;
    if (heap.size() < keep_worst || r.sigma_min < heap.front().sigma_min) {
      heap.push_back({r.sigma_min, s, q});
      std::push_heap(heap.begin(), heap.end(), less);
      if (heap.size() > keep_worst) {
        std::pop_heap(heap.begin(), heap.end(), less);
        heap.pop_back();
      }
    }
  }
  if (progress && scan.status == SamplingStatus::complete) progress(samples, samples);
  std::sort(heap.begin(), heap.end(), less);
  for (const Candidate& c : heap) {
    scan.worst.push_back(measure(classifier, "sample " + std::to_string(c.index), c.q));
  }
  return scan;
}

}  // namespace mjarm
