#include "app/viewer/session.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "planning/motion/scenario.h"

namespace app {
namespace {

class SessionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    setenv("TOPOPLAN_ASSETS", TOPOPLAN_SOURCE_DIR "/assets", 1);
    session_.Apply(SessionCommand(SessionCommand::Kind::kLoad, "unwrap"), &settings_);
  }
  Session session_;
  Settings settings_;
};

TEST_F(SessionTest, LoadsScenarioWithStartConfigurationAndWrithe) {
  ASSERT_TRUE(session_.has_scenario());
  EXPECT_EQ(session_.num_frames(settings_), 0);
  EXPECT_EQ(session_.ShownQ(settings_).size(), 27);  // 20 arm joints + 7 SDH joints
  const Eigen::MatrixXd w = session_.WritheAt(session_.ShownQ(settings_));
  EXPECT_EQ(w.rows(), 20);
  EXPECT_GT(std::abs(w.sum()), 1.0);  // the start coil wraps the pole
}

TEST_F(SessionTest, PlannerPanelStartsFromTheScenariosSolverOptions) {
  const std::unique_ptr<planning::Scenario> file =
      planning::LoadScenario(TOPOPLAN_SOURCE_DIR "/assets/scenarios/unwrap.json");
  EXPECT_EQ(settings_.planner.damping, file->aico.damping);
  EXPECT_EQ(settings_.planner.tolerance, file->aico.tolerance);
  EXPECT_EQ(settings_.planner.max_iterations, file->aico.max_iterations);
  // An edit in the panel is what the next plan uses; loading again restores the file's options.
  settings_.planner.damping = file->aico.damping * 2.0;
  session_.Apply(SessionCommand(SessionCommand::Kind::kPlan), &settings_);
  EXPECT_EQ(session_.aico_options().damping, file->aico.damping * 2.0);
  EXPECT_EQ(session_.scenario()->aico.damping, file->aico.damping);  // the model is not changed
  session_.Apply(SessionCommand(SessionCommand::Kind::kLoad, "unwrap"), &settings_);
  EXPECT_EQ(settings_.planner.damping, file->aico.damping);
}

TEST_F(SessionTest, StepRunsRealSweepsThatMatchTheFullPlan) {
  // The full plan, for reference; with the initial damping λ = 1 instead of the scenario's, so
  // that the plan has enough sweeps to step through.
  settings_.planner.damping = 1.0;
  session_.Apply(SessionCommand(SessionCommand::Kind::kPlan), &settings_);
  ASSERT_TRUE(session_.result().has_value());
  const std::vector<SweepRecord> full = session_.sweeps();
  const Eigen::MatrixXd full_q = session_.result()->trajectory.q;
  ASSERT_GT(full.size(), 4u);

  // Stepping: each step runs exactly one more sweep, then the solver is held.
  session_.Apply(SessionCommand(SessionCommand::Kind::kReset), &settings_);
  session_.Apply(SessionCommand(SessionCommand::Kind::kStep, "", 0, 1.0), &settings_);
  session_.Wait(&settings_);
  ASSERT_EQ(session_.sweeps().size(), 1u);
  EXPECT_EQ(settings_.sweep, 0);
  EXPECT_TRUE(session_.worker_status(settings_).held);
  EXPECT_FALSE(session_.result().has_value());
  session_.Apply(SessionCommand(SessionCommand::Kind::kStep, "", 0, 2.0), &settings_);
  session_.Wait(&settings_);
  ASSERT_EQ(session_.sweeps().size(), 3u);
  EXPECT_EQ(settings_.sweep, 2);
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(session_.sweeps()[k].cost, full[k].cost);
    EXPECT_EQ(session_.sweeps()[k].q, full[k].q);
  }
  // Stepping on to the end gives the plan's result, bit for bit, and RunPlanner's (the viewer
  // drives planning::AicoSolver::Step directly).
  session_.Apply(SessionCommand(SessionCommand::Kind::kStep, "", 0, 1000.0), &settings_);
  session_.Wait(&settings_);
  ASSERT_TRUE(session_.result().has_value());
  EXPECT_EQ(session_.result()->trajectory.q, full_q);
  planning::PlanRequest request;
  request.aico = session_.aico_options();
  const planning::PlanResult direct = planning::RunPlanner(*session_.scenario(), request);
  EXPECT_EQ(session_.result()->trajectory.q, direct.trajectory.q);
  EXPECT_EQ(session_.result()->report.iterations, direct.report.iterations);
  EXPECT_EQ(session_.result()->report.cost, direct.report.cost);
  EXPECT_EQ(session_.result()->report.collision_checks, direct.report.collision_checks);
  EXPECT_EQ(session_.result()->report.success, direct.report.success);
  EXPECT_EQ(session_.result()->report.failure_reason, direct.report.failure_reason);
  EXPECT_FALSE(session_.busy());
  // The final trajectory (sweep −1) ends unwrapped; seek takes seconds (2 s = the last slice).
  settings_.sweep = -1;
  session_.Apply(SessionCommand(SessionCommand::Kind::kSeek, "", 0, 1.0), &settings_);
  EXPECT_EQ(settings_.frame, 25);  // T = 50 over 2 s
  session_.Apply(SessionCommand(SessionCommand::Kind::kSeek, "", 0, 1e9), &settings_);
  EXPECT_EQ(settings_.frame, session_.num_frames(settings_) - 1);
  EXPECT_LT(std::abs(session_.WritheAt(session_.ShownQ(settings_)).sum()), 0.1);
  EXPECT_TRUE(session_.result()->report.success);
  // One colour range for the whole trajectory: at least every slice's own maximum.
  const double limit = session_.HeatmapLimit(settings_);
  for (int f = 0; f < session_.num_frames(settings_); f += 10) {
    settings_.frame = f;
    EXPECT_LE(session_.WritheAt(session_.ShownQ(settings_)).cwiseAbs().maxCoeff(), limit);
  }
}

