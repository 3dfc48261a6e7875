// planning state → render::Scene.
#include "visualize/scene_builder.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/assets.h"
#include "base/json_reader.h"

namespace visualize {
namespace {

render::Material ToMaterial(const std::array<float, 4>& rgba) {
  render::Material m;
  m.rgba = rgba;
  return m;
}

Eigen::Matrix4f ToMatrix(const Eigen::Isometry3d& t) { return t.matrix().cast<float>(); }

std::shared_ptr<const render::TriangleMesh> ConvertMesh(const planning::Mesh& mesh,
                                                        SceneMeshCache* cache) {
  auto it = cache->meshes.find(&mesh);
  if (it != cache->meshes.end()) return it->second;
  return cache->meshes[&mesh] = ToRenderMesh(mesh);
}

render::Shape ToShape(const planning::Robot& model, const planning::Geometry& g,
                      const Eigen::Isometry3d& world_from_geometry,
                      const std::array<float, 4>& rgba, SceneMeshCache* cache) {
  render::Shape s;
  s.world_from_shape = ToMatrix(world_from_geometry);
  s.material = ToMaterial(rgba);
  const Eigen::Vector3f size = g.size.cast<float>();
  switch (g.kind) {
    case planning::Geometry::Kind::kSphere:
      s.kind = render::Shape::Kind::kSphere;
      s.size = Eigen::Vector3f(size.x(), 0, 0);
      break;
    case planning::Geometry::Kind::kCapsule:
      s.kind = render::Shape::Kind::kCapsule;
      s.size = Eigen::Vector3f(size.x(), size.y(), 0);
      break;
    case planning::Geometry::Kind::kCylinder:
      s.kind = render::Shape::Kind::kCylinder;
      s.size = Eigen::Vector3f(size.x(), size.y(), 0);
      break;
    case planning::Geometry::Kind::kBox:
      s.kind = render::Shape::Kind::kBox;
      s.size = size;
      break;
    case planning::Geometry::Kind::kMesh:
      s.kind = render::Shape::Kind::kMesh;
      s.size = size;
      s.mesh = ConvertMesh(model.meshes.at(g.mesh), cache);
      break;
  }
  return s;
}

// Distinct, saturated colours for chains (cycled).
std::array<float, 4> ChainColor(int k) {
  static const std::array<float, 4> kColors[] = {
      {0.10f, 0.75f, 0.25f, 1}, {0.95f, 0.20f, 0.55f, 1}, {0.15f, 0.55f, 0.95f, 1},
      {0.95f, 0.75f, 0.10f, 1}, {0.55f, 0.25f, 0.85f, 1}, {0.10f, 0.80f, 0.80f, 1}};
  return kColors[k % 6];
}

void AddTube(const Eigen::Matrix3Xd& points, const std::array<float, 4>& rgba, float radius,
             render::Scene* scene) {
  render::Tube tube;
  for (Eigen::Index k = 0; k < points.cols(); ++k)
    tube.points.push_back(points.col(k).cast<float>());
  tube.radius = radius;
  tube.bead_radius = 1.6f * radius;
  tube.material = ToMaterial(rgba);
  scene->tubes.push_back(std::move(tube));
}

void AddModel(const planning::Robot& model, const planning::KinematicsData& kin,
              const Eigen::Isometry3d& world_from_model, const SceneBuildOptions& options,
              SceneMeshCache* cache, render::Scene* scene) {
  const std::array<float, 4> kCollisionColor{0.45f, 0.6f, 0.85f, 1.0f};
  for (size_t l = 0; l < model.links.size(); ++l) {
    const Eigen::Isometry3d world_from_link = world_from_model * kin.world_from_link[l];
    const auto& geoms = options.visuals ? model.links[l].visuals : model.links[l].collisions;
    for (const planning::Geometry& g : geoms) {
      scene->shapes.push_back(ToShape(model, g, world_from_link * g.link_from_geometry,
                                      options.visuals ? g.rgba : kCollisionColor, cache));
    }
  }
}

// Scene extent: the diagonal of the bounding box of shape origins, at least 0.3 m.
float SceneSize(const render::Scene& scene) {
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::max());
  Eigen::Vector3f hi = -lo;
  for (const render::Shape& s : scene.shapes) {
    const Eigen::Vector3f p = s.world_from_shape.block<3, 1>(0, 3);
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return scene.shapes.empty() ? 1.0f : std::max(0.3f, (hi - lo).norm());
}

void AddChains(const planning::Robot& model, const planning::KinematicsData& kin,
               const Eigen::Isometry3d& world_from_model, float radius, int* color,
               render::Scene* scene) {
  Eigen::Matrix3Xd p;
  for (int c = 0; c < static_cast<int>(model.chains.size()); ++c) {
    planning::ChainPoints(model, kin, c, &p);
    for (Eigen::Index k = 0; k < p.cols(); ++k) p.col(k) = world_from_model * p.col(k);
    AddTube(p, ChainColor((*color)++), radius, scene);
  }
}

}  // namespace

std::shared_ptr<const render::TriangleMesh> ToRenderMesh(const planning::Mesh& mesh) {
  auto out = std::make_shared<render::TriangleMesh>();
  out->positions = mesh.vertices;
  out->normals = mesh.normals;
  out->indices.reserve(mesh.triangles.size() * 3);
  for (const Eigen::Vector3i& t : mesh.triangles) {
    for (int i = 0; i < 3; ++i) out->indices.push_back(static_cast<std::uint32_t>(t[i]));
  }
  return out;
}

void AddRobotShapes(const planning::Robot& robot, const planning::KinematicsData& kin,
                    const Eigen::Isometry3d& world_from_robot, const SceneBuildOptions& options,
                    SceneMeshCache* cache, render::Scene* scene) {
  int color = 0;
  AddModel(robot, kin, world_from_robot, options, cache, scene);
  if (options.chains) {
    const float r = options.chain_radius > 0 ? options.chain_radius : 0.004f;
    AddChains(robot, kin, world_from_robot, r, &color, scene);
  }
}

void AddEnvironmentShapes(const planning::Environment& env, const SceneBuildOptions& options,
                          SceneMeshCache* cache, render::Scene* scene) {
  int color = 3;
  for (const planning::PlacedObject& o : env.objects) {
    planning::KinematicsData kin(o.model);
    planning::ForwardKinematics(o.model, Eigen::VectorXd::Zero(planning::num_dofs(o.model)), &kin);
    AddModel(o.model, kin, o.world_from_object, options, cache, scene);
    if (options.chains) {
      const float r = options.chain_radius > 0 ? options.chain_radius : 0.004f;
      AddChains(o.model, kin, o.world_from_object, r, &color, scene);
    }
  }
}

render::Scene BuildRobotScene(const planning::Robot& robot, const planning::KinematicsData& kin,
                              const planning::Environment& env, const SceneBuildOptions& options,
                              SceneMeshCache* cache) {
  render::Scene scene;
  SceneBuildOptions local = options;
  local.chains = false;
  AddRobotShapes(robot, kin, Eigen::Isometry3d::Identity(), local, cache, &scene);
  if (options.objects) AddEnvironmentShapes(env, local, cache, &scene);
  // Chains last, with a radius that scales with the scene so they stay visible.
  if (options.chains) {
    const float r = options.chain_radius > 0 ? options.chain_radius : 0.004f * SceneSize(scene);
    int color = 0;
    AddChains(robot, kin, Eigen::Isometry3d::Identity(), std::min(r, 0.012f), &color, &scene);
    if (options.objects) {
      for (const planning::PlacedObject& o : env.objects) {
        planning::KinematicsData okin(o.model);
        planning::ForwardKinematics(o.model, Eigen::VectorXd::Zero(planning::num_dofs(o.model)),
                                    &okin);
        AddChains(o.model, okin, o.world_from_object, std::min(r, 0.012f), &color, &scene);
      }
    }
  }
  if (options.grid) {
    scene.grid.enabled = true;
    const float size = SceneSize(scene);
    scene.grid.extent = std::max(1.0f, 2.0f * size);
    scene.grid.spacing = size > 2.0f ? 0.5f : (size > 0.6f ? 0.1f : 0.05f);
  }
  return scene;
}

namespace {

// Calls grow(p, r) for points p whose balls of radius r cover every shape and tube of `scene`.
template <typename Grow>
void ForEachBoundPoint(const render::Scene& scene, Grow grow) {
  for (const render::Shape& s : scene.shapes) {
    const Eigen::Matrix3f R = s.world_from_shape.block<3, 3>(0, 0);
    const Eigen::Vector3f t = s.world_from_shape.block<3, 1>(0, 3);
    switch (s.kind) {
      case render::Shape::Kind::kSphere:
        grow(t, s.size.x());
        break;
      case render::Shape::Kind::kCapsule:
      case render::Shape::Kind::kCylinder: {
        const Eigen::Vector3f half = R.col(2) * (0.5f * s.size.y());
        grow(t + half, s.size.x());
        grow(t - half, s.size.x());
        break;
      }
      case render::Shape::Kind::kBox:
        for (int c = 0; c < 8; ++c) {
          const Eigen::Vector3f corner(c & 1 ? 0.5f : -0.5f, c & 2 ? 0.5f : -0.5f,
                                       c & 4 ? 0.5f : -0.5f);
          grow(t + R * corner.cwiseProduct(s.size), 0.0f);
        }
        break;
      case render::Shape::Kind::kMesh:
        if (s.mesh) {
          for (const Eigen::Vector3f& v : s.mesh->positions)
            grow(t + R * v.cwiseProduct(s.size), 0);
        }
        break;
    }
  }
  for (const render::Tube& t : scene.tubes) {
    for (const Eigen::Vector3f& p : t.points) grow(p, t.radius);
  }
}

// Unit vectors of a camera looking along -back with +z up: right and up.
void ViewAxes(const Eigen::Vector3f& back, Eigen::Vector3f* right, Eigen::Vector3f* up) {
  *right = (-back).cross(Eigen::Vector3f::UnitZ()).normalized();
  *up = right->cross(-back);
}

}  // namespace

render::Camera FrameSceneCamera(const render::Scene& scene, const Eigen::Vector3f& view_dir,
                                float fovy_deg) {
  // World AABB of every shape and tube.
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::max());
  Eigen::Vector3f hi = -lo;
  ForEachBoundPoint(scene, [&](const Eigen::Vector3f& p, float r) {
    lo = lo.cwiseMin(p - Eigen::Vector3f::Constant(r));
    hi = hi.cwiseMax(p + Eigen::Vector3f::Constant(r));
  });
  render::Camera camera;
  if (!(lo.x() <= hi.x())) return camera;
  // Distance at which every AABB corner fits the vertical and (4:3) horizontal field of view.
  const Eigen::Vector3f center = 0.5f * (lo + hi);
  const Eigen::Vector3f back = view_dir.normalized();  // target → eye
  Eigen::Vector3f right, up;
  ViewAxes(back, &right, &up);
  const float tan_v = std::tan(0.5f * fovy_deg * static_cast<float>(M_PI) / 180.0f);
  const float tan_h = tan_v * 4.0f / 3.0f;
  float distance = 0.1f;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3f corner((c & 1 ? hi : lo).x(), (c & 2 ? hi : lo).y(),
                                 (c & 4 ? hi : lo).z());
    const Eigen::Vector3f d = corner - center;
    const float along = d.dot(back);  // towards the eye: closer to the camera
    distance = std::max(distance, std::abs(d.dot(up)) / tan_v + along);
    distance = std::max(distance, std::abs(d.dot(right)) / tan_h + along);
  }
  camera.target = center;
  camera.eye = center + 1.05f * distance * back;
  camera.fovy_deg = fovy_deg;
  return camera;
}

