#pragma once
/// @file
/// The page's script (web/: three.js and the page's own code, bundled by esbuild at build time
/// into a generated source, cmake/web_bundle.cmake).

#include <string>

namespace mjarm::web_detail {

/// The bundled script; empty when the build holds none.
std::string replay_bundle();
/// Why the build holds no script, and how to get one; empty when it holds one.
std::string replay_bundle_missing();

}  // namespace mjarm::web_detail
