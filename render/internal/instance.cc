// Instance records, unit-mesh placement transforms and instance bounds (see instance.h).
#include "render/internal/instance.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace render::internal {

Eigen::Matrix4f Scale(const Eigen::Vector3f& s) {
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m(0, 0) = s.x();
  m(1, 1) = s.y();
  m(2, 2) = s.z();
  return m;
}

Eigen::Matrix4f Translate(const Eigen::Vector3f& t) {
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<3, 1>(0, 3) = t;
  return m;
}

Eigen::Matrix4f SegmentFrame(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  const Eigen::Vector3f z = (b - a).normalized();
  const Eigen::Vector3f helper =
      std::abs(z.z()) < 0.9f ? Eigen::Vector3f::UnitZ() : Eigen::Vector3f::UnitX();
  const Eigen::Vector3f x = helper.cross(z).normalized();
  const Eigen::Vector3f y = z.cross(x);
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<3, 1>(0, 0) = x;
  m.block<3, 1>(0, 1) = y;
  m.block<3, 1>(0, 2) = z;
  m.block<3, 1>(0, 3) = 0.5f * (a + b);
  return m;
}

Instance MakeInstance(const Eigen::Matrix4f& model, const std::array<float, 4>& rgba,
                      const Material& material) {
  Instance inst;
  std::copy(model.data(), model.data() + 16, inst.model.begin());
  inst.color = rgba;
  inst.material = {material.specular, material.shininess, 0.0f, 0.0f};
  const Eigen::Matrix3f linear = model.block<3, 3>(0, 0);
  const float det = linear.determinant();
  const Eigen::Matrix3f normal =
      std::abs(det) > 0.0f ? Eigen::Matrix3f(linear.inverse().transpose()) : linear;
  std::copy(normal.data(), normal.data() + 9, inst.normal.begin());
  return inst;
}

void AddInstanceBounds(Bounds* b, const Instance& inst, float mesh_radius) {
  const Eigen::Map<const Eigen::Matrix4f> m(inst.model.data());
  const float scale =
      std::max({m.col(0).head<3>().norm(), m.col(1).head<3>().norm(), m.col(2).head<3>().norm()});
  b->Add(m.block<3, 1>(0, 3), scale * mesh_radius);
}

}  // namespace render::internal
