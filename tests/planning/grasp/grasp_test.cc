// Human grasp files, object signed distances, winding encoding and SDH transfer.
#include "planning/grasp/grasp.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include "planning/grasp/grasp_object.h"
#include "planning/grasp/grasp_transfer.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/robot_io.h"

namespace planning {
namespace {

const std::string kAssets = std::string(TOPOPLAN_SOURCE_DIR) + "/assets/";

const std::vector<GraspObject>& Objects() {
  static const std::vector<GraspObject> objects = LoadGraspObjects(kAssets + "grasps/objects.json");
  return objects;
}
const Robot& Human() {
  static const Robot robot = LoadRobot(kAssets + "robots/human_hand.urdf");
  return robot;
}
const Robot& LwrSdh() {
  static const Robot robot = LoadRobot(kAssets + "robots/lwr4_sdh.urdf");
  return robot;
}

std::vector<std::string> GraspFiles() {
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(kAssets + "grasps")) {
    if (e.path().extension() == ".json" && e.path().filename() != "objects.json") {
      files.push_back(e.path().string());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(GraspObjectTest, SignedDistancesOfPrimitivesHaveKnownValues) {
  GraspObject o;
  GraspPrimitive p;
  p.kind = GraspPrimitive::Kind::kCylinder;
  p.size = Eigen::Vector3d(0.03, 0.2, 0);
  o.primitives = {p};
  Eigen::Vector3d g;
  EXPECT_NEAR(SignedDistance(o, Eigen::Vector3d(0.05, 0, 0.0), &g), 0.02, 1e-12);
  EXPECT_NEAR(g.x(), 1.0, 1e-6);
  EXPECT_NEAR(SignedDistance(o, Eigen::Vector3d(0.0, 0, 0.0)), -0.03, 1e-12);
  EXPECT_NEAR(SignedDistance(o, Eigen::Vector3d(0.0, 0, 0.13)), 0.03, 1e-12);
  p.kind = GraspPrimitive::Kind::kTorus;
  p.size = Eigen::Vector3d(0.045, 0.012, M_PI);
  o.primitives = {p};
  EXPECT_NEAR(SignedDistance(o, Eigen::Vector3d(0, 0, 0)), 0.033, 1e-12);       // hole centre
  EXPECT_NEAR(SignedDistance(o, Eigen::Vector3d(0, 0.045, 0)), -0.012, 1e-12);  // core
  p.kind = GraspPrimitive::Kind::kBox;
  p.size = Eigen::Vector3d(0.02, 0.04, 0.06);
  p.object_from_primitive.translation() = Eigen::Vector3d(1, 0, 0);
  o.primitives = {p};
  EXPECT_NEAR(SignedDistance(o, Eigen::Vector3d(1.03, 0, 0)), 0.02, 1e-12);
}

TEST(GraspObjectTest, CatalogueLoadsAndBadFilesNameThePath) {
  EXPECT_GE(Objects().size(), 8u);
  EXPECT_NO_THROW(FindGraspObject(Objects(), "bottle"));
  EXPECT_THROW(FindGraspObject(Objects(), "teapot"), std::invalid_argument);
  const std::string bad = std::string(TOPOPLAN_BINARY_DIR) + "/bad_objects.json";
  auto expect_error = [&](const std::string& text, const std::string& where) {
    std::ofstream(bad) << text;
    try {
      LoadGraspObjects(bad);
      FAIL() << where;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("bad_objects.json: " + where), std::string::npos)
          << e.what();
    }
  };
  expect_error(R"({"objects": [{"name": "x", "mass": 1, "primitives": [{"type": "cone",
                  "size": [1, 1, 1]}], "reference": {"type": "axis"}}]})",
               "objects[0].primitives[0].type");
  expect_error(R"({"objects": [{"name": "x", "mass": 1, "primitives": [{"type": "sphere",
                  "size": [1, 0, 0]}], "reference": {"type": "axis", "point": [0, 0, 0],
                  "direction": [0, 0, 1]}, "extra_references": [{"type": "loop",
                  "points": [[0, 0, 0]]}]}]})",
               "objects[0].extra_references[0].points");
  expect_error(R"({"objects": [{"name": "x", "mass": 1, "primitives": [{"type": "sphere",
                  "size": [1, 0, 0]}], "reference": {"type": "axis", "point": [0, 0, 0],
                  "direction": [0, 0, 1]}, "main_reference_in_target": false}]})",
               "objects[0].main_reference_in_target: false needs extra_references");
  EXPECT_FALSE(FindGraspObject(Objects(), "flat_box").main_reference_in_target);
  EXPECT_TRUE(FindGraspObject(Objects(), "bottle").main_reference_in_target);
}

