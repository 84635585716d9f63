#pragma once
// A JSON file as mjarm's readers take it: strict JSON (nlohmann), one value, no key twice in an
// object (nlohmann would keep the last one without a word), and the line of every key, so that
// an unknown key is named with its line and the closest known key (closest_names.hpp,
// `unknown_name_message`), as the scene files' YAML reader does. Internal to the library.

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace mjarm {

class JsonDocument {
 public:
  /// Parses @p text; @p name prefixes every error ("waypoints 'wp.json'").
  /// @throws Error "NAME: not valid JSON (…)" with nlohmann's line and column, or
  ///         "NAME line 4: key 'position' appears twice in one object".
  JsonDocument(std::string_view text, std::string name);

  const nlohmann::json& root() const noexcept { return root_; }

  /// "NAME line L" for the key @p key of the object at JSON pointer @p object ("" for the root,
  /// "/waypoints/2"); "NAME" when the key is not in the text.
  std::string where(const std::string& object, const std::string& key) const;

  /// Refuses a key of the object at JSON pointer @p object that is not in @p known:
  /// "NAME line 5: unknown key 'quaternoin' in waypoint 1; closest: quaternion; keys: …"
  /// (@p what: "waypoint 1"). Keys are checked in the order of the text.
  /// @throws Error as above.
  void check_keys(const std::string& object, const std::vector<std::string>& known,
                  std::string_view what) const;

 private:
  nlohmann::json root_;
  std::string name_;
  struct Place {
    std::size_t offset;  // of the key's closing quote
    int line;
  };
  std::map<std::string, Place> key_places_;  // JSON pointer of a key ("/waypoints/2/position")
};

}  // namespace mjarm
