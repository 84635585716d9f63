// The passive viewer: the window thread, the hand-over (`sync`) and the markers.
#include "mjarm/teleop/passive_viewer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <future>
#include <utility>

#include "mjarm/error.hpp"
#include "passive_shared.hpp"
#include "viewer_shell.hpp"

namespace mjarm {

// ---- markers ----

ViewerMarkers::ViewerMarkers(int capacity) : capacity_(std::max(0, capacity)) {
  geoms_.reserve(static_cast<std::size_t>(capacity_));
}

mjvGeom* ViewerMarkers::next() {
  if (size() >= capacity_) return nullptr;
  geoms_.emplace_back();
  return &geoms_.back();
}

namespace {

bool finite(const Eigen::Vector3d& p) { return p.allFinite(); }

}  // namespace

bool ViewerMarkers::add_frame(const Pose& X, double length) {
  static constexpr Rgba kAxes[3] = {
      {0.9f, 0.1f, 0.1f, 1.0f}, {0.1f, 0.8f, 0.1f, 1.0f}, {0.1f, 0.2f, 0.9f, 1.0f}};
  bool all = true;
  for (int i = 0; i < 3; ++i) {
    all = add_arrow(X.p, X.p + length * X.R.col(i), kAxes[i], 0.04 * length) && all;
  }
  return all;
}

bool ViewerMarkers::add_arrow(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                              const Rgba& rgba, double radius) {
  if (!finite(from) || !finite(to) || !std::isfinite(radius)) return false;
  mjvGeom* g = next();
  if (g == nullptr) return false;
  mjv_initGeom(g, mjGEOM_ARROW, nullptr, nullptr, nullptr, rgba.data());
  mjv_connector(g, mjGEOM_ARROW, radius, from.data(), to.data());
  g->category = mjCAT_DECOR;
  return true;
}

bool ViewerMarkers::add_sphere(const Eigen::Vector3d& p, double radius, const Rgba& rgba) {
  if (!finite(p) || !(radius > 0.0) || !std::isfinite(radius)) return false;
  mjvGeom* g = next();
  if (g == nullptr) return false;
  const mjtNum size[3] = {radius, radius, radius};
  mjv_initGeom(g, mjGEOM_SPHERE, size, p.data(), nullptr, rgba.data());
  g->category = mjCAT_DECOR;
  return true;
}

bool ViewerMarkers::add_line(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Rgba& rgba,
                             double width) {
  if (!finite(a) || !finite(b) || !std::isfinite(width)) return false;
  mjvGeom* g = next();
  if (g == nullptr) return false;
  mjv_initGeom(g, mjGEOM_LINE, nullptr, nullptr, nullptr, rgba.data());
  mjv_connector(g, mjGEOM_LINE, width, a.data(), b.data());
  g->category = mjCAT_DECOR;
  return true;
}

bool ViewerMarkers::add_text(const Eigen::Vector3d& p, std::string_view text, const Rgba& rgba) {
  if (!finite(p)) return false;
  mjvGeom* g = next();
  if (g == nullptr) return false;
  const mjtNum size[3] = {0.01, 0.01, 0.01};
  mjv_initGeom(g, mjGEOM_LABEL, size, p.data(), nullptr, rgba.data());
  const std::size_t n = std::min(text.size(), sizeof(g->label) - 1);
  std::memcpy(g->label, text.data(), n);
  g->label[n] = '\0';
  g->category = mjCAT_DECOR;
  return true;
}

// ---- what the loop and the window share ----

namespace detail {

std::vector<LimitedActuator> limited_actuators(const mjModel& m) {
  std::vector<LimitedActuator> out;
  for (int a = 0; a < m.nu && static_cast<int>(out.size()) < kPassiveFigureLines; ++a) {
    const mjtNum* force = m.actuator_forcerange + 2 * a;
    const mjtNum* ctrl = m.actuator_ctrlrange + 2 * a;
    double limit = 0.0;
    if (m.actuator_forcelimited[a] != 0) {
      limit = std::max(std::abs(force[0]), std::abs(force[1]));
    } else if (m.actuator_ctrllimited[a] != 0 && m.actuator_gaintype[a] == mjGAIN_FIXED &&
               m.actuator_biastype[a] == mjBIAS_NONE) {
      // a motor: its force (before the gear) is gain × control
      limit = std::max(std::abs(ctrl[0]), std::abs(ctrl[1])) *
              std::abs(m.actuator_gainprm[mjNGAIN * a]);
    }
    if (limit > 0.0 && std::isfinite(limit)) out.push_back({a, limit});
  }
  return out;
}

FigureSample figure_sample(const mjModel& m, const mjData& d,
                           const std::vector<LimitedActuator>& actuators,
                           const std::array<double, kPassiveFigureLines>& plots) {
  FigureSample s;
  s.time = d.time;
  double contact = 0.0;
  for (int i = 0; i < d.ncon; ++i) {
    mjtNum wrench[6];
    mj_contactForce(&m, &d, i, wrench);
    contact += wrench[0];  // the normal force, along the contact frame's first axis
  }
  s.contact = static_cast<float>(contact);
  s.contacts = d.ncon;
  for (std::size_t k = 0; k < actuators.size(); ++k) {
    s.actuator[k] = static_cast<float>(100.0 * std::abs(d.actuator_force[actuators[k].id]) /
                                       actuators[k].limit);
  }
  for (std::size_t k = 0; k < plots.size(); ++k) s.plots[k] = static_cast<float>(plots[k]);
  return s;
}

PassiveShared::PassiveShared(const Robot& r, const PassiveViewerOptions& o)
    : robot(r), options(o), actuators(limited_actuators(r.model())), incoming(r.make_data()) {
  markers.reserve(static_cast<std::size_t>(o.max_markers));
  samples.resize(1024);
  mjv_defaultPerturb(&pert);
}

void PassiveShared::push(const FigureSample& sample) {
  const std::size_t slot = (sample_start + sample_count) % samples.size();
  samples[slot] = sample;
  if (sample_count == samples.size()) {
    sample_start = (sample_start + 1) % samples.size();  // the window fell behind: oldest goes
  } else {
    ++sample_count;
  }
}

namespace {

// the window thread: the shell on the passive driver until the window closes
void run_window(const std::shared_ptr<PassiveShared>& shared, std::promise<void> opened) {
  bool open = false;
  try {
    const PassiveViewerOptions& o = shared->options;
    ViewerOptions options;
    options.width = o.width;
    options.height = o.height;
    options.rates.render_hz = o.render_hz;
    options.rates.input_hz = std::max(o.render_hz, 30.0);
    options.script = o.script;
    ViewerShell shell(make_passive_driver(shared), options,
                      o.title.empty() ? "mjarm: " + shared->robot.name() : o.title);
    shared->running = true;
    open = true;
    opened.set_value();
    ViewerReport report = shell.run();
    const std::lock_guard lock(shared->mutex);
    shared->report = std::move(report);
  } catch (...) {
    if (!open) {
      opened.set_exception(std::current_exception());
    } else {
      const std::lock_guard lock(shared->mutex);
      shared->failure = std::current_exception();
      shared->report.ended_by = "error";
    }
  }
  shared->running = false;
}

}  // namespace

}  // namespace detail

// ---- the viewer ----

PassiveViewer::PassiveViewer(const Robot& robot, mjData& data, const PassiveViewerOptions& options)
    : robot_(robot), data_(&data), markers_(options.max_markers) {
  check_fields(options);
  shared_ = std::make_shared<detail::PassiveShared>(robot, options);
  // a data's arena and buffer sizes come from its model: a mismatch is another model's data
  if (data.narena != shared_->incoming->narena || data.nbuffer != shared_->incoming->nbuffer) {
    throw Error("passive viewer: the mjData was not made for model '" + robot.name() + "'");
  }
  require_display();
  plot_names_.reserve(plot_values_.size());
  mjv_copyData(shared_->incoming.get(), &robot.model(), &data);  // the first frame: the state now
  shared_->fresh = true;
  std::promise<void> opened;
  std::future<void> window = opened.get_future();
  thread_ = std::thread([shared = shared_, opened = std::move(opened)]() mutable {
    detail::run_window(shared, std::move(opened));
  });
  try {
    window.get();  // the window is up, or its error
  } catch (...) {
    thread_.join();
    throw;
  }
}

PassiveViewer::~PassiveViewer() {
  try {
    close();
  } catch (...) {  // NOLINT(bugprone-empty-catch): a destructor reports nothing; close() does
  }
}

bool PassiveViewer::running() const noexcept { return shared_->running.load(); }

namespace {

void raise_failure(detail::PassiveShared& shared) {
  if (shared.failure) std::rethrow_exception(std::exchange(shared.failure, nullptr));
}

// the spring's row of xfrc_applied back to zero once the drag is over
void release_body(detail::PassiveShared& shared, mjData& d) {
  if (shared.applied_body <= 0) return;
  std::fill_n(d.xfrc_applied + 6 * shared.applied_body, 6, 0.0);
  shared.applied_body = 0;
}

}  // namespace

void PassiveViewer::sync() {
  const mjModel& m = robot_.model();
  mjData& d = *data_;
  if (!running()) {
    const std::lock_guard lock(shared_->mutex);
    release_body(*shared_, d);
    raise_failure(*shared_);
    return;
  }
  const detail::FigureSample sample = detail::figure_sample(m, d, shared_->actuators, plot_values_);
  const std::lock_guard lock(shared_->mutex);
  raise_failure(*shared_);
  // the mouse's spring → the user's data
  release_body(*shared_, d);
  const mjvPerturb& pert = shared_->pert;
  if (pert.active != 0 && pert.select > 0 && pert.select < m.nbody) {
    mjv_applyPerturbPose(&m, &d, &pert, 0);  // a mocap body follows the pointer
    mjv_applyPerturbForce(&m, &d, &pert);
    shared_->applied_body = pert.select;
  }
  // the state, the markers and the figures' values → the window
  mjv_copyData(shared_->incoming.get(), &m, &d);
  shared_->fresh = true;
  markers_.swap(shared_->markers);
  markers_.clear();
  shared_->push(sample);
  if (shared_->plot_names.size() != plot_names_.size()) shared_->plot_names = plot_names_;
  ++shared_->syncs;
}

void PassiveViewer::plot(std::string_view line, double value) {
  if (!std::isfinite(value))
    throw Error("passive viewer: plot '" + std::string(line) + "' got a non-finite value");
  const auto found = std::find(plot_names_.begin(), plot_names_.end(), line);
  std::size_t k = static_cast<std::size_t>(found - plot_names_.begin());
  if (found == plot_names_.end()) {
    if (plot_names_.size() == plot_values_.size()) {
      throw Error("passive viewer: at most " + std::to_string(plot_values_.size()) +
                  " plot lines; '" + std::string(line) + "' would be one more");
    }
    plot_names_.emplace_back(line);
  }
  plot_values_[k] = value;
}

void PassiveViewer::close() {
  shared_->close_requested = true;
  if (thread_.joinable()) thread_.join();
  const std::lock_guard lock(shared_->mutex);
  release_body(*shared_, *data_);
  raise_failure(*shared_);
}

ViewerReport PassiveViewer::report() const {
  const std::lock_guard lock(shared_->mutex);
  return shared_->report;
}

std::int64_t PassiveViewer::syncs() const noexcept {
  const std::lock_guard lock(shared_->mutex);
  return shared_->syncs;
}

int PassiveViewer::selected_body() const noexcept {
  const std::lock_guard lock(shared_->mutex);
  return shared_->pert.select;
}

bool PassiveViewer::perturbing() const noexcept {
  const std::lock_guard lock(shared_->mutex);
  return shared_->pert.active != 0;
}

}  // namespace mjarm
