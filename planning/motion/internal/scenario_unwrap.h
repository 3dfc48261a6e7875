// Private: `scenario new --task unwrap` (planning/motion/scenario_new.h): an arm hooked around a
// pole that must unwrap (total writhe arm × pole → 0) while its tool reaches a target.
#pragma once

#include <string>

#include "planning/motion/internal/scenario_arm.h"
#include "planning/motion/robot_scene.h"
#include "planning/motion/scenario_new.h"

namespace planning::internal {

// The unwrap scenario of `scene` (loaded from `urdf`) for the arm `setup`; `out` holds the notes
// so far and is returned completed. How the start hook, the pole and the goal are found is in
// scenario_new.h. Throws std::invalid_argument when no hook or no unwrapped goal is found (the
// message says how many samples were tried and what rejected them).
NewScenario MakeUnwrapScenario(const RobotScene& scene, const std::string& urdf,
                               const NewScenarioOptions& options, const ArmSetup& setup,
                               NewScenario out);

}  // namespace planning::internal
