// Inverse kinematics: joint values that put points of links at world positions (and link axes
// along world directions), inside the joint limits, by damped least squares with multistart.
//
// Usage (one IkData per robot and thread, reused for every solve):
//   planning::IkProblem problem;
//   problem.targets.push_back({FindLink(robot, "tool"), Eigen::Vector3d(0, 0, 0.1),  // offset
//                              Eigen::Vector3d(0.4, 0.2, 0.5)});                      // position
//   problem.targets[0].axis = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d(1, 0, 0)};   // optional
//   problem.seed = q_start;                // empty: the middle of the limits
//   problem.frozen_dofs = {7, 8};          // held at the seed value
//   planning::IkOptions options;           // options.is_valid = collision check, if wanted
//   planning::IkData data(robot);
//   const planning::IkResult r = planning::SolveIk(robot, problem, options, &data);
//   if (r.status == planning::IkStatus::kSolved) use(r.q);
//
// Method: Levenberg–Marquardt on the stacked weighted residual e(q) (damped least squares,
// Wampler 1986, Nakamura & Hanafusa 1986; Buss 2004): Δq = (JᵀJ + λI)⁻¹ Jᵀe over the free joints,
// projected onto the joint box (joints that would leave it are held at the bound and the step is
// solved again for the others), accepted when it lowers ½‖e‖², else λ grows. Start 0 is the seed;
// starts 1.. are uniform in the limits (base/random.h, seeded: the same inputs give the same q).
// Units: q in rad (revolute, continuous) and m (prismatic); positions in m in the world frame
// (robot.world_from_root applied, as ForwardKinematics).
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "base/enum_names.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/robot.h"

namespace planning {

// A link-local direction that must point along a world direction (an approach axis).
struct IkAxis {
  Eigen::Vector3d local = Eigen::Vector3d::UnitZ();  // in the link frame; normalised by SolveIk
  Eigen::Vector3d world = Eigen::Vector3d::UnitZ();  // in the world frame; normalised by SolveIk
};

// One target: the point `offset` of `link` (link frame, m) at `position` (world, m), and
// optionally the link axis along a world direction. Residual rows:
//   position: position_weight · (position − world_from_link · offset)        (3 rows, m)
//   axis:     axis_weight · (axis.world − R_link · axis.local)               (3 rows, m)
// (‖world − R·local‖ = 2 sin(θ/2) for the angle θ between the two.) The weights only shape the
// path; convergence is judged on the errors against IkOptions' tolerances.
struct IkTarget {
  int link = -1;                                       // index into robot.links (FindLink)
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();    // point on the link, link frame [m]
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // where it must be, world frame [m]
  std::optional<IkAxis> axis;                          // approach axis, if any
  double position_weight = 1.0;                        // > 0, unitless
  double axis_weight = 0.2;                            // > 0, in m (weighs 2 sin(θ/2))
};

struct IkProblem {
  std::vector<IkTarget> targets;  // at least one
  // Start configuration (size num_dofs) or empty (the middle of each joint's limits, 0 for an
  // unbounded joint). Entries outside the limits are moved to the nearest bound.
  Eigen::VectorXd seed;
  // Dof indices (q order, DofNames) held at the seed value; it must lie inside the limits.
  std::vector<int> frozen_dofs;
};

struct IkOptions {
  int starts = 8;                    // >= 1: the seed, then starts − 1 random configurations
  int max_iterations = 200;          // >= 1, Levenberg–Marquardt iterations per start
  std::uint32_t random_seed = 0;     // the random starts' generator (std::mt19937)
  double position_tolerance = 1e-5;  // [m], > 0: solved when every position error is below
  double axis_tolerance = 1e-5;      // [rad], > 0: and every axis error is below
  double initial_damping = 1e-3;  // λ₀ > 0 [m²]; λ /= 3 after an accepted step, × 4 otherwise
  double max_step = 0.5;  // > 0: largest |Δq_k| per iteration [rad or m]; longer steps are scaled
  // Optional: a reached q is kept only if is_valid(q) (e.g. collision-free); else the next start
  // runs. Called once per reached q, never inside the iterations.
  std::function<bool(const Eigen::VectorXd& q)> is_valid;
};

enum class IkStatus {
  kSolved,      // every target within tolerance, q valid (is_valid true or not given)
  kNotReached,  // no start reached the targets: q is the start with the lowest ½‖e‖²
  kInvalid,     // some start reached the targets, but is_valid rejected every such q (q: the first)
};
inline constexpr base::EnumName<IkStatus> kIkStatusNames[] = {
    {IkStatus::kSolved, "solved"},
    {IkStatus::kNotReached, "not_reached"},
    {IkStatus::kInvalid, "invalid"}};
constexpr std::span<const base::EnumName<IkStatus>> EnumNames(IkStatus) { return kIkStatusNames; }
inline const char* IkStatusName(IkStatus status) { return base::ToName(status); }

struct IkResult {
  IkStatus status = IkStatus::kNotReached;
  Eigen::VectorXd q;            // size num_dofs, inside the limits, frozen dofs = seed
  double position_error = 0.0;  // max over targets of ‖position − p‖ [m]
  double axis_error = 0.0;      // max over axis targets of the angle [rad] (0 without any)
  int iterations = 0;           // LM iterations over all starts run
  int starts = 0;               // starts run (stops at the first solved one)
  int start = -1;               // the start that gave q (0 = the seed)
  int rejected = 0;             // reached configurations is_valid refused
};

// Workspace: sized once per robot (and reused by every solve with the same number of targets;
// another number of targets resizes it once at the start of SolveIk).
struct IkData {
  explicit IkData(const Robot& robot);
  void Resize(int num_residuals);

  KinematicsData kin;
  Eigen::VectorXd lower, upper;     // joint limits (n), narrowed by the limits of mimic joints
  Eigen::VectorXd q, q_try, dq, g;  // n
  Eigen::VectorXd e, e_try;         // residual (m = 3 per position + 3 per axis)
  Eigen::MatrixXd J;                // m × n
  Eigen::MatrixXd frame_J;          // 6 × n, frame Jacobian of an axis target's link
  Eigen::MatrixXd A;                // n × n normal matrix
  Eigen::LLT<Eigen::MatrixXd> llt;  // sized n
  std::vector<char> held;           // per dof: frozen or at a bound this step
  std::vector<char> frozen;         // per dof: frozen by the problem
};

// Solves the problem from options.starts starts (see the file comment). Returns kSolved at the
// first start whose q reaches every target (and passes is_valid). Throws std::invalid_argument on
// bad input: no targets, a link index out of range, a non-finite position/offset/axis/weight or
// seed entry, a zero axis, a seed of the wrong size, a frozen dof out of range or with a seed
// value outside its limits, options out of range, or `data` sized for another robot.
// Allocates nothing inside the iterations (data holds every buffer).
IkResult SolveIk(const Robot& robot, const IkProblem& problem, const IkOptions& options,
                 IkData* data);

// Position and axis errors of q for the problem's targets ([m], [rad]; max over targets).
void IkErrors(const Robot& robot, const IkProblem& problem, const Eigen::VectorXd& q,
              KinematicsData* kin, double* position_error, double* axis_error);

// Dof indices of the named joints (q order); throws std::invalid_argument naming an unknown or
// non-dof joint and listing the robot's dof joints.
std::vector<int> DofIndices(const Robot& robot, const std::vector<std::string>& joint_names);

}  // namespace planning
