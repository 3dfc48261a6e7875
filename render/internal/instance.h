// What the scene renderer draws: instances (a 4x4 model matrix, colour, material and 3x3 normal
// matrix, 33 floats uploaded per instance) of GPU meshes, the transforms that place unit meshes
// (scale, translate, a frame along a segment), and axis-aligned world bounds of instances for the
// clip planes and the shadow frustum. CPU only apart from the GL names held by GpuMesh.
#pragma once

#include <Eigen/Core>
#include <array>

#include "render/internal/gl_api.h"
#include "render/scene.h"

namespace render::internal {

// One drawn copy of a unit mesh: model matrix, colour, material (specular, shininess, 0, 0).
struct Instance {
  std::array<float, 16> model;
  std::array<float, 4> color;
  std::array<float, 4> material;
  std::array<float, 9> normal;  // column-major inverse transpose of the model's 3x3
};
static_assert(sizeof(Instance) == 33 * sizeof(float));

// A mesh uploaded to GL: vertex array, interleaved position + normal buffer (6 floats per
// vertex), index buffer (3 per triangle) and the per-instance buffer of Instance records.
struct GpuMesh {
  GLuint vao = 0, vertex_buffer = 0, index_buffer = 0, instance_buffer = 0;
  GLsizei index_count = 0;
  float bound_radius = 1.0f;  // radius about the mesh origin enclosing every vertex
  bool closed = false;  // closed surface, counter-clockwise outside (back faces never visible)
};

// diag(s.x, s.y, s.z, 1).
Eigen::Matrix4f Scale(const Eigen::Vector3f& s);
// Identity with translation t.
Eigen::Matrix4f Translate(const Eigen::Vector3f& t);
// A rigid frame whose z axis runs from a to b, origin at their midpoint.
Eigen::Matrix4f SegmentFrame(const Eigen::Vector3f& a, const Eigen::Vector3f& b);

// The instance record of `model` (world from mesh) drawn in `rgba` with `material`; the normal
// matrix is the inverse transpose of the model's 3x3 (the 3x3 itself when singular).
Instance MakeInstance(const Eigen::Matrix4f& model, const std::array<float, 4>& rgba,
                      const Material& material);

// Axis-aligned bounds accumulated from spheres.
struct Bounds {
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(1e30f), hi = Eigen::Vector3f::Constant(-1e30f);
  void Add(const Eigen::Vector3f& c, float r) {
    lo = lo.cwiseMin(c - Eigen::Vector3f::Constant(r));
    hi = hi.cwiseMax(c + Eigen::Vector3f::Constant(r));
  }
  bool empty() const { return lo.x() > hi.x(); }
};

// Adds the sphere enclosing `inst`: centre at its origin, radius mesh_radius times the largest
// column norm of its 3x3.
void AddInstanceBounds(Bounds* b, const Instance& inst, float mesh_radius);

}  // namespace render::internal
