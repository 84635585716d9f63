#include "mjarm/model/robot.hpp"

#include <tinyxml2.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <limits>
#include <mutex>

#include "mjarm/error.hpp"
#include "mjarm/model/finite_model.hpp"
#include "mjarm/model/model_size.hpp"
#include "mjarm/model/names.hpp"
#include "mjarm/model/user_file.hpp"
#include "mjcf_detail.hpp"
#include "mjcf_staging.hpp"
#include "mujoco_caller.hpp"
#include "mujoco_loading.hpp"
#include "urdf_assets.hpp"
#include "urdf_names.hpp"

namespace mjarm {
namespace {

using model_detail::LoadWarnings;
using model_detail::xml_loader_mutex;

// MuJoCo's warnings while a model loads on this thread, for the robot's load report
thread_local std::vector<std::string>* load_warnings_sink = nullptr;

// every warning printed below, for `mujoco_warning_count` (a soak fails on any)
std::atomic<std::uint64_t> mujoco_warnings_printed{0};

void print_mujoco_warning(const char* message) {
  mujoco_warnings_printed.fetch_add(1, std::memory_order_relaxed);
  if (load_warnings_sink != nullptr) load_warnings_sink->emplace_back(message);
  std::cerr << "mujoco warning: " << message << "\n";
}

// the log handler in place before mjarm's (MuJoCo's default: print, and exit on an error)
std::atomic<mjfLogHandler> previous_log_handler{nullptr};

/// MuJoCo's messages: an error raised under mjarm's frames becomes an `Error`, a warning there
/// goes to stderr and the load report; messages raised under anyone else's frames (MuJoCo's
/// Python bindings, a viewer thread) go to the handler that was there before, as if mjarm were
/// not loaded (mujoco_caller.hpp).
void mujoco_log_handler(const mjLogMessage* message) {
  const bool mjarm_message = message->level >= mjLOG_WARNING && detail::mujoco_called_by_mjarm();
  if (!mjarm_message) {
    previous_log_handler.load()(message);
    return;
  }
  std::string text = message->subject;
  if (message->body != nullptr && message->body[0] != '\0')
    text += std::string("\n") + message->body;
  if (message->level == mjLOG_ERROR) throw Error("MuJoCo error: " + text);
  print_mujoco_warning(text.c_str());
}

void count_xml_elements(const tinyxml2::XMLElement& parent, ModelSizeCount& count) {
  for (const auto* child = parent.FirstChildElement(); child != nullptr;
       child = child->NextSiblingElement()) {
    count.add(child->Name());
    count_xml_elements(*child, count);
  }
}

/// The root element's name ("mujoco" or "robot"). A document that is not MJCF (URDF) is
/// checked against the model size bound here: it goes to MuJoCo as it is.
/// @throws Error with the parser's message and line when the XML is malformed, or for a URDF
///         beyond `max_model_elements()`.
std::string root_element(std::string_view xml, const std::string& source) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS) {
    throw Error(mjcf_detail::xml_parse_error(doc, source));
  }
  const tinyxml2::XMLElement& root = mjcf_detail::single_root(doc, source);
  if (std::string_view(root.Name()) != "mujoco") {
    ModelSizeCount count;
    count_xml_elements(root, count);
    count.check("model " + source);
  }
  return root.Name();
}

struct MemoryFsDeleter {
  void operator()(mjVFS* vfs) const {
    mj_deleteVFS(vfs);
    delete vfs;
  }
};

/// A loaded model and MuJoCo's warnings while loading it.
struct Loaded {
  mjModel* model = nullptr;
  std::vector<std::string> warnings;
};

/// Loads XML text through MuJoCo's virtual file system; paths in it must be absolute. With
/// @p staged, line numbers in MuJoCo's messages are mapped back to the user's files.
Loaded load_from_memory(const std::string& xml, const std::string& source,
                        const StagedMjcf* staged = nullptr) {
  const std::unique_ptr<mjVFS, MemoryFsDeleter> vfs(new mjVFS);
  mj_defaultVFS(vfs.get());
  const char* file_name = "mjarm_model.xml";
  if (xml.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()) ||
      mj_addBufferVFS(vfs.get(), file_name, xml.data(), static_cast<int>(xml.size())) != 0)
    throw Error("cannot stage " + source + " in MuJoCo's virtual file system");
  char error[1024] = "";
  Loaded loaded;
  {
    const std::lock_guard<std::mutex> guard(xml_loader_mutex());
    const LoadWarnings capture(loaded.warnings);
    loaded.model = mj_loadXML(file_name, vfs.get(), error, sizeof(error));
  }
  std::string message = staged ? staged->to_source_lines(error) : error;
  if (loaded.model == nullptr) throw Error("cannot load " + source + ": " + message);
  model_detail::add_load_message(loaded.warnings, error, std::move(message));
  return loaded;
}

