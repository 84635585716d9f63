#include "mjarm/sim/recorder.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <limits>
#include <optional>

#include "csv_stream.hpp"
#include "mjarm/control/task_error.hpp"
#include "mjarm/error.hpp"
#include "mjarm/file_writer.hpp"
#include "mjarm/sim/simulation.hpp"
#include "recorder_summary.hpp"
#include "staging_dir.hpp"

namespace mjarm {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr std::size_t kEventText = 1024;
const std::string kState = "state.csv";
const std::string kTask = "task.csv";
const std::string kEvents = "events.csv";
const std::string kSummary = "summary.json";
// the compiled model, as MuJoCo saves it (mj_saveModel): a recording of a composed scene (the
// pick and place) names no file to load again, and `mjarm replay-html` needs its geometry
const std::string kModel = "model.mjb";

std::string object_name(const mjModel& m, int type, int id, const char* fallback) {
  const char* name = mj_id2name(&m, type, id);
  return (name != nullptr && name[0] != '\0') ? name : fallback + std::to_string(id);
}

// "q.elbow", or "q.box.0" … "q.box.6" for joints with several coordinates
void add_joint_columns(const mjModel& m, const char* prefix, bool positions,
                       std::vector<std::string>& columns) {
  for (int j = 0; j < m.njnt; ++j) {
    const int type = m.jnt_type[j];
    const int n = type == mjJNT_FREE   ? (positions ? 7 : 6)
                  : type == mjJNT_BALL ? (positions ? 4 : 3)
                                       : 1;
    const std::string name = std::string(prefix) + object_name(m, mjOBJ_JOINT, j, "joint");
    if (n == 1) {
      columns.push_back(name);
    } else {
      for (int k = 0; k < n; ++k) columns.push_back(name + "." + std::to_string(k));
    }
  }
}

void add_pose_columns(const char* prefix, std::vector<std::string>& columns) {
  for (const char* c : {"x", "y", "z", "qw", "qx", "qy", "qz"})
    columns.push_back(std::string(prefix) + c);
}

// position then unit quaternion (w, x, y, z) of a row-major rotation
void add_pose(sim_detail::CsvStream& csv, const double* p, const double* R_rowmajor) {
  double quat[4];
  mju_mat2Quat(quat, R_rowmajor);
  for (int i = 0; i < 3; ++i) csv.add(p[i]);
  for (double q : quat) csv.add(q);
}

// The range of the actuator's scalar force (before the gear): forcerange when force-limited; a
// motor (force = gain·ctrl) is also bounded by gain·ctrlrange, which the simulation clips to.
sim_detail::SummaryInfo::Actuator actuator_info(const mjModel& m, const ActuatorInfo& a) {
  sim_detail::SummaryInfo::Actuator out;
  out.name = a.name;
  out.kind = to_string(a.kind);
  out.joint = a.joint ? object_name(m, mjOBJ_JOINT, *a.joint, "joint") : "";
  out.gear = a.gear;
  double lower = -std::numeric_limits<double>::infinity(), upper = -lower;
  if (a.force_limited) {
    lower = a.force_lower;
    upper = a.force_upper;
  }
  if (a.kind == ActuatorKind::motor && a.ctrl_limited) {
    const double gain = m.actuator_gainprm[a.id * mjNGAIN];
    const double l = gain * a.ctrl_lower, u = gain * a.ctrl_upper;
    lower = std::max(lower, std::min(l, u));
    upper = std::min(upper, std::max(l, u));
  }
  out.force_limited = std::isfinite(lower) && std::isfinite(upper) && lower < upper;
  out.force_lower = lower;
  out.force_upper = upper;
  return out;
}

}  // namespace

struct Recorder::Impl {
  const Simulation* simulation = nullptr;
  int controller_count = 0;
  RecorderOptions options;
  sim_detail::StagingDir staging;
  std::unique_ptr<sim_detail::CsvStream> state, task, events;
  std::optional<FrameRef> frame;
  int qref_size = 0;                            // first controller's chain size (qref columns)
  std::vector<int> saturation_columns;          // actuators with a sat.* column
  std::vector<std::int64_t> saturation_counts;  // per saturation column
  std::int64_t steps_seen = 0;
  bool contact_forces = true;  // false in kinematic mode: no constraint forces are computed
  sim_detail::SummaryInfo info;
  std::vector<char> model_bytes;  // model.mjb, saved at construction: written by finalize

  Impl(const Simulation& sim, const std::filesystem::path& dir, const RecorderOptions& opt)
      : simulation(&sim), controller_count(sim.controller_count()), options(opt), staging(dir) {}
};

