// Mesh files → planning::Mesh: the one mesh loader of the project. Robot collision and visual
// geometry (planning/robot_io.h) and the mesh entries of scene files (app/scene_json.h) both read
// their files here, so what collides is exactly what is drawn.
//
// Axes and units. The result is in the mesh's own frame as URDF uses it: right-handed, z up,
// lengths in metres.
//   - COLLADA (.dae) carries <asset><unit meter=..> and <up_axis>: both are honoured. Vertices are
//     scaled to metres and rotated so that the file's up axis becomes +z: Z_UP files keep their
//     coordinates, Y_UP files map (x, y, z) → (x, −z, y), X_UP files map their +x onto +z.
//     (assimp itself scales to metres and rotates to its own y-up convention; this loader turns
//     that y-up result into z-up, so a Z_UP file's coordinates come back unchanged.)
//   - STL, OBJ, PLY and the other formats have no axis or unit metadata: their coordinates are
//     taken as they are, in metres.
#pragma once

#include <string>

#include "planning/robot.h"

namespace planning {

// Loads a mesh file with assimp (STL, DAE, OBJ, PLY, ...): every mesh of the file merged with its
// node transforms applied, triangulated, axes and units as stated above. Normals: one unit normal
// per vertex (rotated with the vertices), the file's own where it has them, otherwise smooth
// normals averaged over the adjacent faces; zero-length ones become +z. Geometry scale (URDF <mesh
// scale>, scene "scale") is not applied: consumers apply it per use, so one loaded file serves
// every scale. Throws std::invalid_argument naming the file when it is missing, assimp cannot read
// it, or it has no triangles.
Mesh LoadMesh(const std::string& path);

// Convex hull of the mesh's vertices (qhull), as a closed triangle mesh with outward
// counter-clockwise faces; `path` is kept, normals are the face normals averaged per vertex.
// Returns an empty mesh (no triangles) when the points span less than three dimensions (a flat or
// degenerate mesh has no solid hull; callers fall back to the triangles themselves).
// O(v log v) for v vertices.
Mesh ConvexHull(const Mesh& mesh);

}  // namespace planning
