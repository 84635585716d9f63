#include "teleop_ui.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <string>
#include <vector>

#include "mjarm/error.hpp"
#include "mjarm/model/chain.hpp"

namespace mjarm {

namespace {

std::string capitalized(std::string name) {
  if (!name.empty()) name[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(name[0])));
  return name;
}

}  // namespace

std::vector<PanelRanges> teleop_ranges(const TeleopSession& session, std::size_t samples) {
  std::vector<PanelRanges> ranges;
  const TeleopTargets& initial = session.initial_targets();
  for (std::size_t i = 0; i < session.hands().size(); ++i) {
    const Chain chain(session.robot(), session.hands()[i].frame);
    ranges.push_back(panel_ranges(chain, initial.hands[i].X_WT, samples));
  }
  return ranges;
}

std::unique_ptr<ViewerUi> make_teleop_ui(TeleopPanel& panel, const TeleopSession& session,
                                         const std::vector<PanelRanges>& ranges) {
  const auto& hands = session.hands();
  if (panel.hands.size() != hands.size() || ranges.size() != hands.size())
    throw Error("teleop panel: " + std::to_string(panel.hands.size()) + " hand sections and " +
                std::to_string(ranges.size()) + " slider ranges for " +
                std::to_string(hands.size()) + " hands");
  auto ui = std::make_unique<ViewerUi>();
  std::string hand_names;
  for (const auto& h : hands) hand_names += (hand_names.empty() ? "" : "\n") + capitalized(h.name);
  const auto lift = session.lift_range();
  std::vector<UiItemDef> simulation = {
      {mjITEM_RADIO, "Mode", 1, &panel.mode, "Kinematic\nPosition\nMotor", "mode"},
      {mjITEM_RADIO, "Priority", 1, &panel.priority, "Equal\nR over L\nL over R", "priority"},
      {mjITEM_RADIO, "Keys move", 1, &panel.selected, hand_names, "hand"},
      {mjITEM_SLIDERNUM, "lift [m]", session.has_lift() ? 1 : 0, &panel.lift,
       ui_range(lift[0], std::max(lift[1], lift[0] + 1e-6)), "lift"}};
  for (auto& button : run_buttons()) simulation.push_back(std::move(button));
  ui->add_section("Simulation", simulation);
  for (std::size_t i = 0; i < hands.size(); ++i) {
    ui->add_section(capitalized(hands[i].name) + " hand",
                    target_items(panel.hands[i].pose, panel.hands[i].gripper, ranges[i],
                                 !hands[i].fingers.empty(), hands[i].name + "."));
  }
  CameraPanel& c = panel.camera;
  ui->add_section(
      "Camera", {{mjITEM_SLIDERNUM, "azimuth", 1, &c.azimuth, "-360 360", "camera.azimuth"},
                 {mjITEM_SLIDERNUM, "elevation", 1, &c.elevation, "-89.9 89.9", "camera.elevation"},
                 {mjITEM_SLIDERNUM, "distance", 1, &c.distance, "0.2 8", "camera.distance"},
                 {mjITEM_SLIDERNUM, "look-at x", 1, &c.lookat[0], "-2 2", "camera.lookat_x"},
                 {mjITEM_SLIDERNUM, "look-at y", 1, &c.lookat[1], "-2 2", "camera.lookat_y"},
                 {mjITEM_SLIDERNUM, "look-at z", 1, &c.lookat[2], "0 2.5", "camera.lookat_z"},
                 {mjITEM_RADIO, "Preset", 1, &c.preset, "Front\nLeft\nRight\nTop\nOverview",
                  "camera.preset"}});
  return ui;
}

}  // namespace mjarm
