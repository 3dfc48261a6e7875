// Figures of the budget-free verdicts and the ablations of `bench unwrap` (docs/results/unwrap.md):
// survival curves (fraction solved against the budget, Planner Arena's cumulative time-to-solve,
// Moll, Sucan, Kavraki 2015) and the AICO ablation panels.
#pragma once

#include <vector>

#include "planning/motion/unwrap_benchmark.h"
#include "render/figure.h"
#include "render/plot.h"

namespace visualize {

// One panel per (unit, planner): one row per unit present in `points` (in their order); x = log10
// of the budget, y = fraction of the seeds solved within it, one curve per angle. Each panel's
// title names the failures at the largest budget that stopped at the budget (more budget may solve
// them) and the others (no budget solves them). Throws std::invalid_argument for no points.
render::Figure UnwrapSurvivalFigure(const planning::UnwrapBenchmarkResult& result,
                                    const std::vector<planning::UnwrapSurvivalPoint>& points);

// Three panels over the angle to unwrap, one series per ablation (in `ablations` order, legend on
// the second): success fraction over the seeds; median |final total writhe| [turns]; median final
// reach error [m]. Series k of K is drawn at angle + (k − (K−1)/2)·δ, δ = 0.4·step / (K−1)
// (step: the smallest angle step, 90° for one angle), so that variants with equal values stay
// visible side by side.
// Throws std::invalid_argument for a result without runs.
std::vector<render::PlotPanel> UnwrapAblationPanels(
    const planning::UnwrapBenchmarkResult& result,
    const std::vector<planning::UnwrapAblation>& ablations);
// The three panels side by side (1380 × 480 px) under a title naming the seeds.
render::Figure UnwrapAblationFigure(const planning::UnwrapBenchmarkResult& result,
                                    const std::vector<planning::UnwrapAblation>& ablations);

}  // namespace visualize
