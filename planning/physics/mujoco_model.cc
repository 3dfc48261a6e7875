// MJCF of a hand and an object for the MuJoCo stability backend (planning/physics/
// mujoco_stability.h), the engine switch and EngineAvailable. Builds with or without MuJoCo.
#include <cmath>
#include <cstdio>
#include <functional>
#include <stdexcept>
#include <string>

#include "base/str_cat.h"
#include "planning/physics/internal/grasp_simulation_impl.h"
#include "planning/physics/mujoco_stability.h"

namespace planning::physics {
namespace {

using base::StrCat;

// Shortest round-trip text of a double (locale independent).
std::string Num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.17g", v);
  return buf;
}

std::string MjVec(const Eigen::Vector3d& v) {
  return StrCat(Num(v.x()), " ", Num(v.y()), " ", Num(v.z()));
}

// pos="x y z" quat="w x y z" of a pose.
std::string PoseAttributes(const Eigen::Isometry3d& pose) {
  const Eigen::Quaterniond q(pose.linear());
  return StrCat("pos=\"", MjVec(pose.translation()), "\" quat=\"", Num(q.w()), " ", Num(q.x()), " ",
                Num(q.y()), " ", Num(q.z()), "\"");
}

double ShapeVolume(const SimShape& s) {
  if (s.kind == SimShape::Kind::kTrimesh) {
    throw std::invalid_argument("MuJoCo backend: trimesh shapes are not supported");
  }
  return PrimitiveVolume(s);
}

// One geom per shape, `mass` spread by volume; contype/conaffinity from `collision`.
std::string Geoms(const std::vector<SimShape>& shapes, double mass, const std::string& collision,
                  const std::string& prefix) {
  double total = 0.0;
  for (const SimShape& s : shapes) total += ShapeVolume(s);
  std::string out;
  for (size_t k = 0; k < shapes.size(); ++k) {
    const SimShape& s = shapes[k];
    std::string type, size;
    switch (s.kind) {
      case SimShape::Kind::kSphere:
        type = "sphere";
        size = Num(s.size.x());
        break;
      case SimShape::Kind::kCapsule:
      case SimShape::Kind::kCylinder:
        type = s.kind == SimShape::Kind::kCapsule ? "capsule" : "cylinder";
        size = StrCat(Num(s.size.x()), " ", Num(0.5 * s.size.y()));
        break;
      case SimShape::Kind::kBox:
        type = "box";
        size = MjVec(0.5 * s.size);
        break;
      case SimShape::Kind::kTrimesh:
        break;
    }
    const double m = total > 0 ? mass * ShapeVolume(s) / total : mass / shapes.size();
    out.append(StrCat("<geom name=\"", prefix, std::to_string(k), "\" type=\"", type, "\" size=\"",
                      size, "\" ", PoseAttributes(s.body_from_shape), " mass=\"", Num(m), "\" ",
                      collision, "/>\n"));
  }
  return out;
}

}  // namespace

