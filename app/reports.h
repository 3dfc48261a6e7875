// Output formats of the experiments, shared by the commands (`plan`, `bench unwrap`,
// `grasp transfer`) and the demo, so that files and tables come from the same result structs.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "app/io.h"
#include "planning/physics/grasp_trials.h"
#include "planning/planner.h"
#include "planning/unwrap_benchmark.h"
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
// the scenario has one) and DIR/writhe_cost.png (total writhe and task cost / max over the
// frames). `on_frame`, if given, sees every robot frame and its heatmap (null when none). Throws
// EnvironmentError when there is no GL context.
struct PlanFrames {
  render::FrameSequence frames, heatmaps;
};
PlanFrames WritePlanFrames(const planning::Scenario& scenario,
                           const planning::Trajectory& trajectory, const std::string& dir,
                           const std::function<void(const render::Image& frame,
                                                    const render::Image* heatmap)>& on_frame = {});

// A plan report (PlanReportJson) as a two-column HTML table of its main fields.
std::string PlanReportHtml(const nlohmann::json& report);

// --- bench unwrap (Fig. 4.5) --------------------------------------------------------------------

// unwrap.csv: "angle_deg,planner,seed,success,failure_reason,collision_checks,narrow_phase_calls,
// time_s,path_length,reach_error_m,pole_offset_m", one row per run in result.runs order.
std::string UnwrapCsv(const planning::UnwrapBenchmarkResult& result);

// unwrap.png: mean collision checks of successful runs vs angle (log y), one curve per planner in
// the result's planner order, x markers at the failed runs' check counts. Empty when there is
// nothing to draw (no successful run and no failure).
std::optional<render::Image> UnwrapFigure(const planning::UnwrapBenchmarkResult& result);

// HTML table: one row per angle, one column per planner (result order): "solved/runs, mean checks
// of successful runs" (&ndash; when none solved), the same numbers as the figure.
std::string UnwrapHtmlTable(const planning::UnwrapBenchmarkResult& result);

// --- grasp transfer -----------------------------------------------------------------------------

// report.json of `grasp transfer`: mu, protocol, per grasp (name, type, object, file, human
// windings, per method: windings, winding_error, epsilon_quality, clearance, solver, q,
// stability) and per-method summary (stable, grasps, success_rate). Values rounded to 1e-6
// (rotations 1e-3, rates 1e-4).
nlohmann::json GraspReportJson(const planning::physics::GraspTrialsResult& result);

// summary.md: directions passed out of 6 per grasp and method, then one "eps METHOD" column per
// method (GraspTrial::epsilon_quality, 4 decimals), and the success-rate row.
std::string GraspSummaryMarkdown(const planning::physics::GraspTrialsResult& result);

// summary.png: directions held per grasp, one marker series per method.
render::Image GraspSummaryFigure(const planning::physics::GraspTrialsResult& result);

// Writes DIR/report.json (GraspReportJson, 1-space indent), DIR/summary.md and DIR/summary.png;
// returns the report.json text.
std::string WriteGraspOutputs(const planning::physics::GraspTrialsResult& result,
                              const std::string& dir);

// HTML table of the same numbers as summary.md (header and cells from result.methods).
std::string GraspHtmlTable(const planning::physics::GraspTrialsResult& result);

// `s` with <, >, & escaped for HTML text.
std::string HtmlEscape(const std::string& s);

}  // namespace app