TEST(HumanGraspTest, AtLeastEightPlausibleGraspsWithFingersOnTheSurface) {
  const std::vector<std::string> files = GraspFiles();
  ASSERT_GE(files.size(), 8u);
  const HandSpheres spheres = SampleHandSpheres(Human(), {}, 0.002);
  KinematicsData kin(Human());
  for (const std::string& f : files) {
    const HumanGrasp g = LoadHumanGrasp(f);
    const GraspObject& object = FindGraspObject(Objects(), g.object);
    ForwardKinematics(Human(), HumanConfiguration(Human(), g), &kin);
    std::vector<double> per_link;
    const double clearance =
        HandClearance(Human(), kin, spheres, object, g.world_from_object, &per_link);
    EXPECT_GE(clearance, -0.003) << f << ": penetration beyond 3 mm";
    int touching = 0;
    for (double d : per_link) touching += std::abs(d) <= 0.002 ? 1 : 0;
    EXPECT_GE(touching, 3) << f << ": fewer than 3 hand links on the object surface";
  }
}

TEST(HumanGraspTest, PowerGraspWindsClearlyAroundTheBottleAxis) {
  Robot human = Human();
  const std::vector<int> chains = AddGraspChains(true, &human);
  const HumanGrasp g = LoadHumanGrasp(kAssets + "grasps/power_bottle.json");
  const GraspObject& bottle = FindGraspObject(Objects(), "bottle");
  KinematicsData kin(human);
  ForwardKinematics(human, HumanConfiguration(human, g), &kin);
  const GraspEncoding enc =
      EncodeGrasp(human, kin, chains, TransformReference(bottle.reference, g.world_from_object));
  ASSERT_EQ(enc.finger.size(), 5);
  EXPECT_LT(enc.finger[0], -0.2);  // the thumb wraps the other way round
  for (int f = 1; f < 5; ++f) EXPECT_GT(enc.finger[f], 0.3) << HumanFingers()[f];
  // Per phalanx: the segments sum to the finger value.
  for (int f = 0; f < 5; ++f) EXPECT_NEAR(enc.phalanx[f].sum(), enc.finger[f], 1e-12);
}

TEST(HumanGraspTest, MalformedGraspFilesNameThePath) {
  const std::string dir = std::string(TOPOPLAN_BINARY_DIR) + "/";
  std::ofstream(dir + "bad_grasp.json") << "{\"name\": \"x\", \"object\": \"bottle\"";
  EXPECT_THROW(LoadHumanGrasp(dir + "bad_grasp.json"), std::invalid_argument);
  std::ofstream(dir + "bad_joint.json")
      << R"({"name": "x", "object": "bottle", "object_pose": {"xyz": [0,0,0], "rpy": [0,0,0]},
             "palm_pose": {"xyz": [0,0,0], "rpy": [0,0,0]}, "joints": {"index_pip": 7.0}})";
  const HumanGrasp g = LoadHumanGrasp(dir + "bad_joint.json");
  try {
    HumanConfiguration(Human(), g);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("bad_joint.json: joints.index_pip"), std::string::npos)
        << e.what();
  }
}

