// Checks of a COLLADA file before assimp reads it: assimp expands node instances recursively and
// without limit, so a node that instances itself (directly or through others) crashes it and a
// few kilobytes of nested instances expand to gigabytes. Private to planning/robot.
#pragma once

#include <cstddef>
#include <string>

namespace planning::internal {

// Most node instances a COLLADA scene may expand to (every <node> and <instance_node> counted as
// often as it appears after expansion).
inline constexpr std::size_t kMaxColladaInstances = 100'000;

// Throws std::invalid_argument "<path>: ..." when the node graph of `xml` (child <node>s and
// <instance_node url="#id">) has a cycle (naming the nodes on it), when the expanded scene would
// hold more than kMaxColladaInstances node instances, or more than `max_triangles` triangles
// (each <instance_geometry> counted with its geometry's <triangles>/<polylist>/<polygons>/
// <trifans>/<tristrips> count= per expanded instance). Computed on the graph, never by expanding.
void CheckColladaStructure(const std::string& xml, const std::string& path,
                           std::size_t max_triangles);

}  // namespace planning::internal
