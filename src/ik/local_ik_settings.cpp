#include "mjarm/ik/local_ik_settings.hpp"

#include <string>

#include "option_check.hpp"

namespace mjarm {

void check(const LocalIkSettings& settings, std::string_view solver) {
  detail::check_fields(detail::OptionCheck(std::string(solver) + " option "), settings);
}

namespace detail {

void check_fields(const OptionCheck& require, const LocalIkSettings& s) {
  require.positive("damping", s.damping);
  require.require(s.step > 0.0 && s.step <= 1.0, "step", s.step, "in (0, 1]");
  require.at_least("max_backtracks", s.max_backtracks, 0);
  require.non_negative("null_space_damping", s.null_space_damping);
  require.positive("max_step", s.max_step);
  require.non_negative("secondary_ratio", s.secondary_ratio);
  check_fields(require.member("limits"), s.limits);
  check_fields(require.member("posture"), s.posture);
  require.at_least("max_iterations", s.max_iterations, 1);
  require.at_least("stall_iterations", s.stall_iterations, 1);
  require.require(s.stall_progress >= 0.0 && s.stall_progress < 1.0, "stall_progress",
                  s.stall_progress, "in [0, 1)");
  check_fields(require.member("collision"), s.collision);
}

}  // namespace detail
}  // namespace mjarm