Loaded load_from_disk(const std::filesystem::path& path) {
  char error[1024] = "";
  Loaded loaded;
  {
    const std::lock_guard<std::mutex> guard(xml_loader_mutex());
    const LoadWarnings capture(loaded.warnings);
    loaded.model = mj_loadXML(path.c_str(), nullptr, error, sizeof(error));
  }
  if (loaded.model == nullptr) throw Error("cannot load '" + path.string() + "': " + error);
  model_detail::add_load_message(loaded.warnings, error, error);
  return loaded;
}

ActuatorKind classify(const mjModel& m, int id) {
  const double* gain = m.actuator_gainprm + id * mjNGAIN;
  const double* bias = m.actuator_biasprm + id * mjNBIAS;
  const bool fixed_gain = m.actuator_gaintype[id] == mjGAIN_FIXED;
  if (m.actuator_dyntype[id] != mjDYN_NONE || !fixed_gain) return ActuatorKind::general;
  if (m.actuator_biastype[id] == mjBIAS_NONE) return ActuatorKind::motor;
  if (m.actuator_biastype[id] == mjBIAS_AFFINE) {
    if (bias[0] == 0.0 && std::abs(bias[1] + gain[0]) <= 1e-12 * std::abs(gain[0]))
      return ActuatorKind::position;
    if (bias[0] == 0.0 && bias[1] == 0.0 &&
        std::abs(bias[2] + gain[0]) <= 1e-12 * std::abs(gain[0]))
      return ActuatorKind::velocity;
  }
  return ActuatorKind::general;
}

int joint_coordinates(JointType type, bool position) {
  switch (type) {
    case JointType::free:
      return position ? 7 : 6;
    case JointType::ball:
      return position ? 4 : 3;
    default:
      return 1;
  }
}

void check_values(std::span<const double> values, std::size_t expected, const std::string& what) {
  if (values.size() != expected) {
    throw Error(what + " expects " + std::to_string(expected) + " value(s), got " +
                std::to_string(values.size()));
  }
  for (double v : values)
    if (!std::isfinite(v)) throw Error(what + " got a non-finite value");
}

