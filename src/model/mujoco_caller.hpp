#pragma once
/// @file
/// Who called MuJoCo when it reports an error: mjarm's code, or another library's (MuJoCo's own
/// Python bindings, a viewer thread) sharing the process and the library. Only an error raised
/// under mjarm's own frames may become a C++ exception: any other caller cannot catch it, and an
/// exception unwinding through its frames crashes the process.

namespace mjarm::detail {

/// Counts the code object (executable or shared library) holding @p address as mjarm's, besides
/// the one holding the library itself (the Python extension, when the library is shared).
void note_mjarm_code(const void* address) noexcept;

/// True when the nearest caller of MuJoCo on the current stack (the first frame above MuJoCo's
/// own frames, walked from the handler that asks) is mjarm's code.
bool mujoco_called_by_mjarm() noexcept;

}  // namespace mjarm::detail
