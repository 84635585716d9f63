#include "mjarm/teleop/viewer_script.hpp"

#include <mujoco/mjui.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "mjarm/error.hpp"
#include "mjarm/model/names.hpp"
#include "mjarm/model/user_file.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/teleop/viewer_panel.hpp"

namespace mjarm {

namespace {

struct KeyName {
  const char* name;
  int code;
};
constexpr KeyName kKeys[] = {{"space", 32},
                             {"right", mjKEY_RIGHT},
                             {"backspace", mjKEY_BACKSPACE},
                             {"escape", mjKEY_ESCAPE},
                             {"tab", 258},
                             {"w", 'W'},
                             {"s", 'S'},
                             {"a", 'A'},
                             {"d", 'D'},
                             {"r", 'R'},
                             {"f", 'F'},
                             {"g", 'G'}};
// the longest `wait`: 10⁷ frames (about 46 h at 60 Hz); a longer one is a mistake
constexpr double kMaxWaitFrames = 1e7;

constexpr const char* kKeyList =
    "space, right, backspace, escape, and for the bimanual panel's nudges w s a d r f g tab "
    "(shift+w … shift+f turn the hand)";

// the bimanual panel's names (TeleopPanel): "<hand>.<value>", "camera.<value>", "lift",
// "priority", "hand" — checked against the session's hands when the script runs
bool teleop_name(const std::string& name) {
  return name.find('.') != std::string::npos || name == "lift" || name == "priority" ||
         name == "hand";
}

std::vector<std::string> split(std::string_view line) {
  std::vector<std::string> words;
  std::istringstream in{std::string(line)};
  for (std::string word; in >> word;) words.push_back(word);
  return words;
}

class LineParser {
 public:
  LineParser(std::string_view source, int line) : source_(source), line_(line) {}

  [[noreturn]] void fail(const std::string& message) const {
    throw Error(std::string(source_) + ":" + std::to_string(line_) + ": " + message);
  }

  double number(const std::string& word, const char* what) const {
    const auto v = number_from_text(word);
    if (!v || !std::isfinite(*v))
      fail(std::string(what) + " must be a finite number, got '" + word + "'");
    return *v;
  }

  void arguments(const std::vector<std::string>& words, std::size_t count,
                 const char* usage) const {
    if (words.size() != count + 1) fail("'" + words[0] + "' takes " + usage);
  }

