#include "recorded_state.hpp"

namespace mjarm::web_detail {
namespace {

std::vector<std::string> joint_columns(const mjModel& m, const char* prefix, bool velocity) {
  std::vector<std::string> columns;
  for (int j = 0; j < m.njnt; ++j) {
    const int type = m.jnt_type[j];
    const int n = type == mjJNT_FREE   ? (velocity ? 6 : 7)
                  : type == mjJNT_BALL ? (velocity ? 3 : 4)
                                       : 1;
    const char* name = mj_id2name(&m, mjOBJ_JOINT, j);
    const std::string base =
        prefix +
        ((name != nullptr && name[0] != '\0') ? std::string(name) : "joint" + std::to_string(j));
    for (int k = 0; k < n; ++k) columns.push_back(n == 1 ? base : base + "." + std::to_string(k));
  }
  return columns;
}

}  // namespace

std::vector<std::string> qpos_columns(const mjModel& m) { return joint_columns(m, "q.", false); }

std::vector<std::string> qvel_columns(const mjModel& m) { return joint_columns(m, "v.", true); }

}  // namespace mjarm::web_detail