Recorder::Recorder(const Simulation& simulation, const std::filesystem::path& directory,
                   const RecorderOptions& options)
    : uncaught_at_construction_(std::uncaught_exceptions()) {
  check_fields(options);
  const Robot& robot = simulation.robot();
  const mjModel& m = robot.model();
  // the frame is checked before anything touches the disk
  std::optional<FrameRef> frame;
  if (!options.frame.empty()) {
    frame = find_frame(robot, options.frame);
  } else if (simulation.controller_count() > 0) {
    frame = simulation.controller(0).chain().frame();
  }
  for (const RecorderChannel& channel : options.channels) {
    if (channel.value == nullptr || channel.name.empty()) {
      throw Error("recorder: channel '" + channel.name + "' needs a name and a value to read");
    }
  }
  impl_ = std::make_unique<Impl>(simulation, directory, options);
  Impl& im = *impl_;
  im.frame = frame;
  im.contact_forces = simulation.mode() != SimulationMode::kinematic;

  std::vector<std::string> state_columns{"t"};
  add_joint_columns(m, "q.", true, state_columns);
  add_joint_columns(m, "v.", false, state_columns);
  for (int a = 0; a < m.nu; ++a)
    state_columns.push_back("ctrl." + object_name(m, mjOBJ_ACTUATOR, a, "actuator"));
  for (int a = 0; a < m.nu; ++a)
    state_columns.push_back("force." + object_name(m, mjOBJ_ACTUATOR, a, "actuator"));
  // every contact of the model, summed: what `mjarm plot` draws as the contact force
  state_columns.push_back("contact.count");
  state_columns.push_back("contact.normal_force");

  std::vector<std::string> task_columns{"t"};
  if (frame) {
    add_pose_columns("ee.", task_columns);
    add_pose_columns("ref.", task_columns);
    for (const char* c : {"vx", "vy", "vz", "wx", "wy", "wz"})
      task_columns.push_back(std::string("err.") + c);
  }
  task_columns.push_back("gripper_ref");
  std::vector<std::string> base_names, controller_names;
  for (int c = 0; c < simulation.controller_count(); ++c) {
    const std::string base(simulation.controller(c).name());
    const auto same = std::count(base_names.begin(), base_names.end(), base);
    base_names.push_back(base);
    // two "joint-pd" controllers: joint-pd, joint-pd#2
    controller_names.push_back(same == 0 ? base : base + "#" + std::to_string(same + 1));
  }
  if (simulation.controller_count() > 0) {
    const Chain& chain = simulation.controller(0).chain();
    im.qref_size = chain.size();
    for (const std::string& j : chain.joint_names()) task_columns.push_back("qref." + j);
  }
  for (int c = 0; c < simulation.controller_count(); ++c) {
    const Controller& controller = simulation.controller(c);
    for (const std::string& j : controller.chain().joint_names())
      task_columns.push_back("cmd." + controller_names[c] + "." + j);
    for (const std::string& n : controller.internal_names())
      task_columns.push_back(controller_names[c] + "." + n);
    for (int a : simulation.binding(c).actuators()) im.saturation_columns.push_back(a);
  }
  for (int a : im.saturation_columns)
    task_columns.push_back("sat." + object_name(m, mjOBJ_ACTUATOR, a, "actuator"));
  im.saturation_counts.assign(im.saturation_columns.size(), 0);
  for (const RecorderChannel& channel : options.channels) {
    if (std::find(task_columns.begin(), task_columns.end(), channel.name) != task_columns.end()) {
      // nothing was recorded yet: leave no staging folder behind
      std::error_code ec;
      std::filesystem::remove_all(im.staging.staging(), ec);
      throw Error("recorder: channel '" + channel.name + "' repeats a task.csv column name");
    }
    task_columns.push_back(channel.name);
  }

  try {
    im.state = std::make_unique<sim_detail::CsvStream>(im.staging.staged(kState), state_columns,
                                                       options.flush_rows);
    im.task = std::make_unique<sim_detail::CsvStream>(im.staging.staged(kTask), task_columns,
                                                      options.flush_rows);
    im.events = std::make_unique<sim_detail::CsvStream>(
        im.staging.staged(kEvents), std::vector<std::string>{"t", "kind", "message"}, 1,
        kEventText);
  } catch (...) {
    // nothing was recorded yet: leave no staging folder behind
    im.state.reset();
    im.task.reset();
    im.events.reset();
    std::error_code ec;
    std::filesystem::remove_all(im.staging.staging(), ec);
    throw;
  }

  // what the summary says, captured now: the simulation may be gone when the recorder finalizes
  sim_detail::SummaryInfo& info = im.info;
  info.invocation = sim_detail::current_invocation(options.seed ? &*options.seed : nullptr);
  info.model = robot.name();
  info.source = robot.source();
  info.mode = to_string(simulation.mode());
  info.integrator = simulation.uses_rk4() ? "RK4" : "Euler";
  info.timestep = simulation.timestep();
  info.control_period = simulation.control_period();
  info.steps_per_tick = simulation.steps_per_tick();
  info.state_decimation = options.state_decimation;
  info.start_time = info.end_time = simulation.time();
  info.frame = frame ? frame->name : "";
  for (int c = 0; c < simulation.controller_count(); ++c) {
    const Controller& controller = simulation.controller(c);
    info.controllers.push_back(
        {controller_names[c],
         controller.command_kind() == CommandKind::torque ? "torque" : "position",
         controller.chain().joint_names()});
  }
  for (int a : im.saturation_columns)
    info.saturation.push_back({object_name(m, mjOBJ_ACTUATOR, a, "actuator"), 0});
  for (const ActuatorInfo& a : robot.actuators()) info.actuators.push_back(actuator_info(m, a));
  // the model the simulation steps (its own copy when it has one), saved now: the simulation may
  // be gone when the recorder finalizes
  const mjModel& stepped = simulation.model();
  im.model_bytes.resize(static_cast<std::size_t>(mj_sizeModel(&stepped)));
  mj_saveModel(&stepped, nullptr, im.model_bytes.data(),
               static_cast<mjtSize>(im.model_bytes.size()));
  info.files = {{"state", kState, static_cast<int>(state_columns.size())},
                {"task", kTask, static_cast<int>(task_columns.size())},
                {"events", kEvents, 3}};
}

