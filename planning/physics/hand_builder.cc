#include "planning/physics/hand_builder.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "planning/robot/kinematics.h"
#include "planning/robot/pose.h"

namespace planning::physics {
namespace {

SimShape ToSimShape(const Geometry& g, const Eigen::Isometry3d& body_from_geometry, bool* ok) {
  SimShape s;
  *ok = true;
  switch (g.kind) {
    case Geometry::Kind::kBox:
      s.kind = SimShape::Kind::kBox;
      break;
    case Geometry::Kind::kSphere:
      s.kind = SimShape::Kind::kSphere;
      break;
    case Geometry::Kind::kCylinder:
      s.kind = SimShape::Kind::kCylinder;
      break;
    case Geometry::Kind::kCapsule:
      s.kind = SimShape::Kind::kCapsule;
      break;
    case Geometry::Kind::kMesh:
      *ok = false;
      break;
  }
  s.size = g.size;
  s.body_from_shape = body_from_geometry;
  return s;
}

// First entry whose key is a substring of `name`, else nullptr.
const double* FindBySubstring(const std::vector<std::pair<std::string, double>>& table,
                              const std::string& name) {
  for (const auto& [key, value] : table) {
    if (name.find(key) != std::string::npos) return &value;
  }
  return nullptr;
}

bool Holds(const HandBuildOptions& o, const std::string& joint) {
  for (const std::string& h : o.hold_joints) {
    if (joint.find(h) != std::string::npos) return true;
  }
  return false;
}

}  // namespace

SimHand BuildSimHand(const Robot& robot, const Eigen::VectorXd& q, const std::string& palm_link,
                     const HandBuildOptions& options) {
  if (q.size() != num_dofs(robot)) {
    throw std::invalid_argument("BuildSimHand: q has " + std::to_string(q.size()) +
                                " entries, the robot " + std::to_string(num_dofs(robot)));
  }
  const int palm = FindLink(robot, palm_link);
  // Start configuration: flexion joints opened by open_by (within limits).
  Eigen::VectorXd q_start = q;
  for (int k = 0; k < num_dofs(robot); ++k) {
    const Joint& j = robot.joints[robot.dof_joints[k]];
    if (j.type != JointType::kRevolute || Holds(options, j.name)) continue;
    // Only joints below the palm are hand joints.
    int li = j.child_link;
    bool under_palm = false;
    while (li >= 0) {
      if (li == palm) under_palm = true;
      const int pj = robot.links[li].parent_joint;
      li = pj < 0 ? -1 : robot.joints[pj].parent_link;
    }
    if (under_palm && j.child_link != palm) {
      q_start[k] = std::max(j.limits.lower, q[k] - options.open_by);
    }
  }
  KinematicsData start(robot), grasp(robot);
  ForwardKinematics(robot, q_start, &start);
  ForwardKinematics(robot, q, &grasp);

  SimHand hand;
  hand.limit_stop_torque = options.limit_stop_torque;
  std::vector<int> body_of(robot.links.size(), -1);
  body_of[palm] = 0;
  SimHandLink palm_link_sim;
  palm_link_sim.name = robot.links[palm].name;
  palm_link_sim.world_from_link = start.world_from_link[palm];
  palm_link_sim.mass = options.default_mass;
  hand.links.push_back(palm_link_sim);
  auto mass_of = [&](const std::string& name) {
    const double* m = FindBySubstring(options.link_masses, name);
    return m ? *m : options.default_mass;
  };
  hand.links[0].mass = mass_of(robot.links[palm].name);
  for (size_t i = 0; i < robot.links.size(); ++i) {
    const int pj = robot.links[i].parent_joint;
    if (static_cast<int>(i) != palm) {
      if (pj < 0 || body_of[robot.joints[pj].parent_link] < 0) continue;  // not below the palm
      const Joint& j = robot.joints[pj];
      const int parent_body = body_of[j.parent_link];
      if (j.type == JointType::kFixed ||
          (options.weld_held_joints && Holds(options, j.name) &&
           (j.type == JointType::kRevolute || j.type == JointType::kContinuous))) {
        body_of[i] = parent_body;
      } else if (j.type == JointType::kRevolute || j.type == JointType::kContinuous) {
        SimHandLink l;
        l.name = robot.links[i].name;
        l.parent = parent_body;
        l.world_from_link = start.world_from_link[i];
        l.joint_anchor = start.joint_origin_world[pj];
        l.joint_axis = start.joint_axis_world[pj];
        l.q_start = start.joint_value[pj];
        const double close = Holds(options, j.name) ? 0.0 : options.close_by;
        const double lo = std::isfinite(j.limits.lower) ? j.limits.lower : -std::numbers::pi + 0.01;
        const double hi = std::isfinite(j.limits.upper) ? j.limits.upper : std::numbers::pi - 0.01;
        l.lower = std::max(lo, -std::numbers::pi + 0.01);
        l.upper = std::min(hi, std::numbers::pi - 0.01);
        l.q_start = std::clamp(l.q_start, l.lower, l.upper);
        l.q_target = std::clamp(grasp.joint_value[pj] + close, l.lower, l.upper);
        const double* torque = FindBySubstring(options.joint_torques, j.name);
        l.max_torque = torque ? *torque
                       : std::isfinite(j.limits.effort) && j.limits.effort > 0
                           ? j.limits.effort
                           : options.default_torque;
        l.mass = mass_of(l.name);
        body_of[i] = static_cast<int>(hand.links.size());
        hand.links.push_back(l);
      } else {
        throw std::invalid_argument("BuildSimHand: prismatic joint '" + j.name +
                                    "' below the palm is not supported");
      }
    }
    // Geometry of link i goes to its body, expressed in the body's frame.
    const int b = body_of[i];
    const Eigen::Isometry3d body_from_link =
        hand.links[b].world_from_link.inverse() * start.world_from_link[i];
    for (const Geometry& g : robot.links[i].collisions) {
      bool ok = false;
      SimShape s = ToSimShape(g, body_from_link * g.link_from_geometry, &ok);
      if (ok) hand.links[b].shapes.push_back(s);
    }
  }
  if (options.density > 0) {
    for (SimHandLink& l : hand.links) {
      if (FindBySubstring(options.link_masses, l.name)) continue;
      double volume = 0.0;
      for (const SimShape& s : l.shapes) volume += PrimitiveVolume(s);
      if (volume > 0) l.mass = options.density * volume;
    }
  }
  return hand;
}

HandBuildOptions HumanHandBuildOptions() {
  HandBuildOptions o;
  o.hold_joints = {"_abd"};
  o.link_masses.clear();
  o.density = 1100.0;
  o.default_mass = 0.005;
  o.limit_stop_torque = true;
  o.weld_held_joints = true;
  return o;
}

std::vector<std::string> SimHandLinkNames(const SimHand& hand) {
  std::vector<std::string> names;
  for (const SimHandLink& l : hand.links) names.push_back(l.name);
  return names;
}

SimObject BuildSimObject(const GraspObject& object, const Eigen::Isometry3d& world_from_object,
                         int torus_segments) {
  SimObject o;
  o.mass = object.mass;
  o.world_from_object = world_from_object;
  for (const GraspPrimitive& p : object.primitives) {
    SimShape s;
    s.body_from_shape = p.object_from_primitive;
    s.size = p.size;
    switch (p.kind) {
      case GraspPrimitive::Kind::kSphere:
        s.kind = SimShape::Kind::kSphere;
        o.shapes.push_back(s);
        break;
      case GraspPrimitive::Kind::kCylinder:
        s.kind = SimShape::Kind::kCylinder;
        o.shapes.push_back(s);
        break;
      case GraspPrimitive::Kind::kBox:
        s.kind = SimShape::Kind::kBox;
        o.shapes.push_back(s);
        break;
      case GraspPrimitive::Kind::kCapsule:
        s.kind = SimShape::Kind::kCapsule;
        o.shapes.push_back(s);
        break;
      case GraspPrimitive::Kind::kTorus: {
        const double half =
            p.size.z() > 0 ? std::min(p.size.z(), std::numbers::pi) : std::numbers::pi;
        const int n =
            std::max(4, static_cast<int>(std::ceil(torus_segments * half / std::numbers::pi)));
        for (int k = 0; k < n; ++k) {
          const double a0 = -half + 2 * half * k / n, a1 = -half + 2 * half * (k + 1) / n;
          const Eigen::Vector3d p0(p.size.x() * std::cos(a0), p.size.x() * std::sin(a0), 0);
          const Eigen::Vector3d p1(p.size.x() * std::cos(a1), p.size.x() * std::sin(a1), 0);
          SimShape c;
          c.kind = SimShape::Kind::kCapsule;
          c.size = Eigen::Vector3d(p.size.y(), (p1 - p0).norm(), 0);
          Eigen::Isometry3d local = Eigen::Isometry3d::Identity();
          local.translation() = 0.5 * (p0 + p1);
          local.linear() = RotationFromZ(p1 - p0);
          c.body_from_shape = p.object_from_primitive * local;
          o.shapes.push_back(c);
        }
        break;
      }
    }
  }
  return o;
}

double PrimitiveVolume(const SimShape& s) {
  const double r = s.size.x();
  switch (s.kind) {
    case SimShape::Kind::kSphere:
      return 4.0 / 3.0 * std::numbers::pi * r * r * r;
    case SimShape::Kind::kCapsule:
      return std::numbers::pi * r * r * s.size.y() + 4.0 / 3.0 * std::numbers::pi * r * r * r;
    case SimShape::Kind::kCylinder:
      return std::numbers::pi * r * r * s.size.y();
    case SimShape::Kind::kBox:
      return s.size.prod();
    case SimShape::Kind::kTrimesh:
      return 0.0;
  }
  return 0.0;
}

}  // namespace planning::physics
