#include "planning/physics/grasp_report.h"

#include "base/numbers.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <locale>
#include <sstream>

#include "planning/grasp/grasp_quality.h"

namespace planning::physics {
namespace {

namespace fs = std::filesystem;

nlohmann::json VecJson(const Eigen::VectorXd& v) {
  nlohmann::json a = nlohmann::json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(std::round(v[i] * 1e6) / 1e6);
  return a;
}

double Round(double v, double scale = 1e6) { return std::round(v * scale) / scale; }

// {trials, stable, rate, ci95: [lo, hi]} (Wilson 95 %) of perturbed repetitions.
nlohmann::json PerturbedJson(int trials, int stable) {
  nlohmann::json j = {{"trials", trials}, {"stable", stable}};
  if (trials > 0) {
    const Eigen::Vector2d ci = WilsonInterval(stable, trials);
    j["rate"] = Round(static_cast<double>(stable) / trials, 1e4);
    j["ci95"] = {Round(ci[0], 1e4), Round(ci[1], 1e4)};
  }
  return j;
}

// Spearman's rank correlation of ε against the ODE outcome over every trial of the run (each
// grasp × method, and each perturbed repetition): {trials, spearman_stable,
// spearman_directions}; a correlation is null when undefined (e.g. every trial stable).
nlohmann::json EpsilonOutcomeJson(const GraspTrialsResult& result) {
  std::vector<double> eps, stable, directions;
  for (const std::vector<GraspTrial>& row : result.trials) {
    for (const GraspTrial& trial : row) {
      eps.push_back(trial.epsilon_quality);
      stable.push_back(trial.stability.stable ? 1.0 : 0.0);
      directions.push_back(trial.stability.directions_passed);
      for (const PerturbedTrial& p : trial.perturbed) {
        eps.push_back(p.epsilon_quality);
        stable.push_back(p.stable ? 1.0 : 0.0);
        directions.push_back(p.directions_passed);
      }
    }
  }
  auto value = [](const std::optional<double>& r) {
    return r ? nlohmann::json(Round(*r, 1e4)) : nlohmann::json(nullptr);
  };
  return {{"trials", eps.size()},
          {"spearman_stable", value(SpearmanCorrelation(eps, stable))},
          {"spearman_directions", value(SpearmanCorrelation(eps, directions))}};
}

// The stability protocol: times, contact model, grip travel, thresholds and ODE's constraint
// solver (the same for every hand and method).
nlohmann::json ProtocolJson(const GraspTrialsResult& result) {
  const StabilityOptions& stab = result.stability;
  nlohmann::json protocol = {{"close_time_s", stab.close_time},
                             {"trial_time_s", stab.trial_time},
                             {"dt_s", stab.sim.dt},
                             {"contact_patch_radius_m", stab.sim.contact_patch_radius},
                             {"close_by_rad", result.close_by},
                             {"max_slip_m", stab.max_slip},
                             {"max_rotation_deg", stab.max_rotation_deg},
                             {"min_contact_links", stab.min_contact_links}};
  protocol["stepper"] = base::ToName(stab.sim.stepper);
  if (stab.sim.stepper == Stepper::kQuickStep) {
    protocol["quickstep_iterations"] = stab.sim.quickstep_iterations;
  }
  return protocol;
}

// The outcome under each gravity direction of a stability test.
nlohmann::json DirectionsJson(const StabilityResult& r) {
  nlohmann::json dirs = nlohmann::json::array();
  for (const auto& d : r.directions) {
    dirs.push_back({{"gravity", d.label},
                    {"passed", d.passed},
                    {"slip_m", Round(d.slip_m)},
                    {"rotation_deg", Round(d.rotation_deg, 1e3)},
                    {"contact_links", d.contact_links},
                    {"blown_up", d.blown_up}});
  }
  return dirs;
}

// Each perturbed repetition of a trial: outcome, ε and how far the object was moved and turned
// from the grasp's pose.
nlohmann::json RepetitionsJson(const GraspTrial& trial, const HumanGrasp& g) {
  nlohmann::json reps = nlohmann::json::array();
  for (const PerturbedTrial& p : trial.perturbed) {
    const Eigen::Isometry3d delta = g.world_from_object.inverse() * p.world_from_object;
    reps.push_back(
        {{"stable", p.stable},
         {"directions_passed", p.directions_passed},
         {"epsilon_quality", Round(p.epsilon_quality)},
         {"offset_m",
          VecJson(p.world_from_object.translation() - g.world_from_object.translation())},
         {"rotation_deg", Round(Eigen::AngleAxisd(delta.linear()).angle() * 180.0 / M_PI, 1e3)}});
  }
  return reps;
}

// One method's entry of a grasp: windings, transfer solver, stability and, with perturb > 0,
// the perturbed repetitions.
nlohmann::json TrialJson(const GraspTrial& trial, const HumanGrasp& g, int perturb) {
  const TransferResult& t = trial.transfer;
  const StabilityResult& r = trial.stability;
  nlohmann::json j;
  j["target_winding"] = VecJson(t.target_winding);
  j["robot_winding"] = VecJson(t.robot_winding);
  // Per extra reference curve of the object (objects.json "extra_references"), stacked: the
  // opposition pair (max, min over the fingers) asked for and reached; [] without such curves.
  j["target_extra_winding"] = VecJson(t.target_extra_winding);
  j["robot_extra_winding"] = VecJson(t.robot_extra_winding);
  nlohmann::json ph = nlohmann::json::array();
  for (const Eigen::VectorXd& v : t.robot_phalanx_winding) ph.push_back(VecJson(v));
  j["robot_phalanx_winding"] = ph;
  j["winding_error"] = Round(trial.winding_error);
  j["epsilon_quality"] = Round(trial.epsilon_quality);
  j["min_clearance_m"] = Round(t.min_clearance);
  j["solver"] = t.solver;
  j["solver_iterations"] = t.iterations;
  j["q"] = VecJson(t.q);
  j["status"] = ToString(r.status);
  j["message"] = r.message;
  j["closure_contact_links"] = r.closure_contact_links;
  j["directions_passed"] = r.directions_passed;
  j["max_slip_m"] = Round(r.max_slip_m);
  j["max_rotation_deg"] = Round(r.max_rotation_deg, 1e3);
  j["stable"] = r.stable;
  j["directions"] = DirectionsJson(r);
  if (perturb > 0) {
    j["perturbed"] =
        PerturbedJson(static_cast<int>(trial.perturbed.size()), trial.perturbed_stable);
    j["perturbed"]["repetitions"] = RepetitionsJson(trial, g);
  }
  return j;
}

// Grasp `gi`: name, type, object, file, the human windings (from its first method's transfer)
// and one entry per method.
nlohmann::json GraspJson(const GraspTrialsResult& result, size_t gi) {
  const HumanGrasp& g = result.grasps[gi];
  nlohmann::json gj;
  gj["name"] = g.name;
  gj["type"] = g.type;
  gj["object"] = g.object;
  gj["file"] = fs::path(g.source).filename().string();
  nlohmann::json mj = nlohmann::json::object();
  for (size_t mi = 0; mi < result.methods.size(); ++mi) {
    const GraspTrial& trial = result.trials[gi][mi];
    const TransferResult& t = trial.transfer;
    if (!gj.contains("human_winding")) {
      gj["human_winding"] = VecJson(t.human_winding);
      nlohmann::json hp = nlohmann::json::array();
      for (const Eigen::VectorXd& v : t.human_phalanx_winding) hp.push_back(VecJson(v));
      gj["human_phalanx_winding"] = hp;
    }
    mj[ToString(result.methods[mi])] = TrialJson(trial, g, result.perturb);
  }
  gj["methods"] = mj;
  return gj;
}

// Per method: stable grasps, success rate and its Wilson 95 % interval (and the perturbed
// repetitions' with perturb > 0).
nlohmann::json SummaryJson(const GraspTrialsResult& result) {
  nlohmann::json summary = nlohmann::json::object();
  for (const GraspMethodSummary& s : result.summary) {
    nlohmann::json sj = {{"stable", s.stable},
                         {"grasps", s.grasps},
                         {"success_rate", Round(s.rate, 1e4)},
                         {"ci95", {Round(s.ci95[0], 1e4), Round(s.ci95[1], 1e4)}}};
    if (result.perturb > 0) sj["perturbed"] = PerturbedJson(s.perturbed_trials, s.perturbed_stable);
    summary[ToString(s.method)] = sj;
  }
  return summary;
}

}  // namespace

std::string RateText(int stable, int trials, const Eigen::Vector2d& ci) {
  char buf[64];
  if (trials > 0) {
    std::snprintf(buf, sizeof buf, "%d/%d (%s-%s)", stable, trials,
                  base::FormatFixed(ci[0], 2).c_str(), base::FormatFixed(ci[1], 2).c_str());
  } else {
    std::snprintf(buf, sizeof buf, "0/0");
  }
  return buf;
}

nlohmann::json GraspReportJson(const GraspTrialsResult& result) {
  nlohmann::json report;
  report["mu"] = result.stability.sim.mu;
  report["protocol"] = ProtocolJson(result);
  report["grasps"] = nlohmann::json::array();
  for (size_t gi = 0; gi < result.grasps.size(); ++gi) {
    report["grasps"].push_back(GraspJson(result, gi));
  }
  report["summary"] = SummaryJson(result);
  report["epsilon_vs_outcome"] = EpsilonOutcomeJson(result);
  if (result.perturb > 0) {
    report["perturb"] = {{"repetitions", result.perturb},
                         {"seed", result.seed},
                         {"max_translation_m", result.perturb_translation},
                         {"max_rotation_deg", result.perturb_rotation_deg}};
  }
  return report;
}

std::string GraspSummaryMarkdown(const GraspTrialsResult& result) {
  std::ostringstream md;
  md.imbue(std::locale::classic());  // "0.5" whatever the global locale
  md << "# Grasp transfer to the SDH: ODE stability (mu = " << result.stability.sim.mu
     << ", soft-finger contact patch " << result.stability.sim.contact_patch_radius * 1e3
     << " mm, flexion set-points " << result.close_by << " rad past the grasp)\n\n"
     << "Directions passed out of 6 (gravity along +-x, +-y, +-z of the palm, 2 s each at 1 kHz); "
        "a grasp is stable when it passes all 6. eps: Ferrari-Canny epsilon of the contacts at "
        "the end of closing.\n\n| grasp |";
  for (TransferMethod m : result.methods) md << " " << ToString(m) << " |";
  for (TransferMethod m : result.methods) md << " eps " << ToString(m) << " |";
  md << "\n|---|";
  for (size_t i = 0; i < 2 * result.methods.size(); ++i) md << "---|";
  md << "\n";
  for (size_t gi = 0; gi < result.grasps.size(); ++gi) {
    md << "| " << result.grasps[gi].name << " |";
    for (const GraspTrial& trial : result.trials[gi]) {
      md << " " << trial.stability.directions_passed << "/6"
         << (trial.stability.stable ? " stable" : "");
      if (result.perturb > 0) {
        md << ", perturbed " << trial.perturbed_stable << "/" << trial.perturbed.size();
      }
      md << " |";
    }
    for (const GraspTrial& trial : result.trials[gi]) {
      md << " " << base::FormatFixed(trial.epsilon_quality, 4) << " |";
    }
    md << "\n";
  }
  md << "| **success rate (95 % CI)** |";
  for (const GraspMethodSummary& s : result.summary) {
    md << " " << RateText(s.stable, s.grasps, s.ci95) << " |";
  }
  for (size_t i = 0; i < result.summary.size(); ++i) md << " |";
  md << "\n";
  if (result.perturb > 0) {
    md << "| **perturbed (95 % CI)** |";
    for (const GraspMethodSummary& s : result.summary) {
      md << " " << RateText(s.perturbed_stable, s.perturbed_trials, s.perturbed_ci95) << " |";
    }
    for (size_t i = 0; i < result.summary.size(); ++i) md << " |";
    md << "\n\nperturbed: " << result.perturb << " repetitions per grasp and method, object moved "
       << "by up to " << result.perturb_translation * 1e3 << " mm per axis and turned by up to "
       << result.perturb_rotation_deg << " deg (seed " << result.seed
       << "); intervals: Wilson 95 %.\n";
  }
  const nlohmann::json rank = EpsilonOutcomeJson(result);
  auto text = [](const nlohmann::json& r) {
    if (r.is_null()) return std::string("undefined (one outcome only)");
    return base::FormatFixed(r.get<double>(), 2);
  };
  md << "\nRank correlation (Spearman) of eps with the outcome over all "
     << rank["trials"].get<size_t>() << " trials"
     << (result.perturb > 0 ? " (incl. perturbed)" : "") << ": " << text(rank["spearman_stable"])
     << " against stable, " << text(rank["spearman_directions"]) << " against directions held.\n";
  return md.str();
}

}  // namespace planning::physics
