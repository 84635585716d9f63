#pragma once
/// @file
/// mjData's arrays by element name, as dm_control's `physics.named.data`: the `qpos` of a joint
/// (one value for a hinge or a slide, 4 for a ball, 7 for a free joint), the `xpos` of a body,
/// the `sensordata` of a sensor. Views into the data, not copies; names are looked up with
/// MuJoCo's own hash (`mj_name2id`), so there is no index to build and nothing allocates.
///
/// @code
/// NamedData named(model, data);
/// named("qpos", "joint1")[0] = 0.3;          // a writable view
/// Eigen::Vector3d p = named("site_xpos", "attachment_site");
/// @endcode

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace mjarm {

/// One array of mjData readable by element name.
struct NamedQuantity {
  std::string_view name;  ///< the mjData field: "qpos", "xpos", "site_xmat"
  mjtObj element;         ///< what a name names: mjOBJ_JOINT, mjOBJ_BODY, mjOBJ_SITE, ...
  /// An input of the next step (qpos, qvel, ctrl, act, applied forces, mocap poses); the others
  /// are results of mj_forward, overwritten by the next one.
  bool input;
  std::string_view doc;  ///< one line, with the unit and the layout of one element's values
};

/// Every quantity, in a fixed order (inputs first).
std::span<const NamedQuantity> named_quantities() noexcept;

/// The quantity called @p name.
/// @throws Error "unknown quantity 'qpso'; closest: qpos; quantities: …"
const NamedQuantity& named_quantity(std::string_view name);

/// Where one element's values sit in its quantity's array.
struct NamedSlice {
  int offset = 0;
  int size = 0;  ///< 0 for an actuator without activation
};

/// The slice of element @p id of quantity @p q in model @p m.
/// @throws Error for an id out of range, or a body that is not a mocap body for mocap_pos and
///         mocap_quat.
NamedSlice named_slice(const mjModel& m, const NamedQuantity& q, int id);

/// The number of elements @p q is indexed by (joints, bodies, sites, ...).
int named_count(const mjModel& m, const NamedQuantity& q) noexcept;

/// The whole array of @p q in @p d (nq for qpos, 3·nbody for xpos, ...).
std::span<mjtNum> named_array(const mjModel& m, mjData& d, const NamedQuantity& q) noexcept;

/// mjData by element name: a model and a data of it, both borrowed (they must outlive this).
class NamedData {
 public:
  NamedData(const mjModel& m, mjData& d) noexcept : model_(&m), data_(&d) {}

  /// The values of element @p element of quantity @p quantity, a view into the data.
  /// @throws Error naming the quantity or the element, with the closest names.
  Eigen::Map<Eigen::VectorXd> operator()(std::string_view quantity, std::string_view element) const;
  /// The values of element number @p id.
  /// @throws Error for an id out of range.
  Eigen::Map<Eigen::VectorXd> operator()(std::string_view quantity, int id) const;

  /// The id of element @p element of @p q.
  /// @throws Error naming the element's kind and the closest names.
  int id(const NamedQuantity& q, std::string_view element) const;
  /// The names of the elements of @p q, in id order ("" for an unnamed one).
  std::vector<std::string> names(const NamedQuantity& q) const;

  const mjModel& model() const noexcept { return *model_; }
  mjData& data() const noexcept { return *data_; }

 private:
  Eigen::Map<Eigen::VectorXd> values(const NamedQuantity& q, int id) const;

  const mjModel* model_;
  mjData* data_;
};

}  // namespace mjarm