render::Camera FitSceneCamera(const render::Scene& scene, const Eigen::Vector3f& view_dir,
                              float fovy_deg, float aspect, float fill) {
  const Eigen::Vector3f back = view_dir.normalized();
  Eigen::Vector3f right, up;
  ViewAxes(back, &right, &up);
  // Extents of the bounding balls along the view axes (right, up, back).
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::max());
  Eigen::Vector3f hi = -lo;
  std::vector<Eigen::Vector4f> balls;  // (right, up, back coordinates, radius)
  ForEachBoundPoint(scene, [&](const Eigen::Vector3f& p, float r) {
    const Eigen::Vector3f c(p.dot(right), p.dot(up), p.dot(back));
    lo = lo.cwiseMin(c - Eigen::Vector3f::Constant(r));
    hi = hi.cwiseMax(c + Eigen::Vector3f::Constant(r));
    balls.emplace_back(c.x(), c.y(), c.z(), r);
  });
  render::Camera camera;
  if (balls.empty()) return camera;
  const Eigen::Vector3f mid = 0.5f * (lo + hi);
  const float tan_v =
      std::clamp(fill, 0.1f, 1.0f) * std::tan(0.5f * fovy_deg * static_cast<float>(M_PI) / 180.0f);
  const float tan_h = tan_v * std::max(aspect, 0.1f);
  // Each ball must fit at its depth: |offset| + r <= tan · (distance − along − r).
  float distance = 0.1f;
  for (const Eigen::Vector4f& b : balls) {
    const float along = b.z() - mid.z() + b.w();
    distance = std::max(distance, (std::abs(b.y() - mid.y()) + b.w()) / tan_v + along);
    distance = std::max(distance, (std::abs(b.x() - mid.x()) + b.w()) / tan_h + along);
  }
  camera.target = mid.x() * right + mid.y() * up + mid.z() * back;
  camera.eye = camera.target + distance * back;
  camera.fovy_deg = fovy_deg;
  return camera;
}

