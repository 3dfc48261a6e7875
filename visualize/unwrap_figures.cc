#include "visualize/unwrap_figures.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "render/plot.h"

namespace visualize {
namespace {

// "90°" for the legend.
std::string AngleLabel(double angle_deg) {
  return render::FormatNumber(angle_deg, 0).append("\u00b0");
}

// Median of v (NaN when empty).
double Median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

render::Figure UnwrapSurvivalFigure(const planning::UnwrapBenchmarkResult& result,
                                    const std::vector<planning::UnwrapSurvivalPoint>& points) {
  if (points.empty()) throw std::invalid_argument("survival figure: no points");
  std::vector<planning::Budget::Unit> units;
  for (const planning::UnwrapSurvivalPoint& p : points) {
    if (std::find(units.begin(), units.end(), p.budget.unit) == units.end()) {
      units.push_back(p.budget.unit);
    }
  }
  std::vector<render::PlotPanel> panels;
  for (planning::Budget::Unit unit : units) {
    const char* x_label = unit == planning::Budget::Unit::kCpuTime     ? "log10 CPU seconds"
                          : unit == planning::Budget::Unit::kPairTests ? "log10 pair tests"
                                                                       : "log10 state queries";
    for (planning::Planner planner : result.planners) {
      render::PlotPanel panel;
      // Failures of the sweep (the same at every budget point of an angle), summed over angles.
      int failed_budget = 0, failed_other = 0;
      for (double angle : result.angles_deg) {
        render::PlotSeries ser;
        ser.label = AngleLabel(angle);
        ser.marker = render::Marker::kNone;
        for (const planning::UnwrapSurvivalPoint& p : points) {
          if (p.budget.unit != unit || p.planner != planner || p.angle_deg != angle) continue;
          if (ser.x.empty()) {
            failed_budget += p.failed_budget;
            failed_other += p.failed_other;
          }
          ser.x.push_back(std::log10(p.budget.value));
          ser.y.push_back(p.runs > 0 ? static_cast<double>(p.solved) / p.runs : 0.0);
        }
        if (!ser.x.empty()) panel.series.push_back(ser);
      }
      panel.axes.title = std::string(planning::PlannerName(planner)) + ": failed " +
                         std::to_string(failed_budget) + " at budget, " +
                         std::to_string(failed_other) + " other";
      panel.axes.x_label = x_label;
      panel.axes.y_label = "Fraction solved";
      panel.axes.y_min = 0.0;
      panel.axes.y_max = 1.05;
      panel.axes.legend =
          panels.empty() ? render::LegendPosition::kTopLeft : render::LegendPosition::kNone;
      panels.push_back(panel);
    }
  }
  render::PanelLayout layout;
  layout.columns = static_cast<int>(result.planners.size());
  layout.width = std::max(640, 330 * layout.columns);
  layout.height = 330 * static_cast<int>(units.size()) + 40;
  layout.title = "Survival: fraction of seeds solved within each budget";
  return render::PanelsFigure(panels, layout);
}

std::vector<render::PlotPanel> UnwrapAblationPanels(
    const planning::UnwrapBenchmarkResult& result,
    const std::vector<planning::UnwrapAblation>& ablations) {
  if (result.runs.empty()) throw std::invalid_argument("ablation figure: no runs");
  render::PlotPanel success, writhe, reach;
  // Variants often share a value (every one solves an angle): each series is drawn dodged
  // sideways by its own offset, the K series together spanning 40 % of the angle step.
  double step = result.angles_deg.size() > 1 ? std::numeric_limits<double>::infinity() : 90.0;
  for (size_t i = 1; i < result.angles_deg.size(); ++i)
    step = std::min(step, std::abs(result.angles_deg[i] - result.angles_deg[i - 1]));
  const double count = static_cast<double>(ablations.size());
  const double dodge = count > 1 ? 0.4 * step / (count - 1) : 0.0;
  for (size_t k = 0; k < ablations.size(); ++k) {
    const planning::UnwrapAblation& ab = ablations[k];
    const double shift = (static_cast<double>(k) - 0.5 * (count - 1)) * dodge;
    render::PlotSeries s(ab.name), w(ab.name), r(ab.name);
    for (double angle : result.angles_deg) {
      int runs = 0, solved = 0;
      std::vector<double> writhes, reaches;
      for (const planning::UnwrapRun& run : result.runs) {
        if (run.variant != ab.name || run.angle_deg != angle) continue;
        ++runs;
        solved += run.report.success ? 1 : 0;
        writhes.push_back(std::abs(run.report.final_writhe_total));
        if (run.report.reach_error_m >= 0.0) reaches.push_back(run.report.reach_error_m);
      }
      s.x.push_back(angle + shift);
      s.y.push_back(runs > 0 ? static_cast<double>(solved) / runs : 0.0);
      w.x.push_back(angle + shift);
      w.y.push_back(Median(writhes));
      r.x.push_back(angle + shift);
      r.y.push_back(Median(reaches));
    }
    success.series.push_back(s);
    writhe.series.push_back(w);
    reach.series.push_back(r);
  }
  success.axes.title = "Success";
  success.axes.y_label = "Fraction of seeds solved";
  success.axes.y_min = 0.0;
  success.axes.y_max = 1.05;
  writhe.axes.title = "Final |total writhe| (median)";
  writhe.axes.y_label = "|writhe| (turns)";
  writhe.axes.y_min = 0.0;
  reach.axes.title = "Final reach error (median)";
  reach.axes.y_label = "Reach error (m)";
  reach.axes.y_min = 0.0;
  for (render::PlotPanel* p : {&success, &writhe, &reach}) {
    p->axes.x_label = "Angle to unwrap (deg; variants side by side)";
    p->axes.legend = render::LegendPosition::kNone;
  }
  writhe.axes.legend = render::LegendPosition::kTopLeft;  // the writhe stays low at small angles
  return {success, writhe, reach};
}

render::Figure UnwrapAblationFigure(const planning::UnwrapBenchmarkResult& result,
                                    const std::vector<planning::UnwrapAblation>& ablations) {
  const std::vector<render::PlotPanel> panels = UnwrapAblationPanels(result, ablations);
  render::PanelLayout layout;
  layout.width = 1380;
  layout.height = 480;
  layout.columns = 3;
  layout.title = "AICO ablations: each task term removed in turn (" + std::to_string(result.seeds) +
                 (result.seeds == 1 ? " seed" : " seeds") + ")";
  return render::PanelsFigure(panels, layout);
}

}  // namespace visualize
