#pragma once
// What the session file's writer (session_log.cpp) and reader (session_log_reader.cpp) share.

namespace mjarm {

/// The first word of a session file (then its version, 1).
inline constexpr const char* kSessionFileMagic = "mjarm-teleop-session";

}  // namespace mjarm
