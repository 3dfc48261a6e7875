#include "visualize/grasp_scene.h"

#include "planning/physics/hand_builder.h"

namespace visualize {
namespace {

render::Material Mat(float r, float g, float b, float a = 1.0f) {
  render::Material m;
  m.rgba = {r, g, b, a};
  return m;
}

render::Shape ToRenderShape(const planning::physics::SimShape& s, const Eigen::Isometry3d& world,
                            const render::Material& material) {
  render::Shape out;
  switch (s.kind) {
    case planning::physics::SimShape::Kind::kSphere:
      out.kind = render::Shape::Kind::kSphere;
      break;
    case planning::physics::SimShape::Kind::kCapsule:
      out.kind = render::Shape::Kind::kCapsule;
      break;
    case planning::physics::SimShape::Kind::kCylinder:
      out.kind = render::Shape::Kind::kCylinder;
      break;
    case planning::physics::SimShape::Kind::kBox:
    case planning::physics::SimShape::Kind::kTrimesh:
      out.kind = render::Shape::Kind::kBox;
      break;
  }
  out.world_from_shape = (world * s.body_from_shape).matrix().cast<float>();
  out.size = s.size.cast<float>();
  out.material = material;
  return out;
}

}  // namespace

// The ODE state as a render scene: hand links (grey-blue), object (orange), contact points (red),
// gravity direction (black line from the object).
render::Scene GraspSimScene(const planning::physics::SimHand& hand,
                            const planning::physics::SimObject& object,
                            const planning::physics::SimState& state,
                            const Eigen::Vector3d& gravity) {
  render::Scene scene;
  for (size_t i = 0; i < hand.links.size(); ++i) {
    for (const auto& s : hand.links[i].shapes) {
      scene.shapes.push_back(ToRenderShape(
          s, state.world_from_link[i], i == 0 ? Mat(0.45f, 0.5f, 0.6f) : Mat(0.6f, 0.65f, 0.75f)));
    }
  }
  for (const auto& s : object.shapes) {
    scene.shapes.push_back(ToRenderShape(s, state.world_from_object, Mat(0.95f, 0.6f, 0.2f)));
  }
  for (const auto& c : state.contacts) {
    scene.shapes.push_back(
        render::MakeSphere(c.position.cast<float>(), 0.005f, Mat(0.9f, 0.05f, 0.05f)));
  }
  if (gravity.norm() > 0) {
    render::Lines g;
    const Eigen::Vector3d o = state.world_from_object.translation();
    g.points = {o.cast<float>(), (o + 0.012 * gravity).cast<float>()};
    g.width = 3.0f;
    scene.lines.push_back(g);
  }
  return scene;
}

void AddGraspObjectShapes(const planning::GraspObject& object, const Eigen::Isometry3d& pose,
                          render::Scene* scene) {
  const planning::physics::SimObject o = planning::physics::BuildSimObject(object, pose);
  for (const auto& s : o.shapes) {
    scene->shapes.push_back(ToRenderShape(s, pose, Mat(0.95f, 0.6f, 0.2f)));
  }
}

}  // namespace visualize