TEST(GraspTransferTest, FloatingSdhReproducesTheArmMountedHandKinematics) {
  const Eigen::Matrix3d nominal =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Robot sdh = MakeFloatingHand(LwrSdh(), "sdh_palm", nominal);
  EXPECT_EQ(num_dofs(sdh), 13);  // 6 floating + 7 SDH (the coupled spread is one variable)
  Eigen::VectorXd q = Eigen::VectorXd::Zero(13);
  q.head<3>() = Eigen::Vector3d(0.1, -0.2, 0.3);
  for (int k = 6; k < 13; ++k) q[k] = 0.1 * (k - 5);
  KinematicsData kin(sdh);
  ForwardKinematics(sdh, q, &kin);
  const Eigen::Isometry3d palm = kin.world_from_link[FindLink(sdh, "sdh_palm")];
  EXPECT_TRUE(palm.linear().isApprox(nominal, 1e-12));
  EXPECT_TRUE(palm.translation().isApprox(Eigen::Vector3d(0.1, -0.2, 0.3), 1e-12));
  // Same finger configuration on the arm: tips agree relative to the palm.
  Eigen::VectorXd qa = Eigen::VectorXd::Zero(num_dofs(LwrSdh()));
  qa.tail<7>() = q.tail<7>();
  KinematicsData ka(LwrSdh());
  ForwardKinematics(LwrSdh(), qa, &ka);
  for (const char* tip : {"sdh_thumb_tip", "sdh_finger_1_tip", "sdh_finger_2_tip"}) {
    const Eigen::Vector3d a = ka.world_from_link[FindLink(LwrSdh(), "sdh_palm")].inverse() *
                              ka.world_from_link[FindLink(LwrSdh(), tip)].translation();
    const Eigen::Vector3d b =
        palm.inverse() * kin.world_from_link[FindLink(sdh, tip)].translation();
    EXPECT_TRUE(a.isApprox(b, 1e-9)) << tip;
  }
}

// A floating SDH with its grasp chains at a generic configuration, and a check of an encoding's
// Jacobian ∂y/∂q against central differences over all 13 dofs.
struct SdhAtGenericPose {
  Robot sdh = MakeFloatingHand(LwrSdh(), "sdh_palm", Eigen::Matrix3d::Identity());
  std::vector<int> chains = AddGraspChains(false, &sdh);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(13);
  SdhAtGenericPose() {
    q.segment<3>(3) = Eigen::Vector3d(0.05, -0.04, 0.03);
    q.tail<7>() << 0.3, 0.4, 0.7, 0.5, 0.6, 0.8, 0.9;
  }
  // encode(kin, J): the encoding at kin, its Jacobian into J when J is not null.
  void ExpectJacobian(
      const std::function<Eigen::VectorXd(const KinematicsData&, Eigen::MatrixXd*)>& encode) {
    KinematicsData kin(sdh);
    ForwardKinematics(sdh, q, &kin);
    Eigen::MatrixXd J;
    encode(kin, &J);
    const double h = 1e-6;
    for (int k = 0; k < 13; ++k) {
      Eigen::VectorXd qp = q, qm = q;
      qp[k] += h;
      qm[k] -= h;
      ForwardKinematics(sdh, qp, &kin);
      const Eigen::VectorXd yp = encode(kin, nullptr);
      ForwardKinematics(sdh, qm, &kin);
      const Eigen::VectorXd ym = encode(kin, nullptr);
      EXPECT_LT(((yp - ym) / (2 * h) - J.col(k)).cwiseAbs().maxCoeff(), 1e-5) << "dof " << k;
    }
  }
};

ReferenceCurve TiltedAxis() {
  ReferenceCurve ref;
  ref.axis.point = Eigen::Vector3d(0.0, 0.0, 0.15);
  ref.axis.direction = Eigen::Vector3d(0.1, 1.0, 0.05);
  return ref;
}

TEST(GraspTransferTest, WindingJacobianMatchesFiniteDifferences) {
  SdhAtGenericPose s;
  const ReferenceCurve ref = TiltedAxis();
  s.ExpectJacobian([&](const KinematicsData& kin, Eigen::MatrixXd* J) {
    return EncodeGrasp(s.sdh, kin, s.chains, ref, J).finger;
  });
}

