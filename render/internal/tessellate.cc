// Primitive tessellation (see tessellate.h).
#include "render/internal/tessellate.h"

#include <cmath>
#include <numbers>

namespace render::internal {
namespace {

void AddQuad(TriangleMesh* m, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
  m->indices.insert(m->indices.end(), {a, b, c, a, c, d});
}

}  // namespace

TriangleMesh UnitSphere(int slices) {
  const int stacks = slices / 2;
  TriangleMesh m;
  const float pi = std::numbers::pi_v<float>;
  // Rings of vertices from the north pole (stack 0) to the south pole (stack stacks); the
  // seam column is duplicated so every quad has its own four corners.
  for (int i = 0; i <= stacks; ++i) {
    const float theta = pi * static_cast<float>(i) / stacks;
    for (int j = 0; j <= slices; ++j) {
      const float phi = 2.0f * pi * static_cast<float>(j) / slices;
      const Eigen::Vector3f p(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                              std::cos(theta));
      m.positions.push_back(p);
      m.normals.push_back(p);
    }
  }
  const int row = slices + 1;
  for (int i = 0; i < stacks; ++i) {
    for (int j = 0; j < slices; ++j) {
      const auto a = static_cast<std::uint32_t>(i * row + j);
      const auto b = static_cast<std::uint32_t>((i + 1) * row + j);
      if (i == 0) {
        m.indices.insert(m.indices.end(), {a, b, b + 1});
      } else if (i == stacks - 1) {
        m.indices.insert(m.indices.end(), {a, b, a + 1});
      } else {
        AddQuad(&m, a, b, b + 1, a + 1);
      }
    }
  }
  return m;
}

TriangleMesh UnitCylinder(int slices) {
  TriangleMesh m;
  const float pi = std::numbers::pi_v<float>;
  // Side: two rings with radial normals.
  for (int j = 0; j <= slices; ++j) {
    const float phi = 2.0f * pi * static_cast<float>(j) / slices;
    const Eigen::Vector3f n(std::cos(phi), std::sin(phi), 0.0f);
    m.positions.push_back(n + Eigen::Vector3f(0, 0, -0.5f));
    m.normals.push_back(n);
    m.positions.push_back(n + Eigen::Vector3f(0, 0, 0.5f));
    m.normals.push_back(n);
  }
  for (int j = 0; j < slices; ++j) {
    const auto a = static_cast<std::uint32_t>(2 * j);
    AddQuad(&m, a, a + 2, a + 3, a + 1);
  }
  // Caps: a centre vertex and a ring each, flat normals.
  for (int cap = 0; cap < 2; ++cap) {
    const float z = cap == 0 ? -0.5f : 0.5f;
    const Eigen::Vector3f n(0, 0, cap == 0 ? -1.0f : 1.0f);
    const auto centre = static_cast<std::uint32_t>(m.positions.size());
    m.positions.emplace_back(0, 0, z);
    m.normals.push_back(n);
    for (int j = 0; j < slices; ++j) {
      const float phi = 2.0f * pi * static_cast<float>(j) / slices;
      m.positions.emplace_back(std::cos(phi), std::sin(phi), z);
      m.normals.push_back(n);
    }
    for (int j = 0; j < slices; ++j) {
      const std::uint32_t a = centre + 1 + static_cast<std::uint32_t>(j);
      const std::uint32_t b = centre + 1 + static_cast<std::uint32_t>((j + 1) % slices);
      if (cap == 0) {
        m.indices.insert(m.indices.end(), {centre, b, a});
      } else {
        m.indices.insert(m.indices.end(), {centre, a, b});
      }
    }
  }
  return m;
}

TriangleMesh UnitBox() {
  TriangleMesh m;
  // For each axis and sign: a face of 4 vertices, counter-clockwise seen from outside.
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign = -1; sign <= 1; sign += 2) {
      Eigen::Vector3f n = Eigen::Vector3f::Zero();
      n[axis] = static_cast<float>(sign);
      const Eigen::Vector3f u = Eigen::Vector3f::Unit((axis + 1) % 3) * static_cast<float>(sign);
      const Eigen::Vector3f v = n.cross(u);
      const auto base = static_cast<std::uint32_t>(m.positions.size());
      const Eigen::Vector3f c = 0.5f * n;
      for (const auto& [su, sv] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
        m.positions.push_back(c + 0.5f * (static_cast<float>(su) * u + static_cast<float>(sv) * v));
        m.normals.push_back(n);
      }
      AddQuad(&m, base, base + 1, base + 2, base + 3);
    }
  }
  return m;
}

TriangleMesh UnitQuad() {
  TriangleMesh m;
  m.positions = {{-0.5f, -0.5f, 0}, {0.5f, -0.5f, 0}, {0.5f, 0.5f, 0}, {-0.5f, 0.5f, 0}};
  m.normals.assign(4, Eigen::Vector3f::UnitZ());
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

TriangleMesh WithNormals(const TriangleMesh& mesh) {
  TriangleMesh m = mesh;
  if (m.normals.size() == m.positions.size()) return m;
  m.normals.assign(m.positions.size(), Eigen::Vector3f::Zero());
  for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const Eigen::Vector3f& a = m.positions[m.indices[t]];
    const Eigen::Vector3f& b = m.positions[m.indices[t + 1]];
    const Eigen::Vector3f& c = m.positions[m.indices[t + 2]];
    const Eigen::Vector3f n = (b - a).cross(c - a);  // length = 2 * area: area weighting
    for (int k = 0; k < 3; ++k) m.normals[m.indices[t + k]] += n;
  }
  for (Eigen::Vector3f& n : m.normals) {
    const float len = n.norm();
    n = len > 0 ? Eigen::Vector3f(n / len) : Eigen::Vector3f::UnitZ();
  }
  return m;
}

}  // namespace render::internal
