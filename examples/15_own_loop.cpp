// Your own loop, in C++: an arm built from the UR5e's DH table, stepped by a plain
// mj_step1/mj_step2 loop that owns its mjData. The state is read and written by name
// (NamedData), the goal comes from IK started at the current joints, a computed-torque law
// drives the motors, every link's frame is read at once (BodyPoses), and a snapshot taken
// mid-run replays the last second bit for bit.
// Exits 0 when the tool reached the goal within 1 mm and the replay matched.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "mjarm/control/computed_torque.hpp"
#include "mjarm/ik/pose_ik.hpp"
#include "mjarm/kinematics/body_poses.hpp"
#include "mjarm/kinematics/constraint_summary.hpp"
#include "mjarm/kinematics/frame_state.hpp"
#include "mjarm/model/dh_model.hpp"
#include "mjarm/model/named_data.hpp"
#include "mjarm/sim/state_snapshot.hpp"

int main() {
  using namespace mjarm;
  constexpr double pi = std::numbers::pi;
  DhArm arm;
  arm.name = "ur5e_dh";
  arm.links = {{.d = 0.1625, .alpha = pi / 2},
               {.a = -0.425},
               {.a = -0.3922},
               {.d = 0.1333, .alpha = pi / 2},
               {.d = 0.0997, .alpha = -pi / 2},
               {.d = 0.0996}};
  arm.effort = 150.0;
  arm.damping = 0.5;
  const Robot robot = dh_robot(arm);
  const mjModel& m = robot.model();
  DataPtr data = robot.make_data();
  mjData& d = *data;

  // the start, by name
  const NamedData named(m, d);
  const double start[] = {0.0, -pi / 2, pi / 2, -pi / 2, -pi / 2, 0.0};
  for (int i = 0; i < 6; ++i) named("qpos", "joint" + std::to_string(i + 1))[0] = start[i];
  mj_forward(&m, &d);

  // the goal: a pose the arm can reach, solved from where the arm is
  const Chain chain(robot, "end");
  const Eigen::VectorXd q_goal =
      (Eigen::VectorXd(6) << 0.5, -1.2, 1.4, -1.8, -1.57, 0.3).finished();
  const Pose goal = forward_kinematics(chain, q_goal);
  PoseIk ik(chain);
  const IkResult solution = ik.solve(goal, chain.gather(d.qpos));
  std::printf("IK from the current joints: %s after %d iterations\n", to_string(solution.status),
              solution.iterations);

  ComputedTorqueController law(chain);
  Reference reference;
  reference.joint.hold(solution.q);
  JointCommand command;
  command.value = Eigen::VectorXd::Zero(6);
  const auto run = [&](double seconds) {
    for (int k = 0; k < static_cast<int>(std::lround(seconds / m.opt.timestep)); ++k) {
      mj_step1(&m, &d);
      law.compute(d, reference, command);
      for (int i = 0; i < 6; ++i) d.ctrl[i] = command.value[i];
      mj_step2(&m, &d);
    }
  };

  run(2.0);
  const StateSnapshot snapshot = StateSnapshot::of(m, d);
  run(1.0);
  const std::vector<mjtNum> after(d.qpos, d.qpos + m.nq);
  snapshot.restore(m, d);
  run(1.0);
  const bool replayed = std::memcmp(after.data(), d.qpos, sizeof(mjtNum) * after.size()) == 0;

  mj_forward(&m, &d);
  const Eigen::Vector3d tool = named("site_xpos", "end");
  const double error = (tool - goal.p).norm();
  BodyPoses links(robot);
  links.update(Eigen::Map<const Eigen::VectorXd>(d.qpos, m.nq));
  const ConstraintSummary constraints = constraint_summary(d);
  std::printf("tool error %.3f mm; elbow (link3) at %.3f %.3f %.3f m; %d constraint rows\n",
              error * 1e3, links.pose("link3").p.x(), links.pose("link3").p.y(),
              links.pose("link3").p.z(), constraints.rows);
  std::printf("replay from the snapshot: %s\n", replayed ? "bit for bit" : "DIFFERENT");
  return solution.ok() && error < 1e-3 && replayed ? 0 : 1;
}
