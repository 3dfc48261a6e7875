// Transfer of a human grasp to the Schunk SDH: finger correspondence, the winding-number method
// (AICO on a floating SDH), its ablations (winding_only, contact_only) and the two classical
// baselines (fingertip mapping, linear joint mapping), all through the same AICO pipeline.
//
// Finger correspondence (documented in README "Grasp transfer"): SDH thumb ← human thumb (the
// opposing finger); SDH finger_2 (the rotating finger on the radial side once the SDH palm is
// placed on the human palm) ← index + middle; SDH finger_1 (ulnar side) ← ring + little.
// Winding targets are averages: y*_SDH = M y_human with
//   M = [1 0 0 0 0; 0 0 0 ½ ½; 0 ½ ½ 0 0]  (rows thumb, finger_1, finger_2).
//
// SDH placement: the SDH palm frame (z out of the palm, x from the thumb towards the rotating
// fingers) is put on the human palm: z_SDH = human palm normal (−y_h), y_SDH = −x_h (so the
// thumb sits on the wrist side, as the human thumb's base does); the palm origin lies on the line
// along z_SDH through the grasp centre (the reference-axis point nearest the human palm centre,
// or the reference loop's centroid), max(0.12, 0.095 + object depth) m before it so the knuckles
// clear the object. All SDH methods start there and optimise the palm pose (6 DOF, with a prior
// towards the placement) together with the fingers.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "base/enum_names.h"
#include "planning/features/task.h"
#include "planning/grasp/grasp.h"
#include "planning/grasp/grasp_object.h"
#include "planning/motion/aico.h"
#include "planning/motion/trajectory.h"
#include "planning/robot/robot.h"

