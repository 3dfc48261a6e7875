// The robot-input flags of fk, check, render and view.
#pragma once

#include <string>

#include "planning/motion/robot_scene.h"

namespace CLI {
class App;
}

namespace app {

// Adds --package-path (repeatable) and --srdf to `cmd`, and --pose when `pose` is not null.
void AddRobotInputFlags(CLI::App* cmd, planning::RobotInputOptions* options, std::string* pose);

}  // namespace app
