#include "yaml_json.hpp"

#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>
#include <limits>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"
#include "yaml_documents.hpp"

namespace mjarm {

namespace {

using Json = nlohmann::ordered_json;

Json scalar_json(const YAML::Node& node) {
  const std::string& text = node.Scalar();
  if (node.Tag() == "!") return text;  // quoted: a string whatever it reads like
  if (text.empty() || text == "~" || text == "null" || text == "Null" || text == "NULL")
    return nullptr;
  if (text == "true" || text == "True" || text == "TRUE") return true;
  if (text == "false" || text == "False" || text == "FALSE") return false;
  long long whole = 0;
  const char* end = text.data() + text.size();
  const char* begin = text.data() + (text.front() == '+' ? 1 : 0);
  if (const auto r = std::from_chars(begin, end, whole); r.ec == std::errc() && r.ptr == end)
    return whole;
  constexpr double inf = std::numeric_limits<double>::infinity();
  if (text == ".inf" || text == ".Inf" || text == ".INF" || text == "+.inf") return inf;
  if (text == "-.inf" || text == "-.Inf" || text == "-.INF") return -inf;
  if (text == ".nan" || text == ".NaN" || text == ".NAN")
    return std::numeric_limits<double>::quiet_NaN();
  if (const auto number = number_from_text(text)) return *number;
  return text;
}

Json node_json(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Map: {
      Json object = Json::object();
      for (const auto& entry : node)
        object[entry.first.as<std::string>()] = node_json(entry.second);
      return object;
    }
    case YAML::NodeType::Sequence: {
      Json array = Json::array();
      for (const auto& item : node) array.push_back(node_json(item));
      return array;
    }
    case YAML::NodeType::Scalar:
      return scalar_json(node);
    default:
      return nullptr;
  }
}

}  // namespace

Json yaml_to_json(const std::string& text, const std::string& source) {
  std::vector<YAML::Node> documents;
  try {
    documents = load_yaml_documents(text, source);
    if (documents.size() > 1)
      throw Error(source + ": one document expected, got " + std::to_string(documents.size()));
    return documents.empty() ? Json(nullptr) : node_json(documents.front());
  } catch (const YAML::Exception& e) {
    throw Error(source + ":" + std::to_string(e.mark.line + 1) +
                ": not valid YAML or JSON: " + e.msg);
  }
}

}  // namespace mjarm
