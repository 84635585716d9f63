#pragma once
/// @file
/// The model a recording was made on: its model.mjb (MuJoCo's binary model, written by the
/// recorder: sim/recorder.hpp), which `mjarm replay-html` and `mjarm render` load.

#include <filesystem>

#include "mjarm/model/robot.hpp"
#include "mjarm/plot/recording.hpp"

namespace mjarm {

/// Loads a binary model written by MuJoCo (`mj_saveModel`) through the checked reader.
/// @throws Error naming the file when it is missing or unreadable, or when MuJoCo cannot load it
///         (another MuJoCo version wrote it, or it is damaged).
Robot load_mjb_model(const std::filesystem::path& path);

/// The recording's model.mjb.
/// @throws Error naming the recording when it has none (recorded before the recorder kept it:
///         pass the model instead, `--model`), or as `load_mjb_model`.
Robot recorded_model(const plot::Recording& recording);

}  // namespace mjarm
