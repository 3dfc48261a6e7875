// The Python classes Robot and Scenario (shared by the planning and render bindings).
#pragma once

#include "planning/collision/collision.h"
#include "planning/motion/scenario.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/robot.h"
#include "planning/robot/robot_io.h"
#include "planning/motion/robot_scene.h"
#include "python/bind/common.h"

namespace topoplan_py {

// --- robots ----------------------------------------------------------------------------------

// A robot model with its kinematics workspace and placed collision objects.
struct PyRobot {
  planning::Robot robot;
  std::unique_ptr<planning::KinematicsData> kin;
  planning::Environment env;
  std::unique_ptr<planning::CollisionData> coll;  // built on first use, reset by add_object

  static PyRobot Load(const fs::path& urdf_path, const std::vector<fs::path>& package_path_list) {
    const std::string urdf = urdf_path.string();
    RequireFile(urdf, "urdf");
    std::vector<std::string> package_paths;
    for (const fs::path& p : package_path_list) package_paths.push_back(p.string());
    PyRobot r;
    planning::RobotLoadOptions options;
    options.package_paths = planning::PackagePaths(package_paths);
    r.robot = planning::LoadRobot(urdf, options);
    r.kin = std::make_unique<planning::KinematicsData>(r.robot);
    return r;
  }

  // q as an array in joint order or a dict {joint name: value} (other joints 0).
  Eigen::VectorXd Q(const py::handle& q) const {
    const int n = planning::num_dofs(robot);
    if (q.is_none()) return Eigen::VectorXd::Zero(n);
    if (py::isinstance<py::dict>(q)) {
      Eigen::VectorXd out = Eigen::VectorXd::Zero(n);
      const std::vector<std::string> names = planning::DofNames(robot);
      for (const auto& [key, value] : py::cast<py::dict>(q)) {
        const std::string name = py::str(key);
        const auto it = std::find(names.begin(), names.end(), name);
        if (it == names.end()) {
          ThrowValue("q: unknown joint '" + name + "' (joints: " + Join(names) + ")");
        }
        double v = 0.0;
        try {
          v = py::cast<double>(value);
        } catch (const py::cast_error&) {
          ThrowValue("q: joint '" + name + "' is not a number");
        }
        if (!std::isfinite(v)) ThrowValue("q: joint '" + name + "' is not finite");
        out[it - names.begin()] = v;
      }
      return out;
    }
    return ToVector(q, "q", n);
  }

  int Link(const std::string& name) const {
    for (size_t i = 0; i < robot.links.size(); ++i) {
      if (robot.links[i].name == name) return static_cast<int>(i);
    }
    ThrowValue("link: unknown link '" + name + "' (links: " + Join(Names(robot.links)) + ")");
  }

  int Chain(const std::string& name) const {
    for (size_t i = 0; i < robot.chains.size(); ++i) {
      if (robot.chains[i].name == name) return static_cast<int>(i);
    }
    ThrowValue("chain: unknown chain '" + name + "' (chains: " + Join(Names(robot.chains)) + ")");
  }

  void Fk(const py::handle& q) { planning::ForwardKinematics(robot, Q(q), kin.get()); }

  planning::CollisionData* Coll() {
    if (!coll) coll = std::make_unique<planning::CollisionData>(robot, env);
    return coll.get();
  }
};

// --- scenarios -------------------------------------------------------------------------------

struct PyScenario {
  std::unique_ptr<planning::Scenario> scenario;
};

// Thrown through RunPlanner when the Python callback returns False or raises.
struct CallbackStop {};

}  // namespace topoplan_py
