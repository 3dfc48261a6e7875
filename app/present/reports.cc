#include "app/present/reports.h"

#include "base/numbers.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <limits>
#include <sstream>

#include "visualize/figures.h"
#include "app/cli/io.h"
#include "visualize/scene_builder.h"
#include "planning/grasp/grasp_quality.h"
#include "planning/robot/kinematics.h"
#include "render/heatmap.h"
#include "render/offscreen_context.h"
#include "render/plot.h"
#include "render/renderer.h"
#include "topology/writhe.h"

namespace app {
namespace {

namespace fs = std::filesystem;
namespace phys = planning::physics;

}  // namespace

// --- plan ---------------------------------------------------------------------------------------

nlohmann::json WritePlanOutputs(const planning::Scenario& s, const planning::PlanResult& result,
                                unsigned seed, const std::string& dir) {
  nlohmann::json report = planning::PlanReportJson(s, result.report, seed);
  report["provenance"] = ProvenanceJson();
  base::WriteFileAtomic((fs::path(dir) / "trajectory.csv").string(),
                        planning::TrajectoryCsv(s, result.trajectory));
  base::WriteFileAtomic((fs::path(dir) / "report.json").string(), report.dump(2) + "\n");
  return report;
}

nlohmann::json StoppedReportJson(const StopRequested& stop, nlohmann::json fields) {
  fields["provenance"] = ProvenanceJson();
  fields["success"] = false;
  fields["status"] = stop.timeout ? "timeout" : "interrupted";
  return fields;
}

PlanFrames WritePlanFrames(
    const planning::Scenario& s, const planning::Trajectory& tr, const std::string& dir,
    const std::function<void(const render::Image& frame, const render::Image* heatmap)>& on_frame,
    const MovingObjectFrames* moving, const PlanFrameOptions& frame_opts) {
  planning::Trajectory frames = tr;
  if (moving != nullptr &&
      (moving->object < 0 || moving->object >= static_cast<int>(s.initial.objects.objects.size()) ||
       moving->positions.size() != static_cast<size_t>(tr.num_points()) || tr.dt == 0.0)) {
    throw std::invalid_argument("WritePlanFrames: moving object positions do not match the frames");
  }
  planning::Environment moved;  // with `moving`: the objects, the moving one placed per frame
  if (moving) moved = s.initial.objects;
  Eigen::Vector3d home = Eigen::Vector3d::Zero();
  if (moving) home = s.initial.objects.objects[moving->object].world_from_object.translation();
  const bool moving_report =
      moving && s.spec.writhe_report &&
      s.spec.writhe_report->object.name == s.initial.objects.objects[moving->object].name;
  if (tr.dt == 0.0 && tr.num_points() > 1) {
    frames = planning::Densify(tr, std::max(planning::PathLength(tr) / 100.0, 1e-6));
  }
  render::OffscreenContext context;
  render::Renderer renderer(context.proc_loader());
  planning::KinematicsData kin(s.robot);
  visualize::SceneMeshCache cache;
  visualize::SceneBuildOptions options;
  render::Camera camera;
  planning::TaskWorkspace ws(s.initial.problem);
  std::vector<double> x, writhe, cost;  // x: time (s)
  std::vector<Eigen::MatrixXd> matrices;
  for (int t = 0; t < frames.num_points(); ++t) {
    Eigen::MatrixXd W;
    if (moving_report) {
      planning::ForwardKinematics(s.robot, frames.q.col(t), &kin);
      Eigen::Matrix3Xd P;
      planning::ChainPoints(s.robot, kin, s.report_chain, &P);
      W = topology::WritheMatrix(P,
                                 s.initial.report_object_chain.colwise() + (moving->positions[t] - home));
      writhe.push_back(W.sum());
    } else {
      writhe.push_back(planning::ReportWritheTotal(s, frames.q.col(t), &W));
    }
    matrices.push_back(W);
    // Task cost at the matching time slice (RRT frames are mapped onto 0..T); time τ · slice.
    const double slice_t = frames.num_points() > 1 ? static_cast<double>(t) * s.initial.problem.num_steps /
                                                         (frames.num_points() - 1)
                                                   : 0.0;
    const int slice = static_cast<int>(std::lround(slice_t));
    x.push_back(slice_t * planning::tau(s.initial.problem));
    planning::EvaluateTasks(s.initial.problem, slice, frames.q.col(t), true, &ws);
    cost.push_back(planning::TaskCost(s.initial.problem, slice, Eigen::VectorXd(), ws));
  }
  // One camera for the whole trajectory: it fits the robot's swept volume and the box regions.
  constexpr int kWidth = 640, kHeight = 480;
  render::Scene swept;
  visualize::SceneBuildOptions swept_options = options;
  swept_options.objects = false;
  swept_options.grid = false;
  for (int t = 0; t < frames.num_points(); ++t) {
    planning::ForwardKinematics(s.robot, frames.q.col(t), &kin);
    render::Scene robot = visualize::BuildRobotScene(s.robot, kin, s.initial.objects, swept_options, &cache);
    std::move(robot.shapes.begin(), robot.shapes.end(), std::back_inserter(swept.shapes));
    std::move(robot.tubes.begin(), robot.tubes.end(), std::back_inserter(swept.tubes));
  }
  visualize::AddTaskBoxes(s.spec, &swept);
  camera = visualize::FitSceneCamera(swept, Eigen::Vector3f(1.0f, -1.3f, 0.8f), 35.0f,
                          static_cast<float>(kWidth) / kHeight);
  swept = render::Scene();
  // Time stamps: the time slices' times, or the share of the path length without time (RRTs).
  PlanFrames out;
  const double length = planning::PathLength(frames);
  double walked = 0.0;
  for (int t = 0; t < frames.num_points(); ++t) {
    char stamp[64];
    if (frames.dt > 0.0) {
      std::snprintf(stamp, sizeof stamp, "t = %.2f s", t * frames.dt);
    } else {
      if (t > 0) walked += (frames.q.col(t) - frames.q.col(t - 1)).norm();
      std::snprintf(stamp, sizeof stamp, "path %.0f%%", length > 0 ? 100.0 * walked / length : 0.0);
    }
    out.labels.push_back(stamp);
  }
  // Numbered PNGs plus a contact sheet each, and an MP4 of the frames when ffmpeg exists.
  render::FrameWriterOptions frame_options;
  frame_options.prefix = "frame_";
  render::FrameWriter frame_writer((fs::path(dir) / "frames").string(), frame_options);
  render::FrameWriterOptions heatmap_options;
  heatmap_options.prefix = "heatmap_";
  heatmap_options.video = false;
  render::FrameWriter heatmap_writer((fs::path(dir) / "heatmaps").string(), heatmap_options);
  const double heatmap_limit = visualize::PlanHeatmapLimit(matrices);  // one colour range for the sequence
  for (int t = 0; t < frames.num_points(); ++t) {
    planning::ForwardKinematics(s.robot, frames.q.col(t), &kin);
    if (moving)
      moved.objects[moving->object].world_from_object.translation() = moving->positions[t];
    render::Scene scene =
        visualize::BuildRobotScene(s.robot, kin, moving ? moved : s.initial.objects, options, &cache);
    visualize::AddTaskBoxes(s.spec, &scene);
    render::Image frame = renderer.Render(scene, camera, kWidth, kHeight, {});
    if (frame_opts.stamp) render::DrawStamp(&frame, {s.name, out.labels[t]});
    frame_writer.Add(frame, out.labels[t]);
    std::optional<render::Image> heatmap;
    if (matrices[t].size() > 0) {
      const render::Figure figure = visualize::PlanHeatmapFigure(s, matrices[t], x[t], heatmap_limit);
      heatmap = figure.Raster();
      visualize::WriteVectorFormats(heatmap_writer.Add(*heatmap, out.labels[t]), figure, frame_opts.formats);
    }
    if (on_frame) on_frame(frame, heatmap ? &*heatmap : nullptr);
    Progress("frames %d/%d", t + 1, frames.num_points());
  }
  EndProgress();
  out.frames = frame_writer.Finish();
  out.heatmaps = heatmap_writer.Finish();
  const render::Figure plot = visualize::WritheCostFigure(s.name, x, writhe, cost);
  render::WriteFigure((fs::path(dir) / "writhe_cost.png").string(), plot);
  visualize::WriteVectorFormats((fs::path(dir) / "writhe_cost.png").string(), plot, frame_opts.formats);
  return out;
}

std::string PlanReportHtml(const nlohmann::json& r) {
  if (!r.is_object()) return "<p><em>no report</em></p>";
  // Each field as a person reads it: a name, the value rounded to what it means, its unit.
  struct Row {
    const char* key;
    const char* label;
    int digits;  // < 0: not a number
    const char* unit;
    double scale;
  };
  static const Row kRows[] = {
      {"planner", "planner", -1, "", 1.0},
      {"success", "success", -1, "", 1.0},
      {"status", "solver status", -1, "", 1.0},
      {"collision_checks", "collision checks", 0, "", 1.0},
      {"iterations", "iterations (sweeps)", 0, "", 1.0},
      {"cost", "final cost", 1, "", 1.0},
      {"time_s", "planning time", 2, "s", 1.0},
      {"path_length", "path length", 3, "rad", 1.0},
      {"start_wrap_deg", "start wrap", 1, "&deg;", 1.0},
      {"start_writhe_total", "total writhe at the start", 3, "turns", 1.0},
      {"final_writhe_total", "total writhe at the end", 3, "turns", 1.0},
      {"min_clearance_m", "minimum clearance", 1, "mm", 1000.0},
      {"reach_error_m", "reach error", 1, "mm", 1000.0},
  };
  std::ostringstream t;
  t << "<table>";
  for (const Row& row : kRows) {
    if (!r.contains(row.key)) continue;
    const nlohmann::json& v = r[row.key];
    std::string text;
    if (row.digits >= 0 && v.is_number()) {
      const double x = v.get<double>();
      if (std::string(row.key) == "reach_error_m" && x < 0) continue;  // no reach criterion
      text = base::FormatFixed(x * row.scale, row.digits);
      if (*row.unit) text += std::string(" ") + row.unit;
    } else {
      text = HtmlEscape(v.is_string() ? v.get<std::string>() : v.dump());
    }
    t << "<tr><th>" << row.label << "</th><td>" << text << "</td></tr>";
  }
  t << "</table>\n";
  return t.str();
}

// --- bench unwrap -------------------------------------------------------------------------------

std::string UnwrapHtmlTable(const planning::UnwrapBenchmarkResult& result) {
  std::ostringstream t;
  t << "<table><tr><th>angle to unwrap</th>";
  for (planning::Planner p : result.planners) {
    t << "<th>" << planning::PlannerName(p)
      << ": solved, median collision checks of solved runs (as in the figure)</th>";
  }
  t << "</tr>\n";
  for (size_t a = 0; a < result.angles_deg.size(); ++a) {
    t << "<tr><td>" << base::FormatShortest(result.angles_deg[a]) << "&deg;</td>";
    for (size_t p = 0; p < result.planners.size(); ++p) {
      const planning::UnwrapCell& c = planning::UnwrapSummaryCell(result, a, p);
      char buf[96];
      if (std::isfinite(c.median_checks)) {
        std::snprintf(buf, sizeof buf, "<td>%d/%d, %s</td>", c.successes, c.runs,
                      base::FormatFixed(c.median_checks, 0).c_str());
      } else {
        std::snprintf(buf, sizeof buf, "<td>%d/%d, &ndash;</td>", c.successes, c.runs);
      }
      t << buf;
    }
    t << "</tr>\n";
  }
  t << "</table>\n";
  return t.str();
}

// --- grasp transfer -----------------------------------------------------------------------------
std::string WriteGraspOutputs(const phys::GraspTrialsResult& result, const std::string& dir,
                              const std::vector<render::FigureFormat>& formats) {
  return WriteGraspOutputs(result, dir, planning::physics::GraspReportJson(result), formats);
}

std::string WriteGraspOutputs(const phys::GraspTrialsResult& result, const std::string& dir,
                              const nlohmann::json& report,
                              const std::vector<render::FigureFormat>& formats) {
  fs::create_directories(dir);
  nlohmann::json with_provenance = report;
  with_provenance["provenance"] = ProvenanceJson();
  const std::string text = with_provenance.dump(1) + "\n";
  base::WriteFileAtomic((fs::path(dir) / "report.json").string(), text);
  base::WriteFileAtomic((fs::path(dir) / "summary.md").string(), planning::physics::GraspSummaryMarkdown(result));
  if (!result.grasps.empty()) {  // a run stopped before its first grasp has nothing to plot
    const render::Figure figure = visualize::GraspSummaryFigure(visualize::GraspSummaryDataOf(result));
    const std::string png = (fs::path(dir) / "summary.png").string();
    render::WriteFigure(png, figure);
    visualize::WriteVectorFormats(png, figure, formats);
  }
  return text;
}

std::string GraspHtmlTable(const phys::GraspTrialsResult& result) {
  std::ostringstream t;
  t << "<table><tr><th>grasp</th>";
  for (planning::TransferMethod m : result.methods) {
    t << "<th>" << planning::ToString(m) << "</th>";
  }
  t << "</tr>\n";
  for (size_t gi = 0; gi < result.grasps.size(); ++gi) {
    t << "<tr><td>" << HtmlEscape(result.grasps[gi].name) << "</td>";
    for (const phys::GraspTrial& trial : result.trials[gi]) {
      t << "<td>" << trial.stability.directions_passed << "/6"
        << (trial.stability.stable ? " stable" : "") << "</td>";
    }
    t << "</tr>\n";
  }
  t << "<tr><td><b>success rate (95 % CI)</b></td>";
  for (const phys::GraspMethodSummary& s : result.summary) {
    t << "<td>" << planning::physics::RateText(s.stable, s.grasps, s.ci95) << "</td>";
  }
  t << "</tr></table>\n";
  return t.str();
}

std::string HtmlEscape(const std::string& s) { return render::XmlEscape(s); }

}  // namespace app