namespace planning {

// Methods (README "Grasp transfer"). Every SDH method runs the same pipeline (MakeTransferProblem:
// AICO on the floating SDH with the shared terms of SharedTransferTasks) and differs only in its
// target term:
//   winding       windings + the shared terms (non-penetration and contact)
//   winding_only  windings + non-penetration only (no contact term)
//   contact_only  the shared terms alone (no target term)
//   fingertip     fingertip positions + the shared terms
//   joint         linear joint mapping as the start posture, then non-penetration only
//   human         the demonstrated human grasp itself; not an SDH transfer: TransferGrasp and
//                 MakeTransferProblem reject it, physics::RunGraspTrials runs RunHumanTrial.
enum class TransferMethod {
  kWinding,
  kWindingOnly,
  kContactOnly,
  kFingertip,
  kJointMapping,
  kHuman
};
inline constexpr base::EnumName<TransferMethod> kTransferMethodNames[] = {
    {TransferMethod::kWinding, "winding"},          {TransferMethod::kWindingOnly, "winding_only"},
    {TransferMethod::kContactOnly, "contact_only"}, {TransferMethod::kFingertip, "fingertip"},
    {TransferMethod::kJointMapping, "joint"},       {TransferMethod::kHuman, "human"},
};
constexpr std::span<const base::EnumName<TransferMethod>> EnumNames(TransferMethod) {
  return kTransferMethodNames;
}
inline const char* ToString(TransferMethod method) { return base::ToName(method); }
// One of the names above; throws std::invalid_argument "unknown transfer method 'x' (winding,
// winding_only, ...)" otherwise.
inline TransferMethod ParseTransferMethod(const std::string& text) {
  return base::ParseEnum<TransferMethod>(text, "transfer method");
}
// All six methods in the order above (`--method all`).
std::vector<TransferMethod> AllTransferMethods();

// A floating copy of a robot's subtree: 6 joints (hand_tx, hand_ty, hand_tz prismatic along the
// world axes, then hand_rz, hand_ry, hand_rx revolute) carry `root_link` and everything below it.
// The rotation joints are measured from `nominal`: palm = Trans(t)·R_nominal·Rz·Ry·Rx, so small
// rotations about the nominal orientation stay far from the Euler singularity. q = (t, rz, ry, rx,
// subtree dofs in the source order); mimic joints keep their masters. Chains whose points all lie
// in the subtree are kept. Throws std::invalid_argument if root_link does not exist.
Robot MakeFloatingHand(const Robot& source, const std::string& root_link,
                       const Eigen::Matrix3d& nominal);

struct TransferOptions {
  AicoOptions aico;
  int num_steps = 10;                // AICO time slices (approach motion)
  double winding_precision = 1e3;    // per turn²
  double contact_precision = 1e4;    // per m² (fingers to the surface)
  double clearance_precision = 1e5;  // per m² (hinge on penetration)
  double clearance_margin = 0.001;   // [m]
  double tip_precision = 1e4;        // fingertip method, per m²
  double palm_precision = 100.0;     // palm pose prior (6 floating dofs), per m² / rad²
  // Start postures of the SDH flexion joints [rad]; AICO runs from each, the lowest cost wins.
  std::vector<double> initial_flexions = {0.0, 0.2};
  double retreat = 0.03;  // start pose: palm retracted along −z_SDH [m], fingers open
  // Equal baselines (`bench grasp`, issue 36): the joint method also gets the contact term and
  // one AICO run per initial flexion (added to its mapped flexion joints, clamped), so that every
  // SDH method runs the same optimiser with the same starts, the same iteration cap
  // (aico.max_iterations) and the same shared terms; only the target term differs; and the
  // winding target follows one rule for every object (WindingTarget(setup, true): the main
  // reference only, no per-object extra curves or main_reference_in_target). Off: the
  // joint method runs once from its mapped posture with non-penetration only (`grasp transfer`).
  bool equal_baselines = false;
};

// Result of one transfer.
struct TransferResult {
  TransferMethod method = TransferMethod::kWinding;
  Eigen::VectorXd q;              // final SDH configuration (floating hand robot)
  Trajectory trajectory;          // AICO motion (joint: from the mapped posture)
  Eigen::VectorXd human_winding;  // 5: thumb, index, middle, ring, little
  std::vector<Eigen::VectorXd> human_phalanx_winding;  // per finger, per chain segment
  Eigen::VectorXd target_winding;                      // 3: M · human_winding
  Eigen::VectorXd robot_winding;                       // 3: SDH thumb, finger_1, finger_2 at q
  std::vector<Eigen::VectorXd> robot_phalanx_winding;
  // Opposition pairs (max, min over the fingers) about the object's extra reference curves (2 per
  // curve, stacked; empty without): the human's (the target) and the SDH's at q.
  Eigen::VectorXd target_extra_winding;
  Eigen::VectorXd robot_extra_winding;
  double min_clearance = 0.0;  // hand vs object at q [m] (negative = penetration)
  std::string solver;          // "aico" ("demonstration" for the human reference)
  SolveStatus status = SolveStatus::kConverged;
  int iterations = 0;         // AICO sweeps of the winning start
  int starts = 0;             // AICO runs (multi-start)
  long task_evaluations = 0;  // task evaluations (kinematics + features) summed over the starts
};

// Everything a transfer needs, built once per grasp.
struct TransferSetup {
  Robot human;  // human hand with the grasp chains
  std::vector<int> human_chains;
  Robot sdh;  // floating SDH (nominal = placement rotation) with chains
  std::vector<int> sdh_chains;
  GraspObject object;
  HumanGrasp grasp;
  ReferenceCurve reference;                      // world frame
  std::vector<ReferenceCurve> extra_references;  // object.extra_references, world frame
  Eigen::VectorXd human_q;
  Eigen::Isometry3d sdh_placement;  // nominal SDH palm pose (world)
};

// How the nominal SDH palm pose is found (the shared stage every SDH method starts from):
//   kObjectCentre  the file comment's rule: the line through the grasp centre on the object's
//                  reference curve, the standoff from the object's depth, and for a loop the SDH
//                  finger with the largest *target winding* through the loop's centre — it
//                  reads the object's reference and the winding encoding (`grasp transfer`);
//   kHumanPalm     from the human palm pose alone (no object, no encoding): the SDH point
//                  kSdhGraspDepth along z_SDH from its palm origin is put on the human hand's
//                  grasp point kHumanGraspPoint (hand_palm frame: 4 cm out of the palm surface,
//                  2.65 cm distal of the palm centre (0, −0.014, 0.045)). One rule for every
//                  grasp and method (issue 36); its two constants are the medians, over the 8
//                  nominal grasps, of where the kObjectCentre rule puts the SDH relative to the
//                  human palm, so it is the best single hand-to-hand mapping of that rule.
enum class PlacementRule { kObjectCentre, kHumanPalm };
inline constexpr base::EnumName<PlacementRule> kPlacementRuleNames[] = {
    {PlacementRule::kObjectCentre, "object_centre"},
    {PlacementRule::kHumanPalm, "human_palm"},
};
constexpr std::span<const base::EnumName<PlacementRule>> EnumNames(PlacementRule) {
  return kPlacementRuleNames;
}
inline const char* ToString(PlacementRule rule) { return base::ToName(rule); }
inline constexpr double kHumanGraspPoint[3] = {0.0, -0.054, 0.0715};  // hand_palm frame [m]
inline constexpr double kSdhGraspDepth = 0.14;                        // [m]

// Builds the setup from the human hand model, the LWR4+SDH model (its SDH subtree is used), the
// object and the grasp, with the placement `rule`. Throws std::invalid_argument for inconsistent
// inputs.
TransferSetup MakeTransferSetup(const Robot& human_hand, const Robot& sdh_source,
                                const GraspObject& object, const HumanGrasp& grasp,
                                PlacementRule rule = PlacementRule::kObjectCentre);

// Correspondence matrix M (3 × 5), see the file comment.
Eigen::MatrixXd FingerCorrespondence();

// Target of the winding term (docs/methods.md §9.1): M · w_human about setup.reference (3; left
// out when setup.object.main_reference_in_target is false), then per extra reference curve r the
// opposition pair OppositionPair(w_human^(r)) = (max, min) over the five human fingers (2 each).
// main_only: M · w_human about setup.reference alone, for every object (the one target rule of
// TransferOptions::equal_baselines).
Eigen::VectorXd WindingTarget(const TransferSetup& setup, bool main_only = false);

// SDH palm at the placement (6 floating dofs = (placement translation, 0, 0, 0)), the spread
// joint at grasp.sdh_spread (clamped), every other joint 0. Size = num_dofs(setup.sdh).
Eigen::VectorXd PlacementConfiguration(const TransferSetup& setup);

// The shared terms, built for every SDH method by this one function, in this order:
//   "clearance"    every slice, clearance_precision: hinge max(0, margin − d_k) on every hand
//                  sphere k (d_k = object distance − sphere radius) — non-penetration;
//   "joint_limits" every slice, 1e3: joint-limit hinge;
//   "palm"         final slice, palm_precision: the 6 floating dofs towards the placement;
//   then the method's `target` tasks (moved in, order kept);
//   "contact"      (if `contact`) final slice, contact_precision: per SDH finger the proximal and
//                  the distal link's nearest sphere distance to the surface → 0 (6 outputs).
// T = number of AICO steps (tasks have T + 1 slices).
std::vector<Task> SharedTransferTasks(const TransferSetup& setup, const TransferOptions& options,
                                      int T, std::vector<Task> target, bool contact);

// The AICO problem TransferGrasp solves for an SDH method (kinematic, T = options.num_steps,
// duration 1 s, palm translation metric 100): SharedTransferTasks with the method's target term
//   winding: "winding" (final slice, winding_precision, WindingTarget: M·y_human about the
//     main reference unless the object leaves it out, the opposition pair about each extra
//     curve) + contact;
//   winding_only: "winding", no contact; contact_only: no target + contact;
//   fingertip: "tip_sdh_thumb", "tip_sdh_finger_1", "tip_sdh_finger_2" (final slice,
//     tip_precision, the mean human fingertip of the corresponding fingers) + contact;
//   joint: no target, no contact (non-penetration projection of the mapped posture); with
//     options.equal_baselines the contact term too.
// q0: the joint method starts at the linear joint mapping of the human angles (palm at the
// placement); the others at the placement retracted by options.retreat along −z_SDH (their
// finger flexions are then set per start in options.initial_flexions). Throws
// std::invalid_argument for kHuman.
MotionProblem MakeTransferProblem(const TransferSetup& setup, TransferMethod method,
                                  const TransferOptions& options = {});

// Runs one SDH method: MakeTransferProblem, then AICO (winding, winding_only, contact_only,
// fingertip: one run per initial flexion, the lowest cost wins; joint: one run from the mapped
// posture, or with options.equal_baselines one per initial flexion added to the mapped flexions).
// Deterministic. Throws std::invalid_argument for kHuman (see physics::RunHumanTrial).
TransferResult TransferGrasp(const TransferSetup& setup, TransferMethod method,
                             const TransferOptions& options = {});

}  // namespace planning
