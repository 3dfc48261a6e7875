// The one reader of the JSON robot-chain format, used by the chain sidecars (robot_io.h,
// "<robot>.chains.json": {"chains": [chain, ...]}) and by scenarios ("robot_chains": [chain, ...]):
//
//   {"name": "hand", "closed": false, "points": [{"link": "lwr_link_4", "xyz": [0, 0, 0]}, ...]}
//
// name: string (required, unique on the robot); closed: bool (default false: an open polyline);
// points: at least 2 of {link: string (required), xyz: [x, y, z] in the link frame, metres
// (default [0, 0, 0])}.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "base/json_reader.h"
#include "planning/robot/robot.h"

namespace planning {

// A chain as written, before its link names are resolved on a robot.
struct ChainDescription {
  std::string name;
  bool closed = false;
  std::vector<std::string> links;       // size N
  std::vector<std::string> link_where;  // "file: path" of each point's "link" (for messages)
  Eigen::Matrix3Xd point_local;         // 3 × N, metres
  std::string where;                    // "file: path" of the chain
};

// Reads one chain object; unknown keys, fewer than 2 points, wrong types throw (JSON path).
ChainDescription ReadChainDescription(const base::JsonNode& node);

// Resolves the link names on `robot`. Throws std::invalid_argument naming the JSON path for an
// unknown link and for a name already used by one of robot.chains.
ChainSpec ResolveChain(const ChainDescription& chain, const Robot& robot);

}  // namespace planning
