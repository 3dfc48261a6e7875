#include "visualize/report_figures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "planning/grasp/grasp_quality.h"
#include "planning/physics/grasp_report.h"
#include "render/heatmap.h"
#include "render/plot.h"
#include "visualize/figures.h"

namespace visualize {

namespace phys = planning::physics;

double PlanHeatmapLimit(const std::vector<Eigen::MatrixXd>& matrices, double clim) {
  return clim > 0.0 ? clim : render::SequenceLimit(matrices);
}

namespace {

// "arm" -> "Arm segment".
std::string SegmentLabel(std::string chain) {
  if (chain.empty()) return "Segment";
  chain[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(chain[0])));
  return chain + " segment";
}

}  // namespace

render::Figure PlanHeatmapFigure(const planning::Scenario& s, const Eigen::MatrixXd& w,
                                 double time_s, double limit) {
  visualize::WritheFigureOptions f;
  f.width = 480;
  f.height = 480;
  f.limit = limit;
  f.mark_peak = true;
  f.title = "Writhe matrix at t = " + render::FormatNumber(time_s, 2) + " s (total " +
            render::FormatNumber(w.sum(), 3, /*plus=*/true) + ")";
  if (s.spec.writhe_report) {
    f.row_label = SegmentLabel(s.spec.writhe_report->chain.name);
    f.col_label = SegmentLabel(s.spec.writhe_report->object.name);
  }
  return visualize::WritheFigure(w, "robot chain", "object chain", f);
}

render::Figure WritheCostFigure(const std::string& scenario_name, const std::vector<double>& time_s,
                                const std::vector<double>& writhe,
                                const std::vector<double>& cost) {
  render::PlotPanel top, bottom;
  render::PlotSeries ws("", time_s, writhe);
  ws.marker = render::Marker::kNone;
  top.series = {ws};
  top.axes.y_label = "Total writhe (turns)";
  top.axes.legend = render::LegendPosition::kNone;
  render::PlotSeries cs("", time_s, cost);
  cs.marker = render::Marker::kNone;
  cs.rgba = {214, 39, 40, 255};
  bottom.series = {cs};
  bottom.axes.x_label = "Time (s)";
  bottom.axes.y_label = "Task cost";
  bottom.axes.legend = render::LegendPosition::kNone;
  bottom.axes.y_min = 0.0;
  if (!time_s.empty()) {  // both panels on the same time axis
    for (render::PlotPanel* p : {&top, &bottom}) {
      p->axes.x_min = time_s.front();
      p->axes.x_max = std::max(time_s.back(), time_s.front() + 1e-9);
    }
  }
  render::PanelLayout layout;
  layout.width = 640;
  layout.height = 560;
  layout.title = scenario_name + ": total writhe and task cost over the trajectory";
  return render::PanelsFigure({top, bottom}, layout);
}

