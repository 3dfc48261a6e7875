// Shape helpers and mesh loading (assimp) for render::Scene.
#include "render/scene.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <filesystem>
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

void AppendNode(const aiScene* scene, const aiNode* node, const aiMatrix4x4& parent, float scale,
                TriangleMesh* out) {
  const aiMatrix4x4 world = parent * node->mTransformation;
  aiMatrix3x3 normal_matrix(world);
  normal_matrix.Inverse().Transpose();
  for (unsigned k = 0; k < node->mNumMeshes; ++k) {
    const aiMesh* mesh = scene->mMeshes[node->mMeshes[k]];
    const auto base = static_cast<std::uint32_t>(out->positions.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D p = world * mesh->mVertices[v];
      out->positions.emplace_back(scale * p.x, scale * p.y, scale * p.z);
      if (mesh->HasNormals()) {
        aiVector3D n = normal_matrix * mesh->mNormals[v];
        n.Normalize();
        out->normals.emplace_back(n.x, n.y, n.z);
      }
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines
      for (int c = 0; c < 3; ++c) out->indices.push_back(base + face.mIndices[c]);
    }
  }
  for (unsigned c = 0; c < node->mNumChildren; ++c) {
    AppendNode(scene, node->mChildren[c], world, scale, out);
  }
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

std::shared_ptr<const TriangleMesh> LoadMesh(const std::string& path, float scale) {
  if (!std::filesystem::is_regular_file(path)) {
    throw std::invalid_argument(path + ": mesh file not found");
  }
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    throw std::invalid_argument(path + ": cannot read mesh (" + importer.GetErrorString() + ")");
  }
  auto mesh = std::make_shared<TriangleMesh>();
  AppendNode(scene, scene->mRootNode, aiMatrix4x4(), scale, mesh.get());
  if (mesh->indices.empty()) throw std::invalid_argument(path + ": mesh has no triangles");
  // Normals only when every part had them; otherwise the renderer computes them.
  if (mesh->normals.size() != mesh->positions.size()) mesh->normals.clear();
  return mesh;
}

}  // namespace render
