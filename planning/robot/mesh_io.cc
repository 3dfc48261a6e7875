// The mesh loader (assimp). See mesh_io.h for the axis and unit conventions.
#include "planning/robot/mesh_io.h"

#include <assimp/DefaultIOSystem.h>
#include <assimp/commonMetaData.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "base/file_read.h"
#include "planning/robot/internal/collada_check.h"
#include "planning/robot/internal/xml_text.h"

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

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

// Why the file at `path` may not be read as (part of) a mesh, or "" when it may: it must be a
// regular file (a pipe would block, a device such as /dev/zero has no end) of at most
// kMaxMeshFileBytes (checked on its size, so a huge sparse file costs nothing).
std::string Refusal(const std::string& path) {
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(st)) return "mesh file not found";
  if (!std::filesystem::is_regular_file(st)) {
    return "mesh is not a regular file (a folder, pipe or device)";
  }
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (ec) return "cannot read mesh file";
  if (bytes > kMaxMeshFileBytes) {
    return "mesh file of " + std::to_string(bytes) + " bytes is larger than " +
           std::to_string(kMaxMeshFileBytes) + " bytes (limit)";
  }
  return "";
}

// The values of every attribute `name` in XML text (name="v" or name='v', after whitespace).
std::vector<std::string> AttributeValues(const std::string& xml, const std::string& name) {
  std::vector<std::string> out;
  for (size_t at = xml.find(name + "="); at != std::string::npos;
       at = xml.find(name + "=", at + 1)) {
    if (at == 0 || !std::isspace(static_cast<unsigned char>(xml[at - 1]))) continue;
    const size_t open = at + name.size() + 1;
    if (open >= xml.size() || (xml[open] != '"' && xml[open] != '\'')) continue;
    const size_t close = xml.find(xml[open], open + 1);
    if (close == std::string::npos) break;
    out.push_back(xml.substr(open + 1, close - open - 1));
  }
  return out;
}

// A COLLADA <input>/<accessor> whose source="#id" names no element makes assimp 5.2 allocate
// gigabytes (found by fuzzing): such files are refused before assimp reads them.
void CheckColladaSources(const std::string& path) {
  const std::string xml = base::ReadFileBounded(path, "mesh", kMaxMeshFileBytes);
  internal::CheckXmlDepth(xml, path);
  // Node cycles and instance counts on the graph, before assimp expands anything.
  internal::CheckColladaStructure(xml, path, kMaxMeshTriangles);
  const std::vector<std::string> ids = AttributeValues(xml, "id");
  const std::set<std::string> known(ids.begin(), ids.end());
  for (const std::string& source : AttributeValues(xml, "source")) {
    if (source.empty() || source[0] != '#' || known.count(source.substr(1)) == 0) {
      throw std::invalid_argument(path + ": COLLADA source '" + source +
                                  "' names no element of the file");
    }
  }
}

// assimp's file access with every file checked by Refusal first: the mesh itself and the files it
// refers to (an OBJ's material library, ...), which are skipped as missing when refused.
class BoundedIOSystem : public Assimp::DefaultIOSystem {
 public:
  bool Exists(const char* file) const override { return Refusal(file).empty(); }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (std::strpbrk(mode, "wa+") != nullptr || !Refusal(file).empty()) return nullptr;
    return DefaultIOSystem::Open(file, mode);
  }
};

}  // namespace

