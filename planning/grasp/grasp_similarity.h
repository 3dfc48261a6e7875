// Similarity of a transferred grasp to its demonstration, measured independently of every
// transfer encoding (windings, fingertips, joint angles, contact distances):
//   - contact regions: per finger, the cells of a cubic grid (object frame) holding the object
//     surface points the finger touches; compared by intersection over union (Jaccard index);
//   - threading: whether a finger's chain passes through the object's hole (the disc spanned by
//     its loop reference), in the demonstration and in the transfer.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "planning/grasp/grasp.h"
#include "planning/grasp/grasp_object.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/robot.h"

namespace planning {

// Grid cell (i, j, k) = floor(p / cell) of an object-frame surface point p.
using SurfaceCell = std::array<int, 3>;
using CellSet = std::set<SurfaceCell>;

// Intersection over union |A ∩ B| / |A ∪ B| ∈ [0, 1]; nullopt when both are empty (no contact in
// either: nothing to compare).
std::optional<double> RegionIoU(const CellSet& a, const CellSet& b);

struct ContactRegionOptions {
  double tolerance = 0.003;  // a sphere touches when its clearance is below this [m]
  double cell = 0.02;        // grid cell side [m] (about a finger's width)
  double spacing = 0.004;    // hand-sphere spacing (SampleHandSpheres) [m]
};

// Per finger group g (links whose names start with one of groups[g]), the cells of the object
// surface points nearest to the hand spheres that touch: for every sphere of those links (centre
// c in the object frame, radius r) with SignedDistance(c) − r < tolerance, the cell of
// c − d ∇d. `kin` holds ForwardKinematics of `robot`. Throws std::invalid_argument for a
// non-positive cell or spacing.
std::vector<CellSet> FingerContactRegions(const Robot& robot, const KinematicsData& kin,
                                          const std::vector<std::vector<std::string>>& groups,
                                          const GraspObject& object,
                                          const Eigen::Isometry3d& world_from_object,
                                          const ContactRegionOptions& options = {});

// Finger groups in SDH finger order (thumb, finger_1, finger_2) with the correspondence of
// planning/grasp/grasp_transfer.h: the human thumb; ring + little; index + middle.
const std::vector<std::vector<std::string>>& HumanGroupsForSdh();
const std::vector<std::vector<std::string>>& SdhGroups();  // sdh_thumb, sdh_finger_1, _2

// Whether the open polyline `chain` (3 × N) threads the closed loop (3 × M, last point = first):
// a segment of the chain crosses the loop's plane (through its centroid, normal by Newell's
// method) at a point strictly inside the loop's projection onto that plane (even–odd rule).
// Throws std::invalid_argument for a loop with fewer than 4 points or a degenerate plane.
bool ChainThreadsLoop(const Eigen::Matrix3Xd& chain, const Eigen::Matrix3Xd& loop);

// Per finger chain (robot.chains[chains[f]] at `kin`): ChainThreadsLoop against `loop` (world).
std::vector<bool> FingersThreading(const Robot& robot, const KinematicsData& kin,
                                   const std::vector<int>& chains, const Eigen::Matrix3Xd& loop);

// Human finger threading (5 fingers, HumanFingers order) grouped for the SDH fingers as in
// HumanGroupsForSdh: a group threads when one of its fingers does.
std::vector<bool> HumanThreadingForSdh(const std::vector<bool>& human);

// Thread preservation of one transfer: of the SDH fingers whose demonstration group threads,
// how many thread in the transfer.
struct ThreadPreservation {
  int demo = 0;       // fingers threading in the demonstration
  int preserved = 0;  // of those, threading in the transfer
  bool all() const { return preserved == demo; }
};
ThreadPreservation CompareThreading(const std::vector<bool>& demo,
                                    const std::vector<bool>& transfer);

}  // namespace planning