TEST_F(SessionTest, CancelledPlanLeavesNoThreadAndNoResult) {
  session_.Apply(SessionCommand(SessionCommand::Kind::kPlanAsync), &settings_);
  EXPECT_TRUE(session_.busy());
  session_.Apply(SessionCommand(SessionCommand::Kind::kCancel), &settings_);
  session_.Wait(&settings_);
  EXPECT_FALSE(session_.busy());  // the job's thread is joined
  EXPECT_TRUE(session_.settled());
  EXPECT_FALSE(session_.result().has_value());
  EXPECT_NE(session_.status().find("cancelled"), std::string::npos) << session_.status();
  // A held stepped solve is cancelled the same way.
  session_.Apply(SessionCommand(SessionCommand::Kind::kStep, "", 0, 2.0), &settings_);
  session_.Wait(&settings_);
  EXPECT_TRUE(session_.busy());
  session_.Apply(SessionCommand(SessionCommand::Kind::kCancel), &settings_);
  session_.Wait(&settings_);
  EXPECT_FALSE(session_.busy());
  EXPECT_FALSE(session_.result().has_value());
  // Loading while a plan runs drops the plan without waiting for it.
  session_.Apply(SessionCommand(SessionCommand::Kind::kPlanAsync), &settings_);
  session_.Apply(SessionCommand(SessionCommand::Kind::kReset), &settings_);
  session_.Wait(&settings_);
  EXPECT_FALSE(session_.result().has_value());
  EXPECT_TRUE(session_.sweeps().empty());
}

TEST(SessionRrtTest, RrtStepGrowsTheTreesAndEndsOnThePlannersPath) {
  setenv("TOPOPLAN_ASSETS", TOPOPLAN_SOURCE_DIR "/assets", 1);
  Session session;
  Settings settings;
  settings.planner.planner = "rrt";
  session.Apply(SessionCommand(SessionCommand::Kind::kLoad, "reach_through_ring"), &settings);
  session.Apply(SessionCommand(SessionCommand::Kind::kRrtStep, "", 0, 2.0), &settings);
  session.Wait(&settings);
  ASSERT_EQ(session.rrt_trees().size(), 1u);
  const size_t after_two = session.rrt_trees()[0].points.size();
  EXPECT_GE(after_two, 1u);
  EXPECT_LE(after_two, 3u);  // the root + at most one node per iteration
  EXPECT_EQ(session.rrt_trees()[0].parents[0], -1);
  if (!session.result()) {
    EXPECT_TRUE(session.worker_status(settings).held);
    EXPECT_GT(session.worker_status(settings).rrt_checks, 0);
  }
  // Stepping to the end gives RunPlanner's path, bit for bit (same seed, same solver).
  session.Apply(SessionCommand(SessionCommand::Kind::kRrtStep, "", 0, 1e6), &settings);
  session.Wait(&settings);
  ASSERT_TRUE(session.result().has_value()) << session.status();
  const planning::PlanResult direct =
      planning::RunPlanner(*session.scenario(), planning::Planner::kRrt, settings.planner.seed);
  EXPECT_EQ(session.result()->trajectory.q, direct.trajectory.q);
  EXPECT_EQ(session.result()->report.iterations, direct.report.iterations);
  EXPECT_GE(session.worker_status(settings).rrt_nodes, static_cast<long>(after_two));
  // `step` is for AICO only and says so.
  try {
    session.Apply(SessionCommand(SessionCommand::Kind::kStep, "", 0, 1.0), &settings);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("(valid: aico"), std::string::npos) << e.what();
  }
}