Mesh LoadMesh(const std::string& path) {
  if (const std::string why = Refusal(path); !why.empty()) {
    throw std::invalid_argument(path + ": " + why);
  }
  // assimp picks the importer by the extension when exactly one claims it (as for these three),
  // so no other importer sees the file.
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".stl" && ext != ".obj" && ext != ".dae") {
    throw std::invalid_argument(path + ": mesh format '" + ext +
                                "' is not supported (expected .stl, .obj or .dae)");
  }
  if (ext == ".dae") CheckColladaSources(path);
  Assimp::Importer importer;
  importer.SetIOHandler(new BoundedIOSystem);  // the importer owns it
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_GenSmoothNormals |
                aiProcess_PreTransformVertices | aiProcess_SortByPType);
  if (!scene || !scene->mRootNode) {
    throw std::invalid_argument(path + ": cannot read mesh: " + importer.GetErrorString());
  }
  // The sizes of what will be copied, checked before any copy.
  std::size_t triangles = 0, vertices = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* am = scene->mMeshes[m];
    if (!(am->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    triangles += am->mNumFaces;
    vertices += am->mNumVertices;
  }
  if (triangles > kMaxMeshTriangles || vertices > kMaxMeshVertices) {
    throw std::invalid_argument(path + ": mesh of " + std::to_string(triangles) +
                                " triangles and " + std::to_string(vertices) +
                                " vertices is larger than the limit of " +
                                std::to_string(kMaxMeshTriangles) + " triangles and " +
                                std::to_string(kMaxMeshVertices) + " vertices");
  }
  const bool y_up = IsCollada(*scene);
  Mesh mesh;
  mesh.path = path;
  mesh.vertices.reserve(vertices);
  mesh.normals.reserve(vertices);
  mesh.triangles.reserve(triangles);
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* am = scene->mMeshes[m];
    if (!(am->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    const int base = static_cast<int>(mesh.vertices.size());
    for (unsigned v = 0; v < am->mNumVertices; ++v) {
      Eigen::Vector3f p(am->mVertices[v].x, am->mVertices[v].y, am->mVertices[v].z);
      if (!p.allFinite()) {
        throw std::invalid_argument(path + ": mesh vertex " + std::to_string(v) + " of mesh " +
                                    std::to_string(m) + " is not finite");
      }
      aiVector3D an = am->HasNormals() ? am->mNormals[v] : aiVector3D(0, 0, 1);
      const float length = an.Length();
      if (!(length > 1e-12f) || !std::isfinite(length)) an = aiVector3D(0, 0, 1);
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
      for (unsigned k = 0; k < 3; ++k) {
        if (face.mIndices[k] >= am->mNumVertices) {
          throw std::invalid_argument(path + ": mesh face " + std::to_string(f) + " of mesh " +
                                      std::to_string(m) + " has a vertex index out of range");
        }
      }
      mesh.triangles.emplace_back(base + static_cast<int>(face.mIndices[0]),
                                  base + static_cast<int>(face.mIndices[1]),
                                  base + static_cast<int>(face.mIndices[2]));
    }
  }
  if (mesh.triangles.empty()) throw std::invalid_argument(path + ": mesh has no triangles");
  return mesh;
}

Mesh ConvexHull(const Mesh& mesh) {
  Mesh hull;
  hull.path = mesh.path;
  if (mesh.vertices.size() < 4) return hull;
  std::vector<coordT> points;
  points.reserve(3 * mesh.vertices.size());
  for (const Eigen::Vector3f& v : mesh.vertices) {
    for (int i = 0; i < 3; ++i) points.push_back(v[i]);
  }
  // qhull reports degenerate input on its error stream: keep it quiet, the caller falls back.
  const std::unique_ptr<FILE, int (*)(FILE*)> quiet(std::fopen("/dev/null", "w"), &std::fclose);
  qhT qh_storage;
  qhT* qh = &qh_storage;
  qh_zero(qh, quiet.get());
  char options[] = "qhull Qt";  // triangulated output
  const int status = qh_new_qhull(qh, 3, static_cast<int>(mesh.vertices.size()), points.data(),
                                  False, options, nullptr, quiet.get());
  if (status == 0) {
    std::map<int, int> index;  // input point id → hull vertex
    auto vertex_of = [&](const vertexT* v) {
      const int id = qh_pointid(qh, v->point);
      auto [it, added] = index.emplace(id, static_cast<int>(hull.vertices.size()));
      if (added) hull.vertices.push_back(mesh.vertices[id]);
      return it->second;
    };
    facetT* facet;
    FORALLfacets {
      if (qh_setsize(qh, facet->vertices) != 3) continue;
      Eigen::Vector3i t(vertex_of(static_cast<vertexT*>(facet->vertices->e[0].p)),
                        vertex_of(static_cast<vertexT*>(facet->vertices->e[1].p)),
                        vertex_of(static_cast<vertexT*>(facet->vertices->e[2].p)));
      const Eigen::Vector3f a = hull.vertices[t[0]], b = hull.vertices[t[1]],
                            c = hull.vertices[t[2]];
      const Eigen::Vector3f outward(static_cast<float>(facet->normal[0]),
                                    static_cast<float>(facet->normal[1]),
                                    static_cast<float>(facet->normal[2]));
      if ((b - a).cross(c - a).dot(outward) < 0) std::swap(t[1], t[2]);
      hull.triangles.push_back(t);
    }
  }
  qh_freeqhull(qh, !qh_ALL);
  int curlong = 0, totlong = 0;
  qh_memfreeshort(qh, &curlong, &totlong);
  if (status != 0) return Mesh{mesh.path, {}, {}, {}};
  hull.normals.assign(hull.vertices.size(), Eigen::Vector3f::Zero());
  for (const Eigen::Vector3i& t : hull.triangles) {
    const Eigen::Vector3f n = (hull.vertices[t[1]] - hull.vertices[t[0]])
                                  .cross(hull.vertices[t[2]] - hull.vertices[t[0]]);
    for (int i = 0; i < 3; ++i) hull.normals[t[i]] += n;
  }
  for (Eigen::Vector3f& n : hull.normals) {
    n = n.norm() > 0 ? Eigen::Vector3f(n.normalized()) : Eigen::Vector3f::UnitZ();
  }
  return hull;
}

}  // namespace planning
