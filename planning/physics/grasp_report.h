// The files a grasp-transfer run is reported in: report.json and summary.md, plain data out of
// GraspTrialsResult, shared by the command line, the demo, the viewer and the Python module.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "planning/physics/grasp_trials.h"

namespace planning::physics {

// report.json of `grasp transfer`: mu, protocol, per grasp (name, type, object, file, human
// windings, per method: windings, winding_error, epsilon_quality, clearance, solver, q,
// stability; with perturb > 0 also perturbed: {trials, stable, rate, ci95: [lo, hi]}) and
// per-method summary (stable, grasps, success_rate, ci95: Wilson 95 % over the grasps; with
// perturb > 0 perturbed: {trials, stable, rate, ci95} over all repetitions), and with perturb > 0
// "perturb": {repetitions, seed, max_translation_m, max_rotation_deg}. Values rounded to 1e-6
// (rotations 1e-3, rates and intervals 1e-4).
nlohmann::json GraspReportJson(const GraspTrialsResult& result);

// summary.md: directions passed out of 6 per grasp and method, then one "eps METHOD" column per
// method (GraspTrial::epsilon_quality, 4 decimals), and the success-rate row with Wilson 95 %
// intervals; with perturb > 0 each cell also gives "perturbed s/N" and a perturbed-rate row.
std::string GraspSummaryMarkdown(const GraspTrialsResult& result);

// "5/8 (0.31-0.86)": a count of stable trials and its Wilson 95 % interval `ci`; "0/0" for no
// trials.
std::string RateText(int stable, int trials, const Eigen::Vector2d& ci);

}  // namespace planning::physics
