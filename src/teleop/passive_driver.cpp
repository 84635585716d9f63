// The passive viewer's driver: draws the state the user's loop handed over (no physics of its
// own), its markers and figures, and hands the mouse's perturbation back.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <mutex>
#include <utility>

#include "figure_series.hpp"
#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"
#include "passive_shared.hpp"

namespace mjarm::detail {

namespace {

// figures over the bottom right of the 3-D view, stacked upwards
enum FigureIndex { figure_contact = 0, figure_actuators = 1, figure_plots = 2, figure_count = 3 };
constexpr const char* kFigureNames[figure_count] = {"figure.contact", "figure.actuators",
                                                    "figure.plots"};

void style(mjvFigure& figure, const char* title, const char* ylabel_format) {
  mjv_defaultFigure(&figure);
  std::strncpy(figure.title, title, sizeof(figure.title) - 1);
  std::strncpy(figure.xlabel, "time before now [s]", sizeof(figure.xlabel) - 1);
  std::strncpy(figure.yformat, ylabel_format, sizeof(figure.yformat) - 1);
  figure.flg_legend = 1;
  figure.flg_extend = 1;
  figure.figurergba[3] = 0.5f;
  figure.gridsize[0] = 6;
  figure.gridsize[1] = 5;
}

class PassiveDriver final : public ViewerDriver {
 public:
  explicit PassiveDriver(std::shared_ptr<PassiveShared> shared)
      : shared_(std::move(shared)),
        robot_(shared_->robot),
        shown_(robot_.make_data()),
        series_{FigureSeries(1, shared_->options.figure_seconds),
                FigureSeries(kPassiveFigureLines, shared_->options.figure_seconds),
                FigureSeries(kPassiveFigureLines, shared_->options.figure_seconds)},
        figures_(std::make_unique<mjvFigure[]>(figure_count)) {
    markers_.reserve(static_cast<std::size_t>(shared_->options.max_markers));
    const int show = shared_->options.show_figures ? 1 : 0;
    std::vector<UiItemDef> items;
    for (int i = 0; i < figure_count; ++i) {
      shown_figures_[i] = show;
      static constexpr const char* kLabels[figure_count] = {"Contact force", "Actuator force",
                                                            "Your plots"};
      items.push_back({mjITEM_CHECKINT, kLabels[i], 1, &shown_figures_[i], "", kFigureNames[i]});
    }
    ui_.add_section("Figures", items);
    style(figures_[figure_contact], "total normal contact force [N]", "%.1f");
    style(figures_[figure_actuators], "actuator force [% of limit]", "%.0f");
    style(figures_[figure_plots], "your plots", "%.3g");
    contact_names_ = {"contacts"};
    const mjModel& m = robot_.model();
    for (const LimitedActuator& a : shared_->actuators) {
      const char* name = mj_id2name(&m, mjOBJ_ACTUATOR, a.id);
      actuator_names_.push_back(name != nullptr ? name : "actuator " + std::to_string(a.id));
    }
  }

  const Robot& robot() const noexcept override { return robot_; }
  mjData& data() noexcept override { return *shown_; }
  double control_period() const noexcept override { return robot_.model().opt.timestep; }
  ViewerUi& ui() noexcept override { return ui_; }

  int step(int) override { return 0; }  // the user's loop steps the physics
  void read_panel() override {}
  void on_panel(PanelAction, mjvCamera&) override {}
  bool on_key(int, bool) override { return false; }

  void set_value(const std::string& name, const std::string& value, mjvCamera&) override {
    for (int i = 0; i < figure_count; ++i) {
      if (name != kFigureNames[i]) continue;
      if (value != "0" && value != "1")
        throw Error("'" + name + "' is 0 (hidden) or 1 (shown), got '" + value + "'");
      shown_figures_[i] = value == "1" ? 1 : 0;
      return;
    }
    throw Error("the passive viewer's panel has no value '" + name +
                "'; values: figure.contact figure.actuators figure.plots");
  }
  void reset() override {}  // the loop owns the state

  void initial_camera(mjvCamera& camera) override {
    const mjModel& m = robot_.model();
    mjv_defaultFreeCamera(&m, &camera);
    if (!shared_->options.camera) return;
    const CameraSpec& spec = *shared_->options.camera;
    if (spec.kind == CameraKind::model) {
      const int id = mj_name2id(&m, mjOBJ_CAMERA, spec.name.c_str());
      if (id < 0) throw Error("passive viewer: no camera '" + spec.name + "' in the model");
      camera.type = mjCAMERA_FIXED;
      camera.fixedcamid = id;
      return;
    }
    if (spec.kind != CameraKind::free)
      throw Error("passive viewer: the camera at the start is a free or a model camera");
    // checks the numbers with the camera's own messages
    (void)free_camera_view(spec.lookat, spec.distance, spec.azimuth, spec.elevation,
                           m.vis.global.fovy);
    for (int i = 0; i < 3; ++i) camera.lookat[i] = spec.lookat[i];
    camera.distance = spec.distance;
    camera.azimuth = spec.azimuth;
    camera.elevation = spec.elevation;
  }