std::string MujocoModelXml(const SimHand& hand, const SimObject& object, const SimOptions& sim,
                           const MujocoOptions& mj) {
  internal::Validate(hand, object, sim);
  if (sim.hand_mode != HandMode::kMotorized) {
    throw std::invalid_argument("MuJoCo backend: only the motorised hand is supported");
  }
  if (!(mj.kv_per_torque > 0) || !(mj.contact_time_constant > 0) || !(mj.armature >= 0)) {
    throw std::invalid_argument(
        "MuJoCo options: need kv_per_torque > 0, time constant > 0, "
        "armature >= 0");
  }
  const double spin = SoftFingerSpinArm(sim.mu, sim.contact_patch_radius);
  const int condim = spin > 0 ? 4 : 3;
  std::string x =
      "<mujoco model=\"grasp\">\n<compiler angle=\"radian\" inertiafromgeom=\"true\"/>\n";
  x.append(StrCat("<option timestep=\"", Num(sim.dt),
                  "\" gravity=\"0 0 0\" integrator=\"implicit\" cone=\"pyramidal\"/>\n"));
  x.append(StrCat("<default><geom condim=\"", std::to_string(condim), "\" friction=\"", Num(sim.mu),
                  " ", Num(spin), " 0\" solref=\"", Num(mj.contact_time_constant),
                  " 1\"/></default>\n<worldbody>\n"));
  // Hand: nested bodies in link order (a parent's index is smaller than its children's).
  const int n = static_cast<int>(hand.links.size());
  std::vector<std::vector<int>> children(n);
  for (int i = 1; i < n; ++i) children[hand.links[i].parent].push_back(i);
  const std::string hand_collision = "contype=\"1\" conaffinity=\"0\"";
  std::function<void(int)> body = [&](int i) {
    const SimHandLink& l = hand.links[i];
    const Eigen::Isometry3d parent =
        i == 0 ? Eigen::Isometry3d::Identity() : hand.links[l.parent].world_from_link;
    x.append(StrCat("<body name=\"link", std::to_string(i), "\" ",
                    PoseAttributes(parent.inverse() * l.world_from_link), ">\n"));
    if (l.shapes.empty()) {
      x.append(StrCat("<inertial pos=\"0 0 0\" mass=\"", Num(l.mass),
                      "\" diaginertia=\"1e-6 1e-6 1e-6\"/>\n"));
    }
    if (i > 0) {
      const Eigen::Isometry3d link_from_world = l.world_from_link.inverse();
      x.append(StrCat("<joint name=\"j", std::to_string(i), "\" type=\"hinge\" pos=\"",
                      MjVec(link_from_world * l.joint_anchor), "\" axis=\"",
                      MjVec(link_from_world.linear() * l.joint_axis.normalized()),
                      "\" limited=\"true\" range=\"", Num(l.lower - l.q_start), " ",
                      Num(l.upper - l.q_start), "\" armature=\"", Num(mj.armature), "\"/>\n"));
    }
    x.append(Geoms(l.shapes, l.mass, hand_collision, StrCat("h", std::to_string(i), "_")));
    for (int c : children[i]) body(c);
    x.append("</body>\n");
  };
  body(0);
  x.append(StrCat("<body name=\"object\" ", PoseAttributes(object.world_from_object),
                  ">\n<freejoint name=\"object_free\"/>\n"));
  x.append(Geoms(object.shapes, object.mass, "contype=\"0\" conaffinity=\"1\"", "o_"));
  x.append("</body>\n</worldbody>\n<actuator>\n");
  for (int i = 1; i < n; ++i) {
    const double t = hand.links[i].max_torque;
    x.append(StrCat("<velocity name=\"a", std::to_string(i), "\" joint=\"j", std::to_string(i),
                    "\" kv=\"", Num(mj.kv_per_torque * t), "\" forcelimited=\"true\" forcerange=\"",
                    Num(-t), " ", Num(t), "\"/>\n"));
  }
  x.append("</actuator>\n</mujoco>\n");
  return x;
}

bool EngineAvailable(PhysicsEngine engine) {
#ifdef TOPOPLAN_WITH_MUJOCO
  (void)engine;
  return true;
#else
  return engine == PhysicsEngine::kOde;
#endif
}

#ifndef TOPOPLAN_WITH_MUJOCO
StabilityResult TestGraspStabilityMujoco(const SimHand&, const SimObject&, const StabilityOptions&,
                                         const MujocoOptions&, const StateCallback&) {
  throw std::runtime_error(
      "this build has no MuJoCo (install libmujoco-dev and configure with "
      "-DTOPOPLAN_WITH_MUJOCO=ON)");
}
#endif

StabilityResult TestGraspStabilityIn(PhysicsEngine engine, const OdeRuntime& runtime,
                                     const SimHand& hand, const SimObject& object,
                                     const StabilityOptions& options) {
  if (engine == PhysicsEngine::kMujoco) return TestGraspStabilityMujoco(hand, object, options);
  return TestGraspStability(runtime, hand, object, options);
}

}  // namespace planning::physics
