#include "mjarm/env/vector_environment.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "mjarm/benchmark_timing.hpp"
#include "mjarm/env/task_registry.hpp"
#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {
namespace {

int checked_count(int count) {
  if (count < 1 || count > 4096)
    throw Error("vector environment: the number of environments must be from 1 to 4096, got " +
                std::to_string(count));
  return count;
}

}  // namespace

VectorEnvironment::VectorEnvironment(std::unique_ptr<EnvTask> task,
                                     const EnvironmentOptions& options, int count, int threads)
    : pool_((checked_count(count), threads)) {
  if (!task) throw Error("vector environment: no task given");
  environments_.reserve(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    EnvironmentOptions o = options;
    o.seed = splitmix64(options.seed + static_cast<std::uint64_t>(i));
    environments_.push_back(std::make_unique<Environment>(task->clone(), o));
  }
  const std::size_t n = static_cast<std::size_t>(count);
  step_types_.assign(n, StepType::first);
  ends_.assign(n, EpisodeEnd::running);
  rewards_.assign(n, std::numeric_limits<double>::quiet_NaN());
  discounts_.assign(n, std::numeric_limits<double>::quiet_NaN());
  env_cpu_.assign(n, 0.0);
  observations_.assign(n * static_cast<std::size_t>(observation_spec().size()), 0.0);
}

VectorEnvironment::VectorEnvironment(std::string_view task, const EnvironmentOptions& options,
                                     int count, int threads)
    : VectorEnvironment(make_env_task(task), options, count, threads) {}

VectorEnvironment::~VectorEnvironment() = default;

std::span<const double> VectorEnvironment::observation(int i) const {
  if (i < 0 || i >= size())
    throw Error("vector environment: row " + std::to_string(i) + " out of range [0, " +
                std::to_string(size()) + ")");
  const std::size_t width = static_cast<std::size_t>(observation_spec().size());
  return std::span<const double>(observations_).subspan(static_cast<std::size_t>(i) * width, width);
}

void VectorEnvironment::record(int i, const TimeStep& ts) noexcept {
  const std::size_t row = static_cast<std::size_t>(i);
  constexpr double none = std::numeric_limits<double>::quiet_NaN();
  step_types_[row] = ts.step_type;
  ends_[row] = ts.end;
  rewards_[row] = ts.reward.value_or(none);
  discounts_[row] = ts.discount.value_or(none);
  const std::span<const double> values = ts.observation.values();
  std::copy(values.begin(), values.end(),
            observations_.begin() + static_cast<std::ptrdiff_t>(row * values.size()));
}

void VectorEnvironment::close() noexcept {
  for (auto& environment : environments_) environment->close();
  closed_ = true;
}

namespace {

[[noreturn]] void refuse_closed_batch(const Environment& first, const char* call) {
  throw Error("vector environment '" + std::string(first.task().name()) + "': " + call +
              " after close(); a closed environment stays closed: make a new one");
}

}  // namespace

void VectorEnvironment::reset() {
  if (closed_) refuse_closed_batch(*environments_.front(), "reset()");
  auto job = [this](int i) {
    const double start = thread_cpu_seconds();
    record(i, environments_[static_cast<std::size_t>(i)]->reset());
    env_cpu_[static_cast<std::size_t>(i)] = thread_cpu_seconds() - start;
  };
  pool_.run(size(), job);
  started_ = true;
}

void VectorEnvironment::step(std::span<const double> actions) {
  if (closed_) refuse_closed_batch(*environments_.front(), "step()");
  if (!started_) throw Error("vector environment: step() before reset(); call reset() first");
  const ArraySpec& spec = action_spec();
  const std::size_t width = static_cast<std::size_t>(spec.size());
  if (actions.size() != width * environments_.size())
    throw Error("vector environment: the actions need " + std::to_string(environments_.size()) +
                " rows × " + std::to_string(width) +
                " values = " + std::to_string(width * environments_.size()) + ", got " +
                std::to_string(actions.size()));
  // every row checked before any environment moves
  const bool refuse = environments_.front()->options().refuse_out_of_bounds;
  for (std::size_t k = 0; k < actions.size(); ++k) {
    const double a = actions[k];
    const Eigen::Index j = static_cast<Eigen::Index>(k % width);
    if (!std::isfinite(a))
      throw Error("vector environment: action row " + std::to_string(k / width) + " entry " +
                  std::to_string(j) + " is " + number_text(a) + " (finite values needed)");
    if (refuse && (a < spec.minimum[j] || a > spec.maximum[j]))
      throw Error("vector environment: action row " + std::to_string(k / width) + " entry " +
                  std::to_string(j) + " = " + number_text(a) + " is outside its bounds [" +
                  number_text(spec.minimum[j]) + ", " + number_text(spec.maximum[j]) +
                  "] (refuse_out_of_bounds is set)");
  }
  actions_ = actions;
  auto job = [this, width](int i) {
    const double start = thread_cpu_seconds();
    Environment& env = *environments_[static_cast<std::size_t>(i)];
    if (step_types_[static_cast<std::size_t>(i)] == StepType::last) {
      record(i, env.reset());
    } else {
      record(i, env.step(actions_.subspan(static_cast<std::size_t>(i) * width, width)));
    }
    env_cpu_[static_cast<std::size_t>(i)] = thread_cpu_seconds() - start;
  };
  pool_.run(size(), job);
}

}  // namespace mjarm
