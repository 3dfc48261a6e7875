// `topoplan bench unwrap`: thesis Fig. 4.5 (state queries, pair tests and time to unwrap an arm
// coiled around a pole, per planner), its budget-free survival verdicts and the AICO ablations.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <tuple>

#include "app/cli/command.h"
#include "app/cli/figure_flags.h"
#include "app/cli/io.h"
#include "app/present/ompl_log.h"
#include "base/assets.h"
#include "base/numbers.h"
#include "base/version.h"
#include "planning/motion/planner.h"
#include "planning/motion/report.h"
#include "planning/motion/scenario_spec.h"
#include "planning/motion/unwrap_benchmark.h"
#include "render/figure.h"
#include "visualize/figures.h"
#include "visualize/report_figures.h"
#include "visualize/unwrap_figures.h"

namespace app {
namespace {

namespace fs = std::filesystem;

struct BenchArgs {
  std::string angles = "0:900:90", planners, output;  // planners "": DefaultPlanners()
  int seeds = 3;
  std::string budget;     // --budget time=S|queries=N ("": the scenario's limits)
  bool survival = false;  // --survival: budget sweep verdicts (survival.csv, survival.png)
  bool ablation = false;  // --ablation: AICO with each task term removed (ablation.csv/.png)
  double perturb = 0.0;
  std::string geometry;   // --geometry FILE ("": the shipped scene)
  std::string scenario;   // --scenario FILE ("": the shipped unwrap.json)
  std::string aico_stop;  // --aico-stop solved|converged ("": the scenario's)
  double timeout = 0.0;
  std::string
      ompl_log;  // --ompl-log FILE: OMPL benchmark logs, one per angle (app/present/ompl_log.h)
  std::vector<render::FigureFormat> formats;  // --formats
};

// --survival without --budget: every planner runs up to this many state queries.
constexpr double kSurvivalQueries = 1e6;
// The survival sweep: budgets from kSurvivalLow state queries (and 1 ms CPU) to the run budget.
constexpr double kSurvivalLow = 100.0;
constexpr int kSurvivalPoints = 41;

// Largest number of angles in --angles.
constexpr int kMaxAngles = 10000;
// Largest number of runs of one `bench unwrap` (angles × planners × seeds).
constexpr long kMaxBenchRuns = 1000000;
// Largest --perturb: the pole moved by more than a metre leaves the scene.
constexpr double kMaxPerturbM = 1.0;

// "1 run", "3 runs".
std::string RunCount(size_t runs) { return std::to_string(runs) + (runs == 1 ? " run" : " runs"); }

// "a:b:step" → a, a+step, ..., ≤ b.
std::vector<double> ParseRange(const std::string& text, const std::string& flag) {
  const std::vector<double> v = [&] {
    if (std::count(text.begin(), text.end(), ':') != 2 || text.find(',') != std::string::npos) {
      throw std::invalid_argument(
          flag + ": expected a:b:step (three numbers separated by ':'), got '" + text + "'");
    }
    std::string t = text;
    std::replace(t.begin(), t.end(), ':', ',');
    return base::ParseNumberList(t, flag, 3);
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

// "aico,birrt" → the planners, each at most once; "" → planning::DefaultPlanners() (with the OMPL
// peers when the build has them, but not the OMPL goal-region peers).
std::vector<planning::Planner> ParsePlanners(const std::string& text) {
  if (text.empty()) return planning::DefaultPlanners();
  std::vector<planning::Planner> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const planning::Planner p =
        ParseFlag("--planners", [&] { return planning::ParsePlanner(item); });
    if (std::find(out.begin(), out.end(), p) != out.end()) {
      throw std::invalid_argument("--planners: '" + item + "' is listed twice");
    }
    out.push_back(p);
  }
  if (out.empty() || text.back() == ',') {
    throw std::invalid_argument("--planners: empty name in '" + text + "'");
  }
  return out;
}

// The header of the OMPL logs of `bench unwrap`: this host, the start time (UTC) and the options.
OmplLogInfo BenchLogInfo(const planning::UnwrapBenchmarkOptions& options) {
  OmplLogInfo info;
  info.version = base::Version();
  char host[256] = {};
  if (gethostname(host, sizeof host - 1) == 0 && host[0] != '\0') info.host = host;
  for (char& c : info.host) {
    if (c == ' ') c = '_';
  }
  const std::time_t now = std::time(nullptr);
  char stamp[32];
  std::tm utc{};
  gmtime_r(&now, &utc);
  std::strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%S", &utc);
  info.start_time = stamp;
  std::ostringstream setup;
  setup << "topoplan bench unwrap: thesis Fig. 4.5, collision checks to unwrap an arm coiled "
           "around a pole\nscenario "
        << options.scenario_path << "\nplanners";
  for (planning::Planner p : options.planners) setup << " " << planning::PlannerName(p);
  setup << "\nseeds 0.." << options.seeds - 1 << "\nrrt collision-check budget "
        << (options.rrt_budget > 0 ? std::to_string(options.rrt_budget) : "of the scenario")
        << "\npole perturbation " << options.perturb_m
        << " m\nno wall-time or memory limit per run (the planners stop at their budget)\n";
  info.setup = setup.str();
  info.rrt_budget = options.rrt_budget;
  info.budget = planning::BudgetText(options.budget);
  info.perturb_m = options.perturb_m;
  return info;
}

void ProgressBar(int done, int total, const std::string& what) {
  const int width = 30;
  const int filled = total > 0 ? done * width / total : width;
  Progress("[%s%s] %d/%d %s", std::string(filled, '#').c_str(),
           std::string(width - filled, '.').c_str(), done, total, what.c_str());
  if (done == total) EndProgress();
}

// Prints each set-up warning of `run` once per angle and seed ("topoplan: warning: at 720 deg
// (seed 0): ..."); `printed` holds the ones already printed.
void WarnOnce(const planning::UnwrapRun& run, std::set<std::string>* printed) {
  for (const std::string& text : run.setup_warnings) {
    char where[64];
    std::snprintf(where, sizeof(where),
                  "at %s deg (seed %d): ", base::FormatShortest(run.angle_deg).c_str(), run.seed);
    const std::string line = where + text;
    if (!printed->insert(line).second) continue;
    EndProgress();  // off the progress bar's line (a terminal's)
    std::fprintf(stderr, "topoplan: warning: %s\n", line.c_str());
  }
}

// DIR/survival.csv and DIR/survival.png of a sweep run at `budget`: state queries and pair tests
// from kSurvivalLow to the budget in that unit (or the most any run spent), CPU seconds from 1 ms
// to the time budget (or the most any run spent).
void WriteSurvival(const planning::UnwrapBenchmarkResult& result, const planning::Budget& budget,
                   const std::string& dir, const std::vector<render::FigureFormat>& formats) {
  using Unit = planning::Budget::Unit;
  double max_queries = kSurvivalLow * 10.0, max_pairs = kSurvivalLow * 10.0, max_cpu = 0.01;
  for (const planning::UnwrapRun& r : result.runs) {
    max_queries = std::max(max_queries, static_cast<double>(r.report.counts.state_queries));
    max_pairs = std::max(max_pairs, static_cast<double>(r.report.counts.pair_tests()));
    max_cpu = std::max(max_cpu, r.report.cpu_time_s);
  }
  if (budget.unit == Unit::kQueries) max_queries = std::max(budget.value, kSurvivalLow * 10.0);
  if (budget.unit == Unit::kPairTests) max_pairs = std::max(budget.value, kSurvivalLow * 10.0);
  if (budget.unit == Unit::kCpuTime) max_cpu = std::max(budget.value, 0.002);
  std::vector<planning::UnwrapSurvivalPoint> points;
  for (const auto& [unit, lo, hi] : {std::tuple{Unit::kQueries, kSurvivalLow, max_queries},
                                     std::tuple{Unit::kPairTests, kSurvivalLow, max_pairs},
                                     std::tuple{Unit::kCpuTime, 1e-3, max_cpu}}) {
    const std::vector<planning::UnwrapSurvivalPoint> p =
        planning::UnwrapSurvival(result, unit, planning::LogBudgets(lo, hi, kSurvivalPoints));
    points.insert(points.end(), p.begin(), p.end());
  }
  base::WriteFileAtomic((fs::path(dir) / "survival.csv").string(),
                        planning::UnwrapSurvivalCsv(points));
  const render::Figure figure = visualize::UnwrapSurvivalFigure(result, points);
  const std::string png = (fs::path(dir) / "survival.png").string();
  render::WriteFigure(png, figure);
  visualize::WriteVectorFormats(png, figure, formats);
}

// `bench unwrap --ablation`: AICO variants, DIR/ablation.csv and DIR/ablation.png; stopped early
// (--timeout, SIGINT/SIGTERM): the finished rows in DIR/ablation.partial.csv.
ExitCode RunAblation(planning::UnwrapBenchmarkOptions options, const std::string& output,
                     const std::vector<render::FigureFormat>& formats, const StopCheck& stop,
                     OutputDir* out) {
  planning::UnwrapBenchmarkResult finished;  // the runs completed so far
  std::set<std::string> warned;
  options.progress = [&](int done, int total, const planning::UnwrapRun& run) {
    char what[96];
    std::snprintf(what, sizeof(what), "%s @ %.0f deg seed %d", run.variant.c_str(), run.angle_deg,
                  run.seed);
    WarnOnce(run, &warned);
    ProgressBar(done, total, what);
    finished.runs.push_back(run);
    if (done < total) stop.Poll();
  };
  std::vector<planning::UnwrapAblation> ablations;
  planning::UnwrapBenchmarkResult result;
  try {
    result = planning::RunUnwrapAblation(options, &ablations);
  } catch (const StopRequested& e) {
    base::WriteFileAtomic((fs::path(out->staging()) / "ablation.partial.csv").string(),
                          planning::UnwrapAblationCsv(finished));
    out->Commit(/*replace_previous=*/false);
    std::fprintf(stderr, "\n%s: wrote %s/ablation.partial.csv (%s)\n", e.what(), output.c_str(),
                 RunCount(finished.runs.size()).c_str());
    return e.timeout ? kExitFailed : kExitInterrupted;
  }
  base::WriteFileAtomic((fs::path(out->staging()) / "ablation.csv").string(),
                        planning::UnwrapAblationCsv(result));
  if (options.geometry) {  // its planner column names the variant
    base::WriteFileAtomic((fs::path(out->staging()) / "geometry.csv").string(),
                          planning::UnwrapGeometryCsv(*options.geometry, result));
  }
  const render::Figure figure = visualize::UnwrapAblationFigure(result, ablations);
  const std::string png = (fs::path(out->staging()) / "ablation.png").string();
  render::WriteFigure(png, figure);
  visualize::WriteVectorFormats(png, figure, formats);
  out->Commit();
  const std::string geometry_csv = options.geometry ? ", " + output + "/geometry.csv" : "";
  Note("wrote %s/ablation.csv%s and %s/ablation.png (%s, %zu variants)", output.c_str(),
       geometry_csv.c_str(), output.c_str(), RunCount(result.runs.size()).c_str(),
       ablations.size());
  return kExitOk;
}

}  // namespace

void AddBenchCommands(CLI::App* root, CommandList* commands) {
  // bench unwrap ----------------------------------------------------------------------------------
  CLI::App* bench = root->add_subcommand("bench", "Benchmarks that reproduce thesis figures");
  bench->require_subcommand(1);
  auto ba = std::make_shared<BenchArgs>();
  CLI::App* unwrap = bench->add_subcommand(
      "unwrap", "Thesis Fig. 4.5: collision checks vs angle to unwrap, AICO vs RRT vs BiRRT");
  unwrap->add_option("--angles", ba->angles, "start wraps a:b:step in degrees (default 0:900:90)");
  IntIn(unwrap->add_option("--seeds", ba->seeds,
                           "runs per angle and planner, seeds 0..N-1 (default 3)"),
        1, 1000);
  unwrap
      ->add_option(
          "--planners", ba->planners,
          "comma-separated planners, each at most once: " + PlannerChoices() + " (default: " +
              [] {
                std::string c;
                for (const planning::Planner p : planning::DefaultPlanners()) {
                  c.append(c.empty() ? "" : ",").append(planning::PlannerName(p));
                }
                return c;
              }() +
              "; the OMPL goal-region peers only by name)")
      ->check(NonEmpty());
  unwrap
      ->add_option("--budget", ba->budget,
                   "every planner's budget: time=S (CPU seconds of the solve) or queries=N "
                   "(state queries) or pairs=N (pair tests); a bare N: the RRTs' collision-check "
                   "budget only (as "
                   "before); default: the scenario's limits (RRTs 100000 checks, AICO its "
                   "sweeps); with --survival default queries=1000000")
      ->check(NonEmpty());
  unwrap->add_flag(
      "--survival", ba->survival,
      "budget-free verdicts: also write DIR/survival.csv and DIR/survival.png (fraction "
      "solved within each budget of a log sweep, per planner and angle)");
  unwrap->add_flag("--ablation", ba->ablation,
                   "run AICO with each task term removed in turn (writhe, reach, off-pole, winding "
                   "guard, rollout, and the retries when the scenario has them) instead of the "
                   "planners: DIR/ablation.csv, DIR/ablation.png");
  unwrap
      ->add_option("--pole-offset", ba->perturb,
                   "move the pole of each seed by a random offset of at most M metres "
                   "perpendicular to its axis (seeded, reproducible; 0 <= M <= 1, default 0)")
      ->check(NonEmpty());
  AddDeprecatedAlias(unwrap, "--perturb", "--pole-offset", &ba->perturb)->check(NonEmpty());
  unwrap->add_option("--geometry", ba->geometry,
                     "run on the geometry of FILE (pole tilt, radius, translation, target offset, "
                     "arm; planning/motion/unwrap_geometry.h) with the scenario's parameters "
                     "unchanged; also writes DIR/geometry.csv");
  unwrap
      ->add_option("--scenario", ba->scenario,
                   "the unwrap scenario to run, a file or a name in assets/scenarios/ such as "
                   "unwrap_chord (a coil start \"start_wrap_deg\" and a writhe_report pair; "
                   "default: the shipped assets/scenarios/unwrap.json)")
      ->check(NonEmpty());
  unwrap->add_option("--aico-stop", ba->aico_stop, kAicoStopHelp)
      ->check(CLI::IsMember({"solved", "converged"}));
  AddTimeoutFlag(unwrap, &ba->timeout);
  unwrap->add_option("--ompl-log", ba->ompl_log,
                     "also write OMPL benchmark logs (ompl_benchmark_statistics.py, Planner "
                     "Arena): FILE_<angle>deg.log, one experiment per angle");
  unwrap->add_option("-o,--output", ba->output, "output folder")->required();
  AddFormatsFlag(unwrap, &ba->formats);
  unwrap->footer(
      "Writes DIR/unwrap.csv (angle_deg,planner,seed,success,failure_reason,collision_checks,\n"
      "narrow_phase_calls,time_s,path_length,reach_error_m,pole_offset_m,state_queries,\n"
      "bool_pair_tests,distance_pair_tests,cpu_time_s,setup_time_s,goal_samples,\n"
      "goal_sampler_state_queries,goal_sampler_pair_tests,goal_sampler_cpu_time_s: the goal\n"
      "sampler's share of the goal-region planners' totals, 0 for the others) and DIR/unwrap.png "
      "(three\n"
      "panels over the angle, log scale: collision checks, narrow-phase calls, wall time; median\n"
      "and interquartile band over the seeds, one colour per planner, crosses where a run\n"
      "failed; --formats adds unwrap.svg/.pdf). Cost units (docs/results/unwrap.md): a state\n"
      "query is one configuration evaluated against the world, pair tests are narrow-phase pair\n"
      "evaluations (boolean and distance apart), counted the same way for every planner.\n"
      "time_s, cpu_time_s and setup_time_s are measured; everything else is deterministic.\n"
      "Exit 0 when the benchmark ran (failed runs are data, not errors).\n"
      "--survival: DIR/survival.csv (unit,budget,planner,angle_deg,runs,solved,fraction,\n"
      "failed_budget,failed_other) and DIR/survival.png (per planner, fraction solved against\n"
      "state queries, pair tests and CPU seconds, one curve per angle; failed_budget counts\n"
      "the failures that stopped at the budget, failed_other those no budget solves).\n"
      "--ablation: DIR/ablation.csv (angle_deg,ablation,seed,success,failure_reason,\n"
      "final_writhe_total,reach_error_m,final_winding_turns,state_queries,cpu_time_s) and\n"
      "DIR/ablation.png (success, |final writhe| and reach error per angle and ablation).\n"
      "--ompl-log FILE: FILE with _<angle>deg before its extension per angle, in OMPL's\n"
      "benchmark log format (one planner per topoplan planner, one run per seed).\n"
      "--geometry FILE: DIR/geometry.csv (geometry,split,angle_deg,planner,seed,start_wrap_deg,\n"
      "start_closed_wrap_deg,success,failure_reason,final_writhe_total,reach_error_m,\n"
      "final_winding_turns,unwound_winding_turns,goal_meets_end_conditions,state_queries,\n"
      "cpu_time_s,setup_time_s,jumps_through_object,jumps_beyond_ends,jumps_unlocated):\n"
      "start_wrap_deg is the coil the start reached (360 deg x |writhe|);\n"
      "start_closed_wrap_deg the same for the arm closed by its chord (hand back to base): the\n"
      "loops it makes round the pole; unwound_winding_turns the winding of the\n"
      "segment base -> target about the pole's line (about where an arm that does not wrap the\n"
      "pole ends); goal_meets_end_conditions whether the set-up's goal (the RRTs') meets the\n"
      "criterion's end conditions; the jumps count the resampled steps whose winding jumps by\n"
      "at least the criterion's max_jump, by where the arm passes the pole's line: through the\n"
      "pole, only beyond its ends, or not located. With --ablation too, its planner column\n"
      "naming the AICO variant.\n"
      "Shipped geometries: assets/scenarios/unwrap_geometries/ (README.md there).");
  commands->push_back(
      {unwrap, [ba, unwrap]() {
         planning::UnwrapBenchmarkOptions options;
         options.angles_deg = ParseRange(ba->angles, "--angles");
         options.planners = ParsePlanners(ba->planners);
         options.scenario_path = base::ResolveScenarioPath(
             ba->scenario.empty() ? "unwrap" : ba->scenario, "--scenario");
         options.search_roots = {base::AssetRoot()};
         options.seeds = ba->seeds;
         if (!ba->budget.empty()) {
           const planning::Budget b = planning::ParseBudget(ba->budget, "--budget");
           // A bare N keeps its earlier meaning: the RRTs' collision-check budget only.
           if (ba->budget.find('=') == std::string::npos) {
             options.rrt_budget = static_cast<long>(b.value);
           } else {
             options.budget = b;
           }
         } else if (ba->survival) {
           options.budget = {planning::Budget::Unit::kQueries, kSurvivalQueries};
         }
         if (ba->ablation &&
             (ba->survival || unwrap->count("--ompl-log") > 0 || unwrap->count("--planners") > 0)) {
           throw std::invalid_argument(
               "--ablation: runs AICO variants only (no --planners, --survival or --ompl-log)");
         }
         if (!(ba->perturb >= 0.0 && ba->perturb <= kMaxPerturbM)) {
           throw std::invalid_argument("--pole-offset: expected a distance in metres in [0, 1]");
         }
         // Runs per angle and seed: the planners, or with --ablation the AICO variants.
         const size_t per_angle =
             ba->ablation
                 ? planning::UnwrapAblations(planning::ParseScenarioSpec(options.scenario_path))
                       .size()
                 : options.planners.size();
         const long runs = static_cast<long>(options.angles_deg.size()) *
                           static_cast<long>(per_angle) * ba->seeds;
         if (runs > kMaxBenchRuns) {
           throw std::invalid_argument("--seeds: " + std::to_string(runs) + " runs (angles x " +
                                       (ba->ablation ? "ablation variants" : "planners") +
                                       " x seeds), more than " + std::to_string(kMaxBenchRuns));
         }
         options.perturb_m = ba->perturb;
         options.aico_stop_when_solved = ParseAicoStop(ba->aico_stop);
         std::vector<std::string> inputs = {options.scenario_path};
         if (unwrap->count("--geometry") > 0) {
           if (ba->geometry.empty()) throw std::invalid_argument("--geometry: empty path");
           options.geometry = planning::ReadUnwrapGeometry(ba->geometry, {base::AssetRoot()});
           inputs.push_back(ba->geometry);
         }
         OutputDir out(ba->output, "-o", "bench unwrap", inputs);
         const bool ompl_log = unwrap->count("--ompl-log") > 0;  // "" is refused, not ignored
         OmplLogInfo log_info;
         if (ompl_log) {
           if (ba->ompl_log.empty()) throw std::invalid_argument("--ompl-log: empty output path");
           for (double angle : options.angles_deg) {  // each log file, before any work
             base::CheckOutputFile(OmplLogPath(ba->ompl_log, angle), "--ompl-log",
                                   {options.scenario_path});
           }
           log_info = BenchLogInfo(options);
         }
         const StopCheck stop(ba->timeout);
         planning::UnwrapBenchmarkResult finished;  // the runs completed so far
         std::set<std::string> warned;
         options.progress = [&](int done, int total, const planning::UnwrapRun& run) {
           char what[96];
           std::snprintf(what, sizeof(what), "%s @ %.0f deg seed %d",
                         planning::PlannerName(run.planner), run.angle_deg, run.seed);
           WarnOnce(run, &warned);
           ProgressBar(done, total, what);
           finished.runs.push_back(run);
           if (done < total) stop.Poll();  // after the last run the sweep is complete
         };
         if (ba->ablation) return RunAblation(options, ba->output, ba->formats, stop, &out);
         const int total = static_cast<int>(runs);
         ProgressBar(0, total, "");
         planning::UnwrapBenchmarkResult result;
         try {
           result = planning::RunUnwrapBenchmark(options);
         } catch (const StopRequested& e) {
           // Keep the finished rows under a name that says so (no figure of a partial sweep);
           // unwrap.csv and unwrap.png of an earlier complete run in DIR stay as they were.
           base::WriteFileAtomic((fs::path(out.staging()) / "unwrap.partial.csv").string(),
                                 planning::UnwrapCsv(finished));
           out.Commit(/*replace_previous=*/false);
           std::fprintf(stderr, "\n%s: wrote %s/unwrap.partial.csv (%zu of %d runs)\n", e.what(),
                        ba->output.c_str(), finished.runs.size(), total);
           return e.timeout ? kExitFailed : kExitInterrupted;
         }
         base::WriteFileAtomic((fs::path(out.staging()) / "unwrap.csv").string(),
                               planning::UnwrapCsv(result));
         std::vector<std::string> wrote = {ba->output + "/unwrap.csv"};  // for the last line
         if (options.geometry) {
           base::WriteFileAtomic((fs::path(out.staging()) / "geometry.csv").string(),
                                 planning::UnwrapGeometryCsv(*options.geometry, result));
           wrote.push_back(ba->output + "/geometry.csv");
         }
         if (const auto figure = visualize::UnwrapFigure(result)) {
           const std::string png = (fs::path(out.staging()) / "unwrap.png").string();
           render::WriteFigure(png, *figure);
           visualize::WriteVectorFormats(png, *figure, ba->formats);
           wrote.push_back(ba->output + "/unwrap.png");
         }
         if (ba->survival) WriteSurvival(result, options.budget, out.staging(), ba->formats);
         out.Commit();
         if (ompl_log) {  // each log written whole
           for (size_t a = 0; a < result.angles_deg.size(); ++a) {
             base::WriteFileAtomic(OmplLogPath(ba->ompl_log, result.angles_deg[a]),
                                   OmplBenchmarkLog(result, a, log_info));
           }
           Note("wrote %zu OMPL benchmark logs %s", result.angles_deg.size(),
                OmplLogPath(ba->ompl_log, result.angles_deg.front()).c_str());
         }
         std::string files = wrote.front();  // "D/unwrap.csv, D/geometry.csv and D/unwrap.png"
         for (size_t i = 1; i < wrote.size(); ++i) {
           files += (i + 1 == wrote.size() ? " and " : ", ") + wrote[i];
         }
         Note("wrote %s (%s)%s", files.c_str(), RunCount(static_cast<size_t>(total)).c_str(),
              ba->survival ? ", survival.csv and survival.png" : "");
         return kExitOk;
       }});
}

}  // namespace app