TEST(SessionMoveTest, MovingTheRingRePlansWarmStarted) {
  setenv("TOPOPLAN_ASSETS", TOPOPLAN_SOURCE_DIR "/assets", 1);
  Session session;
  Settings settings;
  session.Apply(SessionCommand(SessionCommand::Kind::kLoad, "reach_through_ring"), &settings);
  session.Apply(SessionCommand(SessionCommand::Kind::kPlan), &settings);
  ASSERT_TRUE(session.result().has_value());
  SessionCommand move(SessionCommand::Kind::kMove, "ring");
  move.position = Eigen::Vector3d(0.5, 0.03, 0.96);
  session.Apply(move, &settings);
  session.Wait(&settings);
  ASSERT_TRUE(session.result().has_value()) << session.status();
  EXPECT_EQ(session.result()->report.planner, "aico (warm start)");
  EXPECT_EQ(planning::ObjectPosition(*session.scenario(), *session.world(), "ring"), move.position);
  EXPECT_TRUE(session.result()->report.success) << session.status();
  move.text = "table";
  try {
    session.Apply(move, &settings);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("(valid: ring)"), std::string::npos) << e.what();
  }
}

// The viewer's `move` while the arm executes: the library's receding-horizon step
// (planning::ReplanFrom) from the executed slice, the previous plan shifted as its start, the
// box and reach targets moving with the ring. A 12 cm move: the hand still ends through the ring.
TEST(SessionMoveTest, RingMovedTwelveCentimetresWhileExecuting) {
  setenv("TOPOPLAN_ASSETS", TOPOPLAN_SOURCE_DIR "/assets", 1);
  Session session;
  Settings settings;
  session.Apply(SessionCommand(SessionCommand::Kind::kLoad, "reach_through_ring"), &settings);
  const planning::Scenario& s = *session.scenario();
  const Eigen::Vector3d home = s.initial.objects.objects.at(0).world_from_object.translation();
  session.Apply(SessionCommand(SessionCommand::Kind::kPlan), &settings);
  ASSERT_TRUE(session.result().has_value());
  const Eigen::MatrixXd first = session.result()->trajectory.q;
  session.Apply(SessionCommand(SessionCommand::Kind::kSeek, "", 0, 1.0), &settings);
  ASSERT_EQ(settings.frame, 8);  // τ = 4 s / 32
  SessionCommand move(SessionCommand::Kind::kMove, "ring");
  const Eigen::Vector3d delta(0.0, 0.12, 0.0);
  move.position = home + delta;
  session.Apply(move, &settings);
  EXPECT_NE(session.status().find("from slice 8"), std::string::npos) << session.status();
  session.Wait(&settings);
  ASSERT_TRUE(session.result().has_value()) << session.status();
  const Eigen::MatrixXd& q = session.result()->trajectory.q;
  EXPECT_EQ(q.col(0), first.col(8));  // it starts where the arm was
  EXPECT_TRUE(session.result()->report.success)
      << planning::FailureReasonName(session.result()->report.failure_reason);
  planning::KinematicsData kin(s.robot);
  planning::ForwardKinematics(s.robot, q.col(q.cols() - 1), &kin);
  Eigen::Matrix3Xd hand;
  planning::ChainPoints(s.robot, kin, s.report_chain, &hand);
  EXPECT_TRUE(planning::ChainThroughLoop(hand, s.initial.report_object_chain));
  // A second move goes on from the new plan's slice (receding horizon).
  settings.frame = 4;
  move.position = home + 2 * delta;
  session.Apply(move, &settings);
  EXPECT_NE(session.status().find("from slice 12"), std::string::npos) << session.status();
  session.Wait(&settings);
  ASSERT_TRUE(session.result().has_value()) << session.status();
}

// The worker's jobs run at a lower priority than the thread that draws (per-thread nice).
TEST(WorkerTest, JobsRunNicerThanTheCaller) {
  const int mine = getpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)));
  int theirs = -100;
  Worker worker(3);
  worker.Submit({"nice", [&](Worker&) {
                   theirs = getpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)));
                 }});
  worker.Wait();
  EXPECT_EQ(theirs, std::min(19, mine + 3));
  EXPECT_EQ(getpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid))), mine);
}

