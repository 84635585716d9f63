#include "mjarm/control/wrench_source.hpp"

#include <cmath>

namespace mjarm {

WrenchSource::WrenchSource(const Chain& chain, const WrenchSourceOptions& options)
    : options_(options), model_(&chain.robot().model()) {
  check_fields(options);
  switch (options.kind) {
    case WrenchSourceKind::none:
      break;
    case WrenchSourceKind::sensor:
      sensor_.emplace(chain.robot(), options.site, options.timing);
      tool_body_ = model_->site_bodyid[sensor_->site_id()];
      tool_mass_ = model_->body_subtreemass[tool_body_];
      break;
    case WrenchSourceKind::observer:
      observer_.emplace(chain, options.observer);
      break;
  }
}

void WrenchSource::reset() noexcept {
  if (observer_) observer_->reset();
  wrench_.setZero();
  status_ = WrenchStatus::ok;
  time_ = 0.0;
  has_command_time_ = false;
  last_command_time_ = 0.0;
  period_ = 0.0;
}

WrenchStatus WrenchSource::measure(const mjData& d, const Pose& X_WE) noexcept {
  status_ = WrenchStatus::ok;
  time_ = d.time;
  switch (options_.kind) {
    case WrenchSourceKind::none:
      wrench_.setZero();
      break;
    case WrenchSourceKind::sensor: {
      const WrenchReading r = sensor_->read_world(d, X_WE.p);
      time_ = r.time;
      if (!r.ok()) {
        status_ = WrenchStatus::non_finite;
        wrench_.setZero();
        break;
      }
      // the sensor reads what its parent exerts on the tool: −(environment + the tool's weight)
      wrench_ = -r.wrench;
      if (options_.compensate_tool_weight) {
        const Eigen::Vector3d weight =
            tool_mass_ * Eigen::Map<const Eigen::Vector3d>(model_->opt.gravity);
        const Eigen::Vector3d com =
            Eigen::Map<const Eigen::Vector3d>(d.subtree_com + 3 * tool_body_);
        wrench_.head<3>() -= weight;
        wrench_.tail<3>() -= (com - X_WE.p).cross(weight);
      }
      if (!wrench_.allFinite()) {
        status_ = WrenchStatus::non_finite;
        wrench_.setZero();
      }
      break;
    }
    case WrenchSourceKind::observer: {
      // the estimate of the last record_command (one control period old)
      wrench_ = options_.contact_only ? observer_->contact_wrench() : observer_->wrench();
      time_ = last_command_time_;
      if (!wrench_.allFinite()) {
        status_ = WrenchStatus::non_finite;
        wrench_.setZero();
      }
      break;
    }
  }
  return status_;
}

ObserverStatus WrenchSource::record_command(const mjData& d, const ChainDynamics& dynamics,
                                            const Eigen::Ref<const Eigen::VectorXd>& tau) noexcept {
  if (!observer_) return ObserverStatus::ok;
  // the step the observer predicts over: the fixed period, else the last interval between ticks
  double dt = options_.control_period;
  if (dt == 0.0) {
    const double since = d.time - last_command_time_;
    if (has_command_time_ && std::isfinite(since) && since > 0.0) period_ = since;
    if (period_ == 0.0) period_ = model_->opt.timestep;
    dt = period_;
  }
  last_command_time_ = d.time;
  has_command_time_ = true;
  return observer_->update(d, dynamics, tau, dt);
}

}  // namespace mjarm
