#include "scenarios/scenario_parts.hpp"

#include "mjarm/error.hpp"

namespace mjarm::detail {

RunVideoOptions video_options(const ScenarioOutputs& outputs) {
  RunVideoOptions options;
  options.width = outputs.width;
  options.height = outputs.height;
  options.fps = outputs.fps;
  return options;
}

std::string one_camera(const ScenarioOutputs& outputs, std::string_view scenario) {
  if (outputs.cameras.size() > 1)
    throw Error(std::string(scenario) + " films one camera, got " +
                std::to_string(outputs.cameras.size()));
  return outputs.cameras.empty() ? std::string() : outputs.cameras.front();
}

TrialOutcome outcome_of(const RunResult& run, std::string_view verdict, bool success) {
  TrialOutcome out;
  out.status = run.status;
  out.verdict = verdict;
  out.success = success;
  out.message = run.message;
  out.end_time = run.end_time;
  return out;
}

void take_outputs(TrialOutcome& outcome, const std::filesystem::path& recording,
                  const std::string& recording_error, const std::string& video_error) {
  outcome.recording = recording;
  outcome.recording_error = recording_error;
  outcome.video_error = video_error;
}

}  // namespace mjarm::detail
