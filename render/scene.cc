// Shape helpers for render::Scene.
#include "render/scene.h"

#include <cmath>
#include <stdexcept>

namespace render {
namespace {

Eigen::Matrix4f FrameAlong(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  const Eigen::Vector3f d = b - a;
  if (!(d.norm() > 0.0f)) throw std::invalid_argument("capsule/cylinder: end points coincide");
  const Eigen::Vector3f z = d.normalized();
  const Eigen::Vector3f helper =
      std::abs(z.z()) < 0.9f ? Eigen::Vector3f::UnitZ() : Eigen::Vector3f::UnitX();
  const Eigen::Vector3f x = helper.cross(z).normalized();
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<3, 1>(0, 0) = x;
  m.block<3, 1>(0, 1) = z.cross(x);
  m.block<3, 1>(0, 2) = z;
  m.block<3, 1>(0, 3) = 0.5f * (a + b);
  return m;
}

}  // namespace

Material MakeMaterial(float r, float g, float b, float a) {
  Material m;
  m.rgba = {r, g, b, a};
  return m;
}

Shape MakeSphere(const Eigen::Vector3f& center, float radius, const Material& material) {
  Shape s;
  s.kind = Shape::Kind::kSphere;
  s.world_from_shape.block<3, 1>(0, 3) = center;
  s.size = Eigen::Vector3f(radius, radius, radius);
  s.material = material;
  return s;
}

Shape MakeCapsule(const Eigen::Vector3f& a, const Eigen::Vector3f& b, float radius,
                  const Material& material) {
  Shape s;
  s.kind = Shape::Kind::kCapsule;
  s.world_from_shape = FrameAlong(a, b);
  s.size = Eigen::Vector3f(radius, (b - a).norm(), 0.0f);
  s.material = material;
  return s;
}

Shape MakeCylinder(const Eigen::Vector3f& a, const Eigen::Vector3f& b, float radius,
                   const Material& material) {
  Shape s = MakeCapsule(a, b, radius, material);
  s.kind = Shape::Kind::kCylinder;
  return s;
}

Shape MakeBox(const Eigen::Vector3f& center, const Eigen::Vector3f& edge_lengths,
              const Material& material, const Eigen::Matrix3f& rotation) {
  Shape s;
  s.kind = Shape::Kind::kBox;
  s.world_from_shape.block<3, 3>(0, 0) = rotation;
  s.world_from_shape.block<3, 1>(0, 3) = center;
  s.size = edge_lengths;
  s.material = material;
  return s;
}

}  // namespace render