// the MJCF element of each sensor type (a new type in MuJoCo breaks the build here: -Wswitch)
const char* sensor_type_name(int type) noexcept {
  switch (static_cast<mjtSensor>(type)) {
    case mjSENS_TOUCH: return "touch";
    case mjSENS_ACCELEROMETER: return "accelerometer";
    case mjSENS_VELOCIMETER: return "velocimeter";
    case mjSENS_GYRO: return "gyro";
    case mjSENS_FORCE: return "force";
    case mjSENS_TORQUE: return "torque";
    case mjSENS_MAGNETOMETER: return "magnetometer";
    case mjSENS_RANGEFINDER: return "rangefinder";
    case mjSENS_CAMPROJECTION: return "camprojection";
    case mjSENS_JOINTPOS: return "jointpos";
    case mjSENS_JOINTVEL: return "jointvel";
    case mjSENS_TENDONPOS: return "tendonpos";
    case mjSENS_TENDONVEL: return "tendonvel";
    case mjSENS_ACTUATORPOS: return "actuatorpos";
    case mjSENS_ACTUATORVEL: return "actuatorvel";
    case mjSENS_ACTUATORFRC: return "actuatorfrc";
    case mjSENS_JOINTACTFRC: return "jointactuatorfrc";
    case mjSENS_TENDONACTFRC: return "tendonactuatorfrc";
    case mjSENS_BALLQUAT: return "ballquat";
    case mjSENS_BALLANGVEL: return "ballangvel";
    case mjSENS_JOINTLIMITPOS: return "jointlimitpos";
    case mjSENS_JOINTLIMITVEL: return "jointlimitvel";
    case mjSENS_JOINTLIMITFRC: return "jointlimitfrc";
    case mjSENS_TENDONLIMITPOS: return "tendonlimitpos";
    case mjSENS_TENDONLIMITVEL: return "tendonlimitvel";
    case mjSENS_TENDONLIMITFRC: return "tendonlimitfrc";
    case mjSENS_FRAMEPOS: return "framepos";
    case mjSENS_FRAMEQUAT: return "framequat";
    case mjSENS_FRAMEXAXIS: return "framexaxis";
    case mjSENS_FRAMEYAXIS: return "frameyaxis";
    case mjSENS_FRAMEZAXIS: return "framezaxis";
    case mjSENS_FRAMELINVEL: return "framelinvel";
    case mjSENS_FRAMEANGVEL: return "frameangvel";
    case mjSENS_FRAMELINACC: return "framelinacc";
    case mjSENS_FRAMEANGACC: return "frameangacc";
    case mjSENS_SUBTREECOM: return "subtreecom";
    case mjSENS_SUBTREELINVEL: return "subtreelinvel";
    case mjSENS_SUBTREEANGMOM: return "subtreeangmom";
    case mjSENS_INSIDESITE: return "insidesite";
    case mjSENS_GEOMDIST: return "distance";
    case mjSENS_GEOMNORMAL: return "normal";
    case mjSENS_GEOMFROMTO: return "fromto";
    case mjSENS_CONTACT: return "contact";
    case mjSENS_E_POTENTIAL: return "e_potential";
    case mjSENS_E_KINETIC: return "e_kinetic";
    case mjSENS_CLOCK: return "clock";
    case mjSENS_TACTILE: return "tactile";
    case mjSENS_PLUGIN: return "plugin";
    case mjSENS_USER: return "user";
  }
  return "unknown";
}

/// MuJoCo's checks of a first step (mj_step's mj_checkPos, mj_checkVel and mj_checkAcc) on the
/// model's reference state: their warnings ("Nan, Inf or huge value in QACC ...") join the load
/// warnings, so a model that diverges at once says so when it loads, not at its first step.
/// A model whose first step fails outright (an arena too small for its contacts: "mj_stackAlloc:
/// out of memory") still loads, as it did before the check: the failure is a load warning, and
/// the commands that only need kinematics keep working.
void add_first_state_warnings(const mjModel& m, std::vector<std::string>& warnings) {
  const LoadWarnings capture(warnings);
  try {
    const DataPtr data(mj_makeData(&m));
    if (!data) return;  // no memory for it: the first mj_makeData of a user reports that
    mj_checkPos(&m, data.get());
    mj_checkVel(&m, data.get());
    mj_forward(&m, data.get());
    mj_checkAcc(&m, data.get());
  } catch (const Error& e) {
    warnings.push_back(std::string("the first step at qpos0 fails: ") + e.what());
  }
}

}  // namespace

namespace model_detail {

std::mutex& xml_loader_mutex() {
  static std::mutex mutex;
  return mutex;
}

LoadWarnings::LoadWarnings(std::vector<std::string>& sink) : previous_(load_warnings_sink) {
  load_warnings_sink = &sink;
}

LoadWarnings::~LoadWarnings() { load_warnings_sink = previous_; }

void add_load_message(std::vector<std::string>& warnings, const char* raw, std::string mapped) {
  if (raw[0] == '\0') return;
  const auto seen = std::find(warnings.begin(), warnings.end(), raw);
  if (seen != warnings.end()) {
    *seen = std::move(mapped);
    return;
  }
  print_mujoco_warning(mapped.c_str());  // as the handler prints those it sees
  warnings.push_back(std::move(mapped));
}

}  // namespace model_detail

std::uint64_t mujoco_warning_count() noexcept {
  return mujoco_warnings_printed.load(std::memory_order_relaxed);
}

void install_mujoco_handlers() {
  // the caller's code counts as mjarm's (the Python extension, when the library is shared)
  detail::note_mjarm_code(__builtin_return_address(0));
  static std::once_flag once;
  std::call_once(once, [] {
    // mju_setLogHandler returns the handler it replaces: one installed before mjarm, or
    // MuJoCo's default (which calls the legacy mju_user_error / mju_user_warning when set)
    mjfLogHandler previous = mju_setLogHandler(mujoco_log_handler);
    if (previous == nullptr) {  // NULL stands for the default: ask for the default itself
      mju_setLogHandler(nullptr);
      previous = mju_setLogHandler(mujoco_log_handler);
    }
    previous_log_handler = previous;
  });
}