void AddTaskBoxes(const planning::ScenarioSpec& spec, render::Scene* scene) {
  constexpr std::array<float, 4> kEdge{0.85f, 0.45f, 0.05f, 1.0f};
  for (const planning::TaskSpec& task : spec.tasks) {
    if (task.feature.type != planning::FeatureType::kBox) continue;
    const Eigen::Vector3f c = task.feature.center.cast<float>();
    const Eigen::Vector3f h = task.feature.half_extent.cast<float>();
    scene->shapes.push_back(
        render::MakeBox(c, 2.0f * h, render::MakeMaterial(0.95f, 0.6f, 0.15f, 0.18f)));
    render::Lines edges;
    edges.strip = false;
    edges.width = 2.0f;
    edges.rgba = kEdge;
    for (int a = 0; a < 3; ++a) {  // 4 edges along each axis a
      for (int k = 0; k < 4; ++k) {
        Eigen::Vector3f p = c, q = c;
        const int b = (a + 1) % 3, d = (a + 2) % 3;
        p[a] -= h[a];
        q[a] += h[a];
        p[b] = q[b] = c[b] + (k & 1 ? h[b] : -h[b]);
        p[d] = q[d] = c[d] + (k & 2 ? h[d] : -h[d]);
        edges.points.push_back(p);
        edges.points.push_back(q);
      }
    }
    scene->lines.push_back(std::move(edges));
  }
}

