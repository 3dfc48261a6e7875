// The grasp-transfer study of `bench grasp` (issue 36): many noisy demonstrations per grasp
// type, every SDH method transfers every demonstration under equal budgets, each transfer is
// tested in ODE (and in MuJoCo when built with it) and compared with its demonstration by
// encoding-independent measures (contact-region IoU per finger, thread preservation).
//
// One (grasp, demonstration) is a unit: PrepareStudyUnit does everything but ODE (thread-safe:
// demonstration, transfers, MuJoCo, similarity), FinishStudyUnit runs the ODE verdicts on the
// thread that owns the OdeRuntime.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "planning/grasp/demo_noise.h"
#include "planning/grasp/grasp.h"
#include "planning/grasp/grasp_object.h"
#include "planning/grasp/grasp_similarity.h"
#include "planning/grasp/grasp_transfer.h"
#include "planning/physics/hand_builder.h"
#include "planning/physics/mujoco_stability.h"
#include "planning/physics/stability.h"
#include "planning/robot/robot.h"

namespace planning::physics {

// TransferOptions{} with equal_baselines: every method the same optimiser, starts, cap, terms.
inline TransferOptions EqualBaselineTransfer() {
  TransferOptions o;
  o.equal_baselines = true;
  return o;
}

struct GraspStudyOptions {
  DemoNoiseOptions noise;  // bounds and seed of the demonstrations (NoisyDemonstration)
  // The SDH methods compared (kHuman is not a transfer and is rejected).
  std::vector<TransferMethod> methods = {TransferMethod::kWinding, TransferMethod::kWindingOnly,
                                         TransferMethod::kContactOnly, TransferMethod::kFingertip,
                                         TransferMethod::kJointMapping};
  TransferOptions transfer = EqualBaselineTransfer();  // the same for every method (below)
  StabilityOptions stability;                          // the protocol, the same for both engines
  double close_by = HandBuildOptions{}.close_by;       // grip [rad]
  bool mujoco = false;                                 // also the MuJoCo verdict
  // The shared placement stage, identical for every method. kHumanPalm (default) reads neither
  // the object's reference nor any encoding; kObjectCentre (`grasp transfer`'s rule, which reads
  // the winding target for loops) is the ablation.
  PlacementRule placement = PlacementRule::kHumanPalm;
  ContactRegionOptions regions;
};

// The outcome of one method on one demonstration: one row of grasp.csv.
struct StudyRow {
  std::string grasp;       // nominal grasp name (file stem)
  std::string object;      // object name
  bool threading = false;  // the object has a hole to thread (its reference is a loop)
  int demo = 0;            // demonstration index (NoisyDemonstration)
  std::uint32_t seed = 0;  // DemoNoiseOptions::seed of the demonstration
  TransferMethod method = TransferMethod::kWinding;
  bool ode_stable = false;
  int ode_directions = 0;  // gravity directions held (of 6)
  StabilityStatus ode_status = StabilityStatus::kTested;
  std::optional<bool> mujoco_stable;  // empty without MuJoCo
  int mujoco_directions = 0;
  StabilityStatus mujoco_status = StabilityStatus::kTested;
  // Per SDH finger (thumb, finger_1, finger_2): IoU of the contact regions of the transfer and of
  // the corresponding human fingers in the demonstration; empty when neither touches.
  std::array<std::optional<double>, 3> iou;
  int demo_threads = 0;        // SDH fingers whose human group threads the hole (0: no hole)
  int threads_preserved = 0;   // of those, threading in the transfer
  int starts = 0;              // AICO runs
  long task_evaluations = 0;   // their task evaluations
  int iterations = 0;          // sweeps of the winning run
  double winding_error = 0.0;  // |robot − target winding| [turns]
  double min_clearance = 0.0;  // hand–object clearance at the transfer [m]

  // Mean of the defined per-finger IoUs; empty when none is defined.
  std::optional<double> MeanIoU() const;
};

// A prepared unit: the demonstration, its setup and per method the transfer, the ODE/MuJoCo
// descriptions and the row filled but for the ODE verdict.
struct StudyUnit {
  HumanGrasp demo;
  std::vector<TransferResult> transfers;
  std::vector<SimHand> hands;
  SimObject object;
  std::vector<StudyRow> rows;  // one per options.methods, ODE fields not yet set
};

// Demonstration `demo` of `nominal` (NoisyDemonstration, then RecloseDemonstration with
// nominal.close: give it the close list of the grasp's spec so that the noisy hand touches the
// object again; without one the noisy posture is used as drawn), its setup (MakeTransferSetup with
// `human` and `sdh_source`), every method's transfer with options.transfer, the MuJoCo verdict
// (options.mujoco) and the similarity measures. Thread-safe (no ODE). Throws
// std::invalid_argument for kHuman among the methods or bad inputs (as MakeTransferSetup).
StudyUnit PrepareStudyUnit(const Robot& human, const Robot& sdh_source,
                           const std::vector<GraspObject>& objects, const HumanGrasp& nominal,
                           int demo, const GraspStudyOptions& options);

// Runs the ODE stability test of every method of a prepared unit and fills the ODE fields;
// `on_row` (if set) is called with each row as soon as its verdict is in (`bench grasp` journals
// it there, so that a killed run keeps every finished trial).
void FinishStudyUnit(const OdeRuntime& runtime, const GraspStudyOptions& options, StudyUnit* unit,
                     const std::function<void(const StudyRow&)>& on_row = {});

}  // namespace planning::physics
