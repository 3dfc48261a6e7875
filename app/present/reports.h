// Output formats of the experiments, shared by the commands (`plan`, `bench unwrap`,
// `grasp transfer`) and the demo, so that files and tables come from the same result structs.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/cli/io.h"
#include "planning/motion/report.h"
#include "planning/physics/grasp_report.h"
#include "planning/physics/grasp_trials.h"
#include "visualize/report_figures.h"
#include "planning/motion/planner.h"
#include "planning/motion/unwrap_benchmark.h"
#include "render/figure.h"
#include "render/frames.h"
#include "render/image.h"

namespace app {

// --- plan ---------------------------------------------------------------------------------------

// Writes DIR/trajectory.csv (TrajectoryCsv) and DIR/report.json (PlanReportJson, 2-space
// indent); returns the report.
nlohmann::json WritePlanOutputs(const planning::Scenario& scenario,
                                const planning::PlanResult& result, unsigned seed,
                                const std::string& dir);

// report.json of a run stopped before it finished (--timeout or SIGINT/SIGTERM): `fields` plus
// "success": false and "status": "timeout" or "interrupted".
nlohmann::json StoppedReportJson(const StopRequested& stop, nlohmann::json fields);

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

// A plan report (PlanReportJson) as a two-column HTML table of its main fields.
std::string PlanReportHtml(const nlohmann::json& report);

// --- bench unwrap (Fig. 4.5) --------------------------------------------------------------------

// HTML table: one row per angle, one column per planner (result order): "solved/runs, mean checks
// of successful runs" (&ndash; when none solved), the same numbers as the figure.
std::string UnwrapHtmlTable(const planning::UnwrapBenchmarkResult& result);

// --- grasp transfer -----------------------------------------------------------------------------

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
