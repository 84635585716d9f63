#include "mjarm/sim/reset_data.hpp"

#include <cstddef>
#include <cstring>

namespace mjarm {

void reset_data(const mjModel& m, mjData& d) noexcept {
  // the info header after the constant sizes, up to the buffer pointers: all zero after a reset
  constexpr std::size_t header_begin = offsetof(mjData, pstack);
  constexpr std::size_t header_end = offsetof(mjData, buffer);
  std::memset(reinterpret_cast<char*>(&d) + header_begin, 0, header_end - header_begin);
  std::memset(d.buffer, 0, static_cast<std::size_t>(m.nbuffer));
  std::memcpy(d.qpos, m.qpos0, sizeof(mjtNum) * static_cast<std::size_t>(m.nq));
  for (int body = 0; body < m.nbody; ++body) {
    const int id = m.body_mocapid[body];
    if (id < 0) continue;
    std::memcpy(d.mocap_pos + 3 * id, m.body_pos + 3 * body, 3 * sizeof(mjtNum));
    std::memcpy(d.mocap_quat + 4 * id, m.body_quat + 4 * body, 4 * sizeof(mjtNum));
  }
}

}  // namespace mjarm
