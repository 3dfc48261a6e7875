// Targets and objects placed in another object's frame (scenario_spec.h "Frames"), and the unwrap
// geometries applied to the shipped unwrap scenario (unwrap_geometry.h): moving or tilting the
// pole moves the reach target with it; unknown frames are errors naming the key, and so are
// geometry names that would break geometry.csv and disabled-group prefixes that match no link.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "planning/motion/internal/start_coil.h"
#include "planning/motion/scenario.h"
#include "planning/motion/scenario_spec.h"
#include "planning/motion/success.h"
#include "planning/motion/unwrap_geometry.h"
#include "planning/robot/pose.h"
#include "scenario_test_util.h"

namespace planning {
namespace {

const std::string kAssets = TOPOPLAN_SOURCE_DIR "/assets/";
const std::string kUnwrap = kAssets + "scenarios/unwrap.json";

std::string WriteTemp(const std::string& name, const std::string& text) {
  return WriteTestFile("scenario_frames_test_tmp", name, text);
}

// A small scenario (LWR4 + SDH, zero start, T = 5) with a pole and `extra` objects, and a reach
// task whose target is `target`.
std::string MiniScenario(const std::string& target, const std::string& extra = "") {
  return R"({"robot": ")" + kAssets + R"(robots/lwr4_sdh.urdf",
    "objects": [{"name": "pole", "urdf": ")" +
         kAssets + R"(objects/pole.urdf", "xyz": [0.6, 0.1, 0.5], "rpy": [0.3, -0.2, 0.7]})" +
         extra + R"(],
    "start": {"q": "zero"}, "problem": {"T": 5},
    "tasks": [{"name": "reach", "feature": {"type": "position", "link": "sdh_grasp_link"},
               "target": )" +
         target + R"(, "precision": 1}]})";
}

size_t Index(const ScenarioSpec& spec, const std::string& name) {
  for (size_t i = 0; i < spec.objects.size(); ++i) {
    if (spec.objects[i].name == name) return i;
  }
  ADD_FAILURE() << "no object " << name;
  return 0;
}

const TaskSpec& TaskOf(const ScenarioSpec& spec, const std::string& name) {
  for (const TaskSpec& t : spec.tasks) {
    if (t.name == name) return t;
  }
  throw std::invalid_argument("no task " + name);
}

// The shipped unwrap scenario's reach target resolves to the absolute point it had before it was
// placed in the cylinder's frame (itself in the pole's): bit for bit, so the shipped results stay.
// RotationFromZ(d): a rotation (orthonormal, det +1) taking +z to d/|d|, the identity for d along
// +z, and a half turn for d along -z; the length of d does not matter. Tolerance 1e-9: close to -z
// Eigen's quaternion formula loses digits as 1/(1 + cos): 5e-11 at 2.2 mrad from -z.
TEST(Pose, RotationFromZTakesZToTheDirection) {
  const Eigen::Vector3d dirs[] = {{0, 0, 1},        {0, 0, -2},          {3, 0, 0},
                                  {0.2, -0.5, 0.1}, {-1e-3, 2e-3, -1.0}, {1, 1, 1}};
  for (const Eigen::Vector3d& d : dirs) {
    const Eigen::Matrix3d R = RotationFromZ(d);
    EXPECT_TRUE((R.transpose() * R).isIdentity(1e-9)) << d.transpose();
    EXPECT_NEAR(R.determinant(), 1.0, 1e-9) << d.transpose();
    EXPECT_TRUE((R * Eigen::Vector3d::UnitZ()).isApprox(d.normalized(), 1e-9)) << d.transpose();
  }
  EXPECT_TRUE(RotationFromZ(Eigen::Vector3d(0, 0, 5)).isIdentity(1e-15));
  EXPECT_NEAR(Eigen::AngleAxisd(RotationFromZ(Eigen::Vector3d(0, 0, -1))).angle(), M_PI, 1e-12);
}

TEST(ScenarioFrames, ShippedUnwrapTargetIsTheCylinderInThePoleFrame) {
  ScenarioSpec spec = ParseScenarioSpec(kUnwrap);
  ASSERT_TRUE(TaskOf(spec, "reach").target.frame.has_value());
  EXPECT_EQ(TaskOf(spec, "reach").target.frame->name, "cylinder");
  ASSERT_TRUE(spec.objects[Index(spec, "cylinder")].frame.has_value());
  ResolveSpecFrames(&spec);
  EXPECT_FALSE(TaskOf(spec, "reach").target.frame.has_value());
  EXPECT_EQ(TaskOf(spec, "reach").target.value, Eigen::Vector3d(0.4, -2.4, 2.6));
  const ObjectSpec& cyl = spec.objects[Index(spec, "cylinder")];
  EXPECT_FALSE(cyl.frame.has_value());
  EXPECT_EQ(cyl.xyz, Eigen::Vector3d(0.4, -2.4, 2.6));
  EXPECT_TRUE(PoseFromXyzRpy(cyl.xyz, cyl.rpy).linear().isIdentity(1e-12));
  // A second resolution changes nothing.
  const ScenarioSpec once = spec;
  ResolveSpecFrames(&spec);
  EXPECT_EQ(TaskOf(spec, "reach").target.value, TaskOf(once, "reach").target.value);
  EXPECT_EQ(spec.objects[Index(spec, "cylinder")].xyz, once.objects[Index(once, "cylinder")].xyz);
}

// Moving and tilting the pole (as --pole-offset and the geometries do, in the parsed spec) moves
// the reach target rigidly with it: the target's coordinates in the new pole frame are those in
// the old one.
TEST(ScenarioFrames, MovedAndTiltedPoleMovesTheTarget) {
  const ScenarioSpec parsed = ParseScenarioSpec(kUnwrap);
  const size_t pole = Index(parsed, "pole");
  ScenarioSpec before = parsed;
  ResolveSpecFrames(&before);
  const Eigen::Isometry3d pole0 =
      PoseFromXyzRpy(parsed.objects[pole].xyz, parsed.objects[pole].rpy);
  const Eigen::Vector3d target0 = TaskOf(before, "reach").target.value;

  UnwrapGeometry g;
  g.source = "test";
  g.pole_tilt_deg = Eigen::Vector2d(15.0, -10.0);
  g.pole_translation = Eigen::Vector3d(0.05, -0.02, 0.08);
  ScenarioSpec moved = parsed;
  ApplyUnwrapGeometry(g, &moved);
  const Eigen::Isometry3d pole1 = PoseFromXyzRpy(moved.objects[pole].xyz, moved.objects[pole].rpy);
  ResolveSpecFrames(&moved);
  const Eigen::Vector3d target1 = TaskOf(moved, "reach").target.value;
  EXPECT_GT((target1 - target0).norm(), 0.1);  // it moved (tilted about the pole's centre)
  EXPECT_TRUE((pole1.inverse() * target1).isApprox(pole0.inverse() * target0, 1e-12))
      << (pole1.inverse() * target1).transpose() << " vs "
      << (pole0.inverse() * target0).transpose();
  // The pole's axis was tilted by the two angles: cos of the angle between the axes.
  const double c = pole0.linear().col(2).dot(pole1.linear().col(2));
  EXPECT_NEAR(c, std::cos(15.0 * M_PI / 180) * std::cos(10.0 * M_PI / 180), 1e-12);

  // A pure translation moves the target by exactly that translation.
  UnwrapGeometry shift;
  shift.source = "test";
  shift.pole_translation = Eigen::Vector3d(0.1, 0.0, -0.05);
  ScenarioSpec shifted = parsed;
  ApplyUnwrapGeometry(shift, &shifted);
  ResolveSpecFrames(&shifted);
  EXPECT_TRUE(
      TaskOf(shifted, "reach").target.value.isApprox(target0 + shift.pole_translation, 1e-15));
}

// Through the whole set-up: the problem's reach target at T is the point in the pole's frame, and
// a box centre given in the pole's frame follows the pole too.
TEST(ScenarioFrames, SetUpResolvesTargetsAndBoxCentresInTheirFrames) {
  const std::string path = WriteTemp(
      "frames.json",
      MiniScenario(R"({"type": "interpolate", "value": [0.1, 0.2, 0.3], "frame": "pole"})",
                   R"(, {"name": "mark", "urdf": ")" + kAssets +
                       R"(objects/cylinder.urdf", "frame": "pole", "xyz": [0, 0, 0.4],
                          "collide": false})"));
  const auto s = LoadScenario(path);
  const Eigen::Isometry3d pole =
      PoseFromXyzRpy(Eigen::Vector3d(0.6, 0.1, 0.5), Eigen::Vector3d(0.3, -0.2, 0.7));
  const Eigen::Vector3d want = pole * Eigen::Vector3d(0.1, 0.2, 0.3);
  const planning::Task& reach = s->initial.problem.tasks.at(0);
  EXPECT_TRUE(reach.target.col(reach.target.cols() - 1).isApprox(want, 1e-12));
  EXPECT_TRUE(
      ObjectPosition(*s, s->initial, "mark").isApprox(pole * Eigen::Vector3d(0, 0, 0.4), 1e-12));

  const std::string box = WriteTemp(
      "box_frame.json",
      R"({"robot": ")" + kAssets + R"(robots/lwr4_sdh.urdf",
    "objects": [{"name": "pole", "urdf": ")" +
          kAssets + R"(objects/pole.urdf", "xyz": [0.6, 0.1, 0.5], "rpy": [0.3, -0.2, 0.7]}],
    "start": {"q": "zero"}, "problem": {"T": 5},
    "tasks": [{"name": "box", "feature": {"type": "box", "link": "sdh_grasp_link", "frame": "pole",
               "center": [0.1, 0.2, 0.3], "half_extent": [0.1, 0.1, 0.1]}, "precision": 1}]})");
  const auto b = LoadScenario(box);
  EXPECT_TRUE(b->initial.tasks.at(0).feature.center.isApprox(want, 1e-12));
  EXPECT_FALSE(b->initial.tasks.at(0).feature.frame.has_value());
}

void ExpectParseError(const std::string& name, const std::string& text,
                      const std::string& fragment) {
  const std::string path = WriteTemp(name, text);
  try {
    ParseScenarioSpec(path);
    FAIL() << "expected an error containing '" << fragment << "'";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
  }
}

TEST(ScenarioFrames, UnknownFramesAreErrorsNamingTheKey) {
  ExpectParseError("bad_target_frame.json",
                   MiniScenario(R"({"type": "value", "value": [0, 0, 0], "frame": "polee"})"),
                   "tasks[0].target.frame: unknown object 'polee' (objects: pole) (did you mean "
                   "'pole'?)");
  // An object's frame must be an object before it in the file.
  ExpectParseError(
      "later_object_frame.json",
      MiniScenario(R"({"type": "value", "value": [0, 0, 0]})",
                   R"(, {"name": "a", "urdf": ")" + kAssets +
                       R"(objects/ball.urdf", "frame": "b"}, {"name": "b", "urdf": ")" + kAssets +
                       R"(objects/ball.urdf"})"),
      "objects[1].frame: unknown object 'b' (objects before it: pole)");
  ExpectParseError("scalar_frame.json",
                   MiniScenario(R"({"type": "value", "value": 0, "frame": "pole"})"),
                   "tasks[0].target.frame: \"frame\" needs a point value [x, y, z]");
  ExpectParseError("zero_frame.json", MiniScenario(R"({"type": "zero", "frame": "pole"})"),
                   "tasks[0].target.frame: \"frame\" needs a \"value\" or \"interpolate\" target");
}