// The opposition pair about a plate's rim loop (the extra-curve part of the winding target term):
// the max and min finger values, Jacobian rows of those fingers, matching central differences.
TEST(GraspTransferTest, OppositionPairJacobianMatchesFiniteDifferences) {
  SdhAtGenericPose s;
  ReferenceCurve rim;  // a 60 x 80 mm rectangle in front of the palm
  rim.kind = ReferenceCurve::Kind::kLoop;
  rim.loop.resize(3, 5);
  rim.loop << 0.01, 0.01, 0.01, 0.01, 0.01,  //
      -0.03, 0.03, 0.03, -0.03, -0.03,       //
      0.12, 0.12, 0.20, 0.20, 0.12;
  KinematicsData kin(s.sdh);
  ForwardKinematics(s.sdh, s.q, &kin);
  const Eigen::VectorXd w = EncodeGrasp(s.sdh, kin, s.chains, rim).finger;
  const Eigen::Vector2d o = OppositionPair(w);
  EXPECT_EQ(o[0], w.maxCoeff());
  EXPECT_EQ(o[1], w.minCoeff());
  EXPECT_GT(o[0] - o[1], 0.01) << w.transpose();  // the rim sees the fingers
  s.ExpectJacobian([&](const KinematicsData& k, Eigen::MatrixXd* jac) {
    Eigen::MatrixXd jf;
    const Eigen::VectorXd wf = EncodeGrasp(s.sdh, k, s.chains, rim, jac ? &jf : nullptr).finger;
    return Eigen::VectorXd(OppositionPair(wf, jac ? &jf : nullptr, jac));
  });
  EXPECT_THROW(OppositionPair(Eigen::VectorXd()), std::invalid_argument);
  const Eigen::MatrixXd wrong(2, 13);
  Eigen::MatrixXd out;
  EXPECT_THROW(OppositionPair(w, &wrong, &out), std::invalid_argument);
}

// The lateral pinch: the box's rim sees on which face each fingertip lies (thumb and index on
// opposite faces: opposite signs), where the edge axis sees little; the box leaves the edge axis
// out of the winding term (main_reference_in_target false), whose target is the opposition pair
// about the rim, and the SDH reaches it.
TEST(GraspTransferTest, PlateRimSeesTheLateralPinch) {
  const HumanGrasp g = LoadHumanGrasp(kAssets + "grasps/lateral_pinch_box.json");
  const GraspObject& box = FindGraspObject(Objects(), "flat_box");
  ASSERT_EQ(box.extra_references.size(), 1u);
  const TransferSetup setup = MakeTransferSetup(Human(), LwrSdh(), box, g);
  ASSERT_EQ(setup.extra_references.size(), 1u);
  // About the edge axis the human fingers barely wind (why it is no target).
  KinematicsData hkin(setup.human);
  ForwardKinematics(setup.human, setup.human_q, &hkin);
  const Eigen::VectorXd edge =
      FingerCorrespondence() *
      EncodeGrasp(setup.human, hkin, setup.human_chains, setup.reference).finger;
  EXPECT_LT(edge.cwiseAbs().maxCoeff(), 0.2) << edge.transpose();
  const Eigen::VectorXd target = WindingTarget(setup);
  ASSERT_EQ(target.size(), 2);                       // the opposition pair about the rim
  EXPECT_GT(target[0], 0.2) << target.transpose();   // a finger on one face ...
  EXPECT_LT(target[1], -0.3) << target.transpose();  // ... the thumb on the other
  const MotionProblem p = MakeTransferProblem(setup, TransferMethod::kWinding);
  for (const Task& t : p.tasks) {
    if (t.name == "winding") {
      EXPECT_EQ(t.feature->dim(), 2);
    }
  }
  // The transferred SDH holds the plate between two fingers on opposite faces.
  const TransferResult r = TransferGrasp(setup, TransferMethod::kWinding);
  ASSERT_EQ(r.target_extra_winding.size(), 2);
  ASSERT_EQ(r.robot_extra_winding.size(), 2);
  EXPECT_EQ(r.target_extra_winding, target.tail(2));
  EXPECT_GT(r.robot_extra_winding[0], 0.15) << r.robot_extra_winding.transpose();
  EXPECT_LT(r.robot_extra_winding[1], -0.15) << r.robot_extra_winding.transpose();
}