Recorder::~Recorder() {
  if (finalized_ || !impl_) return;
  const bool unwinding = std::uncaught_exceptions() > uncaught_at_construction_;
  try {
    if (unwinding) {
      finalize("error", "an exception ended the run");
    } else if (!last_run_status_.empty()) {
      finalize(last_run_status_, last_run_message_);
    } else {
      finalize("aborted", "the recorder was destroyed before finalize()");
    }
  } catch (const std::exception& e) {
    std::cerr << "mjarm: " << e.what() << "\n";
  }
}

const std::filesystem::path& Recorder::directory() const noexcept {
  return impl_->staging.directory();
}
std::filesystem::path Recorder::state_path() const { return directory() / kState; }
std::filesystem::path Recorder::task_path() const { return directory() / kTask; }
std::filesystem::path Recorder::events_path() const { return directory() / kEvents; }
std::filesystem::path Recorder::summary_path() const { return directory() / kSummary; }
std::int64_t Recorder::state_rows() const noexcept { return impl_->state->rows(); }
std::int64_t Recorder::task_rows() const noexcept { return impl_->task->rows(); }
std::int64_t Recorder::event_rows() const noexcept { return impl_->events->rows(); }

void Recorder::check_layout(const Simulation& simulation) const {
  if (&simulation != impl_->simulation) {
    throw Error("recorder for '" + directory().string() + "' was built for another simulation");
  }
  if (simulation.controller_count() != impl_->controller_count) {
    throw Error("recorder for '" + directory().string() + "' was built with " +
                std::to_string(impl_->controller_count) + " controllers, the simulation now has " +
                std::to_string(simulation.controller_count()) +
                ": build the recorder after adding them");
  }
}

void Recorder::on_run_end(const RunResult& result) {
  if (finalized_) return;
  last_run_status_ = to_string(result.status);
  last_run_message_ = result.message;
  impl_->info.end_time = result.end_time;
}

void Recorder::event(double time, std::string_view kind, std::string_view message) noexcept {
  if (finalized_) return;
  sim_detail::CsvStream& csv = *impl_->events;
  csv.add(time);
  csv.add_text(kind);
  csv.add_text(message);
  csv.end_row();  // flushes: events are rare and matter most when things go wrong
}

void Recorder::flush() noexcept {
  if (finalized_) return;
  impl_->state->flush();
  impl_->task->flush();
  impl_->events->flush();
}

void Recorder::on_physics_step(const Simulation& simulation, double time, const double* qpos,
                               const double* qvel) noexcept {
  if (finalized_) return;
  Impl& im = *impl_;
  const mjModel& m = simulation.model();
  const mjData& d = simulation.data();
  im.info.end_time = d.time;
  if (im.steps_seen++ % im.options.state_decimation != 0) return;
  sim_detail::CsvStream& csv = *im.state;
  csv.add(time);
  for (int i = 0; i < m.nq; ++i) csv.add(qpos[i]);
  for (int i = 0; i < m.nv; ++i) csv.add(qvel[i]);
  for (int a = 0; a < m.nu; ++a) csv.add(d.ctrl[a]);
  for (int a = 0; a < m.nu; ++a) csv.add(d.actuator_force[a]);
  // after the step d holds the contacts of the state at `time` and their constraint forces
  int contacts = 0;
  double normal_force = 0.0;
  for (int c = 0; c < d.ncon; ++c) {
    if (d.contact[c].exclude != 0) continue;
    ++contacts;
    if (d.contact[c].efc_address < 0) continue;
    mjtNum f_C[6];
    mj_contactForce(&m, &d, c, f_C);
    normal_force += f_C[0];
  }
  csv.add(static_cast<double>(contacts));
  csv.add(im.contact_forces ? normal_force : kNaN);
  csv.end_row();
}

