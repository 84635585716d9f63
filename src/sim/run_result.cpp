#include "mjarm/sim/run_result.hpp"

#include "mjarm/sim/simulation_options.hpp"

namespace mjarm {

const char* to_string(TickStatus status) noexcept {
  switch (status) {
    case TickStatus::ok: return "ok";
    case TickStatus::finished: return "finished";
    case TickStatus::diverged: return "diverged";
    case TickStatus::bad_command: return "bad_command";
  }
  return "?";
}

const char* to_string(RunStatus status) noexcept {
  switch (status) {
    case RunStatus::duration_reached: return "duration_reached";
    case RunStatus::finished: return "finished";
    case RunStatus::diverged: return "diverged";
    case RunStatus::bad_command: return "bad_command";
    case RunStatus::interrupted: return "interrupted";
  }
  return "?";
}

}  // namespace mjarm
