// MJCF staging: parse -> inline <include> -> absolute, checked asset paths -> write with a line map.

#include "mjcf_staging.hpp"

#include <cstdlib>
#include <limits>
#include <sstream>

#include "mjarm/error.hpp"
#include "mjarm/model/model_size.hpp"
#include "mjcf_detail.hpp"

namespace mjarm {

namespace {

std::uint64_t saturating_product(std::uint64_t a, std::uint64_t b) {
  if (a != 0 && b > std::numeric_limits<std::uint64_t>::max() / a)
    return std::numeric_limits<std::uint64_t>::max();
  return a * b;
}

// how many copies of its children MuJoCo makes of an element: <replicate count="N">, and the
// a·b·c grid of a <composite> or <flexcomp count="a b c">
std::uint64_t copies_made(const mjcf_detail::XmlNode& n) {
  if (n.tag != "replicate" && n.tag != "composite" && n.tag != "flexcomp") return 1;
  const std::string* count = n.find("count");
  if (count == nullptr) return 1;
  std::istringstream words(*count);
  std::uint64_t copies = 1;
  double value = 0.0;
  while (words >> value)
    if (value >= 1.0)
      copies = saturating_product(
          copies, value >= 1e18 ? std::uint64_t{1'000'000'000'000'000'000}
                                : static_cast<std::uint64_t>(value));
  return copies;
}

void count_elements(const mjcf_detail::XmlNode& parent, std::uint64_t copies,
                    ModelSizeCount& count) {
  for (const auto& child : parent.children) {
    count.add(child.tag, copies);
    count_elements(child, saturating_product(copies, copies_made(child)), count);
  }
}

}  // namespace

std::string StagedMjcf::to_source_lines(std::string_view message) const {
  return mjcf_detail::to_source_lines(message, source_lines);
}

StagedMjcf stage_mjcf(std::string_view xml, const std::filesystem::path& base_dir,
                      const std::filesystem::path& source_file, bool missing_meshes_as_boxes) {
  using namespace mjcf_detail;
  // an empty base_dir means the working directory
  const std::filesystem::path base =
      (base_dir.empty() ? std::filesystem::current_path() : std::filesystem::absolute(base_dir))
          .lexically_normal();
  XmlNode root = parse_document(
      xml,
      source_file.empty() ? nullptr : std::make_shared<const std::filesystem::path>(source_file));
  if (root.tag != "mujoco") fail(root, "the root element must be <mujoco>");
  inline_includes(root, base);
  // the size bound before any work that grows with it (the asset checks, MuJoCo's compile)
  ModelSizeCount count;
  count_elements(root, 1, count);
  count.check(source_file.empty() ? std::string("the MJCF text")
                                  : "model '" + source_file.string() + "'");
  StagedMjcf result;
  resolve_asset_paths(root, base, missing_meshes_as_boxes ? &result.missing_meshes : nullptr);
  result.xml = write_document(root, &result.source_lines);
  return result;
}

}  // namespace mjarm
