#pragma once
/// @file
/// The dashboard page (sweep_dashboard.hpp): HTML, CSS and the script that draws it from the data
/// put in place of its one `@DATA@`.

#include <string>

namespace mjarm {

const std::string& sweep_dashboard_page();

}  // namespace mjarm
