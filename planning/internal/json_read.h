// Small JSON readers shared by the grasp and grasp-object loaders (planning-internal).
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>

namespace planning::internal {

// Reads [x, y, z] of finite numbers; throws std::invalid_argument naming `where` otherwise.
Eigen::Vector3d ReadJsonVec3(const nlohmann::json& j, const std::string& where);

}  // namespace planning::internal
