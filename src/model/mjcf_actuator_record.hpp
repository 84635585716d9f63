#pragma once
// The per-class actuator record of MJCF and how each actuator element changes it, under the
// MuJoCo 3.x rules and under the 2.2.2 rules.

#include <array>
#include <map>
#include <string>

#include "mjcf_detail.hpp"

namespace mjarm::mjcf_detail {

inline constexpr std::size_t kNumPrm = 10;  // mjNDYN = mjNGAIN = mjNBIAS = 10 in both versions

/// Dynamics / gain / bias of an actuator, as MJCF builds it from defaults and shortcuts.
struct ActuatorRecord {
  std::string dyntype = "none";
  std::string gaintype = "fixed";
  std::string biastype = "none";
  std::array<double, kNumPrm> dynprm{1, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  std::array<double, kNumPrm> gainprm{1, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  std::array<double, kNumPrm> biasprm{};
  double inheritrange = 0;         ///< 3.x only
  bool force_ctrllimited = false;  ///< damper / adhesion clamp the control
  bool force_actlimited = false;   ///< intvelocity clamps the activation
  bool muscle = false;             ///< built by a <muscle> shortcut (not modelled further)
  bool operator==(const ActuatorRecord&) const = default;
};

/// Applies actuator element `e` (general, motor, position, ...) to `r` with the MuJoCo 3.x rules
/// (`v3` true) or the MuJoCo 2.2.2 rules; throws on invalid values (negative kv, ...).
void apply_record(ActuatorRecord& r, const XmlNode& e, bool v3);

/// Whether `e` carries attributes that only MuJoCo 3.x reads into the record
/// (kv, dampratio, timeconst or inheritrange on position / intvelocity).
bool has_3x_record_attrs(const XmlNode& e);

/// Named joints (with the default class they read) and tendons of a model.
struct TargetIndex {
  struct Entry {
    const XmlNode* node = nullptr;
    std::string cls;
  };
  std::map<std::string, Entry> joints;
  std::map<std::string, Entry> tendons;
};
TargetIndex index_targets(const XmlNode& root);

/// Moves joint / tendon actuatorfrcrange (3.x) into the forcerange of the one actuator that
/// drives the joint or tendon; throws when several do.
void translate_actuator_force_limits(XmlNode& root, Context& ctx, const Defaults& defaults,
                                     const TargetIndex& targets);

}  // namespace mjarm::mjcf_detail
