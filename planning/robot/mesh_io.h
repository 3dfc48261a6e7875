// Mesh files → planning::Mesh: the one mesh loader of the project. Robot collision and visual
// geometry (planning/robot/robot_io.h) and the mesh entries of scene files (app/scene_json.h) both read
// their files here, so what collides is exactly what is drawn.
//
// Axes and units. The result is in the mesh's own frame as URDF uses it: right-handed, z up,
// lengths in metres.
//   - COLLADA (.dae) carries <asset><unit meter=..> and <up_axis>: both are honoured. Vertices are
//     scaled to metres and rotated so that the file's up axis becomes +z: Z_UP files keep their
//     coordinates, Y_UP files map (x, y, z) → (x, −z, y), X_UP files map their +x onto +z.
//     (assimp itself scales to metres and rotates to its own y-up convention; this loader turns
//     that y-up result into z-up, so a Z_UP file's coordinates come back unchanged.)
//   - STL and OBJ have no axis or unit metadata: their coordinates are taken as they are, in
//     metres.
// Formats: STL (ASCII and binary), Wavefront OBJ and COLLADA, chosen by the file's extension
// (.stl, .obj, .dae, any case). assimp's other importers are not used: they are not fuzzed here,
// and some of this assimp version's (5.2) are known to hang or overflow on malformed files (PLY).
#pragma once

#include <cstddef>
#include <string>

#include "planning/robot/robot.h"

namespace planning {

// Limits of one mesh file, checked before assimp reads it (bytes, for the file and for every file
// it refers to, such as an OBJ's .mtl) and after the import (vertices and triangles of all its
// meshes together, before they are copied).
inline constexpr std::size_t kMaxMeshFileBytes = std::size_t{64} << 20;  // 64 MiB
inline constexpr std::size_t kMaxMeshTriangles = 2'000'000;
inline constexpr std::size_t kMaxMeshVertices = 6'000'000;

// Loads a mesh file with assimp (STL, OBJ, DAE): every mesh of the file merged with its
// node transforms applied, triangulated, axes and units as stated above. Normals: one unit normal
// per vertex (rotated with the vertices), the file's own where it has them, otherwise smooth
// normals averaged over the adjacent faces; zero-length or non-finite ones become +z. Geometry
// scale (URDF <mesh scale>, scene "scale") is not applied: consumers apply it per use, so one
// loaded file serves every scale. Throws std::invalid_argument naming the file when it is missing
// or not a regular file (a pipe, a device), has another extension than .stl, .obj or .dae, is
// larger than kMaxMeshFileBytes, assimp cannot read
// it, it has more than kMaxMeshTriangles triangles or kMaxMeshVertices vertices, a non-finite
// vertex or a face index out of range, or no triangles. Files the mesh refers to (materials) are
// opened only when they are regular files within the byte limit; others are skipped as missing.
Mesh LoadMesh(const std::string& path);

// Convex hull of the mesh's vertices (qhull), as a closed triangle mesh with outward
// counter-clockwise faces; `path` is kept, normals are the face normals averaged per vertex.
// Returns an empty mesh (no triangles) when the points span less than three dimensions (a flat or
// degenerate mesh has no solid hull; callers fall back to the triangles themselves).
// O(v log v) for v vertices.
Mesh ConvexHull(const Mesh& mesh);

}  // namespace planning
