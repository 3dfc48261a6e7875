// The grasp study (`bench grasp`): grasp.csv rows round-trip, the paired summary on hand-made
// rows, and one unit run end to end (equal budgets, similarity, both engines).
#include "planning/physics/grasp_study.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "planning/grasp/grasp_inputs.h"
#include "planning/physics/grasp_study_report.h"
#include "planning/robot/robot_io.h"

namespace planning::physics {
namespace {

const std::string kAssets = std::string(TOPOPLAN_SOURCE_DIR) + "/assets/";

StudyRow Row(const std::string& grasp, int demo, TransferMethod m, bool ode, bool threading) {
  StudyRow r;
  r.grasp = grasp;
  r.object = "obj";
  r.threading = threading;
  r.demo = demo;
  r.method = m;
  r.ode_stable = ode;
  r.ode_directions = ode ? 6 : 2;
  return r;
}

TEST(StudyCsvTest, RowsRoundTrip) {
  StudyRow r = Row("ring_grip_torus", 7, TransferMethod::kFingertip, true, true);
  r.seed = 3;
  r.mujoco_stable = false;
  r.mujoco_directions = 4;
  r.mujoco_status = StabilityStatus::kNoGrasp;
  r.iou = {0.25, std::nullopt, 1.0};
  r.demo_threads = 2;
  r.threads_preserved = 1;
  r.starts = 2;
  r.task_evaluations = 1234;
  r.iterations = 17;
  r.winding_error = 0.125;
  r.min_clearance = -0.0005;
  const std::string line = StudyCsvRow(r);
  const std::string header = StudyCsvHeader();
  EXPECT_EQ(std::count(line.begin(), line.end(), ','),
            std::count(header.begin(), header.end(), ','));
  const StudyRow p = ParseStudyCsvRow(line);
  EXPECT_EQ(StudyCsvRow(p), line);
  EXPECT_EQ(p.grasp, r.grasp);
  EXPECT_TRUE(p.threading);
  EXPECT_EQ(*p.mujoco_stable, false);
  EXPECT_EQ(p.mujoco_status, StabilityStatus::kNoGrasp);
  EXPECT_FALSE(p.iou[1].has_value());
  EXPECT_NEAR(*p.MeanIoU(), 0.625, 1e-12);
  EXPECT_EQ(p.task_evaluations, 1234);
  // Without MuJoCo the columns stay empty.
  const StudyRow q = ParseStudyCsvRow(StudyCsvRow(Row("a", 0, TransferMethod::kWinding, 0, 0)));
  EXPECT_FALSE(q.mujoco_stable.has_value());
  EXPECT_THROW(ParseStudyCsvRow("a,b,c"), std::invalid_argument);
}

TEST(StudySummaryTest, PairsPerDemonstrationAndSplitsByClass) {
  // Winding holds every demo; joint holds the control demos only: on the 3 threading demos
  // winding wins 3 discordant pairs, on the 2 control demos none.
  std::vector<StudyRow> rows;
  for (int d = 0; d < 3; ++d) {
    rows.push_back(Row("ring", d, TransferMethod::kWinding, true, true));
    rows.push_back(Row("ring", d, TransferMethod::kJointMapping, false, true));
  }
  for (int d = 0; d < 2; ++d) {
    rows.push_back(Row("box", d, TransferMethod::kWinding, true, false));
    rows.push_back(Row("box", d, TransferMethod::kJointMapping, true, false));
  }
  rows[0].mujoco_stable = true;  // one trial with both verdicts, agreeing
  const StudySummary s =
      SummariseStudy(rows, {TransferMethod::kWinding, TransferMethod::kJointMapping});
  EXPECT_EQ(s.units, 5);
  ASSERT_EQ(s.per_method.size(), 6u);
  EXPECT_EQ(s.per_method[0].trials, 5);  // winding, all
  EXPECT_EQ(s.per_method[0].ode_stable, 5);
  EXPECT_EQ(s.per_method[3].ode_stable, 2);  // joint, all
  EXPECT_EQ(s.per_method[4].ode_stable, 0);  // joint, threading
  EXPECT_EQ(s.per_method[5].ode_stable, 2);  // joint, control
  ASSERT_GE(s.pairs.size(), 3u);
  EXPECT_EQ(s.pairs[0].table.only_a, 3);  // all
  EXPECT_EQ(s.pairs[0].table.only_b, 0);
  EXPECT_DOUBLE_EQ(s.pairs[0].p, 0.25);  // 2 · (½)³
  EXPECT_EQ(s.pairs[2].subset, StudySubset::kControl);
  EXPECT_EQ(s.pairs[2].table.both, 2);
  EXPECT_DOUBLE_EQ(s.pairs[2].p, 1.0);
  EXPECT_EQ(s.agreement.both_hold, 1);
  EXPECT_EQ(s.agreement.trials(), 1);
  const std::string md = StudyTableMarkdown(s);
  EXPECT_NE(md.find("| winding | 5/5"), std::string::npos);
  EXPECT_NE(md.find("| winding vs joint | 3 / 0, p = 0.25"), std::string::npos);
}

TEST(GraspStudyTest, OneUnitWithEqualBudgets) {
  const GraspInputs in = LoadGraspInputs({kAssets + "grasps/power_bottle.json"});
  GraspStudyOptions o;
  o.methods = {TransferMethod::kContactOnly, TransferMethod::kJointMapping};
  o.mujoco = EngineAvailable(PhysicsEngine::kMujoco);
  o.stability.trial_time = 0.5;  // a shorter protocol for the test
  StudyUnit unit = PrepareStudyUnit(in.human, in.lwr_sdh, in.objects, in.grasps[0], 1, o);
  EXPECT_EQ(unit.demo.name, "power_bottle#1");
  ASSERT_EQ(unit.rows.size(), 2u);
  for (const StudyRow& r : unit.rows) {
    EXPECT_EQ(r.starts, 2);  // the joint method gets the same starts (equal baselines)
    EXPECT_GT(r.task_evaluations, 0);
    EXPECT_FALSE(r.threading);
    EXPECT_EQ(r.demo_threads, 0);
    EXPECT_EQ(r.mujoco_stable.has_value(), o.mujoco);
  }
  // The demonstration touches the bottle, so every finger's IoU is defined, in [0, 1].
  for (const StudyRow& r : unit.rows) {
    for (const std::optional<double>& v : r.iou) {
      ASSERT_TRUE(v.has_value());
      EXPECT_GE(*v, 0.0);
      EXPECT_LE(*v, 1.0);
    }
  }
  const OdeRuntime ode;
  FinishStudyUnit(ode, o, &unit);
  EXPECT_GT(unit.rows[0].ode_directions + unit.rows[1].ode_directions, 0);
  // The same unit again: deterministic rows.
  StudyUnit again = PrepareStudyUnit(in.human, in.lwr_sdh, in.objects, in.grasps[0], 1, o);
  FinishStudyUnit(ode, o, &again);
  for (size_t k = 0; k < 2; ++k) EXPECT_EQ(StudyCsvRow(again.rows[k]), StudyCsvRow(unit.rows[k]));
  o.methods = {TransferMethod::kHuman};
  EXPECT_THROW(PrepareStudyUnit(in.human, in.lwr_sdh, in.objects, in.grasps[0], 0, o),
               std::invalid_argument);
}

TEST(GraspStudyTest, ThreadingObjectCountsThreads) {
  const GraspInputs in = LoadGraspInputs({kAssets + "grasps/ring_grip_torus.json"});
  GraspStudyOptions o;
  o.methods = {TransferMethod::kWinding};
  o.stability.trial_time = 0.2;
  const StudyUnit unit = PrepareStudyUnit(in.human, in.lwr_sdh, in.objects, in.grasps[0], 0, o);
  EXPECT_TRUE(unit.rows[0].threading);
  EXPECT_GE(unit.rows[0].demo_threads, 1);  // the ring grip threads the torus
  EXPECT_LE(unit.rows[0].threads_preserved, unit.rows[0].demo_threads);
}

}  // namespace
}  // namespace planning::physics
