// The grasp study's pure parts: McNemar's exact test, paired tables, noisy demonstrations
// (seeded, bounded), contact-region IoU and threading.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "planning/grasp/demo_noise.h"
#include "planning/grasp/grasp.h"
#include "planning/grasp/grasp_object.h"
#include "planning/grasp/grasp_quality.h"
#include "planning/grasp/grasp_similarity.h"
#include "planning/grasp/grasp_stats.h"
#include "planning/grasp/grasp_transfer.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/robot_io.h"

namespace planning {
namespace {

const std::string kAssets = std::string(TOPOPLAN_SOURCE_DIR) + "/assets/";

const Robot& Human() {
  static const Robot robot = LoadRobot(kAssets + "robots/human_hand.urdf");
  return robot;
}

TEST(McNemarTest, TextbookTables) {
  // Agresti (2013), Categorical Data Analysis, Table 11.1 (approval of the president's
  // performance in two surveys): 794 approve both, 150 approve then disapprove, 86 disapprove
  // then approve, 570 disapprove both. Exact two-sided p = 2 P[Bin(236, ½) ≤ 86] = 3.7159e-5
  // (summed with exact rationals).
  const PairedTable t{794, 150, 86, 570};
  EXPECT_EQ(t.trials(), 1600);
  EXPECT_NEAR(McNemarExactP(t), 3.715936e-5, 1e-10);
  // By hand: b = 1, c = 7, n = 8: 2 (C(8,0) + C(8,1)) / 2^8 = 18 / 256.
  EXPECT_NEAR(McNemarExactP(1, 7), 18.0 / 256.0, 1e-13);
  EXPECT_NEAR(McNemarExactP(7, 1), 18.0 / 256.0, 1e-13);
  EXPECT_NEAR(McNemarExactP(0, 10), 2.0 / 1024.0, 1e-15);
  EXPECT_DOUBLE_EQ(McNemarExactP(5, 5), 1.0);
  EXPECT_DOUBLE_EQ(McNemarExactP(0, 0), 1.0);
  EXPECT_THROW(McNemarExactP(-1, 3), std::invalid_argument);
}

TEST(McNemarTest, BinomialCdfDoesNotUnderflow) {
  EXPECT_DOUBLE_EQ(BinomialHalfCdf(-1, 4), 0.0);
  EXPECT_DOUBLE_EQ(BinomialHalfCdf(4, 4), 1.0);
  EXPECT_NEAR(BinomialHalfCdf(2, 4), 11.0 / 16.0, 1e-15);
  EXPECT_NEAR(BinomialHalfCdf(50000, 100000),
              0.5 + 0.5 * std::exp(std::lgamma(100001.0) - 2 * std::lgamma(50001.0) -
                                   100000 * std::log(2.0)),
              1e-9);
}

TEST(PairedTableTest, CountsEveryCell) {
  const PairedTable t =
      MakePairedTable({true, true, false, false, true}, {true, false, true, false, false});
  EXPECT_EQ(t.both, 1);
  EXPECT_EQ(t.only_a, 2);
  EXPECT_EQ(t.only_b, 1);
  EXPECT_EQ(t.neither, 1);
  EXPECT_THROW(MakePairedTable({true}, {}), std::invalid_argument);
}

TEST(WilsonTest, KnownInterval) {
  // 7/8: centre (0.875 + 1.92/16)/(1 + 3.84/8).
  const Eigen::Vector2d ci = WilsonInterval(7, 8);
  EXPECT_NEAR(ci[0], 0.529, 1e-3);
  EXPECT_NEAR(ci[1], 0.978, 1e-3);
}

TEST(DemoNoiseTest, SeededAndBounded) {
  const HumanGrasp nominal = LoadHumanGrasp(kAssets + "grasps/power_bottle.json");
  DemoNoiseOptions o;
  o.joint_deg = 8.0;
  o.palm_translation = 0.015;
  o.palm_rotation_deg = 10.0;
  o.seed = 3;
  double max_joint = 0, max_t = 0, max_r = 0;
  for (int k = 0; k < 40; ++k) {
    const HumanGrasp a = NoisyDemonstration(Human(), nominal, k, o);
    const HumanGrasp b = NoisyDemonstration(Human(), nominal, k, o);
    EXPECT_EQ(a.name, "power_bottle#" + std::to_string(k));
    EXPECT_EQ(a.joints, b.joints);  // reproducible
    EXPECT_TRUE(a.world_from_palm.isApprox(b.world_from_palm, 0.0));
    const DemoDeviation d = MeasureDeviation(Human(), nominal, a);
    EXPECT_LE(d.joint, o.joint_deg * M_PI / 180 + 1e-12);
    EXPECT_LE(d.palm_translation, o.palm_translation + 1e-12);
    EXPECT_LE(d.palm_rotation, o.palm_rotation_deg * M_PI / 180 + 1e-9);
    max_joint = std::max(max_joint, d.joint);
    max_t = std::max(max_t, d.palm_translation);
    max_r = std::max(max_r, d.palm_rotation);
    EXPECT_NO_THROW(HumanConfiguration(Human(), a));  // inside the joint limits
  }
  // The noise is used: 40 demonstrations reach most of each bound.
  EXPECT_GT(max_joint, 0.7 * o.joint_deg * M_PI / 180);
  EXPECT_GT(max_t, 0.7 * o.palm_translation);
  EXPECT_GT(max_r, 0.7 * o.palm_rotation_deg * M_PI / 180);
  // Different indices and seeds give different demonstrations.
  const HumanGrasp d0 = NoisyDemonstration(Human(), nominal, 0, o);
  EXPECT_NE(d0.joints, NoisyDemonstration(Human(), nominal, 1, o).joints);
  DemoNoiseOptions other = o;
  other.seed = 4;
  EXPECT_NE(d0.joints, NoisyDemonstration(Human(), nominal, 0, other).joints);
  // Zero bounds reproduce the nominal demonstration.
  DemoNoiseOptions none;
  none.joint_deg = none.palm_translation = none.palm_rotation_deg = 0;
  const DemoDeviation z =
      MeasureDeviation(Human(), nominal, NoisyDemonstration(Human(), nominal, 5, none));
  EXPECT_EQ(z.joint, 0.0);
  EXPECT_EQ(z.palm_translation, 0.0);
  EXPECT_NEAR(z.palm_rotation, 0.0, 1e-7);
  DemoNoiseOptions bad = o;
  bad.joint_deg = -1;
  EXPECT_THROW(NoisyDemonstration(Human(), nominal, 0, bad), std::invalid_argument);
  EXPECT_THROW(NoisyDemonstration(Human(), nominal, -1, o), std::invalid_argument);
}

TEST(DemoNoiseTest, RecloseTouchesTheObject) {
  HumanGrasp nominal = LoadHumanGrasp(kAssets + "grasps/power_bottle.json");
  nominal.close = LoadHumanGrasp(kAssets + "grasps/specs/power_bottle.json").close;
  ASSERT_FALSE(nominal.close.empty());
  const std::vector<GraspObject> objects = LoadGraspObjects(kAssets + "grasps/objects.json");
  const GraspObject& bottle = FindGraspObject(objects, nominal.object);
  for (int k = 0; k < 3; ++k) {
    HumanGrasp demo = NoisyDemonstration(Human(), nominal, k);
    EXPECT_EQ(demo.close, nominal.close);
    const HumanGrasp drawn = demo;
    const double clearance = RecloseDemonstration(Human(), bottle, &demo);
    EXPECT_TRUE(demo.close.empty());
    EXPECT_GT(clearance, -0.001);  // no deep penetration left
    EXPECT_LT(clearance, 0.002);   // and the hand touches the bottle
    EXPECT_NE(demo.joints, drawn.joints);
    // The palm noise is kept; the palm only backed away along its normal (+y), at most 4 cm.
    EXPECT_TRUE(demo.world_from_palm.linear().isApprox(drawn.world_from_palm.linear(), 0.0));
    const Eigen::Vector3d moved =
        drawn.world_from_palm.linear().transpose() *
        (demo.world_from_palm.translation() - drawn.world_from_palm.translation());
    EXPECT_NEAR(moved.x(), 0.0, 1e-12);
    EXPECT_NEAR(moved.z(), 0.0, 1e-12);
    EXPECT_GE(moved.y(), 0.0);
    EXPECT_LE(moved.y(), 0.0401);
  }
  HumanGrasp no_list =
      NoisyDemonstration(Human(), LoadHumanGrasp(kAssets + "grasps/power_bottle.json"), 0);
  EXPECT_TRUE(std::isinf(RecloseDemonstration(Human(), bottle, &no_list)));
}

TEST(RegionIoUTest, HandMadeSets) {
  const CellSet a = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  const CellSet b = {{2, 0, 0}, {3, 0, 0}, {4, 0, 0}};
  EXPECT_DOUBLE_EQ(*RegionIoU(a, b), 2.0 / 5.0);
  EXPECT_DOUBLE_EQ(*RegionIoU(a, a), 1.0);
  EXPECT_DOUBLE_EQ(*RegionIoU(a, {}), 0.0);
  EXPECT_DOUBLE_EQ(*RegionIoU({{0, 0, 1}}, {{0, 1, 0}}), 0.0);
  EXPECT_FALSE(RegionIoU({}, {}).has_value());
}

TEST(ContactRegionTest, FingersOnABoxFace) {
  // The human hand's fingers against a box: the cells lie on the box surface, and moving the box
  // away leaves none.
  const HumanGrasp g = LoadHumanGrasp(kAssets + "grasps/power_bottle.json");
  const std::vector<GraspObject> objects = LoadGraspObjects(kAssets + "grasps/objects.json");
  const GraspObject& bottle = FindGraspObject(objects, g.object);
  KinematicsData kin(Human());
  ForwardKinematics(Human(), HumanConfiguration(Human(), g), &kin);
  ContactRegionOptions o;
  const std::vector<CellSet> r =
      FingerContactRegions(Human(), kin, HumanGroupsForSdh(), bottle, g.world_from_object, o);
  ASSERT_EQ(r.size(), 3u);
  int total = 0;
  for (const CellSet& s : r) total += static_cast<int>(s.size());
  EXPECT_GT(total, 3);                 // the power grasp touches the bottle with several fingers
  for (const SurfaceCell& c : r[2]) {  // cells near the bottle surface (radius 32.5 mm)
    const Eigen::Vector3d p =
        (Eigen::Vector3d(c[0], c[1], c[2]) + Eigen::Vector3d::Constant(0.5)) * o.cell;
    EXPECT_NEAR(std::hypot(p.x(), p.y()), 0.0325, 0.02);
  }
  Eigen::Isometry3d far = g.world_from_object;
  far.translation() += Eigen::Vector3d(1, 0, 0);
  for (const CellSet& s : FingerContactRegions(Human(), kin, HumanGroupsForSdh(), bottle, far, o)) {
    EXPECT_TRUE(s.empty());
  }
  o.cell = 0;
  EXPECT_THROW(FingerContactRegions(Human(), kin, SdhGroups(), bottle, far, o),
               std::invalid_argument);
}

Eigen::Matrix3Xd Circle(double radius, int n) {  // unit circle in the xy plane, closed
  Eigen::Matrix3Xd loop(3, n + 1);
  for (int i = 0; i <= n; ++i) {
    const double a = 2 * M_PI * i / n;
    loop.col(i) = Eigen::Vector3d(radius * std::cos(a), radius * std::sin(a), 0);
  }
  return loop;
}

TEST(ThreadingTest, ChainThroughAndBesideALoop) {
  const Eigen::Matrix3Xd loop = Circle(0.02, 24);
  Eigen::Matrix3Xd through(3, 3), beside(3, 3), hook(3, 3);
  through << 0, 0, 0.005, 0, 0, 0, -0.03, 0.01, 0.03;     // down the z axis through the hole
  beside << 0.05, 0.05, 0.05, 0, 0, 0, -0.03, 0.0, 0.03;  // outside the ring
  // Into the hole and curled back over the rim without crossing the plane again.
  hook << 0, 0.01, 0.03, 0, 0, 0, 0.03, -0.01, -0.01;
  EXPECT_TRUE(ChainThreadsLoop(through, loop));
  EXPECT_FALSE(ChainThreadsLoop(beside, loop));
  EXPECT_TRUE(ChainThreadsLoop(hook, loop));
  EXPECT_THROW(ChainThreadsLoop(through, loop.leftCols(3)), std::invalid_argument);
  const std::vector<bool> demo = HumanThreadingForSdh({false, true, false, false, true});
  EXPECT_EQ(demo, (std::vector<bool>{false, true, true}));
  const ThreadPreservation t = CompareThreading(demo, {true, false, true});
  EXPECT_EQ(t.demo, 2);
  EXPECT_EQ(t.preserved, 1);
  EXPECT_FALSE(t.all());
}

// Equal baselines: one winding target rule for every object (the main reference only), and the
// human-palm placement reads no object data (moving the object leaves it unchanged).
TEST(StudyRulesTest, OneTargetRuleAndObjectFreePlacement) {
  const std::vector<GraspObject> objects = LoadGraspObjects(kAssets + "grasps/objects.json");
  const Robot sdh = LoadRobot(kAssets + "robots/lwr4_sdh.urdf");
  const HumanGrasp pinch = LoadHumanGrasp(kAssets + "grasps/lateral_pinch_box.json");
  const TransferSetup s =
      MakeTransferSetup(Human(), sdh, FindGraspObject(objects, pinch.object), pinch);
  EXPECT_EQ(WindingTarget(s).size(), 2);        // grasp transfer: the plate's rim curve only
  EXPECT_EQ(WindingTarget(s, true).size(), 3);  // the study: M · w about the main reference
  HumanGrasp moved = pinch;
  moved.world_from_object.translation() += Eigen::Vector3d(0.01, -0.02, 0.03);
  const GraspObject& box = FindGraspObject(objects, pinch.object);
  const TransferSetup a = MakeTransferSetup(Human(), sdh, box, pinch, PlacementRule::kHumanPalm);
  const TransferSetup b = MakeTransferSetup(Human(), sdh, box, moved, PlacementRule::kHumanPalm);
  EXPECT_TRUE(a.sdh_placement.isApprox(b.sdh_placement, 1e-12));
  const TransferSetup c = MakeTransferSetup(Human(), sdh, box, moved);
  EXPECT_FALSE(s.sdh_placement.isApprox(c.sdh_placement, 1e-6));  // object_centre reads it
}

// The study's threading grasps (assets/grasps/study/, scripts/make_grasp_objects.py, and the mug
// hook of assets/grasps/): each loads, fits the joint limits, does not penetrate its object by more
// than 3 mm and threads its hole with the index finger in the nominal demonstration.
TEST(StudyObjectsTest, ThreadingGraspsThreadTheirHoles) {
  const std::vector<GraspObject> objects = LoadGraspObjects(kAssets + "grasps/objects.json");
  const Robot sdh = LoadRobot(kAssets + "robots/lwr4_sdh.urdf");
  std::vector<std::string> paths = {kAssets + "grasps/hook_mug_handle.json"};
  for (const auto& e : std::filesystem::directory_iterator(kAssets + "grasps/study")) {
    if (e.path().extension() == ".json") paths.push_back(e.path().string());
  }
  for (const std::string& path : paths) {
    const HumanGrasp g = LoadHumanGrasp(path);
    const GraspObject& object = FindGraspObject(objects, g.object);
    ASSERT_EQ(object.reference.kind, ReferenceCurve::Kind::kLoop) << g.name;
    const TransferSetup s = MakeTransferSetup(Human(), sdh, object, g);
    KinematicsData kin(s.human);
    ForwardKinematics(s.human, s.human_q, &kin);
    EXPECT_GT(HandClearance(s.human, kin, SampleHandSpheres(s.human, {}, 0.002), object,
                            g.world_from_object),
              -0.003)
        << g.name;
    const std::vector<bool> t = FingersThreading(s.human, kin, s.human_chains, s.reference.loop);
    EXPECT_TRUE(t[1]) << g.name << ": the index finger threads the hole";
  }
  EXPECT_GE(paths.size(), 7u);  // mug, key ring, bangle, thick torus, carabiner, shackle, bar
}

}  // namespace
}  // namespace planning
