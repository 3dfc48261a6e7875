#include "tests/planning/features/feature_factory.h"

#include <Eigen/Geometry>

#include "planning/robot/robot_io.h"

namespace planning::testing {

const FeatureFixture& SharedFixture() {
  static const FeatureFixture* fixture = [] {
    auto* f = new FeatureFixture;
    const std::string root = TOPOPLAN_SOURCE_DIR "/assets/";
    f->robot = LoadRobot(root + "robots/lwr4_sdh.urdf");
    Eigen::Isometry3d ring = Eigen::Isometry3d::Identity();
    ring.translation() = Eigen::Vector3d(0.5, 0.0, 1.35);
    ring.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
    AddObject(LoadRobot(root + "objects/ring.urdf"), ring, "ring", &f->env);
    Eigen::Isometry3d ball = Eigen::Isometry3d::Identity();
    ball.translation() = Eigen::Vector3d(0.35, 0.25, 0.9);
    AddObject(LoadRobot(root + "objects/ball.urdf"), ball, "ball", &f->env);
    AddObject(LoadRobot(root + "objects/ball.urdf"), ball, "ball", &f->primitive_env);
    Eigen::Isometry3d box = Eigen::Isometry3d::Identity();
    box.translation() = Eigen::Vector3d(-0.4, -0.3, 0.6);
    AddObject(LoadRobot(root + "objects/box.urdf"), box, "box", &f->primitive_env);
    return f;
  }();
  return *fixture;
}

std::vector<FeatureCase> AllFeatureCases(const FeatureFixture& f) {
  const Robot& r = f.robot;
  const int palm = FindLink(r, "sdh_palm");
  const int arm = FindChain(r, "arm");
  const int finger = FindChain(r, "sdh_finger_1");
  const Eigen::Matrix3Xd ring = ObjectChainPoints(f.env, FindObject(f.env, "ring"), 0);
  topology::Axis axis;
  axis.point = Eigen::Vector3d(0.3, 0.1, 0.0);
  axis.direction = Eigen::Vector3d(0.1, 0.2, 1.0);
  std::vector<FeatureCase> cases;
  cases.push_back({"position", MakePositionFeature(r, palm, Eigen::Vector3d(0.01, 0.02, 0.1))});
  cases.push_back({"axis_alignment", MakeAxisAlignmentFeature(r, palm, Eigen::Vector3d(0, 0, 1),
                                                              Eigen::Vector3d(1, 0.2, -0.3))});
  cases.push_back({"joint_limits", MakeJointLimitFeature(r, 0.9)});
  cases.push_back({"joint_position", MakeJointPositionFeature(r)});
  cases.push_back(
      {"box", MakeBoxFeature(r, palm, Eigen::Vector3d(0, 0, 0.1), Eigen::Vector3d(0.3, 0.0, 1.0),
                             Eigen::Vector3d(0.2, 0.15, 0.1), 0.02)});
  cases.push_back({"writhe_matrix", MakeWritheFeature(r, arm, ring, WritheOutput::kMatrix)});
  cases.push_back({"writhe_total", MakeWritheFeature(r, finger, ring, WritheOutput::kTotal)});
  cases.push_back({"winding", MakeWindingFeature(r, arm, axis)});
  cases.push_back({"line_clearance", MakeLineClearanceFeature(r, arm, axis, 2.0)});
  CollisionOptions options;
  // Hand self-contacts penetrate at random q (contact depth is not smooth), and FCL's witness
  // points of mesh-vs-primitive distances come back in swapped order: check primitives only.
  options.self_collision = false;
  cases.push_back({"collision", MakeCollisionFeature(r, f.primitive_env, options, 1.0)});
  // Appended last: a case's random configurations are seeded by its index.
  cases.push_back({"writhe_matrix_chord", MakeWritheFeature(r, arm, ring, WritheOutput::kMatrix,
                                                            /*closed_by_chord=*/true)});
  cases.push_back({"writhe_total_chord", MakeWritheFeature(r, arm, ring, WritheOutput::kTotal,
                                                           /*closed_by_chord=*/true)});
  return cases;
}

int NumFeatureCases() { return static_cast<int>(AllFeatureCases(SharedFixture()).size()); }

}  // namespace planning::testing
