// Human grasps (files in assets/grasps/) and their winding-number encoding.
//
// A grasp is the human hand's joint angles, palm pose and object pose. The encoding measures how
// far each finger chain winds about the object's reference curve (docs/methods.md §9):
//   - finger chain f: palm centre → finger base → ... → fingertip (robot chains "grasp_<finger>"
//     added by AddGraspChains);
//   - axis reference: w_f = topology::WindingNumber(chain_f, axis) (signed, in turns), and per
//     phalanx (segment s) the summand Δθ_s/2π (topology::SegmentWindings);
//   - loop reference: w_f = Σ_ij W_ij with W = topology::WritheMatrix(chain_f, loop) (the Gauss
//     linking integral of the open finger chain with the closed loop), per phalanx the row sums.
// Both are signed and normalised to turns, so a finger wrapped once around a bottle gives ≈ ±1.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <map>
#include <string>
#include <vector>

#include "planning/grasp/grasp_object.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/robot.h"

namespace planning {

// One grasp file (format in assets/grasps/README.md).
struct HumanGrasp {
  std::string name;  // file stem, e.g. "power_bottle"
  std::string type;  // grasp type (taxonomy label)
  std::string description;
  std::string object;  // object name in assets/grasps/objects.json
  Eigen::Isometry3d world_from_object = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d world_from_palm = Eigen::Isometry3d::Identity();  // human palm frame
  std::map<std::string, double> joints;  // finger joint angles [rad] by URDF joint name
  // SDH spread (coupled knuckle angle, rad) for the linear joint-mapping baseline, from the
  // grasp type: 0 cylindrical, π/3 spherical/tripod, π/2 lateral.
  double sdh_spread = 0.0;
  // Joints the synthesiser closes until contact, in order (only read by SynthesizeGrasp).
  std::vector<std::string> close;
  std::string source;  // file it was read from
};

// Reads a grasp file. Throws std::invalid_argument naming the file and JSON path for malformed
// JSON, missing fields, non-finite numbers or a wrong-sized vector.
HumanGrasp LoadHumanGrasp(const std::string& path);
// The grasp as JSON text (the same format; `close` is omitted when empty).
std::string HumanGraspToJson(const HumanGrasp& grasp);

// Finger names of the human hand in encoding order, and of the SDH.
const std::vector<std::string>& HumanFingers();  // thumb, index, middle, ring, little
const std::vector<std::string>& SdhFingers();    // thumb, finger_1, finger_2

// Adds chains "grasp_<finger>" (palm centre point + the hand's finger chain) to `robot` for each
// finger of HumanFingers() (if `human`) or SdhFingers() (SDH, chains "sdh_<finger>") and returns
// their indices in finger order. Throws std::invalid_argument if a source chain is missing.
std::vector<int> AddGraspChains(bool human, Robot* robot);

// Human hand configuration for a grasp: palm joints (hand_tx, hand_ty, hand_tz, hand_rz, hand_ry,
// hand_rx) from world_from_palm, finger joints from the map (absent joints 0). Throws
// std::invalid_argument naming the grasp file for an unknown joint name or a value outside the
// joint limits by more than 1e-6.
Eigen::VectorXd HumanConfiguration(const Robot& human, const HumanGrasp& grasp);

// Winding encoding of a hand posture.
struct GraspEncoding {
  Eigen::VectorXd finger;                // per finger chain, turns (signed)
  std::vector<Eigen::VectorXd> phalanx;  // per finger, per chain segment, turns
};

// Encodes the hand at `kin` (ForwardKinematics done) for chains `chains` about `reference`
// (world frame). If `jacobian` is not null it is resized to chains × n and receives ∂finger/∂q.
GraspEncoding EncodeGrasp(const Robot& robot, const KinematicsData& kin,
                          const std::vector<int>& chains, const ReferenceCurve& reference,
                          Eigen::MatrixXd* jacobian = nullptr);

// Opposition pair of per-finger values w (size F >= 1): o = (max_f w_f, min_f w_f), which finger
// is which left open. If `jacobian` (F × n, row f = ∂w_f/∂q) and `pair_jacobian` are not null,
// `pair_jacobian` is resized to 2 × n and receives the rows of the arg max and the arg min finger
// (the lowest index on ties). Throws std::invalid_argument for an empty w or a jacobian whose row
// count is not F.
Eigen::Vector2d OppositionPair(const Eigen::VectorXd& w, const Eigen::MatrixXd* jacobian = nullptr,
                               Eigen::MatrixXd* pair_jacobian = nullptr);

// Spheres approximating a hand's collision geometry (capsules, cylinders, boxes, spheres), used
// for penetration and contact distances against GraspObject's signed distance.
struct HandSpheres {
  std::vector<int> link;          // link index per sphere
  Eigen::Matrix3Xd center_local;  // centre in the link frame
  std::vector<double> radius;
};
// Samples every collision geometry of `links` (all links if empty) with spheres spaced at most
// `spacing` apart. Meshes are skipped.
HandSpheres SampleHandSpheres(const Robot& robot, const std::vector<int>& links, double spacing);

// Clearance of each sphere: signed distance of its centre to the object minus its radius
// (negative = penetration), world frame. Returns the minimum; `per_link` (optional, size links)
// receives each link's minimum (+∞ for links without spheres).
double HandClearance(const Robot& robot, const KinematicsData& kin, const HandSpheres& spheres,
                     const GraspObject& object, const Eigen::Isometry3d& world_from_object,
                     std::vector<double>* per_link = nullptr);

// Closes the joints listed in grasp->close, in order, from their current values towards their
// upper limit until a link moved by the joint touches the object (clearance within
// [−tolerance, 0]) or the limit is reached; a joint already in penetration is opened instead.
// Writes the results into grasp->joints. Returns the final minimum clearance over the hand.
double SynthesizeGrasp(const Robot& human, const GraspObject& object, HumanGrasp* grasp,
                       double tolerance = 5e-4);

}  // namespace planning
