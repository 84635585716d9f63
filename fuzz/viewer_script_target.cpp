#include "fuzz_targets.hpp"
#include "mjarm/teleop/viewer_script.hpp"
#include "refusal.hpp"

namespace mjarm::fuzz {

int fuzz_viewer_script(const std::uint8_t* data, std::size_t size) {
  return accept_or_refuse([&] { ViewerScript::parse(as_text(data, size), "<fuzz>"); });
}

}  // namespace mjarm::fuzz
