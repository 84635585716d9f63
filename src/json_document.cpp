#include "json_document.hpp"

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <set>

#include "mjarm/closest_names.hpp"
#include "mjarm/error.hpp"

namespace mjarm {

namespace {

// The text as nlohmann's parser reads it, one character at a time, remembering the last one read:
// when the parser reports a key, that is the key's closing quote, so its line is known.
class TrackedText {
 public:
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  TrackedText(const char* at, const char** last_read) : at_(at), last_read_(last_read) {}
  reference operator*() const {
    *last_read_ = at_;
    return *at_;
  }
  TrackedText& operator++() {
    ++at_;
    return *this;
  }
  TrackedText operator++(int) {
    TrackedText before = *this;
    ++at_;
    return before;
  }
  bool operator==(const TrackedText& other) const { return at_ == other.at_; }

 private:
  const char* at_;
  const char** last_read_;
};

// a key as a JSON pointer token (RFC 6901: "~" and "/" escaped)
std::string pointer_token(const std::string& key) {
  std::string out;
  for (char c : key) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}

// an object or array being parsed
struct Container {
  std::string pointer;
  bool array = false;
  long index = -1;             // arrays: the element being read
  std::string key;             // objects: the key being read
  std::set<std::string> keys;  // objects: the keys so far
};

// deeper than any file mjarm reads needs
constexpr std::size_t kMaxDepth = 100;

}  // namespace

JsonDocument::JsonDocument(std::string_view text, std::string name) : name_(std::move(name)) {
  const char* last_read = text.data();
  // lines counted once, up to the last character read
  const char* counted = text.data();
  int line = 1;
  const auto line_at = [&] {
    line += static_cast<int>(std::count(counted, last_read, '\n'));
    counted = last_read;
    return line;
  };
  std::vector<Container> open;
  // where the value now starting sits: the next element of an array, or the current key's value
  const auto child_pointer = [&] {
    if (open.empty()) return std::string();
    Container& parent = open.back();
    if (parent.array) return parent.pointer + "/" + std::to_string(++parent.index);
    return parent.pointer + "/" + pointer_token(parent.key);
  };
  using Event = nlohmann::json::parse_event_t;
  const nlohmann::json::parser_callback_t track = [&](int, Event event, nlohmann::json& parsed) {
    switch (event) {
      case Event::object_start:
      case Event::array_start:
        // a bound on the pointers kept (their length grows with the depth)
        if (open.size() >= kMaxDepth)
          throw Error(name_ + " line " + std::to_string(line_at()) + ": nested more than " +
                      std::to_string(kMaxDepth) + " levels deep");
        open.push_back({child_pointer(), event == Event::array_start, -1, {}, {}});
        break;
      case Event::object_end:
      case Event::array_end:
        open.pop_back();
        break;
      case Event::key: {
        Container& object = open.back();
        object.key = parsed.get<std::string>();
        if (!object.keys.insert(object.key).second)
          throw Error(name_ + " line " + std::to_string(line_at()) + ": key '" + object.key +
                      "' appears twice in one object (JSON would keep only the last)");
        key_places_[object.pointer + "/" + pointer_token(object.key)] = {
            static_cast<std::size_t>(last_read - text.data()), line_at()};
        break;
      }
      case Event::value:
        if (!open.empty() && open.back().array) ++open.back().index;
        break;
    }
    return true;
  };
  try {
    root_ = nlohmann::json::parse(TrackedText(text.data(), &last_read),
                                  TrackedText(text.data() + text.size(), &last_read), track);
  } catch (const nlohmann::json::exception& e) {
    throw Error(name_ + ": not valid JSON (" + e.what() + ")");
  }
}

std::string JsonDocument::where(const std::string& object, const std::string& key) const {
  const auto it = key_places_.find(object + "/" + pointer_token(key));
  return it == key_places_.end() ? name_ : name_ + " line " + std::to_string(it->second.line);
}

void JsonDocument::check_keys(const std::string& object, const std::vector<std::string>& known,
                              std::string_view what) const {
  const nlohmann::json& value = root_.at(nlohmann::json::json_pointer(object));
  if (!value.is_object()) return;
  // the first unknown key in the text
  const std::string* first = nullptr;
  std::size_t first_offset = 0;
  for (auto entry = value.begin(); entry != value.end(); ++entry) {
    const std::string& key = entry.key();
    if (std::find(known.begin(), known.end(), key) != known.end()) continue;
    const auto it = key_places_.find(object + "/" + pointer_token(key));
    const std::size_t offset = it == key_places_.end() ? 0 : it->second.offset;
    if (first == nullptr || offset < first_offset) {
      first = &key;
      first_offset = offset;
    }
  }
  if (first != nullptr)
    throw Error(where(object, *first) + ": " + unknown_name_message("key", *first, known, what));
}

}  // namespace mjarm