  // the newest synced state, its markers and the figures' samples, under the lock for swaps
  void update() override {
    const std::lock_guard lock(shared_->mutex);
    if (shared_->fresh) {
      std::swap(shared_->incoming, shown_);
      markers_.swap(shared_->markers);
      shared_->fresh = false;
    }
    for (; shared_->sample_count > 0; --shared_->sample_count) {
      const FigureSample& s = shared_->samples[shared_->sample_start];
      shared_->sample_start = (shared_->sample_start + 1) % shared_->samples.size();
      series_[figure_contact].add(s.time, std::span(&s.contact, 1));
      series_[figure_actuators].add(s.time, s.actuator);
      series_[figure_plots].add(s.time, s.plots);
      last_ = s;
    }
    if (plot_names_.size() != shared_->plot_names.size()) plot_names_ = shared_->plot_names;
  }
  bool finished() const noexcept override { return shared_->close_requested.load(); }
  bool perturbs() const noexcept override { return true; }
  void set_perturbation(const mjvPerturb& pert) override {
    selected_ = pert.select;
    const std::lock_guard lock(shared_->mutex);
    shared_->pert = pert;
  }
  bool virtual_clock() const noexcept override { return false; }

  void draw(const mjrRect& view, const mjrContext& con) override {
    const std::span<const std::string> names[figure_count] = {contact_names_, actuator_names_,
                                                              plot_names_};
    // a third of the view's width and a quarter of its height, readable in a small window
    const int width = std::min(view.width, std::max(view.width / 3, 260));
    const int height = std::min(view.height / 3, std::max(view.height / 4, 160));
    int bottom = view.bottom;
    for (int i = 0; i < figure_count; ++i) {
      if (shown_figures_[i] == 0 || names[i].empty()) continue;
      series_[i].fill(figures_[i], names[i]);
      mjr_figure(mjrRect{view.left + view.width - width, bottom, width, height}, &figures_[i],
                 &con);
      bottom += height;
    }
  }

  void add_markers(mjvScene& scene) const override {
    for (const mjvGeom& g : markers_) {
      if (scene.ngeom >= scene.maxgeom) return;
      scene.geoms[scene.ngeom++] = g;
    }
  }

  void overlay(const OverlayInfo& info, OverlayText& left, OverlayText& right) const override {
    const mjModel& m = robot_.model();
    left.labels = "Time\nFPS\nContacts\nAt limit\nSelected";
    left.values = number_text(shown_->time, 4) + " s\n" + number_text(info.fps, 3) + "\n" +
                  std::to_string(last_.contacts) + " (" + number_text(last_.contact, 3) +
                  " N normal)\n";
    // the actuators whose force is at its limit (the viewer's saturation line)
    std::string saturated;
    for (std::size_t k = 0; k < actuator_names_.size(); ++k) {
      if (last_.actuator[k] >= 99.5f)
        saturated += (saturated.empty() ? "" : ", ") + actuator_names_[k];
    }
    left.values += (saturated.empty() ? std::string("none") : saturated) + "\n";
    if (selected_ > 0) {
      const char* body = mj_id2name(&m, mjOBJ_BODY, selected_);
      left.values += body != nullptr ? std::string(body) : "body " + std::to_string(selected_);
    } else {
      left.values += "none (double-click a body)";
    }
    right.labels.clear();
    right.values.clear();
  }
  const char* help() const noexcept override {
    return "drag: left rotate, right move, scroll zoom\n"
           "double-click select, ctrl+right drag pull, ctrl+left drag turn, esc quit";
  }

  void describe(ViewerScreenshot& shot) const override { shot.time = shown_->time; }
  void finish(ViewerReport&) override {}

 private:
  std::shared_ptr<PassiveShared> shared_;
  Robot robot_;
  DataPtr shown_;                 // the state drawn (the window thread's own)
  std::vector<mjvGeom> markers_;  // its markers
  ViewerUi ui_;
  int shown_figures_[figure_count] = {0, 0, 0};
  FigureSeries series_[figure_count];
  std::unique_ptr<mjvFigure[]> figures_;  // large (about 800 kB each): on the heap
  std::vector<std::string> contact_names_, actuator_names_, plot_names_;
  int selected_ = 0;  // the selected body (0: none)
  FigureSample last_;  // the newest synced sample, for the overlay
};

}  // namespace

std::unique_ptr<ViewerDriver> make_passive_driver(std::shared_ptr<PassiveShared> shared) {
  return std::make_unique<PassiveDriver>(std::move(shared));
}

}  // namespace mjarm::detail
