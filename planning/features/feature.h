// Task variables ("features"): maps φ: q ↦ y ∈ R^dim with analytic Jacobians J = ∂φ/∂q.
//
// A Feature is immutable (configured in its constructor / factory); anything it caches between
// calls lives in a FeatureData it creates, so one problem can be evaluated at several time steps
// or threads at once. Eval requires ForwardKinematics(robot, q, &kin) to have been called with the
// q to evaluate at. J is dim × num_dofs(robot), world-frame quantities differentiated with respect
// to q (robot.h order). Eval does not allocate once `data` exists and J has the right size.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>

#include "planning/collision/collision.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/robot.h"
#include "topology/winding.h"

namespace planning {

// Mutable per-evaluation buffers of one feature (chain points, Jacobian scratch, collision
// workspace). Created by Feature::CreateData; opaque to callers.
struct FeatureData {
  virtual ~FeatureData() = default;
};

class Feature {
 public:
  virtual ~Feature() = default;
  // Size of y.
  virtual int dim() const = 0;
  // Short type name used in scenario files and messages ("position", "writhe", ...).
  virtual std::string name() const = 0;
  // Buffers for Eval, sized for `robot`. May return nullptr when the feature needs none.
  virtual std::unique_ptr<FeatureData> CreateData(const Robot& robot) const;
  // y = φ(q) (size dim); if J is not null it must be dim × num_dofs and receives ∂φ/∂q.
  // Requires kin == ForwardKinematics(q) and data from CreateData(robot) (or nullptr if that
  // returned nullptr).
  virtual void Eval(const Robot& robot, const KinematicsData& kin, FeatureData* data,
                    Eigen::Ref<Eigen::VectorXd> y, Eigen::MatrixXd* J) const = 0;
  // Number of narrow-phase collision queries made by Evals through `data` so far (0 for features
  // that make none). Planners add these up into their collision_checks report.
  virtual long collision_queries(const FeatureData* data) const;
  // Narrow-phase (shape-pair) FCL calls made through `data` so far (0 for non-collision features).
  virtual long narrow_phase_calls(const FeatureData* data) const;
  // True for features that query the world at a configuration (collision, line clearance,
  // winding): an evaluation pass that evaluates one of them is one state query (QueryCounts).
  virtual bool queries_world() const;
  // This feature's evaluations through `data` so far in the common cost units (collision.h
  // QueryCounts): state_queries = its own evaluations of a configuration, pair tests as made
  // (collision: the CollisionData's; line clearance and winding: one distance pair test per chain
  // segment and evaluation). All zero for features that do not query the world.
  virtual QueryCounts query_counts(const FeatureData* data) const;
};

// --- Factories (throw std::invalid_argument for out-of-range links/chains or bad sizes) --------
// Each concrete feature class has its own header and source, planning/features/<name>_feature.h
// (PositionFeature, AxisAlignmentFeature, JointLimitFeature, JointPositionFeature, BoxFeature,
// WritheFeature, WindingFeature, LineClearanceFeature, CollisionFeature); its factory below,
// defined next to it, checks the arguments the class's constructor assumes valid.

// Position of the point `offset` (link frame) of `link`, world frame: y = T_link·offset ∈ R³,
// J = PointJacobian (3 × n).
std::unique_ptr<Feature> MakePositionFeature(const Robot& robot, int link,
                                             const Eigen::Vector3d& offset);

// Alignment of the link axis a (link frame, normalised) with a world direction d (normalised):
// y = (R_link a)·d ∈ [−1, 1] (target 1 = aligned), J = ((R_link a) × d)ᵀ · J_ω (1 × n), with J_ω
// the angular rows of FrameJacobian.
std::unique_ptr<Feature> MakeAxisAlignmentFeature(const Robot& robot, int link,
                                                  const Eigen::Vector3d& axis_link,
                                                  const Eigen::Vector3d& direction_world);

// Joint limits as a hinge per dof (dim n, target 0):
//   y_k = max(0, (lower_k + margin) − q_k) − max(0, q_k − (upper_k − margin)),
// so ||y||² is a squared hinge; J = −I on the violated rows (0 elsewhere). Infinite limits never
// activate.
std::unique_ptr<Feature> MakeJointLimitFeature(const Robot& robot, double margin,
                                               double prismatic_margin = 0.0);

// The configuration itself ("qitself"): y = q, J = I (n × n). With a velocity-order task
// (Task::order = 1) and target 0 it is the joint-velocity regulariser ν||q̇||².
std::unique_ptr<Feature> MakeJointPositionFeature(const Robot& robot);

// "Remain inside a box" on the position p of `offset` in `link`: per world axis k (dim 3, target 0)
//   y_k = max(0, p_k − (c_k + h_k − margin)) − max(0, (c_k − h_k + margin) − p_k),
// with centre c and half-extents h; J row k = J_pos row k where active, 0 elsewhere.
std::unique_ptr<Feature> MakeBoxFeature(const Robot& robot, int link, const Eigen::Vector3d& offset,
                                        const Eigen::Vector3d& center,
                                        const Eigen::Vector3d& half_extent, double margin);

// Writhe matrix between the robot chain `chain` (points P(q), 3 × N_A, see ChainPoints) and a
// static object chain O (3 × N_B): W = topology::WritheMatrix(P, O) ((N_A−1) × (N_B−1), rows =
// robot segments). kMatrix: y = vec(W) row-major (dim (N_A−1)(N_B−1)); kTotal: y = Σ_ij W_ij
// (dim 1). J by the chain rule ∂W/∂P · ∂P/∂q (topology::ChainWritheJacobian with ChainJacobian).
// closed_by_chord: P is closed by its chord first (its first point appended, N_A rows; see
// writhe_feature.h).
enum class WritheOutput { kMatrix, kTotal };
std::unique_ptr<Feature> MakeWritheFeature(const Robot& robot, int chain,
                                           const Eigen::Matrix3Xd& object_chain,
                                           WritheOutput output, bool closed_by_chord = false);

// Winding number of the robot chain about an axis (dim 1): y = topology::WindingNumber(P(q), axis)
// (signed variant), J = Σ_k (∂w/∂p_k)ᵀ ∂p_k/∂q.
std::unique_ptr<Feature> MakeWindingFeature(const Robot& robot, int chain,
                                            const topology::Axis& axis);

// Clearance of the robot chain from a line (e.g. a pole's axis, taken as infinite both ways) as a
// hinge per chain segment (dim = ChainSize − 1, target 0): with d_s the distance of segment
// s = [p_s, p_{s+1}] to the line and σ_s ∈ [0, 1] its closest segment parameter,
//   y_s = max(0, 1 − d_s / margin),
// J row s = −(1/margin) n_sᵀ ((1 − σ_s) ∂p_s/∂q + σ_s ∂p_{s+1}/∂q) where active (n_s the unit
// vector from the line to the closest point). A segment crossing the line changes the winding
// about it by a whole turn; this keeps the chain off the line also beyond the object's ends.
// Throws std::invalid_argument for a bad chain, a zero direction or margin <= 0.
std::unique_ptr<Feature> MakeLineClearanceFeature(const Robot& robot, int chain,
                                                  const topology::Axis& line, double margin);

// Collision avoidance against `env` (and self-collision per `options`) as a hinge per robot link
// (dim = number of links, target 0): with the FCL proximity pairs p closer than `margin` (signed
// distance d_p, witness points, normal n_p from b to a),
//   y_k = Σ_{p : link_a(p) = k} (1 − d_p / margin),
// so ρ||y||² is the thesis' squared-hinge proxy cost; ∂y_k/∂q = −(1/margin) Σ_p n_pᵀ (J_a(p_a) −
// J_b(p_b)) (J_b = 0 for environment objects). Penetration (d < 0) keeps growing linearly. Each
// Eval makes one ComputeProximity query (counted by collision_queries). `env` must outlive the
// feature. Throws std::invalid_argument for margin <= 0.
std::unique_ptr<Feature> MakeCollisionFeature(const Robot& robot, const Environment& env,
                                              const CollisionOptions& options, double margin);

}  // namespace planning
