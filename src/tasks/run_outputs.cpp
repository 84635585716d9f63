#include "run_outputs.hpp"

namespace mjarm {

std::string finish_recording(Recorder& recorder, double time, const std::string& result_line,
                             const RunResult& run) {
  recorder.event(time, "result", result_line);
  try {
    recorder.finalize(run);
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

}  // namespace mjarm