TEST_F(SessionTest, PlaybackAdvancesAndStopsAtTheEnd) {
  session_.Apply(SessionCommand(SessionCommand::Kind::kPlan), &settings_);
  session_.Apply(SessionCommand(SessionCommand::Kind::kPlay), &settings_);
  EXPECT_TRUE(settings_.playing);
  const int n = session_.num_frames(settings_);
  for (int i = 0; i < n + 5; ++i) session_.Tick(&settings_);
  EXPECT_FALSE(settings_.playing);
  EXPECT_EQ(settings_.frame, n - 1);
}

TEST_F(SessionTest, JointSliderMovesTheRobotAndDropsThePlan) {
  session_.Apply(SessionCommand(SessionCommand::Kind::kPlan), &settings_);
  session_.Apply(SessionCommand(SessionCommand::Kind::kSetJoint, "", 3, 0.25), &settings_);
  EXPECT_FALSE(session_.result().has_value());
  EXPECT_DOUBLE_EQ(session_.ShownQ(settings_)(3), 0.25);
  EXPECT_THROW(
      session_.Apply(SessionCommand(SessionCommand::Kind::kSetJoint, "", 99, 0.0), &settings_),
      std::invalid_argument);
  session_.Apply(SessionCommand(SessionCommand::Kind::kReset), &settings_);
  EXPECT_NE(session_.ShownQ(settings_)(3), 0.25);
}

TEST(ScriptTest, ParsesCommandsAndRejectsBadLinesWithFileAndLine) {
  const std::string path = std::filesystem::temp_directory_path() / "topoplan_script_test.txt";
  {
    std::ofstream f(path);
    f << "# comment\n\nload unwrap\nstep\nframes 3\nclick Plan\nscreenshot /tmp/x.png\nquit\n";
  }
  const std::vector<ScriptLine> lines = ParseScript(path);
  ASSERT_EQ(lines.size(), 6u);
  EXPECT_EQ(lines[0].verb, "load");
  EXPECT_EQ(lines[0].line, 3);
  EXPECT_EQ(lines[3].args.at(0), "Plan");
  {
    std::ofstream f(path);
    f << "step\nfly away\n";
  }
  try {
    ParseScript(path);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(":2: unknown command 'fly'"), std::string::npos);
  }
  const auto error = [&](const std::string& text) {
    std::ofstream(path) << text;
    try {
      ParseScript(path);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  // One format: FILE:LINE: ..., valid choices as "(valid: a, b, c)".
  EXPECT_NE(error("step\nfly away\n").find(path + ":2: unknown command 'fly' (valid: load, plan,"),
            std::string::npos);
  EXPECT_NE(error("seek\n").find(path + ":1: 'seek' takes 1 argument(s), got 0: seek SECONDS"),
            std::string::npos);
  EXPECT_NE(error("toggle fog\n")
                .find(path + ":1: unknown toggle 'fog' (valid: chains, collision, grid, contacts, "
                             "heatmap, cost)"),
            std::string::npos);
  EXPECT_NE(error("plan later\n").find(path + ":1: unknown plan mode 'later' (valid: async)"),
            std::string::npos);
  EXPECT_NE(error("planner dijkstra\n").find("(valid: aico, rrt, birrt"), std::string::npos);
  EXPECT_NE(error("camera 1 2 3 4\n").find(path + ":1: 'camera' takes 3 or 6 arguments"),
            std::string::npos);
  EXPECT_NE(error("step 0\n").find(path + ":1: '0' is out of range [1, 1e+06]"), std::string::npos);
  EXPECT_NE(error("move ring 1 x 3\n").find(path + ":1: 'x' is not a finite number"),
            std::string::npos);
  EXPECT_NE(error("grasp power_bottle magic\n").find("(valid: winding, joint, fingertip)"),
            std::string::npos);
  EXPECT_NE(error("sim_phase 8\n").find(path + ":1: '8' is out of range [1, 7]"),
            std::string::npos);
  EXPECT_NE(error("sim_phase 0.5\n").find(path + ":1: '0.5' is out of range [1, 7]"),
            std::string::npos);
  EXPECT_NE(error("sim_phase 1.5\n").find(path + ":1: '1.5' is not an integer"), std::string::npos);
  EXPECT_NE(error("sim_phase 1 2\n")
                .find(path + ":1: 'sim_phase' takes 0 to 1 argument(s), got 2: sim_phase [N]"),
            std::string::npos);
  EXPECT_EQ(error("plan async\nstep\nstep 3\nwait\ncancel\nrrt_step 5\nsim_step 2\n"
                  "move ring 0.5 0 1\nstatus s.json\ncamera 0 20 3 0 0 1\nsim_phase\n"
                  "sim_phase 7\ndamping 0.5\n"),
            "no error");
  EXPECT_NE(error("damping -1\n").find(path + ":1: '-1' is out of range [0, 1e+06]"),
            std::string::npos);
  EXPECT_NE(error("damping nan\n").find(path + ":1: 'nan' is not a finite number"),
            std::string::npos);
  EXPECT_THROW(ParseScript("/nonexistent/script.txt"), std::invalid_argument);
}

TEST(StatusJsonTest, WritesEveryFieldThroughARename) {
  const std::string path = std::filesystem::temp_directory_path() / "topoplan_status_test.json";
  WorkerStatus st;
  st.job = "plan";
  st.computing = true;
  st.sweep = 3;
  st.cost = 12.5;
  FrameStats frames;
  frames.frame_ms = {16.0, 17.5};
  frames.frame_planning = {false, true};
  frames.frames = 9;
  frames.frames_while_planning = 2;
  frames.scene_renders = 4;
  WriteStatusJson(path, "aico", st, frames);
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const char* key : {"\"planner\": \"aico\"", "\"planning\": true", "\"sweep\": 3",
                          "\"cost\": 12.5", "\"rrt_nodes\": 0", "\"sim_time_s\": 0.0",
                          "\"frame_ms\": [", "17.5", "\"frame_planning\": [", "\"frames\": 9",
                          "\"frames_while_planning\": 2", "\"scene_renders\": 4"}) {
    EXPECT_NE(text.find(key), std::string::npos) << key << " in " << text;
  }
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  EXPECT_THROW(WriteStatusJson("/nonexistent/dir/s.json", "aico", st, FrameStats{}),
               std::invalid_argument);
}

}  // namespace
}  // namespace app

