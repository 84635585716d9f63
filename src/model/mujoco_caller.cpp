#include "mujoco_caller.hpp"

#include <dlfcn.h>
#include <execinfo.h>
#include <mujoco/mujoco.h>

#include <array>
#include <atomic>

namespace mjarm::detail {
namespace {

const void* code_object_of(const void* address) noexcept {
  Dl_info info;
  return dladdr(address, &info) != 0 ? info.dli_fbase : nullptr;
}

// the library's own object first; a few more may be noted (one per extension linking mjarm)
constexpr int kMaxMjarmObjects = 8;
std::array<std::atomic<const void*>, kMaxMjarmObjects> mjarm_objects{};

bool is_mjarm_object(const void* object) noexcept {
  if (object == nullptr) return false;
  if (object == code_object_of(reinterpret_cast<const void*>(&code_object_of))) return true;
  for (const auto& known : mjarm_objects)
    if (known.load(std::memory_order_acquire) == object) return true;
  return false;
}

}  // namespace

void note_mjarm_code(const void* address) noexcept {
  const void* object = code_object_of(address);
  if (object == nullptr || is_mjarm_object(object)) return;
  for (auto& slot : mjarm_objects) {
    const void* empty = nullptr;
    if (slot.compare_exchange_strong(empty, object) || empty == object) return;
  }
}

bool mujoco_called_by_mjarm() noexcept {
  // the version string is MuJoCo's data: its object is the library (see mujoco_library_path)
  const void* mujoco = code_object_of(static_cast<const void*>(mj_versionString()));
  std::array<void*, 64> frames{};
  const int count = backtrace(frames.data(), static_cast<int>(frames.size()));
  bool inside_mujoco = false;
  for (int i = 0; i < count; ++i) {
    const void* object = code_object_of(frames[static_cast<std::size_t>(i)]);
    if (object == mujoco) {
      inside_mujoco = true;
    } else if (inside_mujoco) {
      return is_mjarm_object(object);
    }
  }
  return false;
}

}  // namespace mjarm::detail
