// ODE grasp-simulation state → render::Scene (the stability-test frames and their snapshots).
#pragma once

#include <Eigen/Core>

#include "planning/grasp/grasp_object.h"
#include "planning/physics/grasp_simulation.h"
#include "render/scene.h"

namespace visualize {

// The simulation state as a scene: palm (dark grey-blue) and finger links (light grey-blue) of
// `hand` at state.world_from_link, the object (orange) at state.world_from_object, one red sphere
// (radius 5 mm) per contact point, and a black line from the object's origin along `gravity`
// (world frame, m/s²; 12 mm per m/s², none when zero). Trimesh shapes are drawn as boxes.
render::Scene GraspSimScene(const planning::physics::SimHand& hand,
                            const planning::physics::SimObject& object,
                            const planning::physics::SimState& state,
                            const Eigen::Vector3d& gravity);

// Appends a grasp object (primitives; tori as rings of capsules) at `pose`, in orange.
void AddGraspObjectShapes(const planning::GraspObject& object, const Eigen::Isometry3d& pose,
                          render::Scene* scene);

}  // namespace visualize