Robot::Robot(mjModel* model, std::string source, std::vector<std::string> warnings,
             std::string_view label)
    : Robot(std::shared_ptr<const mjModel>(
                model, [](const mjModel* m) { mj_deleteModel(const_cast<mjModel*>(m)); }),
            std::move(source), std::move(warnings), label) {}

Robot::Robot(std::shared_ptr<const mjModel> model, std::string source,
             std::vector<std::string> warnings, std::string_view label)
    : model_(std::move(model)),
      name_(model_name(*model_)),
      source_(std::move(source)),
      warnings_(std::move(warnings)) {
  // a non-finite number would come out of every algorithm as inf / NaN without an error
  check_model_finite(*model_, !label.empty()            ? std::string(label)
                              : source_ == "<string>" ? std::string("XML string")
                                                      : "'" + source_ + "'");
  add_first_state_warnings(*model_, warnings_);
}

Robot Robot::from_model(std::shared_ptr<const mjModel> model, std::string source) {
  install_mujoco_handlers();
  if (!model) throw Error("Robot::from_model: no model (" + source + ")");
  return Robot(std::move(model), std::move(source), {});
}

Robot Robot::from_file(const std::filesystem::path& path) { return from_file(path, LoadOptions{}); }

Robot Robot::from_file(const std::filesystem::path& path, const LoadOptions& options) {
  install_mujoco_handlers();
  const std::string xml = read_user_file(path, "model file");
  const std::string source = "'" + path.string() + "'";
  if (root_element(xml, source) != "mujoco") {
    // URDF: MuJoCo skips names it does not know; it opens the meshes itself, after the same
    // checks as MJCF assets
    std::vector<std::string> warnings = check_urdf_names(xml, source);
    check_urdf_assets(xml, std::filesystem::absolute(path).parent_path(), source);
    Loaded loaded = load_from_disk(path);
    warnings.insert(warnings.end(), loaded.warnings.begin(), loaded.warnings.end());
    return Robot(loaded.model, path.string(), std::move(warnings));
  }
  // every MJCF file loads staged (includes inlined and read through the checked reader, asset
  // paths checked and absolute), so MuJoCo's line numbers map back to the user's own files
  const StagedMjcf staged = stage_mjcf(xml, std::filesystem::absolute(path).parent_path(), path,
                                       options.missing_meshes_as_boxes);
  Loaded loaded = load_from_memory(staged.xml, source, &staged);
  std::vector<std::string> warnings = staged.missing_meshes;
  warnings.insert(warnings.end(), loaded.warnings.begin(), loaded.warnings.end());
  Robot robot(loaded.model, path.string(), std::move(warnings));
  robot.missing_meshes_ = staged.missing_meshes;
  return robot;
}

Robot Robot::from_string(std::string_view xml, const std::filesystem::path& base_dir) {
  install_mujoco_handlers();
  const std::string source = "XML string";
  const std::string root = root_element(xml, source);
  if (root != "mujoco") {
    // URDF and other formats MuJoCo reads go through unchanged
    std::vector<std::string> warnings = check_urdf_names(xml, source);
    Loaded loaded = load_from_memory(std::string(xml), source);
    warnings.insert(warnings.end(), loaded.warnings.begin(), loaded.warnings.end());
    return Robot(loaded.model, "<string>", std::move(warnings));
  }
  const std::filesystem::path base = base_dir.empty() ? std::filesystem::current_path() : base_dir;
  const StagedMjcf staged = stage_mjcf(xml, std::filesystem::absolute(base));
  Loaded loaded = load_from_memory(staged.xml, source, &staged);
  return Robot(loaded.model, "<string>", std::move(loaded.warnings));
}

Robot Robot::from_spec(mjSpec& spec, std::string_view what, std::vector<std::string> warnings) {
  install_mujoco_handlers();
  mjModel* model = nullptr;
  {
    const LoadWarnings capture(warnings);
    model = mj_compile(&spec, nullptr);
  }
  if (model == nullptr)
    throw Error(std::string(what) + " does not compile: " + mjs_getError(&spec));
  return Robot(model, "<string>", std::move(warnings), what);
}

