#include "tests/planning/physics/test_hands.h"

#include <cstdio>
#include <string>

namespace testing_hands {

using planning::physics::SimHand;
using planning::physics::SimHandLink;
using planning::physics::SimObject;
using planning::physics::SimShape;

SimObject Bottle() {
  SimObject o;
  SimShape s;
  s.kind = SimShape::Kind::kCylinder;
  s.size = Eigen::Vector3d(0.0325, 0.205, 0);
  s.body_from_shape.linear() =
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();  // z → x
  o.shapes.push_back(s);
  o.mass = 0.52;
  o.world_from_object.translation() = Eigen::Vector3d(0, 0, 0.0335);
  return o;
}

SimHand ClawHand(double closing_target) {
  SimHand hand;
  SimHandLink palm;
  palm.name = "palm";
  palm.mass = 0.4;
  SimShape box;
  box.kind = SimShape::Kind::kBox;
  box.size = Eigen::Vector3d(0.10, 0.10, 0.02);
  box.body_from_shape.translation() = Eigen::Vector3d(0, 0, -0.01);
  palm.shapes.push_back(box);
  hand.links.push_back(palm);

  const double lengths[3] = {0.045, 0.035, 0.030};
  struct Finger {
    double x, side;  // side +1: base at y = +0.045, closes towards −y
  };
  const Finger fingers[5] = {{-0.03, 1}, {0.0, 1}, {0.03, 1}, {-0.015, -1}, {0.015, -1}};
  for (int f = 0; f < 5; ++f) {
    int parent = 0;
    double z = 0.0;
    for (int k = 0; k < 3; ++k) {
      SimHandLink l;
      char name[32];  // "f%d_%d" of two ints fits in 25 bytes
      std::snprintf(name, sizeof(name), "f%d_%d", f, k);
      l.name = name;
      l.parent = parent;
      const Eigen::Vector3d base(fingers[f].x, 0.045 * fingers[f].side, z);
      l.world_from_link.translation() = base;
      l.joint_anchor = base;
      l.joint_axis = Eigen::Vector3d::UnitX() * fingers[f].side;
      l.q_start = 0.0;
      l.q_target = closing_target;
      l.lower = -0.5;
      l.upper = 1.6;
      l.max_torque = k == 0 ? 2.0 : 1.4;
      l.mass = 0.03;
      SimShape cap;
      cap.kind = SimShape::Kind::kCapsule;
      cap.size = Eigen::Vector3d(0.009, lengths[k], 0);
      cap.body_from_shape.translation() = Eigen::Vector3d(0, 0, lengths[k] / 2);
      l.shapes.push_back(cap);
      hand.links.push_back(l);
      parent = static_cast<int>(hand.links.size()) - 1;
      z += lengths[k];
    }
  }
  return hand;
}

}  // namespace testing_hands