namespace app {
namespace {

TEST(GraspReplayTest, TransfersRecordsAndStepsTheStabilityTest) {
  setenv("TOPOPLAN_ASSETS", TOPOPLAN_SOURCE_DIR "/assets", 1);
  Session session;
  Settings settings;
  settings.grasp.grasp = "power_bottle";
  settings.grasp.method = "winding";
  // A live simulation held after 5 physics steps (1 ms each), then 5 more.
  session.Apply(SessionCommand(SessionCommand::Kind::kSimStep, "", 0, 5.0), &settings);
  session.Wait(&settings);
  ASSERT_TRUE(session.grasp().has_value());
  EXPECT_FALSE(session.grasp()->finished);
  EXPECT_NEAR(session.worker_status(settings).sim_time_s, 0.005, 1e-9);
  session.Apply(SessionCommand(SessionCommand::Kind::kSimStep, "", 0, 5.0), &settings);
  session.Wait(&settings);
  EXPECT_NEAR(session.worker_status(settings).sim_time_s, 0.010, 1e-9);
  // The whole test, run on the worker.
  session.Apply(SessionCommand(SessionCommand::Kind::kGraspRun), &settings);
  session.Wait(&settings);
  ASSERT_TRUE(session.grasp().has_value());
  EXPECT_TRUE(session.grasp()->finished);
  const GraspReplay& g = *session.grasp();
  // 0.5 s closing + 6 × 2 s at 1 kHz, one frame every 20 steps (trials may stop early).
  EXPECT_GT(g.frames.size(), 100u);
  EXPECT_TRUE(g.result.stable);
  EXPECT_EQ(g.frames.front().phase, 0);
  EXPECT_TRUE(settings.grasp.active);
  EXPECT_EQ(session.GraspGravity(0).norm(), 0.0);  // gravity off while closing
  session.Apply(SessionCommand(SessionCommand::Kind::kGraspStep, "", 0, 60.0), &settings);
  EXPECT_EQ(settings.grasp.frame, 60);
  EXPECT_NEAR(session.GraspGravity(settings.grasp.frame).norm(), 9.81, 1e-9);
  session.Apply(SessionCommand(SessionCommand::Kind::kGraspStep, "", 0, 1e6), &settings);
  EXPECT_EQ(settings.grasp.frame, static_cast<int>(g.frames.size()) - 1);
}

}  // namespace
}  // namespace app
