#pragma once
// A YAML (or JSON) document as JSON: maps as objects, sequences as arrays, plain scalars typed as
// YAML's core schema reads them (null, true/false, integers, numbers with .inf/.nan), quoted
// scalars as strings.

#include <nlohmann/json.hpp>
#include <string>

namespace mjarm {

/// The one document of @p text as JSON; an empty text is null.
/// @throws Error "SOURCE: not valid YAML or JSON: …" for a syntax error (with its line) or a
///         stream of several documents
nlohmann::ordered_json yaml_to_json(const std::string& text, const std::string& source);

}  // namespace mjarm
