// The mesh loader (assimp). See mesh_io.h for the axis and unit conventions.
#include "planning/mesh_io.h"

#include <assimp/commonMetaData.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <filesystem>
#include <stdexcept>

namespace planning {
namespace {

// True when assimp read the file with its COLLADA importer (which has applied <unit> and turned
// <up_axis> into assimp's y-up convention).
bool IsCollada(const aiScene& scene) {
  aiString format;
  return scene.mMetaData != nullptr && scene.mMetaData->Get(AI_METADATA_SOURCE_FORMAT, format) &&
         std::string(format.C_Str()).find("Collada") != std::string::npos;
}

// assimp's y-up → our z-up: a rotation by +90° about x, (x, y, z) → (x, −z, y). Exact in floats.
Eigen::Vector3f YUpToZUp(const Eigen::Vector3f& v) { return {v.x(), -v.z(), v.y()}; }

}  // namespace

Mesh LoadMesh(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) {
    throw std::invalid_argument(path + ": mesh file not found");
  }
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_GenSmoothNormals |
                aiProcess_PreTransformVertices | aiProcess_SortByPType);
  if (!scene || !scene->mRootNode) {
    throw std::invalid_argument(path + ": cannot read mesh: " + importer.GetErrorString());
  }
  const bool y_up = IsCollada(*scene);
  Mesh mesh;
  mesh.path = path;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* am = scene->mMeshes[m];
    if (!(am->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    const int base = static_cast<int>(mesh.vertices.size());
    for (unsigned v = 0; v < am->mNumVertices; ++v) {
      Eigen::Vector3f p(am->mVertices[v].x, am->mVertices[v].y, am->mVertices[v].z);
      aiVector3D an = am->HasNormals() ? am->mNormals[v] : aiVector3D(0, 0, 1);
      if (!(an.Length() > 1e-12f)) an = aiVector3D(0, 0, 1);
      an.Normalize();
      Eigen::Vector3f n(an.x, an.y, an.z);
      if (y_up) {
        p = YUpToZUp(p);
        n = YUpToZUp(n);
      }
      mesh.vertices.push_back(p);
      mesh.normals.push_back(n);
    }
    for (unsigned f = 0; f < am->mNumFaces; ++f) {
      const aiFace& face = am->mFaces[f];
      if (face.mNumIndices != 3) continue;
      mesh.triangles.emplace_back(base + static_cast<int>(face.mIndices[0]),
                                  base + static_cast<int>(face.mIndices[1]),
                                  base + static_cast<int>(face.mIndices[2]));
    }
  }
  if (mesh.triangles.empty()) throw std::invalid_argument(path + ": mesh has no triangles");
  return mesh;
}

}  // namespace planning
