// Output formats of the experiments, shared by the commands (`plan`, `bench unwrap`,
// `grasp transfer`) and the demo, so that files and tables come from the same result structs.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/cli/io.h"
#include "planning/physics/grasp_trials.h"
#include "planning/motion/planner.h"
#include "planning/motion/unwrap_benchmark.h"
#include "render/figure.h"
#include "render/frames.h"
#include "render/image.h"

namespace app {

// --- plan ---------------------------------------------------------------------------------------

// report.json of `topoplan plan`: scenario, planner, seed, success, status, collision_checks,
// narrow_phase_calls, iterations, attempts, cost, path_length [rad], time_s, start_wrap_deg,
// start/final_writhe_total, min_clearance_m, path_collision_free, cost_history, failure_reason
// (planning::FailureReasonName), failure_step, reach_error_m, max_winding_jump_turns,
// final_winding_turns, and writhe_peak {row, col, value} (largest |entry| of the final writhe
// matrix of the report pair; only with a report pair).
nlohmann::json PlanReportJson(const planning::Scenario& scenario,
                              const planning::PlanReport& report, unsigned seed);

// trajectory.csv: "step,time_s,<joint names in robot order>", one row per slice, 17 digits.
std::string TrajectoryCsv(const planning::Scenario& scenario,
                          const planning::Trajectory& trajectory);

// Writes DIR/trajectory.csv (TrajectoryCsv) and DIR/report.json (PlanReportJson, 2-space
// indent); returns the report.
nlohmann::json WritePlanOutputs(const planning::Scenario& scenario,
                                const planning::PlanResult& result, unsigned seed,
                                const std::string& dir);

// report.json of a run stopped before it finished (--timeout or SIGINT/SIGTERM): `fields` plus
// "success": false and "status": "timeout" or "interrupted".
nlohmann::json StoppedReportJson(const StopRequested& stop, nlohmann::json fields);

// One human-readable line: planner, scenario, start wrap, success/status, checks, iterations,
// time, writhe start -> final, min clearance (no trailing newline).
std::string PlanSummaryLine(const planning::Scenario& scenario, const planning::PlanReport& report);

// Writes DIR/frames/frame_*.png (the robot at every trajectory point; RRT paths resampled to at
// most 100 frames), DIR/heatmaps/heatmap_*.png (writhe matrix of the report pair per frame, when
// the scenario has one; one colour range for the whole sequence, PlanHeatmapLimit) and
// DIR/writhe_cost.png (WritheCostFigure). Every robot frame uses one camera that fits the robot's
// swept volume over the whole trajectory and the scenario's box task regions (FitSceneCamera),
// draws those boxes (AddTaskBoxes), and, with options.stamp, carries the scenario name and its
// time stamp in the top-left corner; contact-sheet labels are the time stamps. options.formats
// adds .svg/.pdf of every heatmap and of writhe_cost next to the PNGs (PNG is always written).
// `on_frame`, if given, sees every robot frame and its heatmap (null when none). Throws
// EnvironmentError when there is no GL context.
// With `moving` (re-planning, planning/motion/replan.h), frame t shows object `moving->object` at
// moving->positions[t] (orientation kept) and its writhe (heatmap, curve) uses the report object
// chain moved with it; the task cost is that of the scenario's problem (objects at home).
struct PlanFrameOptions {
  bool stamp = true;  // scenario name and time in a corner of each robot frame (--no-stamp)
  std::vector<render::FigureFormat> formats;  // --formats: vector copies of the figures
};
struct PlanFrames {
  render::FrameSequence frames, heatmaps;
  // Per robot frame: "t = 1.25 s" (time slice × dt), or "path 37%" (share of the joint-space path
  // length) for a path without time (RRTs, dt = 0).
  std::vector<std::string> labels;
};
struct MovingObjectFrames {
  int object = -1;                         // index into scenario.objects
  std::vector<Eigen::Vector3d> positions;  // per trajectory point, world, m
};
PlanFrames WritePlanFrames(const planning::Scenario& scenario,
                           const planning::Trajectory& trajectory, const std::string& dir,
                           const std::function<void(const render::Image& frame,
                                                    const render::Image* heatmap)>& on_frame = {},
                           const MovingObjectFrames* moving = nullptr,
                           const PlanFrameOptions& options = {});

// The colour limit of a heatmap sequence: `clim` when > 0, else the largest |entry| over all
// matrices (render::SequenceLimit): symmetric, the same for every frame.
double PlanHeatmapLimit(const std::vector<Eigen::MatrixXd>& matrices, double clim = 0.0);

// The writhe heatmap of the report pair at time `time_s` of a plan: rows "<Chain> segment",
// columns "<Object> segment" (names from the scenario's writhe_report), colour limit `limit`,
// title "Writhe matrix at t = <time> s (total <sum>)".
render::Figure PlanHeatmapFigure(const planning::Scenario& scenario, const Eigen::MatrixXd& w,
                                 double time_s, double limit);

// Total writhe (turns) and task cost over time (s) on two panels sharing the time axis.
render::Figure WritheCostFigure(const std::string& scenario_name, const std::vector<double>& time_s,
                                const std::vector<double>& writhe, const std::vector<double>& cost);

// A plan report (PlanReportJson) as a two-column HTML table of its main fields.
std::string PlanReportHtml(const nlohmann::json& report);

// --- bench unwrap (Fig. 4.5) --------------------------------------------------------------------

// unwrap.csv: "angle_deg,planner,seed,success,failure_reason,collision_checks,narrow_phase_calls,
// time_s,path_length,reach_error_m,pole_offset_m", one row per run in result.runs order.
std::string UnwrapCsv(const planning::UnwrapBenchmarkResult& result);

// unwrap.png (Fig. 4.5): three panels over the angle to unwrap, log y: collision checks,
// narrow-phase calls and wall time. Per planner (one colour each, result order): the median over
// the seeds' successful runs, an interquartile band when an angle has at least two, and a cross
// at each failed run's value. Empty when there is nothing to draw (no run at all).
std::optional<render::Figure> UnwrapFigure(const planning::UnwrapBenchmarkResult& result);

// HTML table: one row per angle, one column per planner (result order): "solved/runs, mean checks
// of successful runs" (&ndash; when none solved), the same numbers as the figure.
std::string UnwrapHtmlTable(const planning::UnwrapBenchmarkResult& result);

// --- grasp transfer -----------------------------------------------------------------------------

// report.json of `grasp transfer`: mu, protocol, per grasp (name, type, object, file, human
// windings, per method: windings, winding_error, epsilon_quality, clearance, solver, q,
// stability; with perturb > 0 also perturbed: {trials, stable, rate, ci95: [lo, hi]}) and
// per-method summary (stable, grasps, success_rate, ci95: Wilson 95 % over the grasps; with
// perturb > 0 perturbed: {trials, stable, rate, ci95} over all repetitions), and with perturb > 0
// "perturb": {repetitions, seed, max_translation_m, max_rotation_deg}. Values rounded to 1e-6
// (rotations 1e-3, rates and intervals 1e-4).
nlohmann::json GraspReportJson(const planning::physics::GraspTrialsResult& result);

// summary.md: directions passed out of 6 per grasp and method, then one "eps METHOD" column per
// method (GraspTrial::epsilon_quality, 4 decimals), and the success-rate row with Wilson 95 %
// intervals; with perturb > 0 each cell also gives "perturbed s/N" and a perturbed-rate row.
std::string GraspSummaryMarkdown(const planning::physics::GraspTrialsResult& result);

// Input of the grasp summary figure: one group of bars per grasp, one bar (colour) per method,
// with an optional interval [lo, hi] per bar, e.g. a 95% confidence interval over perturbed
// trials. value[m][g] is method m on grasp g; lo and hi are empty or have value's shape (NaN:
// no whisker on that bar).
struct GraspSummaryData {
  std::string title;
  std::string y_label;
  double y_max = 1.0;  // top of the value axis
  std::vector<std::string> grasps, methods;
  std::vector<std::vector<double>> value, lo, hi;
};

// The summary figure's data: without perturbations, gravity directions held out of 6 per grasp
// and method (no whiskers); with --perturb N, the stable fraction of the N perturbed repetitions
// with its Wilson 95 % interval as whiskers. Method names carry their stable count ("winding
// (3/8 stable)").
GraspSummaryData GraspSummaryDataOf(const planning::physics::GraspTrialsResult& result);

// summary.png: grouped bars, grasp names on the x axis, legend of methods at the right.
render::Figure GraspSummaryFigure(const GraspSummaryData& data);

// Writes DIR/report.json (GraspReportJson, 1-space indent), DIR/summary.md and DIR/summary.png
// (plus summary.svg/.pdf per `formats`; no figure when result.grasps is empty: a run stopped
// before its first grasp); returns the report.json text.
std::string WriteGraspOutputs(const planning::physics::GraspTrialsResult& result,
                              const std::string& dir,
                              const std::vector<render::FigureFormat>& formats = {});
// The same with a given report.json (e.g. GraspReportJson with a "status" of a stopped run).
std::string WriteGraspOutputs(const planning::physics::GraspTrialsResult& result,
                              const std::string& dir, const nlohmann::json& report,
                              const std::vector<render::FigureFormat>& formats = {});

// HTML table of the same numbers as summary.md (header and cells from result.methods).
std::string GraspHtmlTable(const planning::physics::GraspTrialsResult& result);

// `s` with <, >, & and " escaped for HTML text (render::XmlEscape).
std::string HtmlEscape(const std::string& s);

}  // namespace app
