// MJCF staging: parse -> inline <include> -> absolute, checked asset paths -> write with a line map.

#include "mjarm/model/mjcf_staging.hpp"

#include "mjarm/error.hpp"
#include "mjcf_detail.hpp"

namespace mjarm {

std::string StagedMjcf::to_source_lines(std::string_view message) const {
  return mjcf_detail::to_source_lines(message, source_lines);
}

StagedMjcf stage_mjcf(std::string_view xml, const std::filesystem::path& base_dir,
                      const std::filesystem::path& source_file) {
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
  resolve_asset_paths(root, base);
  StagedMjcf result;
  result.xml = write_document(root, &result.source_lines);
  return result;
}

}  // namespace mjarm
