#include "mjarm/env/randomization.hpp"

#include <cmath>
#include <string>

#include "mjarm/env/env_task.hpp"
#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/random.hpp"

namespace mjarm {
namespace {

// fills @p factors with draws from [1 − r, 1 + r], or empties it for r = 0
void draw_factors(Eigen::VectorXd& factors, double r, Random& rng) noexcept {
  if (r == 0.0) return;
  for (Eigen::Index i = 0; i < factors.size(); ++i) factors[i] = uniform(rng, 1.0 - r, 1.0 + r);
}

}  // namespace

bool RandomizationOptions::any() const noexcept {
  return mass != 0.0 || friction != 0.0 || damping != 0.0 || gain != 0.0 || object_size != 0.0;
}

void RandomizationOptions::check() const { check_fields(*this); }

DomainRandomizer::DomainRandomizer(const mjModel& nominal, const RandomizationOptions& options,
                                   std::vector<int> object_geoms)
    : nominal_(nominal), options_(options), objects_(std::move(object_geoms)) {
  options.check();
  for (int g : objects_) {
    if (g < 0 || g >= nominal.ngeom)
      throw Error("randomization: object geom id " + std::to_string(g) + " out of range [0, " +
                  std::to_string(nominal.ngeom) + ")");
  }
  if (options.object_size != 0.0 && objects_.empty())
    throw Error("randomization: object_size is set but the task has no objects to resize");
  // sized once: apply() only writes
  if (options.mass != 0.0) mass_ = Eigen::VectorXd::Ones(nominal.nbody);
  if (options.friction != 0.0) friction_ = Eigen::VectorXd::Ones(nominal.ngeom);
  if (options.damping != 0.0) damping_ = Eigen::VectorXd::Ones(nominal.nv);
  if (options.gain != 0.0) gain_ = Eigen::VectorXd::Ones(nominal.nu);
  if (options.object_size != 0.0)
    size_ = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(objects_.size()));
}

void DomainRandomizer::apply(mjModel& model, mjData& scratch, Random& rng) noexcept {
  const mjModel& m0 = nominal_;
  // the nominal values first, so that draws never compound
  std::copy(m0.body_mass, m0.body_mass + m0.nbody, model.body_mass);
  std::copy(m0.body_inertia, m0.body_inertia + 3 * m0.nbody, model.body_inertia);
  std::copy(m0.geom_friction, m0.geom_friction + 3 * m0.ngeom, model.geom_friction);
  std::copy(m0.geom_size, m0.geom_size + 3 * m0.ngeom, model.geom_size);
  std::copy(m0.geom_rbound, m0.geom_rbound + m0.ngeom, model.geom_rbound);
  std::copy(m0.dof_damping, m0.dof_damping + m0.nv, model.dof_damping);
  std::copy(m0.actuator_gainprm, m0.actuator_gainprm + mjNGAIN * m0.nu, model.actuator_gainprm);
  std::copy(m0.actuator_biasprm, m0.actuator_biasprm + mjNBIAS * m0.nu, model.actuator_biasprm);

  // draws, in a fixed order, only for the ranges in use
  if (options_.mass != 0.0) {
    mass_[0] = 1.0;
    for (int b = 1; b < m0.nbody; ++b)
      mass_[b] = uniform(rng, 1.0 - options_.mass, 1.0 + options_.mass);
    for (int b = 1; b < m0.nbody; ++b) {
      model.body_mass[b] *= mass_[b];
      for (int k = 0; k < 3; ++k) model.body_inertia[3 * b + k] *= mass_[b];
    }
  }
  if (options_.friction != 0.0) {
    draw_factors(friction_, options_.friction, rng);
    for (int g = 0; g < m0.ngeom; ++g)
      for (int k = 0; k < 3; ++k) model.geom_friction[3 * g + k] *= friction_[g];
  }
  if (options_.damping != 0.0) {
    draw_factors(damping_, options_.damping, rng);
    for (int v = 0; v < m0.nv; ++v) model.dof_damping[v] *= damping_[v];
  }
  if (options_.gain != 0.0) {
    // the gain and the servo's position and velocity feedback together (zero for a motor)
    draw_factors(gain_, options_.gain, rng);
    for (int a = 0; a < m0.nu; ++a) {
      model.actuator_gainprm[mjNGAIN * a] *= gain_[a];
      model.actuator_biasprm[mjNBIAS * a + 1] *= gain_[a];
      model.actuator_biasprm[mjNBIAS * a + 2] *= gain_[a];
    }
  }
  if (options_.object_size != 0.0) {
    // one factor per object body: geoms of a body drawn earlier share its factor
    for (std::size_t k = 0; k < objects_.size(); ++k) {
      const int body = m0.geom_bodyid[objects_[k]];
      std::size_t first = k;
      for (std::size_t j = 0; j < k; ++j) {
        if (m0.geom_bodyid[objects_[j]] == body) {
          first = j;
          break;
        }
      }
      const double s = first == k
                           ? uniform(rng, 1.0 - options_.object_size, 1.0 + options_.object_size)
                           : size_[static_cast<Eigen::Index>(first)];
      size_[static_cast<Eigen::Index>(k)] = s;
      const int g = objects_[k];
      for (int i = 0; i < 3; ++i) model.geom_size[3 * g + i] *= s;
      model.geom_rbound[g] *= s;
      if (first == k) {
        model.body_mass[body] *= s * s * s;
        for (int i = 0; i < 3; ++i) model.body_inertia[3 * body + i] *= s * s * s * s * s;
      }
    }
  }
  mj_setConst(&model, &scratch);
}

}  // namespace mjarm
