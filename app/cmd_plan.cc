// `topoplan plan` (AICO / RRT / BiRRT on a scenario, with trajectory, report and optional frames)
// and `topoplan bench unwrap` (thesis Fig. 4.5: collision checks vs angle to unwrap).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/assets.h"
#include "app/command.h"
#include "app/io.h"
#include "app/reports.h"
#include "app/robot_scene.h"
#include "planning/planner.h"
#include "planning/scenario.h"
#include "planning/unwrap_benchmark.h"
#include "render/image.h"

namespace app {
namespace {

namespace fs = std::filesystem;

struct PlanArgs {
  std::string scenario, planner = "aico", output;
  unsigned seed = 0;
  double start_wrap = std::numeric_limits<double>::quiet_NaN();  // NaN: not given
  double timeout = 0.0;
  bool frames = false, json = false;
  RobotInputOptions robot_input;  // --package-path, --srdf
};

struct BenchArgs {
  std::string angles = "0:900:90", planners = "aico,rrt,birrt", output;
  int seeds = 3;
  long budget = -1;
  double perturb = 0.0;
  double timeout = 0.0;
};

// Largest number of angles in --angles.
constexpr int kMaxAngles = 10000;

// "a:b:step" → a, a+step, ..., ≤ b.
std::vector<double> ParseRange(const std::string& text, const std::string& flag) {
  const std::vector<double> v = [&] {
    std::string t = text;
    for (char& c : t) {
      if (c == ':') c = ',';
    }
    return ParseNumberList(t, flag, 3);
  }();
  if (!(v[2] > 0.0) || !(v[1] >= v[0]) || !(v[0] >= 0.0) || !(v[1] <= 2000.0)) {
    throw std::invalid_argument(flag + ": expected a:b:step with 0 <= a <= b <= 2000, step > 0");
  }
  // The count is computed (and bounded) first: a tiny step must not loop for ever.
  const double count = std::floor((v[1] - v[0]) / v[2] + 1e-9) + 1.0;
  if (count > kMaxAngles) {
    throw std::invalid_argument(flag + ": more than " + std::to_string(kMaxAngles) +
                                " angles (use a larger step)");
  }
  std::vector<double> out;
  for (int i = 0; i < static_cast<int>(count); ++i) out.push_back(v[0] + i * v[2]);
  return out;
}

// "aico | rrt | birrt ..." from the planner registry of this build.
std::string PlannerChoices() {
  std::string out;
  for (planning::Planner p : planning::AvailablePlanners()) {
    out += (out.empty() ? "" : " | ") + std::string(planning::PlannerName(p));
  }
  return out;
}

std::vector<planning::Planner> ParsePlanners(const std::string& text) {
  std::vector<planning::Planner> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    out.push_back(ParseFlag("--planners", [&] { return planning::ParsePlanner(item); }));
  }
  if (out.empty()) throw std::invalid_argument("--planners: empty list");
  return out;
}

void ProgressBar(int done, int total, const std::string& what) {
  const int width = 30;
  const int filled = total > 0 ? done * width / total : width;
  std::fprintf(stderr, "\r[%s%s] %d/%d %s   ", std::string(filled, '#').c_str(),
               std::string(width - filled, '.').c_str(), done, total, what.c_str());
  if (done == total) std::fprintf(stderr, "\n");
}

}  // namespace

