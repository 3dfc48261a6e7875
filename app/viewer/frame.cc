#include "app/viewer/frame.h"

#include <algorithm>
#include <cmath>

#include "visualize/grasp_scene.h"

namespace app {
namespace {
constexpr float kDegToRad = 3.14159265358979f / 180.0f;
}

render::Scene BuildFrameScene(const Session& session, const Settings& settings,
                              visualize::SceneMeshCache* cache) {
  if (settings.grasp.active && session.grasp() && !session.grasp()->frames.empty()) {
    const GraspReplay& g = *session.grasp();
    const int f = std::clamp(settings.grasp.frame, 0, static_cast<int>(g.frames.size()) - 1);
    planning::physics::SimState state = g.frames[f].state;
    if (!settings.view.contacts) state.contacts.clear();
    render::Scene scene = visualize::GraspSimScene(g.hand, g.object, state, session.GraspGravity(f));
    scene.grid.enabled = false;
    return scene;
  }
  const planning::Robot& robot = session.robot();
  planning::KinematicsData kin(robot);
  planning::ForwardKinematics(robot, session.ShownQ(settings), &kin);
  visualize::SceneBuildOptions options;
  options.visuals = !settings.view.collision_geometry;
  options.chains = settings.view.chains;
  options.grid = settings.view.grid;
  render::Scene scene = visualize::BuildRobotScene(robot, kin, session.objects(), options, cache);
  if (session.scenario()) visualize::AddTaskBoxes(session.scenario()->spec, &scene);
  return scene;
}

render::Camera OrbitToCamera(const OrbitCamera& o) {
  const float y = o.yaw_deg * kDegToRad, p = o.pitch_deg * kDegToRad;
  render::Camera c;
  c.target = o.target;
  c.eye = o.target + o.distance * Eigen::Vector3f(std::cos(p) * std::cos(y),
                                                  std::cos(p) * std::sin(y), std::sin(p));
  c.up = Eigen::Vector3f::UnitZ();
  c.fovy_deg = o.fovy_deg;
  return c;
}

void FrameOrbit(const render::Scene& scene, OrbitCamera* orbit) {
  const render::Camera framed =
      visualize::FrameSceneCamera(scene, Eigen::Vector3f(1.0f, -1.3f, 0.8f), orbit->fovy_deg);
  const Eigen::Vector3f d = framed.eye - framed.target;
  orbit->target = framed.target;
  orbit->distance = 1.1f * d.norm();  // margin: planned motions leave the start pose
  orbit->yaw_deg = std::atan2(d.y(), d.x()) / kDegToRad;
  orbit->pitch_deg =
      std::asin(std::clamp(d.z() / std::max(d.norm(), 1e-6f), -1.0f, 1.0f)) / kDegToRad;
}

void OrbitRotate(float dx, float dy, OrbitCamera* o) {
  o->yaw_deg -= 0.3f * dx;
  o->pitch_deg = std::clamp(o->pitch_deg + 0.3f * dy, -89.0f, 89.0f);
}

void OrbitPan(float dx, float dy, int viewport_height, OrbitCamera* o) {
  const render::Camera c = OrbitToCamera(*o);
  const Eigen::Vector3f forward = (c.target - c.eye).normalized();
  const Eigen::Vector3f right = forward.cross(Eigen::Vector3f::UnitZ()).normalized();
  const Eigen::Vector3f up = right.cross(forward);
  // One pixel at the target's depth spans 2·d·tan(fovy/2)/H metres.
  const float metres_per_pixel = 2.0f * o->distance * std::tan(0.5f * o->fovy_deg * kDegToRad) /
                                 static_cast<float>(std::max(1, viewport_height));
  o->target += metres_per_pixel * (-dx * right + dy * up);
}

void OrbitZoom(float wheel_clicks, OrbitCamera* o) {
  o->distance = std::clamp(o->distance * std::pow(0.9f, wheel_clicks), 0.05f, 500.0f);
}

}  // namespace app
