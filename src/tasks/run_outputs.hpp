#pragma once
/// @file
/// The end of a task run's outputs: the recorder's result line and files, then the video's last
/// frames and file. A failure in either becomes a message for the report, never an exception:
/// the run's figures stand, and the recorder's message says where its rows are.

#include <mujoco/mujoco.h>

#include <string>

#include "mjarm/error.hpp"
#include "mjarm/sim/recorder.hpp"

namespace mjarm {

/// Writes the "result" event (@p result_line at @p time [s]) and finalizes the recording with
/// the run's outcome. @return "" when the files are written, else the error's message.
std::string finish_recording(Recorder& recorder, double time, const std::string& result_line,
                             const RunResult& run);

/// Renders the frames due at @p last and finalizes the file (`RunVideo`, `PickPlaceVideoRun`).
/// @return "" when written, else the error's message.
template <class Video>
std::string finish_video(Video& video, const mjData& last) {
  try {
    video.finish(last);
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

}  // namespace mjarm
