#include "mjarm/teleop/viewer_ui.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "mjarm/error.hpp"

namespace mjarm {

namespace {

mjuiDef definition(int type, const char* name, int state, void* data, const char* other) {
  mjuiDef def{};
  def.type = type;
  std::snprintf(def.name, sizeof(def.name), "%s", name);
  def.state = state;
  def.pdata = data;
  std::snprintf(def.other, sizeof(def.other), "%s", other);
  return def;
}

std::string range_text(double lower, double upper) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.6g %.6g", lower, upper);
  return text;
}

const mjuiItem* find_item(const mjUI& ui, const void* data, int type) {
  for (int s = 0; s < ui.nsect; ++s) {
    for (int i = 0; i < ui.sect[s].nitem; ++i) {
      const mjuiItem& it = ui.sect[s].item[i];
      if (it.type == type && (data == nullptr || it.pdata == data)) return &it;
    }
  }
  return nullptr;
}

const mjuiItem* find_named(const mjUI& ui, const char* name) {
  for (int s = 0; s < ui.nsect; ++s) {
    for (int i = 0; i < ui.sect[s].nitem; ++i) {
      if (std::strcmp(ui.sect[s].item[i].name, name) == 0) return &ui.sect[s].item[i];
    }
  }
  return nullptr;
}

}  // namespace

ViewerUi::ViewerUi(PanelState& state, const PanelRanges& ranges, bool gripper)
    : ui_(std::make_unique<mjUI>()), state_(state) {
  std::memset(ui_.get(), 0, sizeof(mjUI));
  ui_->spacing = mjui_themeSpacing(0);
  ui_->color = mjui_themeColor(0);
  ui_->rectid = rect_panel;
  ui_->auxid = 0;
  ui_->radiocol = 1;  // one mode per row: the names fit

  static const char* const kSliders[6] = {"x [m]",      "y [m]",       "z [m]",
                                          "roll [rad]", "pitch [rad]", "yaw [rad]"};
  std::vector<mjuiDef> defs;
  defs.push_back(definition(mjITEM_SECTION, "Target", 1, nullptr, ""));
  for (int i = 0; i < 6; ++i) {
    defs.push_back(definition(mjITEM_SLIDERNUM, kSliders[i], 1, &state.target[i],
                              range_text(ranges.lower[i], ranges.upper[i]).c_str()));
  }
  defs.push_back(definition(mjITEM_SLIDERNUM, "gripper", gripper ? 1 : 0, &state.gripper, "0 1"));
  defs.push_back(definition(mjITEM_END, "", 0, nullptr, ""));
  mjui_add(ui_.get(), defs.data());

  defs.clear();
  defs.push_back(definition(mjITEM_SECTION, "Simulation", 1, nullptr, ""));
  defs.push_back(definition(mjITEM_RADIO, "Mode", 1, &state.mode, "Kinematic\nPosition\nTorque"));
  defs.push_back(definition(mjITEM_BUTTON, "Pause", 1, nullptr, " #32"));
  defs.push_back(definition(mjITEM_BUTTON, "Step", 1, nullptr, " #262"));
  defs.push_back(definition(mjITEM_BUTTON, "Reset", 1, nullptr, " #259"));
  defs.push_back(definition(mjITEM_END, "", 0, nullptr, ""));
  mjui_add(ui_.get(), defs.data());

  for (int i = 0; i < 6; ++i) items_[i] = find_item(*ui_, &state.target[i], mjITEM_SLIDERNUM);
  items_[6] = find_item(*ui_, &state.gripper, mjITEM_SLIDERNUM);
  items_[7] = find_item(*ui_, &state.mode, mjITEM_RADIO);
  pause_ = find_named(*ui_, "Pause");
  step_ = find_named(*ui_, "Step");
  reset_ = find_named(*ui_, "Reset");
  for (const mjuiItem* it : items_) {
    if (it == nullptr) throw Error("viewer panel: a panel item was not created");
  }
  if (!pause_ || !step_ || !reset_) throw Error("viewer panel: a panel button was not created");

  input_.nrect = 3;
  layout(1, 1);
}

ViewerUi::~ViewerUi() = default;

const mjuiItem* ViewerUi::item(std::string_view name) const noexcept {
  const auto& names = panel_value_names();
  for (std::size_t i = 0; i < names.size() && i < items_.size(); ++i) {
    if (names[i] == name) return items_[i];
  }
  return nullptr;
}

PanelAction ViewerUi::action(const mjuiItem* changed) const noexcept {
  if (changed == nullptr) return PanelAction::none;
  if (changed == items_[7]) return PanelAction::mode;
  if (changed == pause_) return PanelAction::pause;
  if (changed == step_) return PanelAction::step;
  if (changed == reset_) return PanelAction::reset;
  for (int i = 0; i < 7; ++i) {
    if (changed == items_[i]) return PanelAction::target;
  }
  return PanelAction::none;
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
  return std::array<double, 2>{x, y};
}

}  // namespace mjarm
