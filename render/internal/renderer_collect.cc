// Scene -> instances for one frame of the scene renderer (see renderer_impl.h): every shape, tube
// segment and bead becomes an instance of a unit mesh (spheres and cylinders at the level of
// detail of their projected radius) or of a cached user mesh, batched per mesh when opaque and
// listed one by one when translucent (alpha < 1).
#include <Eigen/LU>
#include <algorithm>
#include <vector>

#include "render/internal/renderer_impl.h"
#include "render/internal/tessellate.h"

namespace render {

using internal::Scale;
using internal::Translate;

void Renderer::Impl::Collect(const Scene& scene) {
  for (Batch& batch : opaque_) batch.items.clear();
  translucent_.clear();
  for (const Shape& s : scene.shapes) CollectShape(s);
  for (const Tube& t : scene.tubes) CollectTube(t);
  // Batches unused this frame may point at meshes dropped from the cache: forget them.
  std::erase_if(opaque_, [](const Batch& batch) { return batch.items.empty(); });
}

void Renderer::Impl::CollectShape(const Shape& s) {
  const Eigen::Matrix4f& w = s.world_from_shape;
  const std::array<float, 4>& rgba = s.material.rgba;
  switch (s.kind) {
    case Shape::Kind::kSphere: {
      const Eigen::Matrix4f m = w * Scale(Eigen::Vector3f::Constant(s.size.x()));
      Add(SphereAt(m), m, rgba, s.material);
    } break;
    case Shape::Kind::kCapsule: {
      const float r = s.size.x(), len = s.size.y();
      if (len > 0.0f) {
        const Eigen::Matrix4f m = w * Scale(Eigen::Vector3f(r, r, len));
        Add(CylinderAt(m), m, rgba, s.material);
      }
      for (float z : {-0.5f * len, 0.5f * len}) {
        const Eigen::Matrix4f m =
            w * Translate(Eigen::Vector3f(0, 0, z)) * Scale(Eigen::Vector3f::Constant(r));
        Add(SphereAt(m), m, rgba, s.material);
      }
      break;
    }
    case Shape::Kind::kCylinder: {
      const Eigen::Matrix4f m = w * Scale(Eigen::Vector3f(s.size.x(), s.size.x(), s.size.y()));
      Add(CylinderAt(m), m, rgba, s.material);
    } break;
    case Shape::Kind::kBox:
      Add(&box_, w * Scale(s.size), rgba, s.material);
      break;
    case Shape::Kind::kMesh:
      if (s.mesh && !s.mesh->indices.empty()) {
        Add(MeshFor(s.mesh), w * Scale(s.size), rgba, s.material);
      }
      break;
  }
}

void Renderer::Impl::CollectTube(const Tube& t) {
  const size_t n = t.points.size();
  const bool per_segment = !t.segment_colors.empty() && t.segment_colors.size() + 1 >= n;
  auto colour = [&](size_t seg) {
    return per_segment ? t.segment_colors[std::min(seg, t.segment_colors.size() - 1)]
                       : t.material.rgba;
  };
  for (size_t i = 0; i + 1 < n; ++i) {
    const Eigen::Vector3f& a = t.points[i];
    const Eigen::Vector3f& b = t.points[i + 1];
    const float len = (b - a).norm();
    if (!(len > 0.0f)) continue;
    const Eigen::Matrix4f m =
        internal::SegmentFrame(a, b) * Scale(Eigen::Vector3f(t.radius, t.radius, len));
    Add(CylinderAt(m), m, colour(i), t.material);
  }
  const float bead = t.bead_radius > 0.0f ? t.bead_radius : t.radius;
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Matrix4f m = Translate(t.points[i]) * Scale(Eigen::Vector3f::Constant(bead));
    Add(SphereAt(m), m, colour(i == 0 ? 0 : (i + 1 < n ? i : i - 1)), t.material);
  }
}

void Renderer::Impl::Add(const GpuMesh* mesh, const Eigen::Matrix4f& model,
                         const std::array<float, 4>& rgba, const Material& material) {
  const Instance inst = internal::MakeInstance(model, rgba, material);
  if (rgba[3] < 1.0f) {
    translucent_.emplace_back(mesh, inst);
    return;
  }
  // A mirroring placement turns the mesh inside out (clockwise outside): draw it unculled.
  const bool cull = mesh->closed && model.block<3, 3>(0, 0).determinant() > 0.0f;
  for (Batch& batch : opaque_) {
    if (batch.mesh == mesh && batch.cull == cull) {
      batch.items.push_back(inst);
      return;
    }
  }
  opaque_.push_back(Batch{mesh, cull, {inst}});
}

int Renderer::Impl::Lod(const Eigen::Vector3f& centre, float radius) const {
  const float depth = std::max((centre - lod_eye_).dot(lod_forward_), 1e-6f);
  const float px = focal_px_ * radius / depth;
  return px < internal::kLodMaxRadiusPx[0] ? 0 : (px < internal::kLodMaxRadiusPx[1] ? 1 : 2);
}

const internal::GpuMesh* Renderer::Impl::SphereAt(const Eigen::Matrix4f& model) const {
  const float r = std::max({model.col(0).head<3>().norm(), model.col(1).head<3>().norm(),
                            model.col(2).head<3>().norm()});
  return &sphere_[Lod(model.block<3, 1>(0, 3), r)];
}

const internal::GpuMesh* Renderer::Impl::CylinderAt(const Eigen::Matrix4f& model) const {
  const float r = std::max(model.col(0).head<3>().norm(), model.col(1).head<3>().norm());
  return &cylinder_[Lod(model.block<3, 1>(0, 3), r)];
}

}  // namespace render