void Recorder::on_control_tick(const Simulation& simulation, const Reference& reference) noexcept {
  if (finalized_) return;
  Impl& im = *impl_;
  const mjData& d = simulation.data();
  sim_detail::CsvStream& csv = *im.task;
  csv.add(d.time);
  if (im.frame) {
    const bool site = im.frame->kind == FrameKind::site;
    const double* p = site ? d.site_xpos + 3 * im.frame->id : d.xpos + 3 * im.frame->id;
    const double* R = site ? d.site_xmat + 9 * im.frame->id : d.xmat + 9 * im.frame->id;
    add_pose(csv, p, R);
    Pose X_WE;
    X_WE.p = Eigen::Map<const Eigen::Vector3d>(p);
    X_WE.R = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(R);
    const Pose& X_WD = reference.task.X_WE;
    const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> R_WD = X_WD.R;
    add_pose(csv, X_WD.p.data(), R_WD.data());
    const Vector6d e = task_error(X_WE, X_WD);
    for (int i = 0; i < 6; ++i) csv.add(e[i]);
  }
  csv.add(reference.gripper);
  const bool qref = reference.joint.q.size() == im.qref_size;
  for (int i = 0; i < im.qref_size; ++i) csv.add(qref ? reference.joint.q[i] : kNaN);
  for (int c = 0; c < im.controller_count; ++c) {
    const JointCommand& command = simulation.command(c);
    const Controller& controller = simulation.controller(c);
    const int n = controller.chain().size();
    for (int i = 0; i < n; ++i) csv.add(i < command.value.size() ? command.value[i] : kNaN);
    const std::size_t names = controller.internal_names().size();
    const std::span<const double> values = controller.internal_values();
    for (std::size_t i = 0; i < names; ++i) csv.add(i < values.size() ? values[i] : kNaN);
  }
  const std::span<const std::uint8_t> saturated = simulation.saturated();
  for (std::size_t k = 0; k < im.saturation_columns.size(); ++k) {
    const std::uint8_t s = saturated[im.saturation_columns[k]];
    im.saturation_counts[k] += s;
    csv.add(static_cast<double>(s));
  }
  for (const RecorderChannel& channel : im.options.channels) csv.add(*channel.value);
  csv.end_row();
}

void Recorder::finalize(const RunResult& result) {
  if (!finalized_ && impl_) impl_->info.end_time = result.end_time;
  finalize(to_string(result.status), result.message);
}

void Recorder::finalize(std::string_view status, std::string_view message) {
  if (finalized_ || !impl_) return;
  finalized_ = true;  // whatever happens below, rows are no longer accepted
  Impl& im = *impl_;
  sim_detail::SummaryInfo& info = im.info;
  info.status = status;
  info.message = message;
  info.state_rows = im.state->rows();
  info.task_rows = im.task->rows();
  info.event_rows = im.events->rows();
  for (std::size_t k = 0; k < info.saturation.size(); ++k)
    info.saturation[k].ticks = im.saturation_counts[k];
  std::string failure;
  for (auto* csv : {im.state.get(), im.task.get(), im.events.get()}) {
    if (!csv->close() && failure.empty()) failure = csv->failure();
  }
  if (failure.empty()) {
    try {
      FileWriter model(im.staging.staged(kModel), FileWriter::Mode::in_place, "recorded model");
      model.write(im.model_bytes.data(), im.model_bytes.size());
      model.commit();
    } catch (const Error& e) {
      failure = e.what();
    }
  }
  info.write_error = failure;
  // a recording with a failed write is never moved into the directory: the summary still goes
  // into the staging folder (when it can), so that the partial recording describes itself
  try {
    sim_detail::write_summary(im.staging.staged(kSummary), info);
  } catch (const Error& e) {
    failure =
        failure.empty() ? e.what() : failure + "; " + kSummary + " could not be written either";
    std::error_code ec;
    std::filesystem::remove(im.staging.staged(kSummary), ec);  // a cut summary misleads a reader
  }
  if (!failure.empty()) {
    im.staging.unlock();
    throw Error("recorder: " + failure + "; nothing was moved into '" + directory().string() +
                "': the incomplete recording stays in '" + im.staging.staging().string() + "'");
  }
  im.staging.commit({kState, kTask, kEvents, kModel}, kSummary);
}

}  // namespace mjarm
