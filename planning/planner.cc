#include "planning/planner.h"

#include <chrono>
#include <cmath>
#include <random>
#include <stdexcept>

#include "planning/collision.h"
#include "planning/enum_names.h"
#include "planning/internal/ompl_planners.h"
#include "planning/kinematics.h"
#include "planning/rrt.h"

namespace planning {

inline constexpr EnumName<Planner> kPlannerNames[] = {
    {Planner::kAico, "aico"},
    {Planner::kRrt, "rrt"},
    {Planner::kBiRrt, "birrt"},
    {Planner::kOmplRrt, "ompl-rrt"},
    {Planner::kOmplRrtConnect, "ompl-rrtconnect"},
};
constexpr std::span<const EnumName<Planner>> EnumNames(Planner) { return kPlannerNames; }

namespace {

bool NeedsOmpl(Planner p) { return p == Planner::kOmplRrt || p == Planner::kOmplRrtConnect; }

// The validity checker of every planner and of every output-path check: inside the joint limits
// and not InCollision (one counted query on `coll` per call).
ValidityFn ValidityChecker(const Scenario& s, CollisionData* coll, KinematicsData* kin) {
  const Eigen::VectorXd lo = LowerLimits(s.robot), hi = UpperLimits(s.robot);
  return [&s, coll, kin, lo, hi](const Eigen::VectorXd& q) {
    for (Eigen::Index k = 0; k < q.size(); ++k) {
      if (q[k] < lo[k] || q[k] > hi[k]) return false;
    }
    ForwardKinematics(s.robot, q, kin);
    return !InCollision(s.robot, *kin, coll);
  };
}

}  // namespace

std::vector<Planner> AvailablePlanners() {
  std::vector<Planner> out;
  for (const EnumName<Planner>& e : kPlannerNames) {
    if (!NeedsOmpl(e.value) || OmplAvailable()) out.push_back(e.value);
  }
  return out;
}

Planner ParsePlanner(const std::string& name) {
  const Planner p = ParseEnum<Planner>(name, "planner");
  if (NeedsOmpl(p) && !OmplAvailable()) {
    throw std::invalid_argument("planner '" + name +
                                "': topoplan was built without OMPL (apt-get install "
                                "libompl-dev, then re-run cmake)");
  }
  return p;
}

bool OmplAvailable() {
#ifdef TOPOPLAN_HAVE_OMPL
  return true;
#else
  return false;
#endif
}

const char* PlannerName(Planner planner) { return ToName(planner); }

bool MeetsSuccessCriteria(const Scenario& s, const Eigen::VectorXd& q, double final_writhe) {
  const SuccessCriteria& c = s.success;
  if (c.writhe_total_below >= 0.0 && !(std::abs(final_writhe) < c.writhe_total_below)) {
    return false;
  }
  const int T = s.problem.num_steps;
  for (int idx : {c.position_task, c.box_task}) {
    if (idx < 0) continue;
    const Task& task = s.problem.tasks[idx];
    const Eigen::VectorXd y = FeatureValue(s.robot, *task.feature, q);
    const double err = (y - task.target.col(T)).norm();
    if (idx == c.position_task && err > c.position_tolerance) return false;
    if (idx == c.box_task && err > 1e-9) return false;
  }
  return true;
}

PlanResult RunPlanner(const Scenario& s, Planner planner, unsigned seed,
                      const AicoCallback& callback) {
  PlanResult out;
  PlanReport& rep = out.report;
  rep.planner = PlannerName(planner);
  const int n = num_dofs(s.robot);
  CollisionData coll(s.robot, s.env, s.collision);
  KinematicsData kin(s.robot);
  const ValidityFn valid = ValidityChecker(s, &coll, &kin);
  const auto t0 = std::chrono::steady_clock::now();
  bool found = false;
  if (planner == Planner::kAico) {
    // Attempt k: solve, then validate the path at the edge resolution (counted: a plan is only
    // usable once checked) and test the success criteria; the next attempt only on failure.
    for (int k = 0; k < static_cast<int>(s.aico_attempts.size()) && !found; ++k) {
      MotionProblem later;
      if (k > 0) {
        later = AttemptProblem(s, k);
        ++rep.attempts;
      }
      const MotionProblem& problem = k == 0 ? s.problem : later;
      AicoWorkspace ws(problem);
      const AicoResult r = SolveAico(problem, AttemptOptions(s, k), &ws, callback);
      rep.status = r.status;
      rep.iterations += r.iterations;
      rep.cost = r.cost;
      rep.cost_history = r.cost_history;
      rep.collision_checks += r.collision_queries;
      rep.narrow_phase_calls += NarrowPhaseCalls(problem, ws.tasks);
      out.trajectory = r.trajectory;
      const std::int64_t q0 = coll.queries, n0 = coll.narrow_phase_calls;
      rep.path_collision_free = r.status != SolveStatus::kInvalidInput &&
                                PathIsValid(out.trajectory, s.check_resolution, valid);
      rep.collision_checks += coll.queries - q0;
      rep.narrow_phase_calls += coll.narrow_phase_calls - n0;
      const Eigen::VectorXd q_end = out.trajectory.q.col(out.trajectory.num_points() - 1);
      found =
          rep.path_collision_free && MeetsSuccessCriteria(s, q_end, ReportWritheTotal(s, q_end));
    }
    found = found || out.trajectory.num_points() > 0;
  } else {
    RrtProblem rp;
    rp.lower = LowerLimits(s.robot);
    rp.upper = UpperLimits(s.robot);
    for (int k = 0; k < n; ++k) {  // continuous joints: one turn around the start
      if (!std::isfinite(rp.lower[k])) rp.lower[k] = s.problem.q0[k] - M_PI;
      if (!std::isfinite(rp.upper[k])) rp.upper[k] = s.problem.q0[k] + M_PI;
    }
    rp.start = s.problem.q0;
    rp.goal = s.goal_q;
    std::mt19937 rng(seed);
    RrtResult r;
    switch (planner) {
      case Planner::kRrt:
        r = PlanRrt(rp, s.rrt, valid, &rng);
        break;
      case Planner::kBiRrt:
        r = PlanBiRrt(rp, s.rrt, valid, &rng);
        break;
      case Planner::kOmplRrt:
      case Planner::kOmplRrtConnect:
#ifdef TOPOPLAN_HAVE_OMPL
        r = internal::PlanOmpl(planner == Planner::kOmplRrt ? internal::OmplPlanner::kRrt
                                                            : internal::OmplPlanner::kRrtConnect,
                               rp, s.rrt, valid, seed);
        break;
#else
        throw std::invalid_argument(std::string("planner '") + PlannerName(planner) +
                                    "': topoplan was built without OMPL");
#endif
      case Planner::kAico:
        break;
    }
    rep.status = r.status;
    rep.iterations = r.iterations;
    rep.collision_checks = coll.queries;
    rep.narrow_phase_calls = coll.narrow_phase_calls;
    out.trajectory = r.path;
    found = r.status == SolveStatus::kConverged;
    // RRT paths are checked edge by edge while planning; re-check at the scenario's resolution
    // (on a separate, uncounted collision state).
    if (found && out.trajectory.num_points() > 0) {
      CollisionData recheck(s.robot, s.env, s.collision);
      rep.path_collision_free =
          PathIsValid(out.trajectory, s.check_resolution, ValidityChecker(s, &recheck, &kin));
    }
  }
  rep.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  // Report quantities (not counted).
  rep.start_writhe_total = ReportWritheTotal(s, s.problem.q0);
  if (out.trajectory.num_points() > 0) {
    const Eigen::VectorXd q_end = out.trajectory.q.col(out.trajectory.num_points() - 1);
    rep.final_writhe_total = ReportWritheTotal(s, q_end);
    rep.path_length = PathLength(out.trajectory);
    if (planner != Planner::kAico) rep.cost = rep.path_length;
    // Minimum clearance along the densified path (pairs within 0.2 m; 0.2 if none is closer).
    CollisionData metric(s.robot, s.env, s.collision);
    std::vector<ProximityPair> pairs;
    double clearance = 0.2;
    const Trajectory dense = Densify(out.trajectory, s.check_resolution);
    for (int t = 0; t < dense.num_points(); ++t) {
      ForwardKinematics(s.robot, dense.q.col(t), &kin);
      ComputeProximity(s.robot, kin, 0.2, &metric, &pairs);
      for (const ProximityPair& p : pairs) clearance = std::min(clearance, p.distance);
    }
    rep.min_clearance_m = clearance;
    rep.success =
        found && rep.path_collision_free && MeetsSuccessCriteria(s, q_end, rep.final_writhe_total);
  } else {
    rep.final_writhe_total = rep.start_writhe_total;
    rep.success = false;
  }
  return out;
}

}  // namespace planning
