// Graspable objects for grasp transfer: primitive shapes with an analytic signed distance, a mass,
// and the reference curve (axis or loop) that winding numbers are measured about.
//
// Frames: every quantity is in the object frame unless the name says otherwise. Units SI.
// The catalogue file format is documented in README.md ("Grasp transfer") and
// assets/grasps/README.md.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "planning/robot/pose.h"
#include "topology/polyline.h"
#include "topology/winding.h"

namespace planning {

// One solid primitive placed in the object frame.
struct GraspPrimitive {
  enum class Kind { kSphere, kCylinder, kBox, kCapsule, kTorus };
  Kind kind = Kind::kSphere;
  // kSphere: (radius, −, −). kCylinder: (radius, length, −), axis local z, centred.
  // kBox: full sides (x, y, z). kCapsule: (radius, length between cap centres, −) along local z.
  // kTorus: (major radius R, tube radius r, half-angle of the arc in rad) about local z; the arc
  //   covers polar angles in [−half, +half] around local +x; half-angle ≥ π is a full torus.
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  Eigen::Isometry3d object_from_primitive = Eigen::Isometry3d::Identity();
};

// The curve windings are measured about. kAxis: an oriented line (topology::Axis, object frame),
// used with topology::WindingNumber. kLoop: a closed polyline (3×N, last point = first point),
// used with the Gauss linking integral (topology::TotalWrithe) of the finger chain against it.
struct ReferenceCurve {
  enum class Kind { kAxis, kLoop };
  Kind kind = Kind::kAxis;
  topology::Axis axis;
  topology::Chain loop;
};

struct GraspObject {
  std::string name;
  std::vector<GraspPrimitive> primitives;  // the solid is their union
  double mass = 0.1;                       // [kg]
  ReferenceCurve reference;
  // Further curves the winding method's target term also measures the fingers about, as an
  // opposition pair (JSON "extra_references", optional; docs/methods.md §9.1): e.g. the rim of a
  // thin plate, whose linking integral with a finger chain tells on which face of the plate the
  // fingertip lies.
  // `reference` alone places the SDH and is reported as the grasp's winding vector.
  std::vector<ReferenceCurve> extra_references;
  // Whether the winding target term includes the per-finger windings about `reference` (JSON
  // "main_reference_in_target", default true). False for an object whose fingers do not wind about
  // its main reference in any of its grasps (a thin plate about its edge axis: w ≈ 0 on either
  // face), so that those windings are no target, only the extra curves are; the main reference
  // still places the SDH and is reported. Needs extra_references.
  bool main_reference_in_target = true;
  std::string description;
};

// Signed distance from p (object frame) to the object surface: negative inside, the minimum over
// the primitives (exact for the union's exterior, an upper bound on depth inside overlaps). If
// `grad` is not null it receives ∂d/∂p (unit length almost everywhere) of the closest primitive.
double SignedDistance(const GraspObject& object, const Eigen::Vector3d& p,
                      Eigen::Vector3d* grad = nullptr);

// Signed distance to one primitive (object frame), with gradient as above.
double PrimitiveSignedDistance(const GraspPrimitive& prim, const Eigen::Vector3d& p,
                               Eigen::Vector3d* grad = nullptr);

// Reads the object catalogue (JSON, see README): {"objects": [{"name", "mass", "description",
// "primitives": [{"type": "sphere|cylinder|box|capsule|torus", "size": [..3], "xyz": [..3],
// "rpy": [..3]}], "reference": {"type": "axis", "point": [..], "direction": [..]} or
// {"type": "loop", "points": [[x,y,z], ...]} or {"type": "circle", "center", "normal",
// "radius", "segments"}, "extra_references": [reference, ...] (optional),
// "main_reference_in_target": bool (optional, default true; false needs extra_references)}]}.
// Throws std::invalid_argument naming the file and JSON path.
std::vector<GraspObject> LoadGraspObjects(const std::string& path);

// The object with this name; throws std::invalid_argument listing the known names.
const GraspObject& FindGraspObject(const std::vector<GraspObject>& objects,
                                   const std::string& name);

// Reference curve mapped to the world frame by world_from_object.
ReferenceCurve TransformReference(const ReferenceCurve& ref,
                                  const Eigen::Isometry3d& world_from_object);

}  // namespace planning
