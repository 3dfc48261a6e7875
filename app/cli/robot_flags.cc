#include "app/cli/robot_flags.h"

#include <CLI/CLI.hpp>

#include "app/cli/io.h"

namespace app {

void AddRobotInputFlags(CLI::App* cmd, planning::RobotInputOptions* options, std::string* pose) {
  cmd->add_option("--package-path", options->package_paths,
                  "extra root folder for package://PKG/... mesh URIs (repeatable; "
                  "$ROS_PACKAGE_PATH and the URDF's ancestor folders are searched too)")
      ->check(NonEmpty());
  cmd->add_option("--srdf", options->srdf,
                  "SRDF of the robot: its disable_collisions pairs are not checked, its "
                  "group_states are --pose names (default: NAME.srdf next to NAME.urdf or in "
                  "../srdf/)")
      ->check(NonEmpty());
  if (pose) {
    cmd->add_option("--pose", *pose, "configuration: a group_state of the SRDF (instead of --q)")
        ->check(NonEmpty());
  }
}

}  // namespace app
