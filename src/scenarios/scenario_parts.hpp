#pragma once
// What the built-in scenarios share when they turn a task's report into a TrialOutcome.

#include <algorithm>
#include <deque>
#include <memory>
#include <mutex>
#include <string_view>

#include "mjarm/scenarios/scenario.hpp"
#include "mjarm/tasks/run_video.hpp"

namespace mjarm {

namespace detail {

/// The size, frame rate (and default encoding) of @p outputs' video.
RunVideoOptions video_options(const ScenarioOutputs& outputs);

/// The one camera @p outputs asks for ("" for the default).
/// @throws Error naming @p scenario when it asks for several
std::string one_camera(const ScenarioOutputs& outputs, std::string_view scenario);

/// The outcome's status, verdict, success, message and end time.
TrialOutcome outcome_of(const RunResult& run, std::string_view verdict, bool success);

/// The recording and the video's error, as the task reports them.
void take_outputs(TrialOutcome& outcome, const std::filesystem::path& recording,
                  const std::string& recording_error, const std::string& video_error);

/// The scenes a scenario's trials ask for, each compiled once and shared (its model is
/// immutable): a sweep's trials then spend their time simulating. The last 16 are kept.
template <class Scene>
class SceneCache {
 public:
  /// The kept scene for which @p same(scene) holds, else @p build()'s, kept.
  template <class Same, class Build>
  std::shared_ptr<const Scene> get(Same same, Build build) {
    const std::lock_guard lock(mutex_);
    const auto it = std::find_if(scenes_.begin(), scenes_.end(),
                                 [&](const auto& scene) { return same(*scene); });
    if (it != scenes_.end()) return *it;
    scenes_.push_back(build());
    if (scenes_.size() > 16) scenes_.pop_front();
    return scenes_.back();
  }

 private:
  std::mutex mutex_;
  std::deque<std::shared_ptr<const Scene>> scenes_;
};

}  // namespace detail

}  // namespace mjarm