// The whole winding term of the transfer problem (the feature AICO uses), with the main
// reference's rows (mug: its handle loop, and no extra curve) and without them (plate: only the
// opposition pair about the rim): Jacobian against central differences.
TEST(GraspTransferTest, WindingTermJacobianMatchesFiniteDifferences) {
  for (const std::string name : {"lateral_pinch_box", "hook_mug_handle"}) {
    const HumanGrasp g = LoadHumanGrasp(kAssets + "grasps/" + name + ".json");
    const TransferSetup setup =
        MakeTransferSetup(Human(), LwrSdh(), FindGraspObject(Objects(), g.object), g);
    const MotionProblem p = MakeTransferProblem(setup, TransferMethod::kWinding);
    const Task* term = nullptr;
    for (const Task& t : p.tasks) term = t.name == "winding" ? &t : term;
    ASSERT_NE(term, nullptr) << name;
    const Robot& robot = *p.robot;
    const int dim = term->feature->dim();
    EXPECT_EQ(dim, setup.object.main_reference_in_target ? 3 : 2) << name;
    const std::unique_ptr<FeatureData> data = term->feature->CreateData(robot);
    KinematicsData kin(robot);
    const auto eval = [&](const Eigen::VectorXd& x, Eigen::MatrixXd* J) {
      ForwardKinematics(robot, x, &kin);
      Eigen::VectorXd y(dim);
      term->feature->Eval(robot, kin, data.get(), y, J);
      return y;
    };
    Eigen::VectorXd q = p.q0;
    q.tail<7>() << 0.3, 0.4, 0.7, 0.5, 0.6, 0.8, 0.9;  // fingers part-way closed
    Eigen::MatrixXd J(dim, q.size());
    eval(q, &J);
    const double h = 1e-6;
    for (int k = 0; k < q.size(); ++k) {
      Eigen::VectorXd qp = q, qm = q;
      qp[k] += h;
      qm[k] -= h;
      const Eigen::VectorXd fd = (eval(qp, nullptr) - eval(qm, nullptr)) / (2 * h);
      EXPECT_LT((fd - J.col(k)).cwiseAbs().maxCoeff(), 1e-5) << name << " dof " << k;
    }
  }
}

TEST(GraspTransferTest, PowerGraspTransfersToTheSdhWithMatchingWindings) {
  const HumanGrasp g = LoadHumanGrasp(kAssets + "grasps/power_bottle.json");
  const TransferSetup setup =
      MakeTransferSetup(Human(), LwrSdh(), FindGraspObject(Objects(), "bottle"), g);
  const TransferResult r = TransferGrasp(setup, TransferMethod::kWinding);
  ASSERT_EQ(r.robot_winding.size(), 3);
  EXPECT_LT(r.target_winding[0], -0.2);
  EXPECT_GT(r.target_winding[1], 0.3);
  EXPECT_GT(r.target_winding[2], 0.3);
  EXPECT_LT((r.robot_winding - r.target_winding).cwiseAbs().maxCoeff(), 0.1)
      << "robot " << r.robot_winding.transpose() << " target " << r.target_winding.transpose();
  EXPECT_GE(r.min_clearance, -0.003);
  // Identical inputs, identical numbers.
  const TransferResult again = TransferGrasp(setup, TransferMethod::kWinding);
  EXPECT_EQ((again.q - r.q).cwiseAbs().maxCoeff(), 0.0);
  // Baseline: linear joint mapping keeps the human angles and ignores the object.
  const TransferResult joint = TransferGrasp(setup, TransferMethod::kJointMapping);
  EXPECT_EQ(joint.solver, "aico");
  // The non-penetration projection moves the mapped posture out of the object.
  EXPECT_GE(joint.min_clearance, -0.003);
  EXPECT_GT((joint.robot_winding - joint.target_winding).norm(),
            (r.robot_winding - r.target_winding).norm());
}

