#pragma once
// The checks of the ik room's option structs, with one wording for every bad field:
// "<owner><path> must be <expected>, got <value>", e.g.
// "pose IK option limits.centre_gain must be finite and >= 0, got -1".

#include <string>
#include <string_view>
#include <utility>

namespace mjarm {
struct CollisionSpec;
struct LimitBias;
struct LocalIkSettings;
struct Posture;
}  // namespace mjarm

namespace mjarm::detail {

/// Checks fields of one struct; nested structs get `member(name)`, whose messages name the path.
class OptionCheck {
 public:
  /// @param owner the start of every message, with its separator: "pose IK option ",
  /// "limit bias "
  explicit OptionCheck(std::string owner) : prefix_(std::move(owner)) {}

  /// The check of the fields of member @p name: its messages name "<name>.<field>".
  OptionCheck member(std::string_view name) const;

  /// @throws Error "<owner><name> must be <expected>, got <value>" unless @p ok.
  void require(bool ok, std::string_view name, double value, std::string_view expected) const;
  /// finite and > 0
  void positive(std::string_view name, double value) const;
  /// finite and >= 0
  void non_negative(std::string_view name, double value) const;
  /// >= @p least
  void at_least(std::string_view name, int value, int least) const;

 private:
  std::string prefix_;
};

// The field checks of each struct, written once: the solvers' checks and the structs' own
// entry points (`check(LimitBias)`, `resolve_posture`, `CollisionGuard`) call them.

/// Gains finite and >= 0, zone in [0, 0.5].
void check_fields(const OptionCheck& require, const LimitBias& bias);
/// The gain in [0, 1] (q_pref needs the chain: `resolve_posture`).
void check_fields(const OptionCheck& require, const Posture& posture);
/// The margin finite and >= 0, max_halvings >= 0 (the names need the model: `CollisionGuard`).
void check_fields(const OptionCheck& require, const CollisionSpec& spec);
/// Every field of the shared local-IK settings, nested ones by path.
void check_fields(const OptionCheck& require, const LocalIkSettings& settings);

/// @p options once `check(options)` has passed, so that a constructor validates its options
/// before it builds the members that read them.
template <class Options>
const Options& checked(const Options& options) {
  check(options);
  return options;
}

}  // namespace mjarm::detail
