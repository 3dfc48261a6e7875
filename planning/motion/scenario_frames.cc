// Frames of scenario files (scenario_spec.h "Frames"): object placements and target points given
// in another object's frame, resolved to world coordinates at set-up.
#include <stdexcept>
#include <string>
#include <vector>

#include "base/str_cat.h"
#include "planning/motion/scenario_spec.h"
#include "planning/robot/pose.h"

namespace planning {
namespace {

// Index of the object a frame names; the parser checked it, a spec edited in code may not be.
size_t FrameObject(const ScenarioSpec& spec, const SpecName& frame) {
  for (size_t i = 0; i < spec.objects.size(); ++i) {
    if (spec.objects[i].name == frame.name) return i;
  }
  throw std::invalid_argument(base::StrCat(frame.where, ": unknown object '", frame.name, "'"));
}

}  // namespace

Eigen::Isometry3d ObjectWorldPose(const ScenarioSpec& spec, size_t i) {
  Eigen::Isometry3d pose = PoseFromXyzRpy(spec.objects.at(i).xyz, spec.objects.at(i).rpy);
  // Parents come first in the file (the parser checks it), so the walk ends; the bound guards a
  // spec edited in code into a cycle.
  size_t at = i;
  for (size_t depth = 0; spec.objects[at].frame; ++depth) {
    if (depth > spec.objects.size()) {
      throw std::invalid_argument(
          base::StrCat(spec.objects[i].where, ".frame: the frames form a cycle"));
    }
    at = FrameObject(spec, *spec.objects[at].frame);
    pose = PoseFromXyzRpy(spec.objects[at].xyz, spec.objects[at].rpy) * pose;
  }
  return pose;
}

void ResolveSpecFrames(ScenarioSpec* spec) {
  // Poses of the objects as placed now (before any is rewritten).
  std::vector<Eigen::Isometry3d> world;
  for (size_t i = 0; i < spec->objects.size(); ++i) world.push_back(ObjectWorldPose(*spec, i));
  const auto pose_of = [&](const SpecName& frame) -> const Eigen::Isometry3d& {
    return world[FrameObject(*spec, frame)];
  };
  for (TaskSpec& t : spec->tasks) {
    if (t.target.frame) {
      if (t.target.value.size() != 3 || t.target.scalar) {
        throw std::invalid_argument(
            base::StrCat(t.target.frame->where, ": \"frame\" needs a point value [x, y, z]"));
      }
      const Eigen::Vector3d p = t.target.value;
      t.target.value = pose_of(*t.target.frame) * p;
      t.target.frame.reset();
    }
    FeatureSpec& f = t.feature;
    if (!f.frame) continue;
    const Eigen::Isometry3d& T = pose_of(*f.frame);
    if (f.type == FeatureType::kBox) f.center = T * f.center;
    if (f.type == FeatureType::kWinding) {
      f.axis_point = T * f.axis_point;
      f.axis_direction = T.linear() * f.axis_direction;
    }
    if (f.type == FeatureType::kAxisAlignment) f.direction = T.linear() * f.direction;
    f.frame.reset();
  }
  for (size_t i = 0; i < spec->objects.size(); ++i) {
    ObjectSpec& o = spec->objects[i];
    if (!o.frame) continue;
    PoseToXyzRpy(world[i], &o.xyz, &o.rpy);
    o.frame.reset();
  }
}

}  // namespace planning
