#include "mjarm/version.hpp"

namespace mjarm {

// MJARM_VERSION is given to this file alone (CMakeLists.txt)
const char* version() noexcept { return MJARM_VERSION; }

}  // namespace mjarm
