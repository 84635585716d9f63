#include "parameter_options.hpp"

#include "mjarm/error.hpp"
#include "mjarm/field_table.hpp"

namespace mjarm::cli {

namespace {

/// "the tip is at the target within this [m]; positive and finite (default 0.001)".
std::string parameter_help(const FieldInfo& info) {
  std::string help = info.doc;
  if (!info.unit.empty()) help += " [" + info.unit + "]";
  if (info.kind == FieldKind::number || info.kind == FieldKind::integer ||
      info.kind == FieldKind::numbers)
    help += "; " + info.range.text(info.kind == FieldKind::integer);
  if (!info.names.empty()) help += "; " + join(info.names, " | ");
  if (info.length > 0) help += "; " + std::to_string(info.length) + " numbers";
  help += " (default " +
          (info.value.is_null()     ? std::string(info.optional ? "none" : "inf")
           : info.value.is_string() ? info.value.get<std::string>()
                                    : info.value.dump()) +
          ")";
  return help;
}

}  // namespace

ParameterOptions::ParameterOptions(CLI::App& app, const Scenario& scenario,
                                   const std::set<std::string>& spelled)
    : ParameterOptions(app, scenario.parameters(),
                       "Parameters of " + std::string(scenario.name()) +
                           " (mjarm run --list --json; docs/scenarios.md)",
                       spelled) {}

ParameterOptions::ParameterOptions(CLI::App& app, const std::vector<FieldInfo>& parameters,
                                   const std::string& group, const std::set<std::string>& spelled) {
  for (const FieldInfo& info : parameters) {
    if (spelled.count(info.path) > 0 || app.get_option_no_throw("--" + info.path) != nullptr)
      continue;
    auto given = std::make_unique<Given>();
    given->info = info;
    CLI::Option* option = app.add_option("--" + info.path, given->words, parameter_help(info));
    if (info.kind == FieldKind::flag)
      option->expected(0, 1);
    else if (info.kind == FieldKind::numbers)
      option->expected(1, info.length > 0 ? static_cast<int>(info.length)
                                          : CLI::detail::expected_max_vector_size);
    else
      option->expected(1);
    option->group(group);
    given->option = option;
    given_.push_back(std::move(given));
  }
}

Json ParameterOptions::values() const {
  Json values = Json::object();
  for (const auto& given : given_) {
    if (given->option->count() == 0) continue;
    std::string text;
    if (given->info.kind == FieldKind::flag && given->words.empty()) {
      text = "true";
    } else {
      for (std::size_t i = 0; i < given->words.size(); ++i)
        text += (i > 0 ? "," : "") + given->words[i];
    }
    try {
      values[given->info.path] =
          detail::field_text_to_json(given->info, text, "--" + given->info.path);
    } catch (const Error& e) {
      throw UsageError(e.what());
    }
  }
  return values;
}

}  // namespace mjarm::cli
