#pragma once
/// @file
/// `Robot`: a loaded MuJoCo model, shared and immutable, with names that never fail silently.

#include <mujoco/mujoco.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/fields.hpp"

namespace mjarm {

/// Deletes an `mjData` with `mj_deleteData`.
struct DataDeleter {
  void operator()(mjData* d) const noexcept { mj_deleteData(d); }
};
/// An `mjData` owned by its creator; every algorithm keeps its own scratch one.
using DataPtr = std::unique_ptr<mjData, DataDeleter>;

/// Joint types in MuJoCo's order.
enum class JointType {
  free = mjJNT_FREE,
  ball = mjJNT_BALL,
  slide = mjJNT_SLIDE,
  hinge = mjJNT_HINGE
};

constexpr auto declared_names(const JointType*) {
  using J = JointType;
  return std::array{EnumName{J::free, "free", "6 dofs: position and unit quaternion, nq 7"},
                    EnumName{J::ball, "ball", "3 rotational dofs: unit quaternion, nq 4"},
                    EnumName{J::slide, "slide", "1 translational dof [m]"},
                    EnumName{J::hinge, "hinge", "1 rotational dof [rad]"}};
}

/// One joint of the model.
struct JointInfo {
  std::string name;
  int id = 0;
  JointType type = JointType::hinge;
  int body = 0;          ///< body the joint moves
  int qpos_address = 0;  ///< first index into qpos
  int dof_address = 0;   ///< first index into qvel
  bool limited = false;
  double lower = 0.0;  ///< range [rad or m]; meaningful when limited
  double upper = 0.0;
};

/// What an actuator does, read from its gain and bias parameters.
enum class ActuatorKind {
  motor,     ///< force = gear·ctrl
  position,  ///< force = kp·(ctrl − q) − kv·q̇
  velocity,  ///< force = kv·(ctrl − q̇)
  general    ///< anything else
};

constexpr auto declared_names(const ActuatorKind*) {
  using A = ActuatorKind;
  return std::array{EnumName{A::motor, "motor", "force = gear·ctrl"},
                    EnumName{A::position, "position", "force = kp·(ctrl − q) − kv·q̇"},
                    EnumName{A::velocity, "velocity", "force = kv·(ctrl − q̇)"},
                    EnumName{A::general, "general", "anything else"}};
}

/// One actuator of the model.
struct ActuatorInfo {
  std::string name;
  int id = 0;
  ActuatorKind kind = ActuatorKind::general;
  std::optional<int> joint;  ///< joint it drives, when its transmission is a joint
  bool ctrl_limited = false;
  double ctrl_lower = 0.0;
  double ctrl_upper = 0.0;
  bool force_limited = false;
  double force_lower = 0.0;
  double force_upper = 0.0;
  double gear = 1.0;  ///< first gear component
};

/// One sensor of the model; its values sit at sensordata[address, address + dimension).
struct SensorInfo {
  std::string name;
  int id = 0;
  std::string type;  ///< e.g. "jointpos", "framepos", "force"
  int address = 0;
  int dimension = 0;
};

/// How a model file is loaded.
struct LoadOptions {
  /// A mesh whose file is missing is no error: the mesh is dropped and each geom showing it
  /// becomes a box of the geom's own size, else half-size 0.025 m (a model drawn from a recording
  /// whose meshes are gone: the joints and so the qpos coordinates are unchanged). One message
  /// per missing file in `Robot::missing_meshes()`. MJCF files only.
  bool missing_meshes_as_boxes = false;
};

/// A loaded model. Copies share one immutable `mjModel`; algorithms never modify it.
class Robot {
 public:
  /// Loads MJCF or URDF from @p path as MuJoCo loads it; MJCF is staged first (includes and
  /// asset files read and checked through `read_user_file`, mjcf_staging.hpp).
  /// @throws Error naming the file and MuJoCo's message when the file is missing or invalid.
  static Robot from_file(const std::filesystem::path& path);
  /// As above, with @p options.
  static Robot from_file(const std::filesystem::path& path, const LoadOptions& options);

  /// Loads MJCF or URDF held in @p xml; relative asset paths resolve against @p base_dir.
  /// @throws Error with MuJoCo's message (and line) when the XML is invalid.
  static Robot from_string(std::string_view xml, const std::filesystem::path& base_dir = {});

  /// Compiles an mjSpec (MuJoCo's model-editing API, `mj_compile`): MuJoCo's warnings become
  /// the load warnings, `source()` is "<string>". Compiling records its result in @p spec (as
  /// `mj_compile` does); the spec stays the caller's.
  /// @param what  names the model in errors, e.g. "scene 'pick'".
  /// @param warnings  warnings raised while the spec was assembled (a scene's), listed first in
  ///        `load_warnings()`
  /// @throws Error with MuJoCo's message when the spec does not compile, or naming the element
  ///         of a non-finite number.
  static Robot from_spec(mjSpec& spec, std::string_view what,
                         std::vector<std::string> warnings = {});

  /// Loads a bundled model by name ("panda", "ur5e_torque", ...).
  /// @throws Error listing the bundled names when @p name is not one of them, and as
  ///         `bundled_names()` when the models folder is missing or empty.
  static Robot bundled(std::string_view name);

