#include "yaml_documents.hpp"

#include <yaml-cpp/eventhandler.h>

#include <sstream>

#include "mjarm/error.hpp"

namespace mjarm {

namespace {

// Where each document starts; the parser's other events are not needed.
class DocumentStarts : public YAML::EventHandler {
 public:
  void OnDocumentStart(const YAML::Mark& mark) override { start = mark; }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}

  YAML::Mark start = YAML::Mark::null_mark();
};

}  // namespace

std::vector<YAML::Node> load_yaml_documents(const std::string& text, const std::string& source) {
  std::istringstream in(text);
  YAML::Parser parser(in);
  DocumentStarts starts;
  int previous = -1;
  while (parser.HandleNextDocument(starts)) {
    if (starts.start.pos == previous)
      throw Error(source + ":" + std::to_string(starts.start.line + 1) +
                  ": not valid YAML or JSON: the parser (yaml-cpp) cannot go past column " +
                  std::to_string(starts.start.column + 1) +
                  " (a ',', ']' or '}' outside a flow collection?)");
    previous = starts.start.pos;
  }
  // the parser ends on this stream: LoadAll, which runs the same parser, ends too
  return YAML::LoadAll(text);
}

}  // namespace mjarm
