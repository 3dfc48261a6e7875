// Noisy demonstrations: many human grasps of one type made from a nominal demonstration by seeded,
// bounded noise on the finger joints and the palm pose (the demonstrations of `bench grasp`).
#pragma once

#include <cstdint>
#include <string>

#include "planning/grasp/grasp.h"
#include "planning/grasp/grasp_object.h"
#include "planning/robot/robot.h"

namespace planning {

// Bounds of the noise (uniform distributions, every draw inside its bound).
struct DemoNoiseOptions {
  double joint_deg = 8.0;  // every finger joint: + U[−a, a] [deg], then clamped to limits
  double palm_translation = 0.015;  // palm origin: + U[−t, t] along each world axis [m]
  double palm_rotation_deg = 10.0;  // palm turned about its origin by U[−b, b] [deg] about a
                                    // uniformly random axis (world frame)
  std::uint32_t seed = 0;
};

// Demonstration `index` (>= 0) of `nominal`: every finger dof of `human` (the dofs not named
// hand_*; joints absent from nominal.joints count as 0) gets U[−joint_deg, joint_deg] and is
// clamped to its limits; the palm frame is turned about its own origin by an angle in [−b, b]
// about a random unit axis (world frame; R_palm' = R_w · R_palm) and its origin moved by t
// (each axis in [−t, t]). The object
// pose is unchanged. The draws come from std::mt19937 seeded by std::seed_seq{seed, h_lo, h_hi,
// index} (h = FNV-1a 64 of nominal.name) through base::UniformUnit: reproducible, independent
// of the other demonstrations and of the order they are made in. The name becomes
// "<name>#<index>"; `close` is kept (RecloseDemonstration). Throws std::invalid_argument for index
// < 0, a negative or non-finite bound, or a joint of nominal.joints that `human` lacks.
HumanGrasp NoisyDemonstration(const Robot& human, const HumanGrasp& nominal, int index,
                              const DemoNoiseOptions& options = {});

// The demonstrator closing the noisy hand on the object again: the palm backs away along its
// normal (+y of hand_palm) in 1 mm steps, at most 4 cm, until the palm link clears the object;
// then SynthesizeGrasp with demo->close
// (the joints of the grasp's spec, assets/grasps/specs/) from the noisy joint values — each
// listed joint closes until it touches the object, or opens out of a penetration — then `close`
// is cleared. Returns the final minimum clearance [m]. No-op (returns +inf) without a close list.
double RecloseDemonstration(const Robot& human, const GraspObject& object, HumanGrasp* demo);

// Largest deviation of a demonstration from its nominal one: finger joints [rad] (over every dof
// not named hand_*), palm translation per axis [m] and palm rotation angle [rad].
struct DemoDeviation {
  double joint = 0.0;
  double palm_translation = 0.0;  // max over x, y, z of |Δ|
  double palm_rotation = 0.0;
};
DemoDeviation MeasureDeviation(const Robot& human, const HumanGrasp& nominal,
                               const HumanGrasp& demo);

}  // namespace planning
