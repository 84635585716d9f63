#pragma once
// Every document of a YAML stream, as yaml-cpp's LoadAll, without its endless loop.

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

namespace mjarm {

/// The documents of @p text (YAML or JSON), as `YAML::LoadAll` returns them.
///
/// yaml-cpp 0.7 (Debian 12's) loops for ever on some invalid streams, a lone `,` among them:
/// its parser reports a document without consuming a token, again and again, and `LoadAll`
/// collects a null node each time until memory runs out (fixed upstream after 0.8.0,
/// jbeder/yaml-cpp#1319). The stream is therefore walked with the parser first, which stops at
/// a document that starts where the one before it did.
/// @throws YAML::ParserException as `LoadAll`; Error "SOURCE:LINE: not valid YAML or JSON: …"
///         where the parser stops making progress.
std::vector<YAML::Node> load_yaml_documents(const std::string& text, const std::string& source);

}  // namespace mjarm
