// `topoplan plan` (AICO / RRT / BiRRT on a scenario, with trajectory, report and optional frames)
// and `topoplan bench unwrap` (thesis Fig. 4.5: collision checks vs angle to unwrap).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/assets.h"
#include "app/command.h"
#include "app/figures.h"
#include "app/io.h"
#include "app/scene_builder.h"
#include "planning/planner.h"
#include "planning/scenario.h"
#include "render/frames.h"
#include "render/image.h"
#include "render/offscreen_context.h"
#include "render/plot.h"
#include "render/renderer.h"

namespace app {
namespace {

namespace fs = std::filesystem;

nlohmann::json ReportJson(const planning::Scenario& s, const planning::PlanReport& r,
                          unsigned seed) {
  nlohmann::json j;
  j["scenario"] = s.name;
  j["planner"] = r.planner;
  j["seed"] = seed;
  j["success"] = r.success;
  j["status"] = planning::StatusName(r.status);
  j["collision_checks"] = r.collision_checks;
  j["narrow_phase_calls"] = r.narrow_phase_calls;
  j["iterations"] = r.iterations;
  j["attempts"] = r.attempts;
  j["cost"] = r.cost;
  j["path_length"] = r.path_length;
  j["time_s"] = r.time_s;
  j["start_wrap_deg"] = s.start_wrap_deg;
  j["start_writhe_total"] = r.start_writhe_total;
  j["final_writhe_total"] = r.final_writhe_total;
  j["min_clearance_m"] = r.min_clearance_m;
  j["path_collision_free"] = r.path_collision_free;
  j["cost_history"] = r.cost_history;
  return j;
}

std::string TrajectoryCsv(const planning::Scenario& s, const planning::Trajectory& tr) {
  std::ostringstream out;
  out.precision(17);
  out << "step,time_s";
  for (const std::string& name : planning::DofNames(s.robot)) out << "," << name;
  out << "\n";
  for (int t = 0; t < tr.num_points(); ++t) {
    out << t << "," << t * tr.dt;
    for (int k = 0; k < tr.num_dofs(); ++k) out << "," << tr.q(k, t);
    out << "\n";
  }
  return out.str();
}

// Frames: the robot at every trajectory point (RRT paths are resampled to at most 100 frames),
// a writhe heatmap per frame, and a plot of total writhe and task cost over the frames.
void WriteFrames(const planning::Scenario& s, const planning::Trajectory& tr,
                 const std::string& dir) {
  planning::Trajectory frames = tr;
  if (tr.dt == 0.0 && tr.num_points() > 1) {
    frames = planning::Densify(tr, std::max(planning::PathLength(tr) / 100.0, 1e-6));
  }
  render::OffscreenContext context;
  render::Renderer renderer(context.proc_loader());
  planning::KinematicsData kin(s.robot);
  SceneMeshCache cache;
  SceneBuildOptions options;
  render::Camera camera;
  planning::TaskWorkspace ws(s.problem);
  std::vector<double> x, writhe, cost;
  double max_abs_w = 1e-9;
  std::vector<Eigen::MatrixXd> matrices;
  for (int t = 0; t < frames.num_points(); ++t) {
    Eigen::MatrixXd W;
    writhe.push_back(planning::ReportWritheTotal(s, frames.q.col(t), &W));
    if (W.size() > 0) max_abs_w = std::max(max_abs_w, W.cwiseAbs().maxCoeff());
    matrices.push_back(W);
    x.push_back(t);
    // Task cost at the matching time slice (RRT frames are mapped onto 0..T).
    const int slice =
        frames.num_points() > 1
            ? static_cast<int>(std::lround(static_cast<double>(t) * s.problem.num_steps /
                                           (frames.num_points() - 1)))
            : 0;
    planning::EvaluateTasks(s.problem, slice, frames.q.col(t), true, &ws);
    cost.push_back(planning::TaskCost(s.problem, slice, Eigen::VectorXd(), ws));
  }
  // Numbered PNGs plus a contact sheet each, and an MP4 of the frames when ffmpeg exists.
  render::FrameWriterOptions frame_options;
  frame_options.prefix = "frame_";
  render::FrameWriter frame_writer((fs::path(dir) / "frames").string(), frame_options);
  render::FrameWriterOptions heatmap_options;
  heatmap_options.prefix = "heatmap_";
  heatmap_options.video = false;
  render::FrameWriter heatmap_writer((fs::path(dir) / "heatmaps").string(), heatmap_options);
  for (int t = 0; t < frames.num_points(); ++t) {
    planning::ForwardKinematics(s.robot, frames.q.col(t), &kin);
    const render::Scene scene = BuildRobotScene(s.robot, kin, s.objects, options, &cache);
    if (t == 0) camera = FrameSceneCamera(scene);
    frame_writer.Add(renderer.Render(scene, camera, 640, 480, {}));
    if (matrices[t].size() > 0) {
      char title[128];
      std::snprintf(title, sizeof(title), "Writhe matrix, frame %d (total %+.3f)", t, writhe[t]);
      heatmap_writer.Add(
          WritheHeatmapFigure(matrices[t], "robot chain", "object chain", 480, 480, title));
    }
    std::fprintf(stderr, "\rframes %d/%d", t + 1, frames.num_points());
  }
  std::fprintf(stderr, "\n");
  const render::FrameSequence seq = frame_writer.Finish();
  heatmap_writer.Finish();
  if (!seq.video.empty()) std::fprintf(stderr, "wrote %s\n", seq.video.c_str());
  const double max_cost = std::max(1e-12, *std::max_element(cost.begin(), cost.end()));
  std::vector<double> cost_norm;
  for (double c : cost) cost_norm.push_back(c / max_cost);
  render::PlotSeries ws_series;
  ws_series.label = "total writhe";
  ws_series.x = x;
  ws_series.y = writhe;
  ws_series.marker = render::Marker::kNone;
  render::PlotSeries cost_series;
  cost_series.label = "task cost / max";
  cost_series.x = x;
  cost_series.y = cost_norm;
  cost_series.marker = render::Marker::kNone;
  render::PlotOptions po;
  po.title = s.name + ": total writhe and task cost over the trajectory";
  po.x_label = "frame";
  po.y_label = "value";
  po.legend = render::LegendPosition::kTopRight;
  render::WritePng((fs::path(dir) / "writhe_cost.png").string(),
                   render::RenderPlot({ws_series, cost_series}, po));
}

struct PlanArgs {
  std::string scenario, planner = "aico", output;
  unsigned seed = 0;
  double start_wrap = std::numeric_limits<double>::quiet_NaN();
  bool frames = false, json = false;
};

struct BenchArgs {
  std::string angles = "0:900:90", planners = "aico,rrt,birrt", output;
  int seeds = 3;
  long budget = -1;
};

// "a:b:step" → a, a+step, ..., ≤ b.
std::vector<double> ParseRange(const std::string& text, const std::string& flag) {
  const std::vector<double> v = [&] {
    std::string t = text;
    for (char& c : t) {
      if (c == ':') c = ',';
    }
    return ParseNumberList(t, flag, 3);
  }();
  if (!(v[2] > 0.0) || v[1] < v[0] || v[0] < 0.0 || v[1] > 2000.0) {
    throw std::invalid_argument(flag + ": expected a:b:step with 0 <= a <= b <= 2000, step > 0");
  }
  std::vector<double> out;
  for (double a = v[0]; a <= v[1] + 1e-9; a += v[2]) out.push_back(a);
  return out;
}

std::vector<planning::Planner> ParsePlanners(const std::string& text) {
  std::vector<planning::Planner> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    try {
      out.push_back(planning::ParsePlanner(item));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("--planners: ") + e.what());
    }
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
                   "aico | rrt | birrt | ompl-rrt | ompl-rrtconnect (the OMPL peers need a build "
                   "with libompl-dev)")
      ->check(CLI::IsMember({"aico", "rrt", "birrt", "ompl-rrt", "ompl-rrtconnect"}));
  plan->add_option("--seed", pa->seed, "seed of the RRTs' random generator (default 0)");
  plan->add_option("--start-wrap", pa->start_wrap,
                   "start coil of a coil-start scenario (unwrap): angle to unwrap in degrees");
  plan->add_option("-o,--output", pa->output, "output folder")->required();
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
         return WithRenderErrors([&]() {
           planning::ScenarioOverrides overrides;
           if (!std::isnan(pa->start_wrap)) {
             if (!(pa->start_wrap >= 0.0 && pa->start_wrap <= 2000.0)) {
               throw std::invalid_argument("--start-wrap: expected degrees in [0, 2000]");
             }
             overrides.start_wrap_deg = pa->start_wrap;
           }
           const auto scenario = planning::LoadScenario(ResolveScenarioPath(pa->scenario), overrides);
           const planning::Planner planner = planning::ParsePlanner(pa->planner);
           const planning::PlanResult result = planning::RunPlanner(
               *scenario, planner, pa->seed,
               [](int sweep, double cost, bool accepted, const planning::Trajectory&) {
                 std::fprintf(stderr, "\rsweep %3d  cost %-12.6g %s", sweep, cost,
                              accepted ? "accepted" : "rejected");
               });
           if (planner == planning::Planner::kAico) std::fprintf(stderr, "\n");
           const nlohmann::json report = ReportJson(*scenario, result.report, pa->seed);
           WriteFileAtomic((fs::path(pa->output) / "trajectory.csv").string(),
                           TrajectoryCsv(*scenario, result.trajectory));
           WriteFileAtomic((fs::path(pa->output) / "report.json").string(), report.dump(2) + "\n");
           if (pa->frames && result.trajectory.num_points() > 0) {
             WriteFrames(*scenario, result.trajectory, pa->output);
           }
           if (pa->json) {
             std::printf("%s\n", report.dump(2).c_str());
           } else {
             const planning::PlanReport& r = result.report;
             std::printf(
                 "%s on %s (start wrap %.1f deg): %s [%s], %ld collision checks, %ld iterations, "
                 "%.3f s, writhe %+.3f -> %+.3f, min clearance %.3f m\n",
                 r.planner.c_str(), scenario->name.c_str(), scenario->start_wrap_deg,
                 r.success ? "success" : "FAILED", planning::StatusName(r.status),
                 r.collision_checks, r.iterations, r.time_s, r.start_writhe_total,
                 r.final_writhe_total, r.min_clearance_m);
             std::printf("wrote %s/trajectory.csv, %s/report.json\n", pa->output.c_str(),
                         pa->output.c_str());
           }
           return result.report.success ? kExitOk : kExitFailed;
         });
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
  unwrap->add_option("--budget", ba->budget,
                     "collision-check budget of the RRTs (default: the scenario's, 100000)");
  unwrap->add_option("-o,--output", ba->output, "output folder")->required();
  unwrap->footer(
      "Writes DIR/unwrap.csv (angle_deg,planner,seed,success,collision_checks,time_s) and\n"
      "DIR/unwrap.png (mean collision checks of successful runs vs angle, log scale, one curve\n"
      "per planner, x markers where a run failed). time_s is wall-clock; everything else is\n"
      "deterministic. Exit 0 when the benchmark ran (failed runs are data, not errors).");
  commands->push_back(
      {unwrap, [ba]() {
         return WithRenderErrors([&]() {
           const std::vector<double> angles = ParseRange(ba->angles, "--angles");
           const std::vector<planning::Planner> planners = ParsePlanners(ba->planners);
           const std::string path = ResolveScenarioPath("unwrap");
           std::ostringstream csv;
           csv << "angle_deg,planner,seed,success,collision_checks,time_s\n";
           std::map<planning::Planner, render::PlotSeries> series;
           const int total = static_cast<int>(angles.size() * planners.size()) * ba->seeds;
           int done = 0;
           ProgressBar(0, total, "");
           for (double angle : angles) {
             planning::ScenarioOverrides overrides;
             overrides.start_wrap_deg = angle;
             const auto scenario = planning::LoadScenario(path, overrides);
             if (ba->budget > 0) {
               scenario->rrt.max_checks = ba->budget;
             }
             for (planning::Planner planner : planners) {
               render::PlotSeries& ser = series[planner];
               ser.label = planning::PlannerName(planner);
               double sum = 0.0;
               int ok = 0;
               for (int seed = 0; seed < ba->seeds; ++seed) {
                 const planning::PlanResult r =
                     planning::RunPlanner(*scenario, planner, static_cast<unsigned>(seed));
                 csv << angle << "," << r.report.planner << "," << seed << ","
                     << (r.report.success ? 1 : 0) << "," << r.report.collision_checks << ","
                     << r.report.time_s << "\n";
                 if (r.report.success) {
                   sum += static_cast<double>(r.report.collision_checks);
                   ++ok;
                 } else {
                   ser.failure_x.push_back(angle);
                   ser.failure_y.push_back(
                       static_cast<double>(std::max<long>(r.report.collision_checks, 1)));
                 }
                 char what[96];
                 std::snprintf(what, sizeof(what), "%s @ %.0f deg seed %d", ser.label.c_str(),
                               angle, seed);
                 ProgressBar(++done, total, what);
               }
               ser.x.push_back(angle);
               ser.y.push_back(ok > 0 ? sum / ok : std::numeric_limits<double>::quiet_NaN());
             }
           }
           WriteFileAtomic((fs::path(ba->output) / "unwrap.csv").string(), csv.str());
           std::vector<render::PlotSeries> plot;
           for (auto& [planner, ser] : series) {
             if (ser.failure_x.size() != ser.failure_y.size()) ser.failure_y.clear();
             plot.push_back(ser);
           }
           render::PlotOptions po;
           po.width = 800;
           po.height = 560;
           po.title = "Unwrapping: collision checks vs angle to unwrap (mean of successful runs)";
           po.x_label = "Angle to unwrap (degrees)";
           po.y_label = "collision checks";
           po.log_y = true;
           bool any_finite = false;
           for (const auto& ser : plot) {
             for (double y : ser.y) any_finite |= std::isfinite(y);
             any_finite |= !ser.failure_y.empty();
           }
           // Headroom above the largest value so failure markers (drawn at the budget) are not
           // cut by the top of the frame.
           double y_top = 0.0;
           for (const auto& ser : plot) {
             for (double y : ser.y) {
               if (std::isfinite(y)) y_top = std::max(y_top, y);
             }
             for (double y : ser.failure_y) y_top = std::max(y_top, y);
           }
           if (y_top > 0.0) po.y_max = 2.5 * y_top;
           if (any_finite) {
             render::WritePng((fs::path(ba->output) / "unwrap.png").string(),
                              render::RenderPlot(plot, po));
           }
           std::printf("wrote %s/unwrap.csv and %s/unwrap.png (%d runs)\n", ba->output.c_str(),
                       ba->output.c_str(), total);
           return kExitOk;
         });
       }});
}

}  // namespace app
