// Hand-like capsule sets and objects shared by the physics tests and benchmark.
#pragma once

#include "planning/physics/grasp_simulation.h"

namespace testing_hands {

// Bottle: cylinder radius 0.0325 m, length 0.205 m, 0.52 kg, axis along the palm x axis, lying on
// the palm surface (palm frame = world frame, palm normal +z).
planning::physics::SimObject Bottle();

// A claw-like hand around that bottle: a box palm (top face at z = 0), three 3-phalanx capsule
// fingers on the +y side and two on the −y side, hinges about ±x, start straight up.
// closing_target: the angle every hinge is driven to (≈ 1.2 rad wraps the bottle; 0 or negative
// keeps the hand open).
planning::physics::SimHand ClawHand(double closing_target);

}  // namespace testing_hands