TEST(UnwrapGeometry, ReadsAppliesAndRejects) {
  const std::string path = WriteTemp("geo.json", R"({"split": "tuning", "pole_radius": 0.05,
      "target_offset": [0.01, 0.02, 0.03],
      "arm": {"urdf": ")" + kAssets + R"(robots/arm12_sdh.urdf",
              "disabled_groups": [["sdh_", "arm_link_12"]]}})");
  const UnwrapGeometry g = ReadUnwrapGeometry(path);
  EXPECT_EQ(g.name, "geo");
  EXPECT_EQ(g.split, "tuning");
  ScenarioSpec spec = ParseScenarioSpec(kUnwrap);
  const ScenarioSpec shipped = spec;
  ApplyUnwrapGeometry(g, &spec);
  const ObjectSpec& pole = spec.objects[Index(spec, "pole")];
  ASSERT_TRUE(pole.capsule_chain.has_value());
  EXPECT_EQ(pole.capsule_chain->name, "axis");
  EXPECT_EQ(pole.capsule_radius, 0.05);
  EXPECT_EQ(pole.xyz, shipped.objects[Index(shipped, "pole")].xyz);
  EXPECT_NE(spec.robot.find("arm12_sdh.urdf"), std::string::npos);
  ASSERT_EQ(spec.collision.disabled_groups.size(), 1u);
  EXPECT_EQ(spec.collision.disabled_groups[0][1], "arm_link_12");
  // The target offset moved the cylinder (and with it the target) in the pole's frame.
  const size_t cyl = Index(spec, "cylinder");
  EXPECT_TRUE((spec.objects[cyl].xyz - shipped.objects[cyl].xyz)
                  .isApprox(Eigen::Vector3d(0.01, 0.02, 0.03), 1e-12));
  ScenarioSpec a = shipped, b = spec;
  ResolveSpecFrames(&a);
  ResolveSpecFrames(&b);
  const Eigen::Matrix3d R = PoseFromXyzRpy(pole.xyz, pole.rpy).linear();
  EXPECT_TRUE((TaskOf(b, "reach").target.value - TaskOf(a, "reach").target.value)
                  .isApprox(R * Eigen::Vector3d(0.01, 0.02, 0.03), 1e-12));

  const auto expect_error = [](const std::string& name, const std::string& text,
                               const std::string& fragment) {
    const std::string p = WriteTemp(name, text);
    try {
      ReadUnwrapGeometry(p);
      FAIL() << "expected an error containing '" << fragment << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  expect_error("geo_split.json", R"({"split": "train"})", "split: expected \"tuning\" or \"test\"");
  expect_error("geo_tilt.json", R"({"pole_tilt_deg": [0, 95]})", "pole_tilt_deg: component 1");
  // The bounds and the value in shortest form: a value just outside reads as outside.
  expect_error("geo_shift.json", R"({"pole_translation": [1.0000001, 0, 0]})",
               "pole_translation: component 0 (1.0000001) out of range [-1, 1]");
  expect_error("geo_arm_empty.json", R"({"arm": {"urdf": ""}})", "arm.urdf: empty path");
  expect_error("geo_key.json", R"({"pole_radias": 0.03})", "unknown key 'pole_radias'");
  expect_error("geo_arm.json", R"({"arm": {"urdf": "nope.urdf"}})", "arm.urdf: cannot find");
  // The name is geometry.csv's first column, unquoted: a comma, quote or newline would break its
  // rows, so only letters, digits, '_', '-' and '.' are accepted, from "name" and from the stem.
  expect_error("geo_name.json", R"({"name": "a,b\"c\nd"})",
               "geo_name.json: name: 'a,b\"c?d' holds ','");
  expect_error("geo_quote.json", R"({"name": "a\"b"})", "name: 'a\"b' holds '\"'");
  expect_error("geo_newline.json", R"({"name": "a\nb"})", "holds a control character");
  expect_error("geo_empty.json", R"({"name": ""})", "geo_empty.json: name: is empty");
  expect_error("geo,stem.json", "{}",
               "name: the file's stem (the default name) 'geo,stem' holds ','");
  EXPECT_EQ(ReadUnwrapGeometry(WriteTemp("geo-1.2_x.json", "{}")).name, "geo-1.2_x");
}