// Fairness: every SDH method's problem is SharedTransferTasks plus its own target term; the
// shared terms (names, targets, precisions per slice) are identical across methods.
TEST(GraspTransferTest, MethodsDifferOnlyInTheirTargetTerm) {
  const HumanGrasp g = LoadHumanGrasp(kAssets + "grasps/power_bottle.json");
  const TransferSetup setup =
      MakeTransferSetup(Human(), LwrSdh(), FindGraspObject(Objects(), "bottle"), g);
  const TransferOptions o;
  const std::vector<std::string> base = {"clearance", "joint_limits", "palm"};
  struct Expected {
    TransferMethod method;
    std::vector<std::string> target;
    bool contact;
  };
  const std::vector<Expected> expected = {
      {TransferMethod::kWinding, {"winding"}, true},
      {TransferMethod::kWindingOnly, {"winding"}, false},
      {TransferMethod::kContactOnly, {}, true},
      {TransferMethod::kFingertip, {"tip_sdh_thumb", "tip_sdh_finger_1", "tip_sdh_finger_2"}, true},
      {TransferMethod::kJointMapping, {}, false},
  };
  const MotionProblem reference = MakeTransferProblem(setup, TransferMethod::kWinding, o);
  auto same_task = [](const Task& a, const Task& b) {
    return a.name == b.name && a.precision == b.precision && a.target == b.target &&
           a.feature->dim() == b.feature->dim() && a.feature->name() == b.feature->name();
  };
  const Task& ref_contact = reference.tasks.back();
  ASSERT_EQ(ref_contact.name, "contact");
  for (const Expected& e : expected) {
    SCOPED_TRACE(ToString(e.method));
    const MotionProblem p = MakeTransferProblem(setup, e.method, o);
    std::vector<std::string> names;
    for (const Task& t : p.tasks) names.push_back(t.name);
    std::vector<std::string> want = base;
    want.insert(want.end(), e.target.begin(), e.target.end());
    if (e.contact) want.push_back("contact");
    EXPECT_EQ(names, want);
    ASSERT_EQ(p.tasks.size(), want.size());
    for (size_t k = 0; k < base.size(); ++k) {
      EXPECT_TRUE(same_task(p.tasks[k], reference.tasks[k])) << base[k];
    }
    if (e.contact) {
      EXPECT_TRUE(same_task(p.tasks.back(), ref_contact));
    }
    // Target terms act at the final slice only, with the method's precision.
    for (size_t k = base.size(); k < base.size() + e.target.size(); ++k) {
      const Task& t = p.tasks[k];
      const double rho = t.name == "winding" ? o.winding_precision : o.tip_precision;
      EXPECT_EQ(t.precision[o.num_steps], rho) << t.name;
      EXPECT_EQ(t.precision.head(o.num_steps).cwiseAbs().maxCoeff(), 0.0) << t.name;
    }
    EXPECT_EQ(p.num_steps, o.num_steps);
    EXPECT_EQ(p.metric, reference.metric);
  }
  // The joint method starts from the mapped posture at the placement, the others retracted.
  const Eigen::VectorXd place = PlacementConfiguration(setup);
  const MotionProblem joint = MakeTransferProblem(setup, TransferMethod::kJointMapping, o);
  EXPECT_EQ((joint.q0.head<6>() - place.head<6>()).norm(), 0.0);
  EXPECT_NEAR((reference.q0.head<3>() - place.head<3>()).norm(), o.retreat, 1e-12);
  EXPECT_THROW(MakeTransferProblem(setup, TransferMethod::kHuman, o), std::invalid_argument);
  EXPECT_THROW(TransferGrasp(setup, TransferMethod::kHuman, o), std::invalid_argument);
  EXPECT_EQ(AllTransferMethods().size(), 6u);
}

TEST(GraspTransferTest, CorrespondenceAveragesFingerPairs) {
  Eigen::VectorXd h(5);
  h << -0.3, 0.4, 0.6, 0.2, 0.0;
  const Eigen::Vector3d t = FingerCorrespondence() * h;
  EXPECT_DOUBLE_EQ(t[0], -0.3);
  EXPECT_DOUBLE_EQ(t[1], 0.1);
  EXPECT_DOUBLE_EQ(t[2], 0.5);
  EXPECT_EQ(ParseTransferMethod("fingertip"), TransferMethod::kFingertip);
  try {
    ParseTransferMethod("magic");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "unknown transfer method 'magic' (winding, winding_only, contact_only, "
                 "fingertip, joint, human)");
  }
  for (const auto& e : kTransferMethodNames) {
    EXPECT_EQ(ParseTransferMethod(ToString(e.value)), e.value);
  }
}

}  // namespace
}  // namespace planning