  /// A robot over a model compiled elsewhere (e.g. the `mujoco.MjModel` of a Python user),
  /// shared, not copied: @p model's deleter decides when it is freed, and mjarm never writes it.
  /// Its owner may still edit parameters between calls; objects built from the robot (chains,
  /// controllers) read the limits and ids they cache at construction.
  /// @param source  how messages name the model ("mujoco.MjModel at 0x...").
  /// @throws Error when @p model is null or holds a non-finite number (as a loaded model).
  static Robot from_model(std::shared_ptr<const mjModel> model, std::string source);

  /// A bundled name when @p name_or_path has no '/' and no extension, a file path otherwise.
  static Robot load(std::string_view name_or_path);
  /// As above, with @p options.
  static Robot load(std::string_view name_or_path, const LoadOptions& options);

  /// Directory of the bundled models: $MJARM_MODELS, else the installed models relative to the
  /// installed CLI or Python extension holding the library (a wheel's `mjarm/models`), else the
  /// source tree, else the install prefix's share dir (src/model/models_dir.cpp).
  static std::filesystem::path models_dir();

  /// Names of the bundled models (top-level .xml files in `models_dir()`), sorted.
  /// @throws Error naming the folder (and $MJARM_MODELS when it came from there) when it does not
  ///         exist, is not a folder, cannot be listed or holds no models.
  static std::vector<std::string> bundled_names();

  /// The immutable MuJoCo model.
  const mjModel& model() const noexcept { return *model_; }
  /// The model's name.
  const std::string& name() const noexcept { return name_; }
  /// Where it was loaded from ("<string>" for strings).
  const std::string& source() const noexcept { return source_; }
  /// MuJoCo's warnings while loading the model (parser and compiler), one message each, then
  /// those of MuJoCo's first-step checks on the reference state (qpos0: "Nan, Inf or huge
  /// value in QACC ..."), which the load runs so that a model diverging at once says so here.
  const std::vector<std::string>& load_warnings() const noexcept { return warnings_; }
  /// The meshes whose files were missing, drawn as boxes (`LoadOptions::missing_meshes_as_boxes`):
  /// one message per file, naming it and what its geoms became.
  const std::vector<std::string>& missing_meshes() const noexcept { return missing_meshes_; }

  int nq() const noexcept { return model_->nq; }  ///< position coordinates
  int nv() const noexcept { return model_->nv; }  ///< degrees of freedom
  int nu() const noexcept { return model_->nu; }  ///< actuators

  /// Ids by name; each throws `Error` naming the kind, the name, the model and close names.
  int joint(std::string_view name) const;
  int body(std::string_view name) const;
  int site(std::string_view name) const;
  int geom(std::string_view name) const;
  int actuator(std::string_view name) const;
  int sensor(std::string_view name) const;
  int camera(std::string_view name) const;
  int keyframe(std::string_view name) const;

  std::vector<JointInfo> joints() const;
  JointInfo joint_info(int id) const;
  std::vector<ActuatorInfo> actuators() const;
  std::vector<SensorInfo> sensors() const;
  std::vector<std::string> body_names() const;
  std::vector<std::string> site_names() const;
  std::vector<std::string> camera_names() const;
  std::vector<std::string> keyframe_names() const;

  /// A fresh `mjData` at the model's reference configuration, kinematics computed.
  DataPtr make_data() const;

  /// Named state access. Spans cover the joint's coordinates (1 for hinge/slide, 4 ball, 7 free).
  std::span<const double> qpos(const mjData& d, std::string_view joint) const;
  std::span<const double> qvel(const mjData& d, std::string_view joint) const;
  std::span<const double> sensor_values(const mjData& d, std::string_view sensor) const;
  double ctrl(const mjData& d, std::string_view actuator) const;
  /// @throws Error when @p values has the wrong size or holds NaN/inf.
  void set_qpos(mjData& d, std::string_view joint, std::span<const double> values) const;
  void set_qvel(mjData& d, std::string_view joint, std::span<const double> values) const;
  void set_ctrl(mjData& d, std::string_view actuator, double value) const;

  /// The qpos of keyframe @p name (nq values).
  /// @throws Error when the keyframe does not exist.
  std::vector<double> keyframe_qpos(std::string_view name) const;

 private:
  /// @p label names the model in errors (default: from @p source).
  Robot(mjModel* model, std::string source, std::vector<std::string> warnings,
        std::string_view label = {});
  Robot(std::shared_ptr<const mjModel> model, std::string source,
        std::vector<std::string> warnings, std::string_view label = {});

  std::shared_ptr<const mjModel> model_;
  std::string name_;
  std::string source_;
  std::vector<std::string> warnings_;
  std::vector<std::string> missing_meshes_;
};

/// Installs mjarm's MuJoCo log handler (once per process; `mju_setLogHandler`): an error MuJoCo
/// raises under mjarm's code (the nearest caller of MuJoCo on the stack is mjarm's) becomes an
/// `mjarm::Error` instead of exiting the process, and a warning there is printed to stderr (and
/// kept in `Robot::load_warnings` while a model loads). Messages raised under any other caller
/// sharing the library (MuJoCo's Python bindings, their viewer) go to the handler that was there
/// before, as if mjarm were not loaded. The caller's own code counts as mjarm's from then on.
[[gnu::noinline]] void install_mujoco_handlers();

}  // namespace mjarm