// Each prefix of a disabled group must name links: an empty prefix would match every link (no
// self-collision checks left), and one matching no link is a typo. The error names the file and
// the entry: the geometry's arm.disabled_groups, or the scenario's collision.disabled_groups.
TEST(UnwrapGeometry, DisabledGroupPrefixesMustMatchLinks) {
  const auto expect_error = [](const std::string& groups, const std::string& fragment) {
    const std::string p = WriteTemp("geo_groups.json", R"({"arm": {"urdf": ")" + kAssets +
                                                           R"(robots/arm12_sdh.urdf",
        "disabled_groups": )" + groups + "}}");
    ScenarioSpec spec = ParseScenarioSpec(kUnwrap);
    ApplyUnwrapGeometry(ReadUnwrapGeometry(p), &spec);
    try {
      SetUpScenario(spec, 90.0);
      FAIL() << "expected an error containing '" << fragment << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(p + ": " + fragment), std::string::npos) << e.what();
    }
  };
  expect_error(R"([["nonexistent_prefix_"]])",
               "arm.disabled_groups[0][0]: no link of the robot starts with 'nonexistent_prefix_'");
  expect_error(R"([["sdh_", "arm_link_12"], ["sdh_", ""]])",
               "arm.disabled_groups[1][1]: empty prefix (it would match every link)");
  ScenarioSpec spec = ParseScenarioSpec(kUnwrap);
  spec.collision.disabled_groups = {{"sdh_", "arm_lnk_20"}};
  try {
    SetUpScenario(spec, 90.0);
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(
                  kUnwrap + ": collision.disabled_groups[0][1]: no link of the robot starts with "
                            "'arm_lnk_20'"),
              std::string::npos)
        << e.what();
  }
}

