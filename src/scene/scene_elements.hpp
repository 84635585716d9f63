#pragma once
// Elements made from their MJCF tag and attributes (`Scene::add`, `ElementSpec`): the tag
// tables for actuators and sensors, their shortcut attributes (kp, kv, the transmission, the
// sensed object) and a default class's "<element>.<attribute>". Internal to the scene room.

#include <mujoco/mujoco.h>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/model/mjcf_spec.hpp"
#include "mjarm/scene/scene_spec.hpp"

namespace mjarm::scene_detail {

/// The kind an element of @p tag is found by ("body", …, "actuator", "sensor", "default"), or
/// nullopt for an unknown tag.
std::optional<std::string_view> element_kind(std::string_view tag);

/// Every tag `ElementSpec` takes, for messages.
std::vector<std::string> all_tags();

/// Makes @p element in @p spec: in @p parent (body tags), from default @p def (null: the
/// parent's), and applies its attributes. @p what names it in errors ("geom 'cup'").
/// @throws Error for an attribute the element does not have (closest names) or a bad value.
void make_element(mjSpec& spec, const ElementSpec& element, mjsBody* parent, mjsDefault* def,
                  const std::string& what);

/// A copy of @p scene with @p element made in it (in its parent body, from class @p class_name:
/// "" for the parent's, or for a default its parent class, main), checked names and class
/// assumed: a failure leaves @p scene as it was.
/// @throws Error as `make_element`, or when MuJoCo cannot copy the spec.
SpecPtr with_element(const mjSpec& scene, const ElementSpec& element, const std::string& class_name,
                     const std::string& what);

}  // namespace mjarm::scene_detail
