#pragma once
// What the built-in scenarios share when they turn a task's report into a TrialOutcome.

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

}  // namespace detail

}  // namespace mjarm
