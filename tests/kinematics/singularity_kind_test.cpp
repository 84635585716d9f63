#include "mjarm/kinematics/singularity_kind.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "mjarm/error.hpp"
#include "support/random_configurations.hpp"

namespace mjarm {
namespace {

using Kinds = std::vector<SingularityKind>;

/// A bundled arm, its frame and its regular home configuration (the model's first keyframe).
struct KindArm {
  Robot robot;
  Chain chain;
  Eigen::VectorXd home;
  KindArm(const char* model, const char* frame, std::vector<std::string> joints = {})
      : robot(Robot::bundled(model)),
        chain(joints.empty() ? Chain(robot, frame) : Chain(robot, joints, frame)),
        home(chain.gather(robot.model().key_qpos)) {}
  /// home with joint @p i (chain index) set to @p value
  Eigen::VectorXd with(int i, double value) const {
    Eigen::VectorXd q = home;
    q[i] = value;
    return q;
  }
};

std::string kind_names(const Kinds& kinds) {
  std::string s;
  for (SingularityKind k : kinds) s += std::string(s.empty() ? "" : ",") + to_string(k);
  return s.empty() ? "(none)" : s;
}

/// ‖J·v‖ for the full world-aligned Jacobian at @p q.
double motion_along(const Chain& chain, const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
  ChainKinematics kin(chain);
  kin.update(q);
  Matrix6Xd J(6, chain.size());
  kin.jacobian(J);
  return (J * v).norm();
}

/// Moves joint @p i of @p q until the wrist centre lies on the first joint axis (bisection on the
/// side of the axis the centre is on, within [lo, hi]).
Eigen::VectorXd wrist_on_first_axis(SingularityClassifier& c, Eigen::VectorXd q, int i, double lo,
                                    double hi) {
  const ChainKinematics& kin = c.manipulability().kinematics();
  const auto side = [&](double value) {
    q[i] = value;
    const Eigen::Vector3d W = c.geometry(q).wrist_centre;
    const Eigen::Vector3d r = W - kin.anchor(0);
    // the arm moves in the vertical plane through the first axis: the signed offset along the
    // horizontal in-plane direction
    return kin.axis(1).cross(kin.axis(0)).dot(r);
  };
  double f_lo = side(lo);
  for (int k = 0; k < 100; ++k) {
    const double mid = 0.5 * (lo + hi);
    const double f_mid = side(mid);
    if ((f_mid < 0) == (f_lo < 0)) {
      lo = mid;
      f_lo = f_mid;
    } else {
      hi = mid;
    }
  }
  q[i] = 0.5 * (lo + hi);
  return q;
}

TEST(SingularityKind, FindsTheStructureOfTheBundledArms) {
  const KindArm arm6("arm6", "grip"), iiwa("iiwa14", "attachment_site"),
      ur5e("ur5e", "attachment_site"), panda("panda", "attachment_site");
  const ArmStructure a = SingularityClassifier(arm6.chain).structure();
  EXPECT_TRUE(a.classifiable && a.spherical_wrist && !a.planar_elbow);
  EXPECT_EQ(a.shoulder, (std::vector<int>{0, 1}));
  EXPECT_EQ(a.middle, (std::vector<int>{2}));
  EXPECT_EQ(a.wrist, (std::vector<int>{3, 4, 5}));
  const ArmStructure i = SingularityClassifier(iiwa.chain).structure();
  EXPECT_TRUE(i.spherical_wrist);
  EXPECT_EQ(i.shoulder, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(i.middle, (std::vector<int>{3}));
  const ArmStructure u = SingularityClassifier(ur5e.chain).structure();
  EXPECT_TRUE(!u.spherical_wrist && u.planar_elbow);  // offsets d4, d5, d6; axes 2–4 parallel
  EXPECT_EQ(u.shoulder, (std::vector<int>{0, 1}));
  EXPECT_EQ(u.middle, (std::vector<int>{2}));
  const ArmStructure p = SingularityClassifier(panda.chain).structure();
  EXPECT_TRUE(!p.spherical_wrist && !p.planar_elbow);  // the 0.088 m flange offset
  EXPECT_EQ(p.shoulder, (std::vector<int>{0, 1, 2}));
  // every wrist pair of these arms can align (perpendicular neighbours, 1 and 3 parallel at 0)
  for (const ArmStructure* s : {&a, &i, &u, &p}) EXPECT_EQ(s->wrist_pairs.size(), 3u);
  // a planar two-link arm has no wrist, shoulder or elbow in this sense
  const Robot planar = Robot::bundled("planar2");
  EXPECT_FALSE(SingularityClassifier(Chain(planar, "tip")).structure().classifiable);
}

TEST(SingularityKind, RegularHomesAreNotFlagged) {
  for (const KindArm& arm :
       {KindArm("arm6", "grip"), KindArm("iiwa14", "attachment_site"),
        KindArm("ur5e", "attachment_site"), KindArm("panda", "attachment_site")}) {
    SingularityClassifier c(arm.chain);
    const SingularityClassification r = c.classify(arm.home);
    EXPECT_FALSE(r.below_sigma_min || r.above_condition_number) << arm.robot.name();
    EXPECT_TRUE(r.kinds.empty()) << arm.robot.name() << ": " << kind_names(r.kinds);
    EXPECT_GT(r.sigma_min, 0.05) << arm.robot.name();
    EXPECT_NEAR(r.null_direction.norm(), 1.0, 1e-12);
  }
}

TEST(SingularityKind, WristAxesAlignedOnSixJointArms) {
  // arm6 (spherical wrist): q5 = 0 puts axes 4 and 6 on one line; ur5e: q5 = 0 makes 4 and 6
  // parallel (with 2 and 3): the classic wrist singularities
  for (const KindArm& arm : {KindArm("arm6", "grip"), KindArm("ur5e", "attachment_site")}) {
    SingularityClassifier c(arm.chain);
    const Eigen::VectorXd q = arm.with(4, 0.0);
    const SingularityClassification r = c.classify(q);
    EXPECT_TRUE(r.below_sigma_min && r.above_condition_number) << arm.robot.name();
    EXPECT_EQ(r.kinds, Kinds{SingularityKind::wrist}) << arm.robot.name();
    EXPECT_EQ(r.geometry.aligned_first, 3);
    EXPECT_EQ(r.geometry.aligned_second, 5);
    // the SVD agrees: the lost joint motion turns the two aligned joints, and moves nothing
    EXPECT_GT(std::abs(r.null_direction[3]), 0.3) << r.null_direction.transpose();
    EXPECT_GT(std::abs(r.null_direction[5]), 0.3) << r.null_direction.transpose();
    EXPECT_LT(motion_along(arm.chain, q, r.null_direction), 1e-12);
  }
  // on the spherical wrist the two columns are equal: the motion is e4 − e6
  const KindArm arm6("arm6", "grip");
  SingularityClassifier c(arm6.chain);
  const Eigen::VectorXd v = c.classify(arm6.with(4, 0.0)).null_direction;
  EXPECT_NEAR(v[3], -v[5], 1e-12);
  EXPECT_NEAR(v[3], std::sqrt(0.5), 1e-12);
}

TEST(SingularityKind, NearWristSingularityCrossesTheThresholds) {
  // 2 mrad off the aligned wrist: σmin below 0.01 and condition above 100, still a wrist
  const KindArm arm6("arm6", "grip");
  SingularityClassifier c(arm6.chain);
  const SingularityClassification r = c.classify(arm6.with(4, 0.002));
  EXPECT_GT(r.sigma_min, 0.0);
  EXPECT_TRUE(r.below_sigma_min);
  EXPECT_TRUE(r.above_condition_number);
  EXPECT_EQ(r.kinds, Kinds{SingularityKind::wrist});
  EXPECT_NEAR(r.geometry.wrist_alignment, std::sin(0.002), 1e-12);
  // each threshold on its own
  SingularityClassifier relative(arm6.chain, {}, {.sigma_min = 1e-9});
  const SingularityClassification rr = relative.classify(arm6.with(4, 0.002));
  EXPECT_FALSE(rr.below_sigma_min);
  EXPECT_TRUE(rr.above_condition_number);
  EXPECT_EQ(rr.kinds, Kinds{SingularityKind::wrist});
  SingularityClassifier absolute(arm6.chain, {}, {.condition_number = 1e12});
  const SingularityClassification ra = absolute.classify(arm6.with(4, 0.002));
  EXPECT_TRUE(ra.below_sigma_min);
  EXPECT_FALSE(ra.above_condition_number);
  EXPECT_EQ(ra.kinds, Kinds{SingularityKind::wrist});
  // far enough away, neither
  EXPECT_TRUE(c.classify(arm6.with(4, 0.5)).kinds.empty());
}

TEST(SingularityKind, StretchedElbow) {
  // arm6 q3 = 0, ur5e q3 = 0 (planar elbow), iiwa q4 = 0: shoulder, elbow and wrist in line
  const struct {
    KindArm arm;
    int elbow;
  } cases[] = {{KindArm("arm6", "grip"), 2},
               {KindArm("ur5e", "attachment_site"), 2},
               {KindArm("iiwa14", "attachment_site"), 3}};
  for (const auto& [arm, elbow] : cases) {
    SingularityClassifier c(arm.chain);
    const Eigen::VectorXd q = arm.with(elbow, 0.0);
    const SingularityClassification r = c.classify(q);
    EXPECT_EQ(r.kinds, Kinds{SingularityKind::elbow}) << arm.robot.name();
    EXPECT_LT(r.geometry.elbow_stretch, 1e-12) << arm.robot.name();
    EXPECT_GT(std::abs(r.null_direction[elbow]), 0.3)
        << arm.robot.name() << ": " << r.null_direction.transpose();
    EXPECT_LT(motion_along(arm.chain, q, r.null_direction), 1e-12) << arm.robot.name();
    // folded back the same way it is bent, the elbow measure is the sine of the bend
    EXPECT_GT(c.classify(arm.with(elbow, 0.6)).geometry.elbow_stretch, 0.2) << arm.robot.name();
  }
}

TEST(SingularityKind, WristCentreOnTheFirstAxis) {
  // elbow bent, wrist regular, shoulder pitch chosen so that W lies on axis 1: a shoulder
  // singularity (joint 1 turns about a line through W, which the wrist can do alone)
  const struct {
    KindArm arm;
    int pitch;
  } cases[] = {{KindArm("arm6", "grip"), 1},
               {KindArm("iiwa14", "attachment_site",
                        {"joint1", "joint2", "joint4", "joint5", "joint6", "joint7"}),
                1}};
  for (const auto& [arm, pitch] : cases) {
    SingularityClassifier c(arm.chain);
    const Eigen::VectorXd q = wrist_on_first_axis(c, arm.home, pitch, -1.0, 1.0);
    const SingularityClassification r = c.classify(q);
    EXPECT_LT(r.geometry.shoulder_offset, 1e-9) << arm.robot.name();
    EXPECT_EQ(r.kinds, Kinds{SingularityKind::shoulder}) << arm.robot.name();
    EXPECT_GT(std::abs(r.null_direction[0]), 0.3)
        << arm.robot.name() << ": " << r.null_direction.transpose();
    EXPECT_LT(motion_along(arm.chain, q, r.null_direction), 1e-9) << arm.robot.name();
  }
}

TEST(SingularityKind, RedundantArms) {
  // iiwa: aligning its wrist alone keeps 6 directions (the redundancy covers it)...
  const KindArm iiwa("iiwa14", "attachment_site");
  SingularityClassifier c(iiwa.chain);
  const SingularityClassification aligned = c.classify(iiwa.with(5, 0.0));
  EXPECT_LT(aligned.geometry.wrist_alignment, 1e-12);
  EXPECT_TRUE(aligned.kinds.empty()) << kind_names(aligned.kinds);
  EXPECT_GT(aligned.sigma_min, 0.1);
  // ...and so does its wrist centre on the first axis (joint 1 turns about a line through W,
  // which the other joints follow with a self-motion)
  const Eigen::VectorXd on_axis = wrist_on_first_axis(c, iiwa.home, 1, -1.0, 1.0);
  const SingularityClassification shoulder = c.classify(on_axis);
  EXPECT_LT(shoulder.geometry.shoulder_offset, 1e-9);
  EXPECT_TRUE(shoulder.kinds.empty()) << kind_names(shoulder.kinds);
  // ...with its shoulder aligned as well (axes 1 and 3 on one line) one is lost
  Eigen::VectorXd q = iiwa.with(5, 0.0);
  q[1] = 0.0;
  EXPECT_EQ(c.classify(q).kinds, Kinds{SingularityKind::wrist});
  // locking joint 3 leaves a 6-joint arm whose aligned wrist loses a direction, e5 − e7
  const KindArm locked("iiwa14", "attachment_site",
                       {"joint1", "joint2", "joint4", "joint5", "joint6", "joint7"});
  SingularityClassifier six(locked.chain);
  EXPECT_TRUE(six.structure().spherical_wrist);
  const SingularityClassification r = six.classify(locked.with(4, 0.0));
  EXPECT_EQ(r.kinds, Kinds{SingularityKind::wrist});
  EXPECT_NEAR(r.null_direction[3], -r.null_direction[5], 1e-12);
  // panda (no wrist centre, no planar elbow): its singular zero configuration is unclassified,
  // reported with the lost direction
  const KindArm panda("panda", "attachment_site");
  SingularityClassifier p(panda.chain);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(7);
  const SingularityClassification rp = p.classify(zero);
  EXPECT_TRUE(rp.below_sigma_min);
  EXPECT_EQ(rp.kinds, Kinds{SingularityKind::unclassified});
  EXPECT_LT(motion_along(panda.chain, zero, rp.null_direction), 1e-12);
}

TEST(SingularityKind, OnlyTheFullBlockIsClassified) {
  const KindArm arm6("arm6", "grip");
  SingularityClassifier c(arm6.chain, {.block = JacobianBlock::position}, {.sigma_min = 10.0});
  const SingularityClassification r = c.classify(arm6.with(4, 0.0));
  EXPECT_TRUE(r.below_sigma_min);
  EXPECT_EQ(r.kinds, Kinds{SingularityKind::unclassified});
}

/// The right singular vectors of J at @p q whose σ cross the thresholds (σ < @p sigma_min or
/// σmax/σ > @p condition), as columns, and the singular values.
Eigen::MatrixXd lost_motions(const Chain& chain, const Eigen::VectorXd& q, double sigma_min,
                             double condition) {
  ChainKinematics kin(chain);
  kin.update(q);
  Matrix6Xd J(6, chain.size());
  kin.jacobian(J);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeFullV);
  const Eigen::VectorXd& s = svd.singularValues();
  Eigen::Index k = s.size();
  while (k > 0 && (s[k - 1] < sigma_min || s[0] > condition * s[k - 1])) --k;
  return svd.matrixV().rightCols(chain.size() - k);
}

TEST(SingularityKind, RandomSamplesAgreeWithTheSvd) {
  // wherever a kind is named on a 6-joint arm, J·v = σmin·u, and the named joint moves in the
  // lost motions (the independent SVD of J, thresholds crossed)
  std::mt19937 rng(3);
  for (const KindArm& arm : {KindArm("arm6", "grip"), KindArm("ur5e", "attachment_site")}) {
    SingularityClassifier c(arm.chain, {}, {.sigma_min = 0.05, .condition_number = 20.0});
    int named = 0;
    for (int t = 0; t < 300; ++t) {
      const Eigen::VectorXd q = test::random_q(arm.chain, rng);
      const SingularityClassification r = c.classify(q);
      EXPECT_NEAR(motion_along(arm.chain, q, r.null_direction), r.sigma_min, 1e-9);
      for (SingularityKind k : r.kinds) {
        if (k == SingularityKind::unclassified) continue;
        ++named;
        const int joint = k == SingularityKind::wrist   ? r.geometry.aligned_first
                          : k == SingularityKind::elbow ? c.structure().middle[0]
                                                        : 0;
        const Eigen::MatrixXd lost = lost_motions(arm.chain, q, 0.05, 20.0);
        EXPECT_GE(lost.row(joint).norm(), 0.1)
            << arm.robot.name() << " " << to_string(k) << " q " << q.transpose();
      }
    }
    EXPECT_GT(named, 0) << arm.robot.name();
  }
}

TEST(SingularityKind, RejectsBadInput) {
  const KindArm arm6("arm6", "grip");
  EXPECT_THROW(SingularityClassifier(arm6.chain, {}, {.sigma_min = 0.0}), Error);
  EXPECT_THROW(SingularityClassifier(arm6.chain, {}, {.condition_number = NAN}), Error);
  EXPECT_THROW(SingularityClassifier(arm6.chain, {}, {.geometric_tolerance = -1.0}), Error);
  SingularityClassifier c(arm6.chain);
  EXPECT_THROW(c.classify(Eigen::VectorXd::Zero(5)), Error);
  EXPECT_THROW(c.geometry(Eigen::VectorXd::Constant(6, NAN)), Error);
  EXPECT_STREQ(to_string(SingularityKind::unclassified), "unclassified");
}

}  // namespace
}  // namespace mjarm
