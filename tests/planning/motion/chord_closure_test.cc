// The arm closed by its chord (assets/scenarios/unwrap_chord.json): the writhe end condition
// "writhe_closure": "chord" counts the turns the arm makes round the pole wherever its two ends
// are, and the writhe target "chord_to" aims at the writhe of the straight base → target segment.
// Both are checked against values computed here from the chain points, and on the shipped scene
// and a pole tilted by 20°, where base and target are no longer at one angle round the pole.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "base/json_reader.h"
#include "base/str_cat.h"
#include "planning/motion/planner.h"
#include "planning/motion/scenario.h"
#include "planning/motion/scenario_spec.h"
#include "planning/motion/success.h"
#include "planning/motion/unwrap_geometry.h"
#include "planning/robot/kinematics.h"
#include "topology/writhe.h"

namespace planning {
namespace {

const std::string kAssets = TOPOPLAN_SOURCE_DIR "/assets/";

// unwrap.json (or unwrap_chord.json) set up from `wrap_deg`, with the pole tilted by `tilt_deg`
// about its own x axis.
std::unique_ptr<Scenario> Unwrap(const std::string& file, double wrap_deg, double tilt_deg = 0.0) {
  ScenarioSpec spec = ParseScenarioSpec(kAssets + "scenarios/" + file);
  if (tilt_deg != 0.0) {
    UnwrapGeometry g;
    g.pole_tilt_deg = Eigen::Vector2d(tilt_deg, 0.0);
    ApplyUnwrapGeometry(g, &spec);
  }
  return SetUpScenario(spec, wrap_deg);
}

const Task& FindTask(const Scenario& s, const std::string& name) {
  for (const Task& t : s.initial.problem.tasks) {
    if (t.name == name) return t;
  }
  throw std::invalid_argument("no task " + name);
}

// Total writhe between the straight segment from the report chain's first point at q to `end`
// and the pole's axis chain.
double SegmentWrithe(const Scenario& s, const Eigen::VectorXd& q, const Eigen::Vector3d& end) {
  KinematicsData kin(s.robot);
  ForwardKinematics(s.robot, q, &kin);
  Eigen::Matrix3Xd P;
  ChainPoints(s.robot, kin, s.report_chain, &P);
  Eigen::Matrix3Xd segment(3, 2);
  segment << P.col(0), end;
  return topology::WritheMatrix(segment, s.initial.report_object_chain).sum();
}

TEST(ChordClosure, WritheTargetIsTheWritheOfTheBaseToTargetSegment) {
  for (const double tilt : {0.0, 20.0}) {
    SCOPED_TRACE("tilt " + std::to_string(tilt));
    const auto s = Unwrap("unwrap_chord.json", 360.0, tilt);
    const Task& writhe = FindTask(*s, "writhe");
    const Task& reach = FindTask(*s, "reach");
    const Eigen::Index T = writhe.target.cols() - 1;
    const Eigen::Vector3d target = reach.target.col(T);
    const double chord = SegmentWrithe(*s, s->initial.problem.q0, target);
    EXPECT_NEAR(writhe.target(0, T), chord, 1e-12);
    // The start of the interpolation is the coil's own writhe, as without chord_to.
    EXPECT_NEAR(writhe.target(0, 0), ReportWritheTotal(*s, s->initial.problem.q0), 1e-12);
    if (tilt == 0.0) {
      EXPECT_LT(std::abs(chord), 0.05);  // base and target at about one angle round the pole
    } else {
      EXPECT_GT(std::abs(chord), 0.1);
    }
  }
  // Without chord_to (unwrap.json) the target is the value itself, 0.
  const auto plain = Unwrap("unwrap.json", 360.0, 20.0);
  const Task& writhe = FindTask(*plain, "writhe");
  EXPECT_EQ(writhe.target(0, writhe.target.cols() - 1), 0.0);
}

// Closed by its chord, the coil's writhe with the pole's axis tells the turns it makes round the
// pole: it is the change of the solid angle the loop subtends, followed continuously along the
// axis, over 4π; a whole number for an infinitely long pole, and here, where the pole's ends are
// about as far away as the loop is large, 0.10, 0.85 and 1.82 for the coils of 0, 1 and 2 turns
// (the end condition asks for < 0.05 beside the exact chord-closed winding). The open chain's
// writhe differs from it by exactly the chord's.
TEST(ChordClosure, ClosedWritheCountsTheTurnsOfTheCoil) {
  for (const double wrap : {0.0, 360.0, 720.0}) {
    SCOPED_TRACE("wrap " + std::to_string(wrap));
    const auto s = Unwrap("unwrap.json", wrap);
    SuccessCriteria chord = s->success;
    chord.writhe_closed_by_chord = true;
    const Eigen::VectorXd q0 = s->initial.problem.q0;
    const double open = CheckEndState(*s, s->initial, q0, false, s->success).writhe_total;
    const double closed = CheckEndState(*s, s->initial, q0, false, chord).writhe_total;
    EXPECT_NEAR(std::abs(closed), wrap / 360.0, 0.2);
    KinematicsData kin(s->robot);
    ForwardKinematics(s->robot, q0, &kin);
    Eigen::Matrix3Xd P;
    ChainPoints(s->robot, kin, s->report_chain, &P);
    EXPECT_NEAR(closed, open - SegmentWrithe(*s, q0, P.col(P.cols() - 1)), 1e-9);
  }
}

// On the tilted pole the set-up's goal of unwrap_chord.json (its goal search asks for the closed
// conditions) is unwrapped: its closed writhe and winding are near 0, and it reaches the target;
// its open writhe is the chord's, far from 0, so unwrap.json's open end condition rejects it.
TEST(ChordClosure, TheTiltedPolesGoalIsUnwrappedOnlyWhenClosedByItsChord) {
  const auto s = Unwrap("unwrap_chord.json", 540.0, 20.0);
  const EndState closed = CheckEndState(*s, s->initial, s->goal_q, true);
  EXPECT_TRUE(closed.ok()) << "violation " << closed.violation;
  EXPECT_LT(std::abs(closed.writhe_total), 0.05);
  EXPECT_NEAR(closed.winding_turns, 0.0, 1e-9);
  SuccessCriteria open = s->success;
  open.writhe_closed_by_chord = false;
  open.winding_closed_by_chord = false;
  const EndState e = CheckEndState(*s, s->initial, s->goal_q, true, open);
  EXPECT_GT(std::abs(e.writhe_total), 0.05);
  EXPECT_FALSE(e.writhe_reached);
}

// unwrap_chord.json is unwrap.json with the three keys of the closure and the AICO retries, and
// nothing else changed: with its name, description, chord_to, writhe_closure, final_closure and
// aico.retry taken out it is unwrap.json's document, and each of those keys is there.
TEST(ChordClosure, TheChordScenarioDiffersFromUnwrapOnlyInItsKeys) {
  const nlohmann::json a = base::ParseJsonFile(kAssets + "scenarios/unwrap.json", "scenario");
  nlohmann::json b = base::ParseJsonFile(kAssets + "scenarios/unwrap_chord.json", "scenario");
  EXPECT_EQ(b["name"], "unwrap_chord");
  b["name"] = a["name"];
  b["description"] = a["description"];
  int chord_to = 0;
  for (nlohmann::json& task : b["tasks"]) {
    if (!task.contains("target") || !task["target"].contains("chord_to")) continue;
    EXPECT_EQ(task["target"]["chord_to"], "reach");
    task["target"].erase("chord_to");
    ++chord_to;
  }
  EXPECT_EQ(chord_to, 1);
  EXPECT_EQ(b["success"]["writhe_closure"], "chord");
  b["success"].erase("writhe_closure");
  EXPECT_EQ(b["success"]["winding"]["final_closure"], "chord");
  b["success"]["winding"].erase("final_closure");
  ASSERT_TRUE(b["aico"]["retry"].is_array());
  EXPECT_EQ(b["aico"]["retry"].size(), 4u);
  b["aico"].erase("retry");
  EXPECT_EQ(b, a) << nlohmann::json::diff(a, b).dump(1);
}

// A copy of unwrap.json with `from` replaced by `to` (once).
std::string UnwrapWith(const std::string& tag, const std::string& from, const std::string& to) {
  std::ifstream in(kAssets + "scenarios/unwrap.json");
  std::string text(std::istreambuf_iterator<char>(in), {});
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  const std::filesystem::path dir = std::filesystem::path(TOPOPLAN_BINARY_DIR) / "chord_test_tmp";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / (tag + ".json")).string();
  std::ofstream(path) << text;
  return path;
}

void ExpectError(const std::string& path, const std::string& fragment) {
  try {
    ScenarioOverrides o;
    o.search_roots = {kAssets};
    o.start_wrap_deg = 0.0;
    LoadScenario(path, o);
    ADD_FAILURE() << "expected an error naming " << fragment;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(ChordClosure, KeysAreChecked) {
  const std::string target = R"("target": {"type": "interpolate", "value": 0})";
  ExpectError(UnwrapWith("closure", R"("writhe_total_below": 0.05)",
                         R"("writhe_total_below": 0.05, "writhe_closure": "loop")"),
              "success.writhe_closure: \"loop\" is not \"open\" or \"chord\"");
  ExpectError(UnwrapWith("feature", R"("output": "total"})", R"("output": "total", "closure": 1})"),
              "tasks[0].feature.closure");
  ExpectError(UnwrapWith("unknown", target,
                         R"("target": {"type": "interpolate", "value": 0, "chord_to": "grasp"})"),
              "tasks[0].target.chord_to: no task \"grasp\"");
  ExpectError(UnwrapWith("not_position", target,
                         R"("target": {"type": "interpolate", "value": 0, "chord_to": "limits"})"),
              "task \"limits\" is not a \"position\" task");
  ExpectError(
      UnwrapWith("not_interpolate", target, R"("target": {"value": 0, "chord_to": "reach"})"),
      "\"chord_to\" needs an \"interpolate\" target");
  ExpectError(UnwrapWith("closed_chord_to", "\"output\": \"total\"},\n     " + target,
                         "\"output\": \"total\", \"closure\": \"chord\"},\n     "
                         R"("target": {"type": "interpolate", "value": 0, "chord_to": "reach"})"),
              "\"chord_to\" needs the open writhe");
  // The feature closed by its chord in a scenario: the set-up builds it (and its goal search
  // runs with it).
  const std::string closed = UnwrapWith("closed_feature", R"("output": "total"})",
                                        R"("output": "total", "closure": "chord"})");
  ScenarioOverrides o;
  o.search_roots = {kAssets};
  o.start_wrap_deg = 360.0;
  const auto s = LoadScenario(closed, o);
  const Task& writhe = FindTask(*s, "writhe");
  const double y0 = FeatureValue(s->robot, *writhe.feature, s->initial.problem.q0)[0];
  SuccessCriteria chord = s->success;
  chord.writhe_closed_by_chord = true;
  EXPECT_NEAR(y0, CheckEndState(*s, s->initial, s->initial.problem.q0, false, chord).writhe_total,
              1e-12);
}

}  // namespace
}  // namespace planning
