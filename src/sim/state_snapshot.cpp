#include "mjarm/sim/state_snapshot.hpp"

#include <cstring>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/model/names.hpp"

namespace mjarm {

StateSnapshot StateSnapshot::of(const mjModel& m, const mjData& d) {
  StateSnapshot s;
  s.take(m, d);
  return s;
}

void StateSnapshot::take(const mjModel& m, const mjData& d) {
  state_.resize(static_cast<std::size_t>(mj_stateSize(&m, mjSTATE_INTEGRATION)));
  mj_getState(&m, &d, state_.data(), mjSTATE_INTEGRATION);
  signature_ = m.signature;
  nq_ = m.nq;
  nv_ = m.nv;
  na_ = m.na;
  nu_ = m.nu;
  nmocap_ = m.nmocap;
  neq_ = m.neq;
}

void StateSnapshot::check_model(const mjModel& m) const {
  if (state_.empty()) throw Error("state snapshot: empty (take one first)");
  const bool same_sizes =
      m.nq == nq_ && m.nv == nv_ && m.na == na_ && m.nu == nu_ && m.nmocap == nmocap_ &&
      m.neq == neq_ &&
      static_cast<std::size_t>(mj_stateSize(&m, mjSTATE_INTEGRATION)) == state_.size();
  if (m.signature != signature_ || !same_sizes) {
    throw Error("state snapshot: taken of another model (signature " + std::to_string(signature_) +
                ", nq " + std::to_string(nq_) + ", nv " + std::to_string(nv_) +
                "), not restored into model '" + model_name(m) + "' (signature " +
                std::to_string(m.signature) + ", nq " + std::to_string(m.nq) + ", nv " +
                std::to_string(m.nv) + ")");
  }
}

void StateSnapshot::restore(const mjModel& m, mjData& d) const {
  check_model(m);
  mj_setState(&m, &d, state_.data(), mjSTATE_INTEGRATION);
}

bool StateSnapshot::operator==(const StateSnapshot& other) const noexcept {
  return signature_ == other.signature_ && state_.size() == other.state_.size() &&
         (state_.empty() ||
          std::memcmp(state_.data(), other.state_.data(), state_.size() * sizeof(mjtNum)) == 0);
}

}  // namespace mjarm
