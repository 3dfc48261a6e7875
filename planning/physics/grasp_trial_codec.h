// A grasp trial as bytes, to hand it from the process that ran it to the one that reports it (the
// demo runs trials in forked processes). Not a file format: the bytes are only read back by the
// same build on the same machine.
#pragma once

#include <string>

#include "planning/physics/grasp_trials.h"

namespace planning::physics {

// Every field of `trial` that the reports read, exactly (doubles bit for bit): the transfer
// (method, q, trajectory, windings, clearance, solver and its counts), winding_error,
// epsilon_quality, human, the stability result (closure contacts included) and the perturbed
// repetitions. Not the ODE descriptions `hand` and `object` (decoded empty).
std::string EncodeGraspTrial(const GraspTrial& trial);

// The trial EncodeGraspTrial wrote. Throws std::runtime_error for bytes it did not write
// (truncated, another version).
GraspTrial DecodeGraspTrial(const std::string& bytes);

}  // namespace planning::physics
