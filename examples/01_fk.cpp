// 01_fk: load the bundled Panda, compute forward kinematics at its "home" keyframe, print the
// pose of the end-effector site and check it against MuJoCo's own mj_kinematics.

#include <cmath>
#include <cstdio>

#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/lie/rotation.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"

int main() {
  const mjarm::Robot robot = mjarm::Robot::bundled("panda");
  // the joints from the world to the flange site, root first
  const mjarm::Chain chain(robot, "attachment_site");
  mjarm::ChainKinematics kin(chain);

  const std::vector<double> home = robot.keyframe_qpos("home");
  const Eigen::VectorXd q = chain.gather(home.data());
  const mjarm::Pose& X_WE = kin.update(q);

  const Eigen::Vector4d quat = mjarm::quaternion_from_rotation(X_WE.R);
  const Eigen::Vector3d rpy = mjarm::rpy_from_rotation(X_WE.R);
  std::printf("%s: %d joints to site '%s' at keyframe 'home'\n", robot.name().c_str(), chain.size(),
              chain.frame().name.c_str());
  std::printf("position [m]          %8.4f %8.4f %8.4f\n", X_WE.p.x(), X_WE.p.y(), X_WE.p.z());
  std::printf("quaternion (w x y z)  %8.5f %8.5f %8.5f %8.5f\n", quat[0], quat[1], quat[2],
              quat[3]);
  std::printf("roll pitch yaw [rad]  %8.4f %8.4f %8.4f\n", rpy[0], rpy[1], rpy[2]);

  // the same pose from MuJoCo's full pipeline
  mjarm::DataPtr data = robot.make_data();
  for (int i = 0; i < robot.nq(); ++i) data->qpos[i] = home[static_cast<std::size_t>(i)];
  mj_kinematics(&robot.model(), data.get());
  const int site = robot.site("attachment_site");
  double error = 0.0;
  for (int i = 0; i < 3; ++i)
    error = std::fmax(error, std::fabs(X_WE.p[i] - data->site_xpos[3 * site + i]));
  std::printf("difference to mj_kinematics [m]: %.1e\n", error);
  return error < 1e-12 ? 0 : 1;
}
