// The one Settings struct that both the command line and the interactive window edit.
//
// ImGui panels (app/ui/) edit it in place; CLI flags and `--script` lines fill the same fields.
// Nothing in here owns planning state: that lives in app::Session.
#pragma once

#include <Eigen/Core>
#include <string>

#include "planning/motion/robot_scene.h"

namespace app {

// Orbit camera around `target`: yaw about +z and pitch above the xy plane, in degrees.
struct OrbitCamera {
  Eigen::Vector3f target = Eigen::Vector3f::Zero();
  float yaw_deg = -50.0f;
  float pitch_deg = 25.0f;
  float distance = 4.0f;
  float fovy_deg = 35.0f;
};

struct ViewToggles {
  bool chains = true;               // robot and object chains as tubes
  bool collision_geometry = false;  // collision shapes instead of visuals
  bool grid = true;                 // ground grid
  bool contacts = true;             // contact points of the grasp simulation
  bool heatmap_panel = true;        // live writhe heatmap
  bool cost_panel = true;           // cost per sweep
};

struct PlannerSettings {
  std::string planner = "aico";  // aico | rrt | birrt
  unsigned seed = 0;
  // AICO solver options; loading a scenario sets them to the scenario's own (aico.*).
  int max_iterations = 40;     // AICO sweeps
  double tolerance = 1e-2;     // AICO belief-step tolerance
  double damping = 1.0;        // AICO initial Levenberg damping
  double start_wrap_deg = -1;  // < 0: the scenario's own start coil
};

// The grasp panel: which human grasp and transfer method the ODE stability test replays.
struct GraspSettings {
  std::string grasp = "power_bottle";  // assets/grasps/NAME.json
  std::string method = "winding";      // winding | joint | fingertip
  bool active = false;                 // show the grasp simulation instead of the scenario
  int frame = 0;                       // recorded simulation frame shown
};

// Moving an object with the mouse (modifier + drag) or `move OBJECT X Y Z`.
struct MoveSettings {
  std::string object;  // the object a modifier-drag moves ("" = the scenario's first object)
  bool dragging = false;
  Eigen::Vector3d start = Eigen::Vector3d::Zero();   // its position when the drag began [m]
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // accumulated drag [m]
};

struct Settings {
  std::string scenario_path;
  planning::RobotInputOptions robot_input;  // --package-path, --srdf: used by every load
  PlannerSettings planner;
  ViewToggles view;
  OrbitCamera camera;
  bool camera_initialised = false;  // false: frame the scene on the next render
  int width = 1280, height = 720;   // frame size in pixels
  // Which configuration is shown: the trajectory of `sweep` (−1: the final result) at slice
  // `frame`, or the joint sliders' q when there is no trajectory.
  int sweep = -1;
  int frame = 0;
  bool playing = false;
  int play_stride = 1;  // slices advanced per rendered frame while playing
  GraspSettings grasp;
  MoveSettings move;
};

}  // namespace app
