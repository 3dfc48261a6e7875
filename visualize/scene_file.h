// Scene files: the JSON format of `topoplan render SCENE.json` (documented in README.md, section
// "Rendering"), parsed into a render::Scene and Camera. Reusable by any app code that needs a
// camera, colours or shapes from JSON (scenario files, the viewer).
//
// Every error is a std::invalid_argument whose message starts with the source name and the JSON
// path of the offending value, e.g. "scene.json: shapes[3].radius: expected a number".
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "render/scene.h"

namespace visualize {

// Limits of a scene file, checked while it is parsed (before anything is drawn): entries in
// "shapes" (1000 spheres take about 2 s and 80 MB to draw), points of all "chain" and "lines"
// entries together (as many as one chain file, topology::kMaxChainPoints) and triangles of all
// "mesh" entries together (as many as one mesh file, planning::kMaxMeshTriangles; a mesh listed
// twice is read once but counts twice).
inline constexpr std::size_t kMaxSceneShapes = 1000;
inline constexpr std::size_t kMaxScenePoints = 100000;
inline constexpr std::size_t kMaxSceneTriangles = 2'000'000;

struct SceneDocument {
  render::Scene scene;
  render::Camera camera;  // defaults when has_camera is false
  bool has_camera = false;
  int width = 0, height = 0;  // "size": [w, h] when given, else 0
  std::vector<std::string> warnings;  // robot scenes: planning::RobotScene::warnings and pose's
};

// Parses a scene document. `source` names the file in messages; relative "file" entries (meshes,
// chain CSVs) are resolved against `base_dir`. Numbers must fit single precision (chain files
// too); the limits above are checked.
SceneDocument ParseSceneJson(const nlohmann::json& doc, const std::string& source,
                             const std::string& base_dir);

// Reads and parses a scene file (JSON syntax errors name the file and byte offset).
SceneDocument LoadSceneFile(const std::string& path);

// Pieces for other JSON formats; `path` is the JSON path used in messages (e.g. "camera").
render::Camera ParseCameraJson(const nlohmann::json& j, const std::string& source,
                               const std::string& path);
// [r, g, b] or [r, g, b, a], each in [0, 1].
std::array<float, 4> ParseColorJson(const nlohmann::json& j, const std::string& source,
                                    const std::string& path);

}  // namespace visualize
