#include "viewer_ui.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "mjarm/error.hpp"

namespace mjarm {

std::string ui_range(double lower, double upper) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.6g %.6g", lower, upper);
  return text;
}

ViewerUi::ViewerUi() : ui_(std::make_unique<mjUI>()) {
  std::memset(ui_.get(), 0, sizeof(mjUI));
  ui_->spacing = mjui_themeSpacing(0);
  ui_->color = mjui_themeColor(0);
  ui_->rectid = rect_panel;
  ui_->auxid = 0;
  ui_->radiocol = 1;  // one choice per row: the names fit
  input_.nrect = 3;
  layout(1, 1);
}

std::vector<UiItemDef> target_items(double (&pose)[6], double& gripper, const PanelRanges& ranges,
                                    bool has_gripper, const std::string& prefix) {
  static const char* const kLabels[6] = {"x [m]",      "y [m]",       "z [m]",
                                         "roll [rad]", "pitch [rad]", "yaw [rad]"};
  const auto& names = panel_value_names();  // x y z roll pitch yaw gripper mode
  std::vector<UiItemDef> items;
  for (int i = 0; i < 6; ++i) {
    items.push_back({mjITEM_SLIDERNUM, kLabels[i], 1, &pose[i],
                     ui_range(ranges.lower[i], ranges.upper[i]), prefix + names[i]});
  }
  items.push_back(
      {mjITEM_SLIDERNUM, "gripper", has_gripper ? 1 : 0, &gripper, "0 1", prefix + names[6]});
  return items;
}

std::vector<UiItemDef> run_buttons() {
  return {{mjITEM_BUTTON, "Pause", 1, nullptr, " #32", "pause"},
          {mjITEM_BUTTON, "Step", 1, nullptr, " #262", "step"},
          {mjITEM_BUTTON, "Reset", 1, nullptr, " #259", "reset"}};
}

ViewerUi::ViewerUi(PanelState& state, const PanelRanges& ranges, bool gripper) : ViewerUi() {
  add_section("Target", target_items(state.target, state.gripper, ranges, gripper, ""));
  std::vector<UiItemDef> simulation = {
      {mjITEM_RADIO, "Mode", 1, &state.mode, "Kinematic\nPosition\nTorque", "mode"}};
  for (auto& button : run_buttons()) simulation.push_back(std::move(button));
  add_section("Simulation", simulation);
}

ViewerUi::~ViewerUi() = default;

void ViewerUi::add_section(const std::string& title, const std::vector<UiItemDef>& items) {
  if (ui_->nsect >= mjMAXUISECT || items.size() >= static_cast<std::size_t>(mjMAXUIITEM))
    throw Error("viewer panel: no room for section '" + title + "'");
  std::vector<mjuiDef> defs(items.size() + 2);
  auto fill = [](mjuiDef& def, int type, const std::string& label, int state, void* data,
                 const std::string& other) {
    def = mjuiDef{};
    def.type = type;
    std::snprintf(def.name, sizeof(def.name), "%s", label.c_str());
    def.state = state;
    def.pdata = data;
    std::snprintf(def.other, sizeof(def.other), "%s", other.c_str());
  };
  fill(defs.front(), mjITEM_SECTION, title, 1, nullptr, "");
  for (std::size_t i = 0; i < items.size(); ++i) {
    const UiItemDef& it = items[i];
    fill(defs[i + 1], it.type, it.label, it.state, it.data, it.other);
    if (!it.name.empty() && item(it.name) != nullptr)
      throw Error("viewer panel: two items called '" + it.name + "'");
  }
  fill(defs.back(), mjITEM_END, "", 0, nullptr, "");
  const int before = ui_->nsect;
  mjui_add(ui_.get(), defs.data());
  if (ui_->nsect != before + 1 || ui_->sect[before].nitem != static_cast<int>(items.size()))
    throw Error("viewer panel: MuJoCo did not create section '" + title + "'");
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (!items[i].name.empty()) named_.emplace_back(items[i].name, &ui_->sect[before].item[i]);
  }
}

const mjuiItem* ViewerUi::item(std::string_view name) const noexcept {
  for (const auto& [n, it] : named_) {
    if (n == name) return it;
  }
  return nullptr;
}

std::string_view ViewerUi::name_of(const mjuiItem* item) const noexcept {
  for (const auto& [n, it] : named_) {
    if (it == item) return n;
  }
  return {};
}

PanelAction ViewerUi::action(const mjuiItem* changed) const noexcept {
  const std::string_view name = name_of(changed);
  if (name.empty()) return PanelAction::none;
  if (name == "mode") return PanelAction::mode;
  if (name == "pause") return PanelAction::pause;
  if (name == "step") return PanelAction::step;
  if (name == "reset") return PanelAction::reset;
  if (name == "priority") return PanelAction::priority;
  if (name == "hand") return PanelAction::hand;
  if (name == "camera.preset") return PanelAction::camera_preset;
  if (name.substr(0, 7) == "camera.") return PanelAction::camera;
  return PanelAction::target;
}

void ViewerUi::attach(mjrContext& con) {
  mjui_resize(ui_.get(), &con);
  mjr_addAux(ui_->auxid, ui_->width, ui_->maxheight, ui_->spacing.samples, &con);
  attached_ = true;
  layout(input_.rect[rect_window].width, input_.rect[rect_window].height);
  mjui_update(-1, -1, ui_.get(), &input_, &con);
}

void ViewerUi::refresh(const mjrContext& con) {
  if (attached_) mjui_update(-1, -1, ui_.get(), &input_, &con);
}

void ViewerUi::layout(int width, int height) noexcept {
  width = std::max(width, 1);
  height = std::max(height, 1);
  const int panel = std::min(attached_ ? ui_->width : 0, width - 1);
  input_.rect[rect_window] = mjrRect{0, 0, width, height};
  input_.rect[rect_panel] = mjrRect{0, 0, panel, height};
  input_.rect[rect_view] = mjrRect{panel, 0, width - panel, height};
}

void ViewerUi::move_pointer(double x, double y) noexcept {
  input_.dx = x - input_.x;
  input_.dy = y - input_.y;
  input_.x = x;
  input_.y = y;
  // rectangle 0 is the whole window: search the others, report 0 when outside them all
  input_.mouserect =
      mjr_findRect(static_cast<int>(std::lround(x)), static_cast<int>(std::lround(y)),
                   input_.nrect - 1, input_.rect + 1) +
      1;
}

std::optional<std::array<double, 2>> ViewerUi::slider_point(std::string_view name,
                                                            double fraction) const noexcept {
  const mjuiItem* it = item(name);
  if (!attached_ || it == nullptr || it->type != mjITEM_SLIDERNUM) return std::nullopt;
  // inverse of MuJoCo's mapping from window to panel coordinates: the panel is drawn at the top
  // of its rectangle, scrolled by ui.scroll when taller than it
  const mjrRect& r = input_.rect[rect_panel];
  const mjUI& ui = *ui_;
  double y = it->rect.bottom + 0.5 * it->rect.height + (r.height - ui.height) + r.bottom;
  if (ui.height > r.height) y += ui.scroll;
  const double x = r.left + it->rect.left + fraction * it->rect.width;
  if (y < r.bottom || y > r.bottom + r.height) return std::nullopt;  // scrolled out of sight
  return std::array<double, 2>{x, y};
}

}  // namespace mjarm