std::vector<std::string> Robot::bundled_names() {
  const std::filesystem::path dir = models_dir();
  const char* env = std::getenv("MJARM_MODELS");
  const std::string folder = "bundled models folder '" + dir.string() + "'" +
                             (env != nullptr && *env != '\0' ? " (from $MJARM_MODELS)" : "");
  std::error_code ec;
  const auto status = std::filesystem::status(dir, ec);
  if (!std::filesystem::exists(status)) throw Error(folder + " does not exist");
  if (!std::filesystem::is_directory(status)) throw Error(folder + " is not a folder");
  std::vector<std::string> names;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code type_ec;
    if (it->is_regular_file(type_ec) && has_extension(it->path(), ".xml"))
      names.push_back(it->path().stem().string());
  }
  if (ec) throw Error(folder + " cannot be listed: " + ec.message());
  if (names.empty()) throw Error(folder + " holds no models (no .xml files)");
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  return names;
}

Robot Robot::bundled(std::string_view name) {
  // the list first: a missing or empty folder is reported as such, not as an unknown name
  const auto names = bundled_names();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    std::string message =
        "no bundled model named '" + std::string(name) + "' in " + models_dir().string();
    message += "; bundled models: ";
    for (std::size_t i = 0; i < names.size(); ++i) message += (i ? ", " : "") + names[i];
    throw Error(message);
  }
  // the file as the folder spells it: "NAME.xml", else the extension in another case
  std::filesystem::path file = models_dir() / (std::string(name) + ".xml");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    for (const auto& entry : std::filesystem::directory_iterator(models_dir(), ec))
      if (std::error_code type_ec; entry.path().stem() == name &&
                                   has_extension(entry.path(), ".xml") &&
                                   entry.is_regular_file(type_ec))
        file = entry.path();
  }
  return from_file(file);
}

Robot Robot::load(std::string_view name_or_path) { return load(name_or_path, LoadOptions{}); }

Robot Robot::load(std::string_view name_or_path, const LoadOptions& options) {
  const std::filesystem::path path(name_or_path);
  const bool looks_like_path = path.has_extension() || path.has_parent_path();
  return looks_like_path ? from_file(path, options) : bundled(name_or_path);
}

int Robot::joint(std::string_view n) const { return find_object(*model_, mjOBJ_JOINT, n); }
int Robot::body(std::string_view n) const { return find_object(*model_, mjOBJ_BODY, n); }
int Robot::site(std::string_view n) const { return find_object(*model_, mjOBJ_SITE, n); }
int Robot::geom(std::string_view n) const { return find_object(*model_, mjOBJ_GEOM, n); }
int Robot::actuator(std::string_view n) const { return find_object(*model_, mjOBJ_ACTUATOR, n); }
int Robot::sensor(std::string_view n) const { return find_object(*model_, mjOBJ_SENSOR, n); }
int Robot::camera(std::string_view n) const { return find_object(*model_, mjOBJ_CAMERA, n); }
int Robot::keyframe(std::string_view n) const { return find_object(*model_, mjOBJ_KEY, n); }

JointInfo Robot::joint_info(int id) const {
  const mjModel& m = *model_;
  if (id < 0 || id >= m.njnt)
    throw Error("joint id " + std::to_string(id) + " out of range [0, " + std::to_string(m.njnt) +
                ")");
  JointInfo info;
  const char* n = mj_id2name(&m, mjOBJ_JOINT, id);
  info.name = n ? n : "";
  info.id = id;
  info.type = static_cast<JointType>(m.jnt_type[id]);
  info.body = m.jnt_bodyid[id];
  info.qpos_address = m.jnt_qposadr[id];
  info.dof_address = m.jnt_dofadr[id];
  info.limited = m.jnt_limited[id] != 0;
  info.lower = m.jnt_range[2 * id];
  info.upper = m.jnt_range[2 * id + 1];
  return info;
}

std::vector<JointInfo> Robot::joints() const {
  std::vector<JointInfo> result;
  for (int id = 0; id < model_->njnt; ++id) result.push_back(joint_info(id));
  return result;
}

