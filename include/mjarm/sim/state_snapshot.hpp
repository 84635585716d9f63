#pragma once
/// @file
/// Everything that determines the next step of an `mjData`, saved and put back bit for bit:
/// restore a snapshot, step N times, and the trajectory is the one that followed the snapshot.

#include <mujoco/mujoco.h>

#include <cstdint>
#include <span>
#include <vector>

namespace mjarm {

/// The integration state of an `mjData` (MuJoCo's `mjSTATE_INTEGRATION`: time, qpos, qvel, act,
/// actuator and sensor history, the solver's warm start, ctrl, applied forces, equality
/// activations, mocap poses, userdata, plugin state), with the signature and sizes of the model
/// it belongs to, so that it is never restored into another model.
class StateSnapshot {
 public:
  /// An empty snapshot (restoring it is an error).
  StateSnapshot() = default;

  /// The state of @p d, a data of @p m.
  static StateSnapshot of(const mjModel& m, const mjData& d);

  /// Saves the state of @p d into this snapshot; allocates only when the model's state is larger
  /// than the one saved before.
  void take(const mjModel& m, const mjData& d);

  /// Writes the state into @p d. Derived quantities (body poses, contacts, forces) are not
  /// recomputed: the next `mj_step` does, or call `mj_forward`, which writes no part of the state
  /// (the steps that follow are the same with or without it).
  /// @throws Error when @p m is not the model the snapshot was taken of (its signature or its
  ///         sizes differ), or the snapshot is empty.
  void restore(const mjModel& m, mjData& d) const;

  bool empty() const noexcept { return state_.empty(); }
  /// Simulated time of the state [s].
  double time() const noexcept { return state_.empty() ? 0.0 : state_[0]; }
  /// The values, in mj_getState's order for `mjSTATE_INTEGRATION`.
  std::span<const mjtNum> values() const noexcept { return state_; }
  /// The signature of the model (`mjModel::signature`).
  std::uint64_t signature() const noexcept { return signature_; }

  /// Same model and bit-identical values.
  bool operator==(const StateSnapshot& other) const noexcept;

 private:
  void check_model(const mjModel& m) const;

  std::vector<mjtNum> state_;
  std::uint64_t signature_ = 0;
  int nq_ = 0, nv_ = 0, na_ = 0, nu_ = 0, nmocap_ = 0, neq_ = 0;
};

}  // namespace mjarm
