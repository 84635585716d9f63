#pragma once
/// @file
/// `DeclaredScenario<P>`: a `Scenario` whose parameters are the declared fields of struct @p P
/// (fields.hpp). A scenario then writes only its description and `run_trial(const P&, …)`; the
/// parameter table, the names as command lines write them, and the checks of every value come
/// from the declaration.

#include <string>

#include "mjarm/field_table.hpp"
#include "mjarm/scenarios/scenario.hpp"

namespace mjarm {

namespace detail {

/// The field path a parameter name stands for: dashes as underscores.
std::string parameter_path(std::string_view name);

/// Checks that @p name (dashes or underscores) is a parameter of @p table.
/// @throws Error "where: unknown parameter 'objct-size'; closest: object-size; parameters: …"
void check_parameter_name(const std::vector<FieldInfo>& table, std::string_view name,
                          std::string_view where);

/// @p table with every path written as a parameter name.
std::vector<FieldInfo> as_parameters(std::vector<FieldInfo> table);

}  // namespace detail

/// Sets @p values (an object of parameter names, dashes or underscores, to values) on the
/// declared fields of @p p, each checked; @p p is unchanged when one is refused.
/// @throws Error "where: unknown parameter 'objct-size'; closest: object-size; …", or naming
///         the parameter for a value of the wrong kind or out of range
template <Declared P>
void set_parameters(P& p, const nlohmann::ordered_json& values, std::string_view where) {
  const std::string owner(where);
  if (!values.is_object())
    throw Error(owner + ": the parameters must be an object of names to values, got " +
                values.dump());
  P changed = p;
  const std::vector<FieldInfo> table = detail::as_parameters(field_table(P{}));
  for (auto it = values.begin(); it != values.end(); ++it) {
    detail::check_parameter_name(table, it.key(), owner);
    detail::set_listed_field(changed, detail::parameter_path(it.key()), it.value(), owner);
  }
  p = std::move(changed);
}

template <Declared P>
class DeclaredScenario : public Scenario {
 public:
  using Parameters = P;

  std::vector<FieldInfo> parameters() const override {
    return detail::as_parameters(field_table(P{}));
  }

  /// The typed parameters @p values stand for, every value checked.
  /// @throws Error as `resolve`
  P parameters_from(const nlohmann::ordered_json& values) const {
    P p;
    set(p, values);
    return p;
  }

  /// Sets @p values (an object of parameter names to values) on @p p, each checked; @p p is
  /// unchanged when one is refused.
  /// @throws Error as `resolve`
  void set(P& p, const nlohmann::ordered_json& values) const { set_parameters(p, values, name()); }
  nlohmann::ordered_json resolve(const nlohmann::ordered_json& values) const override {
    return values_of(parameters_from(values));
  }

  TrialOutcome run(const nlohmann::ordered_json& values,
                   const ScenarioOutputs& outputs = {}) const override {
    const P p = parameters_from(values);
    TrialOutcome outcome = run_trial(p, outputs);
    outcome.scenario = name();
    outcome.parameters = values_of(p);
    return outcome;
  }

  /// Runs one trial with typed parameters (checked by the caller or by `parameters_from`).
  virtual TrialOutcome run_trial(const P& parameters, const ScenarioOutputs& outputs) const = 0;

 private:
  static nlohmann::ordered_json values_of(const P& p) {
    nlohmann::ordered_json values = nlohmann::ordered_json::object();
    for (const FieldInfo& info : detail::as_parameters(field_table(p)))
      values[info.path] = info.value;
    return values;
  }
};

}  // namespace mjarm
