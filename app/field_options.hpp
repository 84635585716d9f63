#pragma once
/// @file
/// Command-line options from declared enums and fields (mjarm/fields.hpp): the accepted names
/// come from the declaration, and a wrong one is refused with the closest.

#include <CLI/CLI.hpp>
#include <string>

#include "mjarm/closest_names.hpp"
#include "mjarm/fields.hpp"
#include "output.hpp"

namespace mjarm::cli {

/// Accepts the names @p E declares ("kinematic|position|torque" in the help); another word is
/// refused as "unknown mode 'torq'; closest: torque; modes: kinematic, position, torque".
/// @param kind what the value is, for the message ("mode")
template <DeclaredEnum E>
CLI::Validator name_of(const std::string& kind) {
  return CLI::Validator(
      [kind](std::string& text) -> std::string {
        if (enum_from_name<E>(text)) return {};
        return unknown_name_message(kind, text, enum_names<E>());
      },
      join(enum_names<E>(), "|"), "name_of");
}

}  // namespace mjarm::cli
