// `topoplan plan` (AICO / RRT / BiRRT on a scenario, with trajectory, report and optional frames)
// (`topoplan bench unwrap` is in cmd_bench.cc).
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "app/cli/command.h"
#include "app/cli/figure_flags.h"
#include "app/cli/io.h"
#include "app/cli/robot_flags.h"
#include "app/present/reports.h"
#include "base/assets.h"
#include "base/version.h"
#include "planning/motion/planner.h"
#include "planning/motion/replan.h"
#include "planning/motion/robot_scene.h"
#include "planning/motion/scenario.h"
#include "render/figure.h"
#include "render/image.h"
#include "visualize/figures.h"

namespace app {

// --aico-stop: when AICO stops ("solved": at the first accepted sweep that is a success;
// "converged": when the sweeps converge). Empty: the scenario's aico.stop_when_solved.
const char* const kAicoStopHelp =
    "when AICO stops: 'solved' (the first accepted sweep whose trajectory passes the success "
    "criteria, status \"solved\"; a success first reached by the last sweep keeps its solver "
    "status) or 'converged' (run the sweeps to convergence); default: the scenario's "
    "aico.stop_when_solved";

// The value of --aico-stop (checked by the flag: "solved" or "converged"; "" when not given).
std::optional<bool> ParseAicoStop(const std::string& text) {
  if (text.empty()) return std::nullopt;
  return text == "solved";
}

// "aico | rrt | birrt ..." from the planner registry of this build.
std::string PlannerChoices() {
  std::string out;
  for (planning::Planner p : planning::AvailablePlanners()) {
    out += (out.empty() ? "" : " | ") + std::string(planning::PlannerName(p));
  }
  return out;
}

namespace {

namespace fs = std::filesystem;

struct PlanArgs {
  std::string scenario, planner = "aico", output;
  unsigned seed = 0;
  double start_wrap = std::numeric_limits<double>::quiet_NaN();  // NaN: not given
  std::string aico_stop;  // --aico-stop solved|converged ("": the scenario's)
  std::string geometry;   // --geometry FILE ("": the scenario's own scene)
  double timeout = 0.0;
  bool frames = false, json = false;
  bool no_stamp = false;                      // --no-stamp: frames without scenario name and time
  planning::RobotInputOptions robot_input;    // --package-path, --srdf
  std::vector<render::FigureFormat> formats;  // --formats
  // Re-planning with a moving object (planning/motion/replan.h).
  std::string moving_object, object_path;
  double replan_period = 0.1;
  int replan_sweeps = 3;
};

// "step,time_s,x,y,z": the moving object's position at every executed slice.
std::string ObjectPositionsCsv(const planning::ReplanResult& r) {
  std::ostringstream out;
  out.precision(17);
  out << "step,time_s,x,y,z\n";
  for (size_t t = 0; t < r.object_positions.size(); ++t) {
    const Eigen::Vector3d& p = r.object_positions[t];
    out << t << "," << static_cast<double>(t) * r.executed.dt << "," << p.x() << "," << p.y() << ","
        << p.z() << "\n";
  }
  return out.str();
}

// The input files of a plan run (never to be replaced by its outputs): the scenario file (when
// the argument names one) and the object path.
std::vector<std::string> PlanInputs(const PlanArgs& pa) {
  std::vector<std::string> inputs{pa.scenario};
  if (!pa.geometry.empty()) inputs.push_back(pa.geometry);  // --geometry FILE
  if (!pa.object_path.empty()) inputs.push_back(pa.object_path);
  return inputs;
}

// A plan stopped before it finished (--timeout, SIGINT/SIGTERM): DIR/report.json with `fields`
// and the stop's status (StoppedReportJson), committed; the same JSON on stdout with --json.
// Exit 1 after a timeout, 130 after a signal.
ExitCode StoppedPlanExit(const StopRequested& e, nlohmann::json fields, const PlanArgs& pa,
                         OutputDir* out) {
  const nlohmann::json report = StoppedReportJson(e, std::move(fields));
  base::WriteFileAtomic((fs::path(out->staging()) / "report.json").string(), report.dump(2) + "\n");
  out->Commit();
  std::fprintf(stderr, "\n%s: wrote %s/report.json\n", e.what(), pa.output.c_str());
  if (pa.json) std::printf("%s\n", report.dump(2).c_str());
  return e.timeout ? kExitFailed : kExitInterrupted;
}

// `plan SCENARIO --moving-object NAME --object-path FILE`: re-planning while the object moves.
ExitCode RunMovingObjectPlan(const PlanArgs& pa, const planning::ScenarioOverrides& overrides,
                             planning::Planner planner) {
  if (pa.moving_object.empty() || pa.object_path.empty()) {
    throw std::invalid_argument("--moving-object and --object-path must be given together");
  }
  if (!planning::IsAico(planner)) {
    throw std::invalid_argument("--moving-object: re-planning uses AICO (--planner aico)");
  }
  if (!(pa.replan_period > 0.0) || !std::isfinite(pa.replan_period)) {
    throw std::invalid_argument("--replan-period: expected a finite number of seconds > 0");
  }
  OutputDir out(pa.output, "-o", "plan", PlanInputs(pa));  // checked before any work
  const planning::ObjectPath path =
      ParseFlag("--object-path", [&] { return planning::ReadObjectPath(pa.object_path); });
  const auto scenario = planning::LoadScenarioArg(pa.scenario, overrides);
  ReportWarnings(scenario->warnings);
  ParseFlag("--moving-object", [&] {  // unknown names list the valid ones
    planning::ObjectPosition(*scenario, scenario->initial, pa.moving_object);
  });
  const StopCheck stop(pa.timeout);
  planning::ReplanOptions options;
  options.replan_period_s = pa.replan_period;
  options.sweeps = pa.replan_sweeps;
  options.on_replan = [&stop](const planning::ReplanStep& step) {
    Progress("re-plan at t = %.3f s: %d sweeps, %.1f ms", step.time_s, step.sweeps, step.wall_ms);
    stop.Poll();
  };
  planning::ReplanResult r;
  try {
    r = planning::RunReplanning(*scenario, pa.moving_object, path, options);
  } catch (const StopRequested& e) {
    return StoppedPlanExit(
        e, {{"scenario", scenario->name}, {"planner", "aico"}, {"moving_object", pa.moving_object}},
        pa, &out);
  }
  EndProgress();
  const planning::PlanReport rep = planning::ReplanReport(r);
  nlohmann::json report = planning::PlanReportJson(*scenario, rep, pa.seed);
  nlohmann::json replans = nlohmann::json::array();
  for (const planning::ReplanStep& step : r.replans) {
    replans.push_back(
        {{"time_s", step.time_s},
         {"object_position",
          {step.object_position.x(), step.object_position.y(), step.object_position.z()}},
         {"sweeps", step.sweeps},
         {"status", planning::StatusName(step.status)},
         {"cost", step.cost},
         {"cpu_ms", step.cpu_ms},
         {"wall_ms", step.wall_ms}});
  }
  report["replanning"] = {{"object", pa.moving_object},
                          {"object_path", pa.object_path},
                          {"count", r.replans.size()},
                          {"period_s", r.period_s},
                          {"sweeps", options.sweeps},
                          {"rate_hz", r.rate_hz},
                          {"wall_rate_hz", r.wall_rate_hz},
                          {"median_ms", r.median_cpu_ms},
                          {"max_ms", r.max_cpu_ms},
                          {"median_wall_ms", r.median_wall_ms},
                          {"max_wall_ms", r.max_wall_ms},
                          {"initial_solve_ms", r.initial_cpu_ms},
                          {"passed_through", r.passed_through},
                          {"replans", replans}};
  report["provenance"] = ProvenanceJson();
  const std::string dir = out.staging();
  base::WriteFileAtomic((fs::path(dir) / "trajectory.csv").string(),
                        planning::TrajectoryCsv(*scenario, r.executed));
  base::WriteFileAtomic((fs::path(dir) / "object_path.csv").string(), ObjectPositionsCsv(r));
  base::WriteFileAtomic((fs::path(dir) / "report.json").string(), report.dump(2) + "\n");
  if (pa.frames) {
    MovingObjectFrames moving;
    moving.object = r.object;
    moving.positions = r.object_positions;
    WritePlanFrames(
        *scenario, r.executed, dir,
        [&stop](const render::Image&, const render::Image*) { stop.Poll(); }, &moving,
        PlanFrameOptions{.stamp = !pa.no_stamp, .formats = pa.formats});
  }
  out.Commit();
  if (pa.json) {
    std::printf("%s\n", report.dump(2).c_str());
  } else {
    std::printf("%s\n", planning::PlanSummaryLine(*scenario, rep).c_str());
    std::printf(
        "re-planning: %zu re-plans every %.3f s, %.1f per CPU second, %.1f per wall second "
        "(median %.1f ms, max %.1f ms CPU), %s the %s\n",
        r.replans.size(), r.period_s, r.rate_hz, r.wall_rate_hz, r.median_cpu_ms, r.max_cpu_ms,
        r.passed_through ? "passed through" : "did not pass through", pa.moving_object.c_str());
    Note("wrote %s/trajectory.csv, %s/object_path.csv, %s/report.json", pa.output.c_str(),
         pa.output.c_str(), pa.output.c_str());
  }
  return r.success ? kExitOk : kExitFailed;
}

}  // namespace

void AddPlanCommands(CLI::App* root, CommandList* commands) {
  // plan ------------------------------------------------------------------------------------------
  auto pa = std::make_shared<PlanArgs>();
  CLI::App* plan = root->add_subcommand(
      "plan", "Plan a scenario with AICO (topology task variables) or an RRT baseline");
  plan->add_option("SCENARIO", pa->scenario,
                   "scenario JSON file, or a name in assets/scenarios/ (unwrap, unwrap_chord, "
                   "reach_through_ring, tinyarm_ring)")
      ->required();
  plan->add_option("--planner", pa->planner,
                   PlannerChoices() +
                       " (default aico; the OMPL peers need a build with "
                       "libompl-dev)")
      ->check(NonEmpty());
  plan->add_option("--seed", pa->seed, "seed of the RRTs' random generator (default 0)");
  plan->add_option("--start-wrap", pa->start_wrap,
                   "start coil of a coil-start scenario (unwrap): angle to unwrap in degrees")
      ->check(FiniteIn(0.0, 2000.0));
  plan->add_option("--aico-stop", pa->aico_stop, kAicoStopHelp)
      ->check(CLI::IsMember({"solved", "converged"}));
  plan->add_option("--geometry", pa->geometry,
                   "plan on the unwrap geometry of FILE (pole tilt, radius, translation, target "
                   "offset, arm; as bench unwrap --geometry; assets/scenarios/unwrap_geometries/)");
  AddTimeoutFlag(plan, &pa->timeout);
  plan->add_option("-o,--output", pa->output, "output folder")->required();
  AddRobotInputFlags(plan, &pa->robot_input, nullptr);
  plan->add_flag("--frames", pa->frames,
                 "also render DIR/frames/*.png, DIR/heatmaps/*.png (writhe per frame) and "
                 "DIR/writhe_cost.png");
  plan->add_flag("--no-stamp", pa->no_stamp,
                 "with --frames: no scenario name and time stamp in the frames' corner");
  plan->add_flag("--json", pa->json, "print report.json to stdout");
  plan->add_option("--moving-object", pa->moving_object,
                   "re-plan while this object of the scenario (e.g. ring, pole) follows "
                   "--object-path (AICO, receding horizon, warm-started)")
      ->check(NonEmpty());
  plan->add_option("--object-path", pa->object_path,
                   "CSV 't,x,y,z' (header, then seconds of plan time and the object's world "
                   "position in m; linear in between, held after the last row)")
      ->check(NonEmpty());
  plan->add_option("--replan-period", pa->replan_period,
                   "plan time between re-plans in seconds, rounded to whole time slices "
                   "(default 0.1)")
      ->check(NonEmpty());
  IntIn(plan->add_option("--replan-sweeps", pa->replan_sweeps,
                         "AICO sweep budget of each re-plan (default 3)"),
        1, 1000);
  AddFormatsFlag(plan, &pa->formats);
  plan->footer(
      "Writes DIR/trajectory.csv (step,time_s,<joints in robot order>) and DIR/report.json\n"
      "(planner, success, collision_checks, iterations, cost, time_s, start_writhe_total,\n"
      "final_writhe_total, min_clearance_m, ...). Exit codes: 0 success, 1 the planner failed\n"
      "(no path, collision, goal not met), 2 bad scenario/flags, 3 no GL context for --frames.\n"
      "With --moving-object NAME --object-path FILE the arm executes its plan while the object\n"
      "moves; every --replan-period AICO re-plans from the current state, warm-started with the\n"
      "previous plan shifted. trajectory.csv is the executed motion, DIR/object_path.csv the\n"
      "object per step, report.json gains \"replanning\": {count, rate_hz (re-plans per CPU\n"
      "second), wall_rate_hz (per wall second), median_ms, max_ms (CPU), median_wall_ms,\n"
      "max_wall_ms, passed_through, ...}; --frames shows the object moving.");
  commands->push_back(
      {plan, [pa, plan]() {
         planning::ScenarioOverrides overrides;
         if (!std::isnan(pa->start_wrap)) overrides.start_wrap_deg = pa->start_wrap;
         overrides.stop_when_solved = ParseAicoStop(pa->aico_stop);
         const planning::Planner planner =
             ParseFlag("--planner", [&] { return planning::ParsePlanner(pa->planner); });
         overrides.package_paths = planning::PackagePaths(pa->robot_input.package_paths);
         overrides.srdf = pa->robot_input.srdf;
         if (plan->count("--geometry") > 0) {
           if (pa->geometry.empty()) throw std::invalid_argument("--geometry: empty path");
           overrides.geometry = pa->geometry;
         }
         if (!pa->moving_object.empty() || !pa->object_path.empty()) {
           return RunMovingObjectPlan(*pa, overrides, planner);
         }
         OutputDir out(pa->output, "-o", "plan", PlanInputs(*pa));  // checked before any work
         const StopCheck stop(pa->timeout);
         const auto scenario = planning::LoadScenarioArg(pa->scenario, overrides);
         ReportWarnings(scenario->warnings);
         Detail("scenario %s from %s; robot %s (%d joints); planner %s, seed %u; output %s",
                scenario->name.c_str(), scenario->source.c_str(), scenario->robot.name.c_str(),
                planning::num_dofs(scenario->robot), planning::PlannerName(planner), pa->seed,
                pa->output.c_str());
         planning::PlanResult result;
         try {
           result = planning::RunPlanner(
               *scenario, planner, pa->seed,
               [&stop](int sweep, double cost, bool accepted, const planning::Trajectory&) {
                 Progress("sweep %3d  cost %-12.6g %s", sweep, cost,
                          accepted ? "accepted" : "rejected");
                 stop.Poll();
               },
               [&stop] { stop.Poll(); });
         } catch (const StopRequested& e) {
           return StoppedPlanExit(
               e,
               {{"scenario", scenario->name},
                {"planner", planning::PlannerName(planner)},
                {"seed", pa->seed},
                {"attempts", 1},
                {"failure_reason", e.timeout ? "budget_exhausted" : "interrupted"}},
               *pa, &out);
         }
         if (planning::IsAico(planner)) EndProgress();
         const nlohmann::json report = WritePlanOutputs(*scenario, result, pa->seed, out.staging());
         std::string frames_note;
         if (pa->frames && result.trajectory.num_points() > 0) {
           const PlanFrames frames = WritePlanFrames(
               *scenario, result.trajectory, out.staging(),
               [&stop](const render::Image&, const render::Image*) { stop.Poll(); }, nullptr,
               PlanFrameOptions{.stamp = !pa->no_stamp, .formats = pa->formats});
           // Named in the output folder, never in the staging area (gone after Commit).
           frames_note = ", " + pa->output + "/frames/ (" + std::to_string(frames.labels.size()) +
                         " frames" + (frames.frames.video.empty() ? "" : ", movie") + ")";
         }
         out.Commit();
         if (pa->json) {
           std::printf("%s\n", report.dump(2).c_str());
         } else {
           std::printf("%s\n", planning::PlanSummaryLine(*scenario, result.report).c_str());
           Note("wrote %s/trajectory.csv, %s/report.json%s", pa->output.c_str(), pa->output.c_str(),
                frames_note.c_str());
         }
         return result.report.success ? kExitOk : kExitFailed;
       }});

  AddBenchCommands(root, commands);  // bench unwrap (cmd_bench.cc)
}

}  // namespace app