namespace {

// Quantile q in [0, 1] of `v` (sorted in place), linear between order statistics.
double Quantile(std::vector<double>* v, double q) {
  std::sort(v->begin(), v->end());
  const double pos = q * static_cast<double>(v->size() - 1);
  const size_t k = static_cast<size_t>(pos);
  if (k + 1 >= v->size()) return v->back();
  return (*v)[k] + (pos - static_cast<double>(k)) * ((*v)[k + 1] - (*v)[k]);
}

// One panel of the unwrap figure: a measure of a run's report on a log axis.
struct UnwrapMeasure {
  const char* title;
  const char* y_label;
  double (*value)(const planning::PlanReport&);
  // Zero cannot be drawn on a log axis: a run with no count sits at 1 (the axis floor; wall
  // time: 1e-4 s).
  double floor;
};

const UnwrapMeasure kUnwrapMeasures[3] = {
    {"Collision checks", "Collision checks",
     [](const planning::PlanReport& r) { return static_cast<double>(r.collision_checks); }, 1.0},
    {"Narrow-phase calls", "Narrow-phase calls",
     [](const planning::PlanReport& r) { return static_cast<double>(r.narrow_phase_calls); }, 1.0},
    {"Wall time", "Wall time (s)", [](const planning::PlanReport& r) { return r.time_s; }, 1e-4}};

// Planner `p`'s series of measure `m`: per angle the median and interquartile range over the
// solved runs (NaN without), and a failure cross per failed run. Failure crosses are staggered
// vertically by planner (factors 1.25^k about the run's value, k centred on the planner list)
// so that the failures of several planners at one budget stay visible; on the log axes that is
// 0.1 decade between neighbouring planners.
render::PlotSeries UnwrapSeries(const planning::UnwrapBenchmarkResult& result, size_t p,
                                const UnwrapMeasure& m) {
  const double planners = static_cast<double>(result.planners.size());
  const double stagger = std::pow(1.25, static_cast<double>(p) - 0.5 * (planners - 1.0));
  render::PlotSeries ser;
  ser.label = planning::PlannerName(result.planners[p]);
  bool any_band = false;
  for (double angle : result.angles_deg) {
    std::vector<double> solved;
    for (const planning::UnwrapRun& r : result.runs) {
      if (r.planner != result.planners[p] || r.angle_deg != angle) continue;
      const double v = std::max(m.value(r.report), m.floor);
      if (r.report.success) {
        solved.push_back(v);
      } else {
        ser.failure_x.push_back(angle);
        ser.failure_y.push_back(v * stagger);
      }
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    ser.x.push_back(angle);
    ser.y.push_back(solved.empty() ? nan : Quantile(&solved, 0.5));
    ser.y_lo.push_back(solved.size() >= 2 ? Quantile(&solved, 0.25) : nan);
    ser.y_hi.push_back(solved.size() >= 2 ? Quantile(&solved, 0.75) : nan);
    any_band |= solved.size() >= 2;
  }
  if (!any_band) ser.y_lo.clear(), ser.y_hi.clear();
  return ser;
}

// Headroom above the data (a third of the decades shown) for the legend and the failure markers
// at the budget: the log y range from the decade below the smallest value.
void SetLogRange(render::PlotPanel* panel) {
  double y_top = 0.0, y_bottom = std::numeric_limits<double>::infinity();
  for (const auto& ser : panel->series) {
    for (const std::vector<double>* v : {&ser.y, &ser.y_lo, &ser.y_hi, &ser.failure_y}) {
      for (double y : *v) {
        if (std::isfinite(y) && y > 0.0) {
          y_top = std::max(y_top, y);
          y_bottom = std::min(y_bottom, y);
        }
      }
    }
  }
  if (y_top > 0.0) {
    const double lo = std::floor(std::log10(y_bottom)), hi = std::log10(y_top);
    panel->axes.y_min = std::pow(10.0, lo);
    panel->axes.y_max = std::pow(10.0, std::ceil(hi + 0.5 * std::max(1.0, hi - lo)));
  }
}

// The panel of measure `m` over the angle to unwrap, one series per planner, with the legend
// where `legend` says.
render::PlotPanel UnwrapPanel(const planning::UnwrapBenchmarkResult& result, const UnwrapMeasure& m,
                              render::LegendPosition legend) {
  render::PlotPanel panel;
  for (size_t p = 0; p < result.planners.size(); ++p) {
    panel.series.push_back(UnwrapSeries(result, p, m));
  }
  panel.axes.title = m.title;
  panel.axes.x_label = "Angle to unwrap (deg)";
  panel.axes.y_label = m.y_label;
  panel.axes.log_y = true;
  panel.axes.legend = legend;
  SetLogRange(&panel);
  return panel;
}

}  // namespace

std::optional<render::Figure> UnwrapFigure(const planning::UnwrapBenchmarkResult& result) {
  if (result.runs.empty()) return std::nullopt;
  int seeds = 0;
  for (const planning::UnwrapRun& r : result.runs) seeds = std::max(seeds, r.seed + 1);
  // Up to kMaxPanelLegendPlanners the legend fits in the first panel's headroom above the data;
  // more go in a column right of the last panel (the figure grows by about the legend's width),
  // where the legend hides no failure marker.
  constexpr size_t kMaxPanelLegendPlanners = 6;
  const bool outside = result.planners.size() > kMaxPanelLegendPlanners;
  std::vector<render::PlotPanel> panels;
  for (const UnwrapMeasure& m : kUnwrapMeasures) {
    render::LegendPosition legend = render::LegendPosition::kNone;
    if (!outside && panels.empty()) legend = render::LegendPosition::kTopLeft;
    if (outside && panels.size() + 1 == std::size(kUnwrapMeasures)) {
      legend = render::LegendPosition::kOutsideRight;
    }
    panels.push_back(UnwrapPanel(result, m, legend));
  }
  render::PanelLayout layout;
  layout.width = outside ? 1700 : 1380;
  layout.height = 480;
  layout.columns = 3;
  layout.title = "Unwrapping (Fig. 4.5): median over the solved runs of " + std::to_string(seeds) +
                 (seeds == 1 ? " seed" : " seeds") +
                 (seeds >= 2 ? ", band: interquartile range" : "") +
                 "; \u2715 failed run (staggered by planner)";
  return render::PanelsFigure(panels, layout);
}

GraspSummaryData GraspSummaryDataOf(const phys::GraspTrialsResult& result) {
  GraspSummaryData d;
  // The grip travel is named only when it is not the protocol's.
  std::string mu = render::FormatNumber(result.stability.sim.mu, 2);
  if (result.close_by != phys::HandBuildOptions{}.close_by) {
    mu += ", grip \u03b4 = " + render::FormatNumber(result.close_by, 2) + " rad";
  }
  const bool perturbed = result.perturb > 0;
  if (perturbed) {
    d.title = "Stable fraction of " + std::to_string(result.perturb) +
              " perturbed poses, \u03bc = " + mu + " (Wilson 95 %)";
    d.y_label = "Stable fraction of perturbed repetitions";
    d.y_max = 1.0;
  } else {
    d.title = "Gravity directions held, \u03bc = " + mu + " (legend: stable, Wilson 95 %)";
    d.y_label = "Gravity directions held (of 6)";
    d.y_max = 6.0;
  }
  for (const planning::HumanGrasp& g : result.grasps) d.grasps.push_back(g.name);
  for (size_t mi = 0; mi < result.methods.size(); ++mi) {
    const phys::GraspMethodSummary& s = result.summary[mi];
    // The legend carries each method's rate with its Wilson 95 % interval: over the grasps
    // (stable = all six directions held) and, with perturbations, over every repetition.
    std::string label = std::string(planning::ToString(s.method)) + ": " +
                        phys::RateText(s.stable, s.grasps, s.ci95);
    if (perturbed) {
      label +=
          ", perturbed " + phys::RateText(s.perturbed_stable, s.perturbed_trials, s.perturbed_ci95);
    }
    d.methods.push_back(label);
    d.value.emplace_back();
    if (perturbed) {
      d.lo.emplace_back();
      d.hi.emplace_back();
    }
    for (size_t gi = 0; gi < result.grasps.size(); ++gi) {
      const phys::GraspTrial& trial = result.trials[gi][mi];
      if (!perturbed) {
        d.value.back().push_back(trial.stability.directions_passed);
        continue;
      }
      const int n = static_cast<int>(trial.perturbed.size());
      const Eigen::Vector2d ci =
          n > 0 ? planning::WilsonInterval(trial.perturbed_stable, n) : Eigen::Vector2d(0, 1);
      d.value.back().push_back(n > 0 ? static_cast<double>(trial.perturbed_stable) / n : 0.0);
      d.lo.back().push_back(ci[0]);
      d.hi.back().push_back(ci[1]);
    }
  }
  return d;
}

render::Figure GraspSummaryFigure(const GraspSummaryData& d) {
  render::BarChart chart;
  chart.categories = d.grasps;
  for (size_t m = 0; m < d.methods.size(); ++m) {
    render::BarSeries b;
    b.label = d.methods[m];
    b.values = d.value.at(m);
    if (!d.lo.empty()) {
      b.lo = d.lo.at(m);
      b.hi = d.hi.at(m);
    }
    chart.series.push_back(b);
  }
  render::PlotOptions po;
  po.width = 1280;  // room for the legend's rates with their intervals
  po.height = 560;
  po.title = d.title;
  po.x_label = "Grasp";
  po.y_label = d.y_label;
  po.y_min = 0.0;
  po.y_max = d.y_max;
  po.legend = render::LegendPosition::kOutsideRight;
  return render::BarChartFigure(chart, po);
}

}  // namespace visualize