void AddPlanCommands(CLI::App* root, CommandList* commands) {
  // plan ------------------------------------------------------------------------------------------
  auto pa = std::make_shared<PlanArgs>();
  CLI::App* plan = root->add_subcommand(
      "plan", "Plan a scenario with AICO (topology task variables) or an RRT baseline");
  plan->add_option("SCENARIO", pa->scenario,
                   "scenario JSON file, or a name in assets/scenarios/ (unwrap, "
                   "reach_through_ring)")
      ->required();
  plan->add_option("--planner", pa->planner,
                   PlannerChoices() +
                       " (default aico; the OMPL peers need a build with "
                       "libompl-dev)");
  plan->add_option("--seed", pa->seed, "seed of the RRTs' random generator (default 0)");
  plan->add_option("--start-wrap", pa->start_wrap,
                   "start coil of a coil-start scenario (unwrap): angle to unwrap in degrees")
      ->check(FiniteIn(0.0, 2000.0));
  AddTimeoutFlag(plan, &pa->timeout);
  plan->add_option("-o,--output", pa->output, "output folder")->required();
  AddRobotInputFlags(plan, &pa->robot_input, nullptr);
  plan->add_flag("--frames", pa->frames,
                 "also render DIR/frames/*.png, DIR/heatmaps/*.png (writhe per frame) and "
                 "DIR/writhe_cost.png");
  plan->add_flag("--json", pa->json, "print report.json to stdout");
  plan->footer(
      "Writes DIR/trajectory.csv (step,time_s,<joints in robot order>) and DIR/report.json\n"
      "(planner, success, collision_checks, iterations, cost, time_s, start_writhe_total,\n"
      "final_writhe_total, min_clearance_m, ...). Exit codes: 0 success, 1 the planner failed\n"
      "(no path, collision, goal not met), 2 bad scenario/flags, 3 no GL context for --frames.");
  commands->push_back(
      {plan, [pa]() {
         planning::ScenarioOverrides overrides;
         if (!std::isnan(pa->start_wrap)) overrides.start_wrap_deg = pa->start_wrap;
         const planning::Planner planner =
             ParseFlag("--planner", [&] { return planning::ParsePlanner(pa->planner); });
         overrides.package_paths = PackagePaths(pa->robot_input.package_paths);
         overrides.srdf = pa->robot_input.srdf;
         OutputDir out(pa->output, "-o");  // checked before any work
         const StopCheck stop(pa->timeout);
         const auto scenario = LoadScenarioArg(pa->scenario, overrides);
         planning::PlanResult result;
         try {
           result = planning::RunPlanner(
               *scenario, planner, pa->seed,
               [&stop](int sweep, double cost, bool accepted, const planning::Trajectory&) {
                 std::fprintf(stderr, "\rsweep %3d  cost %-12.6g %s", sweep, cost,
                              accepted ? "accepted" : "rejected");
                 stop.Poll();
               },
               [&stop] { stop.Poll(); });
         } catch (const StopRequested& e) {
           const nlohmann::json report =
               StoppedReportJson(e, {{"scenario", scenario->name},
                                     {"planner", planning::PlannerName(planner)},
                                     {"seed", pa->seed}});
           WriteFileAtomic((fs::path(out.staging()) / "report.json").string(),
                           report.dump(2) + "\n");
           out.Commit();
           std::fprintf(stderr, "\n%s: wrote %s/report.json\n", e.what(), pa->output.c_str());
           if (pa->json) std::printf("%s\n", report.dump(2).c_str());
           return e.timeout ? kExitFailed : kExitInterrupted;
         }
         if (planner == planning::Planner::kAico) std::fprintf(stderr, "\n");
         const nlohmann::json report = WritePlanOutputs(*scenario, result, pa->seed, out.staging());
         if (pa->frames && result.trajectory.num_points() > 0) {
           WritePlanFrames(*scenario, result.trajectory, out.staging(),
                           [&stop](const render::Image&, const render::Image*) { stop.Poll(); });
         }
         out.Commit();
         if (pa->json) {
           std::printf("%s\n", report.dump(2).c_str());
         } else {
           std::printf("%s\n", PlanSummaryLine(*scenario, result.report).c_str());
           std::printf("wrote %s/trajectory.csv, %s/report.json\n", pa->output.c_str(),
                       pa->output.c_str());
         }
         return result.report.success ? kExitOk : kExitFailed;
       }});

  // bench unwrap ----------------------------------------------------------------------------------
  CLI::App* bench = root->add_subcommand("bench", "Benchmarks that reproduce thesis figures");
  bench->require_subcommand(1);
  auto ba = std::make_shared<BenchArgs>();
  CLI::App* unwrap = bench->add_subcommand(
      "unwrap", "Thesis Fig. 4.5: collision checks vs angle to unwrap, AICO vs RRT vs BiRRT");
  unwrap->add_option("--angles", ba->angles, "start wraps a:b:step in degrees (default 0:900:90)");
  unwrap->add_option("--seeds", ba->seeds, "runs per angle and planner, seeds 0..N-1 (default 3)")
      ->check(CLI::Range(1, 1000));
  unwrap->add_option("--planners", ba->planners,
                     "comma-separated subset of aico,rrt,birrt,ompl-rrt,ompl-rrtconnect");
  unwrap
      ->add_option("--budget", ba->budget,
                   "collision-check budget of the RRTs (default: the scenario's, 100000)")
      ->check(CLI::Range(1L, 1000000000L));
  unwrap->add_option("--perturb", ba->perturb,
                     "move the pole of each seed by a random offset of at most M metres "
                     "perpendicular to its axis (seeded, reproducible; default 0)");
  AddTimeoutFlag(unwrap, &ba->timeout);
  unwrap->add_option("-o,--output", ba->output, "output folder")->required();
  unwrap->footer(
      "Writes DIR/unwrap.csv (angle_deg,planner,seed,success,failure_reason,collision_checks,\n"
      "narrow_phase_calls,time_s,path_length,reach_error_m,pole_offset_m) and\n"
      "DIR/unwrap.png (mean collision checks of successful runs vs angle, log scale, one curve\n"
      "per planner, x markers where a run failed). time_s is wall-clock; everything else is\n"
      "deterministic. Exit 0 when the benchmark ran (failed runs are data, not errors).");
  commands->push_back(
      {unwrap, [ba]() {
         planning::UnwrapBenchmarkOptions options;
         options.angles_deg = ParseRange(ba->angles, "--angles");
         options.planners = ParsePlanners(ba->planners);
         options.scenario_path = ResolveScenarioPath("unwrap");
         options.search_roots = {AssetRoot()};
         options.seeds = ba->seeds;
         options.rrt_budget = ba->budget;
         if (!(ba->perturb >= 0.0) || !std::isfinite(ba->perturb)) {
           throw std::invalid_argument("--perturb: expected a finite distance >= 0 in metres");
         }
         options.perturb_m = ba->perturb;
         OutputDir out(ba->output, "-o");  // checked before any work
         const StopCheck stop(ba->timeout);
         planning::UnwrapBenchmarkResult finished;  // the runs completed so far
         options.progress = [&](int done, int total, const planning::UnwrapRun& run) {
           char what[96];
           std::snprintf(what, sizeof(what), "%s @ %.0f deg seed %d",
                         planning::PlannerName(run.planner), run.angle_deg, run.seed);
           ProgressBar(done, total, what);
           finished.runs.push_back(run);
           stop.Poll();
         };
         const int total =
             static_cast<int>(options.angles_deg.size() * options.planners.size()) * ba->seeds;
         ProgressBar(0, total, "");
         planning::UnwrapBenchmarkResult result;
         try {
           result = planning::RunUnwrapBenchmark(options);
         } catch (const StopRequested& e) {
           // Keep the finished rows: unwrap.csv only (no figure of a partial sweep).
           WriteFileAtomic((fs::path(out.staging()) / "unwrap.csv").string(), UnwrapCsv(finished));
           out.Commit();
           std::fprintf(stderr, "\n%s: wrote %s/unwrap.csv (%zu of %d runs)\n", e.what(),
                        ba->output.c_str(), finished.runs.size(), total);
           return e.timeout ? kExitFailed : kExitInterrupted;
         }
         WriteFileAtomic((fs::path(out.staging()) / "unwrap.csv").string(), UnwrapCsv(result));
         if (const auto figure = UnwrapFigure(result)) {
           render::WritePng((fs::path(out.staging()) / "unwrap.png").string(), *figure);
         }
         out.Commit();
         std::printf("wrote %s/unwrap.csv and %s/unwrap.png (%d runs)\n", ba->output.c_str(),
                     ba->output.c_str(), total);
         return kExitOk;
       }});
}

}  // namespace app
