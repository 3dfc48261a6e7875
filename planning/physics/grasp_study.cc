// The grasp-transfer study (planning/physics/grasp_study.h).
#include "planning/physics/grasp_study.h"

#include <stdexcept>

#include "planning/robot/kinematics.h"

namespace planning::physics {
namespace {

// Threading of the human demonstration (per SDH finger group) or of the SDH at q; empty for an
// object without a hole.
std::vector<bool> Threading(const TransferSetup& s, bool human, const Eigen::VectorXd& q) {
  if (s.reference.kind != ReferenceCurve::Kind::kLoop) return {};
  const Robot& robot = human ? s.human : s.sdh;
  KinematicsData kin(robot);
  ForwardKinematics(robot, q, &kin);
  const std::vector<bool> t =
      FingersThreading(robot, kin, human ? s.human_chains : s.sdh_chains, s.reference.loop);
  return human ? HumanThreadingForSdh(t) : t;
}

std::vector<CellSet> Regions(const TransferSetup& s, bool human, const Eigen::VectorXd& q,
                             const ContactRegionOptions& o) {
  const Robot& robot = human ? s.human : s.sdh;
  KinematicsData kin(robot);
  ForwardKinematics(robot, q, &kin);
  return FingerContactRegions(robot, kin, human ? HumanGroupsForSdh() : SdhGroups(), s.object,
                              s.grasp.world_from_object, o);
}

}  // namespace

std::optional<double> StudyRow::MeanIoU() const {
  double sum = 0;
  int n = 0;
  for (const std::optional<double>& v : iou) {
    if (!v) continue;
    sum += *v;
    ++n;
  }
  if (n == 0) return std::nullopt;
  return sum / n;
}

StudyUnit PrepareStudyUnit(const Robot& human, const Robot& sdh_source,
                           const std::vector<GraspObject>& objects, const HumanGrasp& nominal,
                           int demo, const GraspStudyOptions& o) {
  for (TransferMethod m : o.methods) {
    if (m == TransferMethod::kHuman) {
      throw std::invalid_argument("grasp study: 'human' is the demonstration, not a transfer");
    }
  }
  StudyUnit unit;
  unit.demo = NoisyDemonstration(human, nominal, demo, o.noise);
  const GraspObject& object = FindGraspObject(objects, nominal.object);
  RecloseDemonstration(human, object, &unit.demo);
  const TransferSetup setup = MakeTransferSetup(human, sdh_source, object, unit.demo, o.placement);
  unit.object = BuildSimObject(object, unit.demo.world_from_object);
  const std::vector<bool> demo_threads = Threading(setup, true, setup.human_q);
  const std::vector<CellSet> demo_regions = Regions(setup, true, setup.human_q, o.regions);
  HandBuildOptions build;
  build.close_by = o.close_by;
  for (TransferMethod m : o.methods) {
    TransferResult t = TransferGrasp(setup, m, o.transfer);
    StudyRow row;
    row.grasp = nominal.name;
    row.object = object.name;
    row.threading = setup.reference.kind == ReferenceCurve::Kind::kLoop;
    row.demo = demo;
    row.seed = o.noise.seed;
    row.method = m;
    const std::vector<CellSet> regions = Regions(setup, false, t.q, o.regions);
    for (int f = 0; f < 3; ++f) row.iou[f] = RegionIoU(demo_regions[f], regions[f]);
    if (row.threading) {
      const ThreadPreservation tp = CompareThreading(demo_threads, Threading(setup, false, t.q));
      row.demo_threads = tp.demo;
      row.threads_preserved = tp.preserved;
    }
    row.starts = t.starts;
    row.task_evaluations = t.task_evaluations;
    row.iterations = t.iterations;
    row.winding_error = (t.robot_winding - t.target_winding).norm();
    row.min_clearance = t.min_clearance;
    SimHand hand = BuildSimHand(setup.sdh, t.q, "sdh_palm", build);
    if (o.mujoco) {
      const StabilityResult r = TestGraspStabilityMujoco(hand, unit.object, o.stability);
      row.mujoco_stable = r.stable;
      row.mujoco_directions = r.directions_passed;
      row.mujoco_status = r.status;
    }
    unit.transfers.push_back(std::move(t));
    unit.hands.push_back(std::move(hand));
    unit.rows.push_back(row);
  }
  return unit;
}

void FinishStudyUnit(const OdeRuntime& runtime, const GraspStudyOptions& o, StudyUnit* unit,
                     const std::function<void(const StudyRow&)>& on_row) {
  for (size_t k = 0; k < unit->rows.size(); ++k) {
    const StabilityResult r =
        TestGraspStability(runtime, unit->hands[k], unit->object, o.stability);
    unit->rows[k].ode_stable = r.stable;
    unit->rows[k].ode_directions = r.directions_passed;
    unit->rows[k].ode_status = r.status;
    if (on_row) on_row(unit->rows[k]);
  }
}

}  // namespace planning::physics
