// Unit meshes the renderer instances for every primitive (fixed tessellation counts, so renders
// are deterministic), plus vertex normals for meshes that come without them.
#pragma once

#include "render/scene.h"

namespace render::internal {

// Levels of detail: slices around the axis (spheres use slices/2 stacks). The renderer picks a
// level from the projected radius in pixels, so small beads cost few triangles.
constexpr int kLodSlices[3] = {12, 20, 32};
constexpr float kLodMaxRadiusPx[2] = {6.0f, 20.0f};  // below: level 0, below: level 1, else 2

// Unit sphere (radius 1, centred at the origin) with `slices` around z and slices/2 stacks,
// smooth normals; slices * (slices/2 - 1) * 2 triangles.
TriangleMesh UnitSphere(int slices);
// Cylinder of radius 1 from z = -0.5 to z = +0.5 with flat caps (smooth side normals);
// 4 * slices triangles.
TriangleMesh UnitCylinder(int slices);
// Cube with edges of length 1 centred at the origin, flat normals (24 vertices).
TriangleMesh UnitBox();
// Square [-0.5, 0.5]^2 in the z = 0 plane, normal +z.
TriangleMesh UnitQuad();

// Area-weighted vertex normals when mesh.normals is empty (returns a copy with normals filled).
TriangleMesh WithNormals(const TriangleMesh& mesh);

}  // namespace render::internal