 private:
  std::string_view source_;
  int line_;
};

}  // namespace

int viewer_key_code(std::string_view name) noexcept {
  for (const auto& key : kKeys) {
    if (name == key.name) return key.code;
  }
  return 0;
}

ViewerScript ViewerScript::parse(std::string_view text, std::string_view source) {
  ViewerScript script;
  std::istringstream in{std::string(text)};
  int number = 0;
  for (std::string raw; std::getline(in, raw);) {
    ++number;
    const std::string line = raw.substr(0, raw.find('#'));
    const std::vector<std::string> words = split(line);
    if (words.empty()) continue;
    const LineParser p(source, number);
    ScriptCommand c;
    c.line = number;
    const std::string& verb = words[0];
    const auto action = enum_from_name<ScriptAction>(verb);
    if (!action) p.fail(unknown_name_message("command", verb, enum_names<ScriptAction>()));
    c.action = *action;
    if (c.action == ScriptAction::wait) {
      p.arguments(words, 1, "a frame count: wait N");
      const double n = p.number(words[1], "the frame count");
      if (n < 0 || n != std::floor(n)) p.fail("the frame count must be a whole number ≥ 0");
      if (n > kMaxWaitFrames)
        p.fail("the frame count " + number_text(n) + " is more than the bound of 10⁷ frames");
      c.frames = static_cast<int>(n);
    } else if (c.action == ScriptAction::set) {
      p.arguments(words, 2, "a name and a value: set NAME VALUE");
      const auto& names = panel_value_names();
      if (std::find(names.begin(), names.end(), words[1]) == names.end() &&
          !teleop_name(words[1])) {
        p.fail("unknown panel value '" + words[1] +
               "'; values: x y z roll pitch yaw gripper mode (one arm), <hand>.x … <hand>.gripper, "
               "lift, camera.*, priority, hand (several hands)");
      }
      c.name = words[1];
      c.value = words[2];
    } else if (c.action == ScriptAction::slider) {
      p.arguments(words, 2, "a slider and a fraction: slider NAME FRACTION");
      const auto& names = panel_value_names();
      const auto found = std::find(names.begin(), names.end(), words[1]);
      const bool teleop = teleop_name(words[1]) && words[1] != "priority" && words[1] != "hand" &&
                          words[1] != "camera.preset";
      if ((found == names.end() && !teleop) || words[1] == "mode") {
        p.fail("unknown slider '" + words[1] +
               "'; sliders: x y z roll pitch yaw gripper (one arm), <hand>.x … <hand>.gripper, "
               "lift, camera.azimuth … camera.lookat_z (several hands)");
      }
      c.name = words[1];
      c.x = p.number(words[2], "the slider fraction");
      if (c.x < 0.0 || c.x > 1.0) p.fail("the slider fraction must lie in [0, 1]");
    } else if (c.action == ScriptAction::key) {
      p.arguments(words, 1, "a key name: key space|right|backspace|escape|w|shift+w|…");
      const bool shift = words[1].rfind("shift+", 0) == 0;
      const std::string key = shift ? words[1].substr(6) : words[1];
      const int code = viewer_key_code(key);
      if (code == 0 || (shift && (code < 'A' || code > 'Z'))) {
        p.fail("unknown key '" + words[1] + "'; keys: " + kKeyList);
      }
      c.name = key;
      if (shift) c.value = "shift";
    } else if (c.action == ScriptAction::drag) {
      p.arguments(words, 3, "a button and a displacement: drag left|right|middle DX DY");
      if (words[1] != "left" && words[1] != "right" && words[1] != "middle") {
        p.fail(unknown_name_message("mouse button", words[1], {"left", "right", "middle"}));
      }
      c.name = words[1];
      c.x = p.number(words[2], "DX");
      c.y = p.number(words[3], "DY");
    } else if (c.action == ScriptAction::select || c.action == ScriptAction::move) {
      p.arguments(words, 2, "a point: DX DY pixels from the view's centre");
      c.x = p.number(words[1], "DX");
      c.y = p.number(words[2], "DY");
    } else if (c.action == ScriptAction::press) {
      p.arguments(words, 3, "a button and a point: press [ctrl+]left|right|middle DX DY");
      const bool control = words[1].rfind("ctrl+", 0) == 0;
      const std::string button = control ? words[1].substr(5) : words[1];
      if (button != "left" && button != "right" && button != "middle") {
        p.fail(unknown_name_message("mouse button", words[1],
                                    {"left", "right", "middle", "ctrl+left", "ctrl+right"}));
      }
      c.name = button;
      if (control) c.value = "ctrl";
      c.x = p.number(words[2], "DX");
      c.y = p.number(words[3], "DY");
    } else if (c.action == ScriptAction::release) {
      p.arguments(words, 0, "no argument");
    } else if (c.action == ScriptAction::scroll) {
      p.arguments(words, 1, "an amount: scroll DY");
      c.x = p.number(words[1], "the scroll amount");
    } else if (c.action == ScriptAction::screenshot) {
      p.arguments(words, 1, "a file: screenshot PATH");
      c.name = words[1];
    } else if (c.action == ScriptAction::quit) {
      p.arguments(words, 0, "no argument");
    }
    script.commands.push_back(std::move(c));
  }
  return script;
}

ViewerScript ViewerScript::load(const std::filesystem::path& path) {
  return parse(read_user_file(path, "viewer script"), path.string());
}

}  // namespace mjarm