// On test_01 (30-link arm, pole tilted by 4.2° and 4.3°, moved and resized) the pole passes through
// the arm's zero pose, and the writhe continuation to 540° used to end there too: the start
// collided (arm_link_19 in the pole) and no planner could solve the run. The continuation is now
// run again from the zero pose pushed out of collision, and the start is collision-free near the
// angle asked. At 720° the first continuation ends collision-free and is kept.
// unwrap.json on the geometry `file` (under assets/scenarios/unwrap_geometries/), set up at
// `wrap`°.
std::unique_ptr<Scenario> UnwrapOn(const std::string& file, double wrap) {
  const UnwrapGeometry g = ReadUnwrapGeometry(kAssets + "scenarios/unwrap_geometries/" + file);
  ScenarioSpec spec = ParseScenarioSpec(kUnwrap);
  ApplyUnwrapGeometry(g, &spec);
  return SetUpScenario(spec, wrap);
}

TEST(UnwrapGeometry, AStartCoilIsCollisionFreeWhenThePolePassesThroughTheZeroPose) {
  for (const double wrap : {540.0, 720.0}) {
    SCOPED_TRACE("wrap " + std::to_string(wrap));
    const auto s = UnwrapOn("test/test_01_arm30.json", wrap);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(s->initial.problem.q0.size());
    EXPECT_FALSE(CheckEndState(*s, zero, true).collision_free);  // the pole through the zero pose
    EXPECT_TRUE(CheckEndState(*s, s->initial.problem.q0, true).collision_free);
    EXPECT_NEAR(s->start_wrap_deg, wrap, 5.0);
  }
}