std::vector<ActuatorInfo> Robot::actuators() const {
  const mjModel& m = *model_;
  std::vector<ActuatorInfo> result;
  for (int id = 0; id < m.nu; ++id) {
    ActuatorInfo info;
    const char* n = mj_id2name(&m, mjOBJ_ACTUATOR, id);
    info.name = n ? n : "";
    info.id = id;
    info.kind = classify(m, id);
    if (m.actuator_trntype[id] == mjTRN_JOINT) info.joint = m.actuator_trnid[2 * id];
    info.ctrl_limited = m.actuator_ctrllimited[id] != 0;
    info.ctrl_lower = m.actuator_ctrlrange[2 * id];
    info.ctrl_upper = m.actuator_ctrlrange[2 * id + 1];
    info.force_limited = m.actuator_forcelimited[id] != 0;
    info.force_lower = m.actuator_forcerange[2 * id];
    info.force_upper = m.actuator_forcerange[2 * id + 1];
    info.gear = m.actuator_gear[6 * id];
    result.push_back(std::move(info));
  }
  return result;
}

std::vector<SensorInfo> Robot::sensors() const {
  const mjModel& m = *model_;
  std::vector<SensorInfo> result;
  for (int id = 0; id < m.nsensor; ++id) {
    SensorInfo info;
    const char* n = mj_id2name(&m, mjOBJ_SENSOR, id);
    info.name = n ? n : "";
    info.id = id;
    const int type = m.sensor_type[id];
    info.type = sensor_type_name(type);
    info.address = m.sensor_adr[id];
    info.dimension = m.sensor_dim[id];
    result.push_back(std::move(info));
  }
  return result;
}

std::vector<std::string> Robot::body_names() const { return object_names(*model_, mjOBJ_BODY); }
std::vector<std::string> Robot::site_names() const { return object_names(*model_, mjOBJ_SITE); }
std::vector<std::string> Robot::camera_names() const { return object_names(*model_, mjOBJ_CAMERA); }
std::vector<std::string> Robot::keyframe_names() const { return object_names(*model_, mjOBJ_KEY); }

DataPtr Robot::make_data() const {
  DataPtr data(mj_makeData(model_.get()));
  if (!data) throw Error("cannot allocate mjData for model '" + name_ + "'");
  mj_forward(model_.get(), data.get());
  return data;
}

std::span<const double> Robot::qpos(const mjData& d, std::string_view joint_name) const {
  const JointInfo info = joint_info(joint(joint_name));
  return {d.qpos + info.qpos_address, static_cast<std::size_t>(joint_coordinates(info.type, true))};
}

std::span<const double> Robot::qvel(const mjData& d, std::string_view joint_name) const {
  const JointInfo info = joint_info(joint(joint_name));
  return {d.qvel + info.dof_address, static_cast<std::size_t>(joint_coordinates(info.type, false))};
}

std::span<const double> Robot::sensor_values(const mjData& d, std::string_view sensor_name) const {
  const int id = sensor(sensor_name);
  return {d.sensordata + model_->sensor_adr[id], static_cast<std::size_t>(model_->sensor_dim[id])};
}

double Robot::ctrl(const mjData& d, std::string_view actuator_name) const {
  return d.ctrl[actuator(actuator_name)];
}

void Robot::set_qpos(mjData& d, std::string_view joint_name, std::span<const double> values) const {
  const JointInfo info = joint_info(joint(joint_name));
  check_values(values, joint_coordinates(info.type, true), "qpos of joint '" + info.name + "'");
  std::copy(values.begin(), values.end(), d.qpos + info.qpos_address);
}

void Robot::set_qvel(mjData& d, std::string_view joint_name, std::span<const double> values) const {
  const JointInfo info = joint_info(joint(joint_name));
  check_values(values, joint_coordinates(info.type, false), "qvel of joint '" + info.name + "'");
  std::copy(values.begin(), values.end(), d.qvel + info.dof_address);
}

void Robot::set_ctrl(mjData& d, std::string_view actuator_name, double value) const {
  const int id = actuator(actuator_name);
  check_values({&value, 1}, 1, "ctrl of actuator '" + std::string(actuator_name) + "'");
  d.ctrl[id] = value;
}

std::vector<double> Robot::keyframe_qpos(std::string_view key_name) const {
  const int id = keyframe(key_name);
  const double* begin = model_->key_qpos + static_cast<std::ptrdiff_t>(id) * model_->nq;
  return {begin, begin + model_->nq};
}

}  // namespace mjarm