SceneDocument RobotSceneDocument(const std::string& path, const std::string& q_text,
                                 const SceneBuildOptions& options) {
  return RobotSceneDocument(path, q_text, "", planning::RobotInputOptions{}, options);
}

SceneDocument RobotSceneDocument(const std::string& path, const std::string& q_text,
                                 const std::string& pose, const planning::RobotInputOptions& input,
                                 const SceneBuildOptions& options) {
  planning::RobotScene rs = planning::LoadRobotScene(path, input);
  std::vector<std::string> warnings = rs.warnings;
  rs.q = planning::ChooseQ(rs, q_text, pose, &warnings);
  planning::KinematicsData kin(rs.robot);
  planning::ForwardKinematics(rs.robot, rs.q, &kin);
  SceneMeshCache cache;
  SceneDocument doc;
  doc.warnings = std::move(warnings);
  doc.scene = BuildRobotScene(rs.robot, kin, rs.env, options, &cache);
  // A planning scenario: its "box" tasks, as plan frames and the viewer draw them.
  if (rs.document.is_object() && rs.document.contains("tasks")) {
    planning::ScenarioSpec spec = planning::ParseScenarioSpec(path, {base::AssetRoot()});
    planning::ResolveSpecFrames(&spec);  // box centres given in an object's frame
    AddTaskBoxes(spec, &doc.scene);
  }
  doc.camera = FrameSceneCamera(doc.scene);
  if (rs.document.is_object() && rs.document.contains("camera")) {
    doc.camera = ParseCameraJson(rs.document["camera"], path, "camera");
    doc.has_camera = true;
  }
  if (rs.document.is_object() && rs.document.contains("size")) {
    const base::JsonNode s(rs.document["size"], path, "size");
    if (!s.IsArray() || s.Size() != 2) s.Fail("expected [width, height]");
    doc.width = static_cast<int>(s.At(size_t{0}).Integer(16, 8192));
    doc.height = static_cast<int>(s.At(size_t{1}).Integer(16, 8192));
  }
  return doc;
}

}  // namespace visualize
