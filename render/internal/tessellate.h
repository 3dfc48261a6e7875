// Unit meshes the renderer instances for every primitive (fixed tessellation counts, so renders
// are deterministic), plus vertex normals for meshes that come without them.
#pragma once

#include "render/scene.h"

namespace render::internal {

constexpr int kSphereSlices = 32;  // around z
constexpr int kSphereStacks = 16;  // pole to pole
constexpr int kCylinderSlices = 32;

// Unit sphere (radius 1, centred at the origin), smooth normals.
TriangleMesh UnitSphere();
// Cylinder of radius 1 from z = -0.5 to z = +0.5 with flat caps (smooth side normals).
TriangleMesh UnitCylinder();
// Cube with edges of length 1 centred at the origin, flat normals (24 vertices).
TriangleMesh UnitBox();
// Square [-0.5, 0.5]^2 in the z = 0 plane, normal +z.
TriangleMesh UnitQuad();

// Area-weighted vertex normals when mesh.normals is empty (returns a copy with normals filled).
TriangleMesh WithNormals(const TriangleMesh& mesh);

}  // namespace render::internal