// A short arm's continuation stops in a local minimum well short of the angle asked: the 12-link
// arm on tuning_01's pole stopped at 275° of 540°. The continuation is then run again from seeded
// perturbations of the zero pose and the collision-free end closest to the angle is kept (424°).
TEST(UnwrapGeometry, AShortStartCoilIsRetriedFromPerturbedStarts) {
  const auto s = UnwrapOn("tuning/tuning_01_arm12.json", 540.0);
  EXPECT_TRUE(CheckEndState(*s, s->initial.problem.q0, true).collision_free);
  EXPECT_GT(s->start_wrap_deg, 400.0);
  EXPECT_LE(s->start_wrap_deg, 550.0);
  EXPECT_TRUE(s->warnings.empty());
}

// On tuning_14's pole (tilted by 18.9° and 10.8°) the 30-link arm's continuation to 720° ends with
// its tail past the pole's end, 1.1 cm from the pole's line: one small move from passing it, so
// that the winding jumped by a turn in the first resampled step of every plan ("tunnelled"
// whatever the planner). Such a start is restarted like one that collides, and the start kept is
// a coil about the line: no segment within the coil margin (5 cm) of it beyond the ends.
TEST(UnwrapGeometry, AStartCoilKeepsClearOfThePolesLineBeyondItsEnds) {
  const auto s = UnwrapOn("tuning/tuning_14_arm30.json", 720.0);
  const double margin = s->spec.start.margin;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(s->initial.problem.q0.size());
  const Eigen::VectorXd first = internal::WritheContinuation(
      *s, zero, 2.0 * std::copysign(1.0, ReportWritheTotal(*s, zero)), s->spec.start.step, margin);
  EXPECT_LT(ReportLineDistanceBeyondEnds(*s, first), 0.02);  // the continuation alone: 1.1 cm
  const Eigen::VectorXd& q0 = s->initial.problem.q0;
  EXPECT_GE(ReportLineDistanceBeyondEnds(*s, q0), margin);
  EXPECT_TRUE(CheckEndState(*s, q0, true).collision_free);
  EXPECT_NEAR(s->start_wrap_deg, 720.0, 10.0);
  EXPECT_TRUE(s->warnings.empty());
}

// The first test run with restarts kept, on test_12's 12-link arm, a restart that ended at
// arm_joint_1 = -2.013 rad, outside its limits of ±2 rad (the continuation's limit task is soft):
// every tree refused the start. Only ends inside the limits are kept now.
TEST(UnwrapGeometry, ARestartOutsideTheJointLimitsIsRefused) {
  const auto s = UnwrapOn("test/test_12_arm12.json", 540.0);
  const Eigen::VectorXd& q0 = s->initial.problem.q0;
  EXPECT_TRUE((q0.array() >= LowerLimits(s->robot).array()).all());
  EXPECT_TRUE((q0.array() <= UpperLimits(s->robot).array()).all());
  EXPECT_TRUE(CheckEndState(*s, q0, true).collision_free);
  EXPECT_TRUE(s->warnings.empty());
}

}  // namespace
}  // namespace planning
