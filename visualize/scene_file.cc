// Scene-file parser (see scene_json.h and README "Rendering").
#include "visualize/scene_file.h"

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>

#include "visualize/scene_builder.h"
#include "base/json_reader.h"
#include "planning/robot/mesh_io.h"
#include "topology/polyline.h"

namespace visualize {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Error helper: "<source>: <path>: <what>" (the message format of planning::JsonNode).
[[noreturn]] void Fail(const std::string& source, const std::string& path,
                       const std::string& what) {
  static const json kNull;
  base::JsonNode(kNull, source, path).Fail(what);
}

// Scene-specific reads (float vectors, colours, files, rotations) on top of planning::JsonNode,
// which does the typed, located reads.
class Reader {
 public:
  Reader(std::string source, std::string base_dir)
      : source_(std::move(source)), base_dir_(std::move(base_dir)) {}

  const std::string& source() const { return source_; }
  base::JsonNode Node(const json& j, const std::string& path) const {
    return {j, source_, path};
  }

  void ExpectObject(const json& j, const std::string& path) const {
    if (!j.is_object()) Fail(source_, path, "expected an object");
  }
  // Rejects keys outside `allowed` (catches typos such as "raduis", with a did-you-mean hint).
  void OnlyKeys(const json& j, const std::string& path,
                const std::set<std::string>& allowed) const {
    Node(j, path).CheckKeys(std::vector<std::string>(allowed.begin(), allowed.end()));
  }
  static std::string Join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }
  const json& Required(const json& obj, const std::string& path, const std::string& key) const {
    return Node(obj, path).At(key).json();
  }
  // Every scene number becomes a float: finite doubles beyond FLT_MAX are refused here.
  double Number(const json& j, const std::string& path) const { return Node(j, path).Float(); }
  double Positive(const json& j, const std::string& path) const {
    const double v = Number(j, path);
    if (!(v > 0.0)) Fail(source_, path, "expected a positive number, got " + j.dump());
    return v;
  }
  std::vector<double> Numbers(const json& j, const std::string& path, size_t n_min,
                              size_t n_max) const {
    const base::JsonNode n = Node(j, path);
    if (!j.is_array()) n.Fail("expected an array of numbers");
    if (j.size() < n_min || j.size() > n_max) {
      n.Fail("expected " +
             (n_min == n_max ? std::to_string(n_min)
                             : std::to_string(n_min) + " to " + std::to_string(n_max)) +
             " numbers, got " + std::to_string(j.size()));
    }
    std::vector<double> out;
    for (size_t i = 0; i < j.size(); ++i) out.push_back(n.At(i).Float());
    return out;
  }
  Eigen::Vector3f Vec3(const json& j, const std::string& path) const {
    const std::vector<double> v = Numbers(j, path, 3, 3);
    return Eigen::Vector3f(static_cast<float>(v[0]), static_cast<float>(v[1]),
                           static_cast<float>(v[2]));
  }
  std::array<float, 4> Color(const json& j, const std::string& path) const {
    const std::vector<double> v = Numbers(j, path, 3, 4);
    std::array<float, 4> c{1, 1, 1, 1};
    for (size_t i = 0; i < v.size(); ++i) {
      if (v[i] < 0.0 || v[i] > 1.0) {
        Fail(source_, path + "[" + std::to_string(i) + "]", "colour components must be in [0, 1]");
      }
      c[i] = static_cast<float>(v[i]);
    }
    return c;
  }
  std::string String(const json& j, const std::string& path) const {
    return Node(j, path).String();
  }
  bool Bool(const json& j, const std::string& path) const { return Node(j, path).Bool(); }
  std::string File(const json& j, const std::string& path) const {
    const std::string f = String(j, path);
    const fs::path p(f);
    return p.is_absolute() ? f : (fs::path(base_dir_) / p).string();
  }
  // Rotation from "rpy": [roll, pitch, yaw] (radians, R = Rz(yaw) Ry(pitch) Rx(roll)) or
  // "quaternion": [w, x, y, z] inside `obj`; identity when neither is present.
  Eigen::Matrix3f Rotation(const json& obj, const std::string& path) const {
    if (obj.contains("rpy") && obj.contains("quaternion")) {
      Fail(source_, path, "give either rpy or quaternion, not both");
    }
    if (obj.contains("rpy")) {
      const Eigen::Vector3f rpy = Vec3(obj.at("rpy"), Join(path, "rpy"));
      return (Eigen::AngleAxisf(rpy.z(), Eigen::Vector3f::UnitZ()) *
              Eigen::AngleAxisf(rpy.y(), Eigen::Vector3f::UnitY()) *
              Eigen::AngleAxisf(rpy.x(), Eigen::Vector3f::UnitX()))
          .toRotationMatrix();
    }
    if (obj.contains("quaternion")) {
      const std::vector<double> q = Numbers(obj.at("quaternion"), Join(path, "quaternion"), 4, 4);
      Eigen::Quaternionf quat(static_cast<float>(q[0]), static_cast<float>(q[1]),
                              static_cast<float>(q[2]), static_cast<float>(q[3]));
      // Components near the float limit: the norm overflows, so scale by the largest first.
      if (!std::isfinite(quat.norm())) quat.coeffs() /= quat.coeffs().cwiseAbs().maxCoeff();
      if (!(quat.norm() > 0.0f)) Fail(source_, Join(path, "quaternion"), "must not be zero");
      return quat.normalized().toRotationMatrix();
    }
    return Eigen::Matrix3f::Identity();
  }
  render::Material Material(const json& obj, const std::string& path) const {
    render::Material m;
    if (obj.contains("color")) m.rgba = Color(obj.at("color"), Join(path, "color"));
    if (obj.contains("specular")) {
      m.specular = static_cast<float>(Number(obj.at("specular"), Join(path, "specular")));
    }
    if (obj.contains("shininess")) {
      m.shininess = static_cast<float>(Positive(obj.at("shininess"), Join(path, "shininess")));
    }
    return m;
  }

 private:
  std::string source_, base_dir_;
};

const std::set<std::string> kMaterialKeys = {"type", "color", "specular", "shininess"};

std::set<std::string> With(std::set<std::string> keys) {
  keys.insert(kMaterialKeys.begin(), kMaterialKeys.end());
  return keys;
}

// Running totals of a scene against its limits (scene_json.h), and the meshes read so far (a file
// listed again is shared, not read again).
class SceneBudget {
 public:
  explicit SceneBudget(std::string source) : source_(std::move(source)) {}
  std::map<std::string, std::shared_ptr<const render::TriangleMesh>> meshes;
  void AddPoints(size_t n, const std::string& path) {
    points_ += n;
    if (points_ > kMaxScenePoints) {
      Fail(source_, path,
           "more than " + std::to_string(kMaxScenePoints) + " chain and line points (limit)");
    }
  }
  void AddTriangles(size_t n, const std::string& path) {
    triangles_ += n;
    if (triangles_ > kMaxSceneTriangles) {
      Fail(source_, path,
           "more than " + std::to_string(kMaxSceneTriangles) + " mesh triangles (limit)");
    }
  }

 private:
  std::string source_;
  size_t points_ = 0, triangles_ = 0;
};

void ParseShape(const Reader& r, const json& s, const std::string& path, render::Scene* scene,
                SceneBudget* budget) {
  r.ExpectObject(s, path);
  const std::string type = r.String(r.Required(s, path, "type"), Reader::Join(path, "type"));
  auto key = [&](const std::string& k) { return Reader::Join(path, k); };
  const render::Material material = r.Material(s, path);
  if (type == "sphere") {
    r.OnlyKeys(s, path, With({"center", "radius"}));
    scene->shapes.push_back(render::MakeSphere(
        r.Vec3(r.Required(s, path, "center"), key("center")),
        static_cast<float>(r.Positive(r.Required(s, path, "radius"), key("radius"))), material));
  } else if (type == "box") {
    r.OnlyKeys(s, path, With({"center", "size", "rpy", "quaternion"}));
    const Eigen::Vector3f size = r.Vec3(r.Required(s, path, "size"), key("size"));
    if (!(size.minCoeff() > 0.0f)) Fail(r.source(), key("size"), "edge lengths must be positive");
    scene->shapes.push_back(render::MakeBox(r.Vec3(r.Required(s, path, "center"), key("center")),
                                            size, material, r.Rotation(s, path)));
  } else if (type == "capsule" || type == "cylinder") {
    r.OnlyKeys(s, path, With({"from", "to", "radius"}));
    const Eigen::Vector3f a = r.Vec3(r.Required(s, path, "from"), key("from"));
    const Eigen::Vector3f b = r.Vec3(r.Required(s, path, "to"), key("to"));
    if (!((b - a).norm() > 0.0f)) Fail(r.source(), key("to"), "must differ from \"from\"");
    const auto radius =
        static_cast<float>(r.Positive(r.Required(s, path, "radius"), key("radius")));
    scene->shapes.push_back(type == "capsule" ? render::MakeCapsule(a, b, radius, material)
                                              : render::MakeCylinder(a, b, radius, material));
  } else if (type == "mesh") {
    r.OnlyKeys(s, path, With({"file", "pose", "scale"}));
    render::Shape shape;
    shape.kind = render::Shape::Kind::kMesh;
    shape.material = material;
    const std::string file = r.File(r.Required(s, path, "file"), key("file"));
    std::shared_ptr<const render::TriangleMesh>& mesh = budget->meshes[file];
    try {
      if (!mesh) mesh = ToRenderMesh(planning::LoadMesh(file));
    } catch (const std::invalid_argument& e) {
      Fail(r.source(), key("file"), e.what());
    }
    shape.mesh = mesh;
    budget->AddTriangles(shape.mesh->indices.size() / 3, key("file"));
    if (s.contains("pose")) {
      const json& pose = s.at("pose");
      r.ExpectObject(pose, key("pose"));
      r.OnlyKeys(pose, key("pose"), {"position", "rpy", "quaternion"});
      if (pose.contains("position")) {
        shape.world_from_shape.block<3, 1>(0, 3) =
            r.Vec3(pose.at("position"), key("pose.position"));
      }
      shape.world_from_shape.block<3, 3>(0, 0) = r.Rotation(pose, key("pose"));
    }
    if (s.contains("scale")) {
      const json& sc = s.at("scale");
      shape.size =
          sc.is_array()
              ? r.Vec3(sc, key("scale"))
              : Eigen::Vector3f::Constant(static_cast<float>(r.Positive(sc, key("scale"))));
    }
    scene->shapes.push_back(shape);
  } else if (type == "chain") {
    r.OnlyKeys(s, path, With({"points", "file", "radius", "bead_radius", "segment_colors"}));
    render::Tube tube;
    tube.material = material;
    if (s.contains("points") == s.contains("file")) {
      Fail(r.source(), path, "a chain needs exactly one of \"points\" or \"file\"");
    }
    if (s.contains("points")) {
      const json& pts = s.at("points");
      if (!pts.is_array()) Fail(r.source(), key("points"), "expected an array of [x, y, z]");
      budget->AddPoints(pts.size(), key("points"));
      for (size_t i = 0; i < pts.size(); ++i) {
        tube.points.push_back(r.Vec3(pts[i], key("points") + "[" + std::to_string(i) + "]"));
      }
    } else {
      const std::string file = r.File(s.at("file"), key("file"));
      const topology::Chain chain = topology::ReadChainCsv(file);
      budget->AddPoints(static_cast<size_t>(chain.cols()), key("file"));
      for (Eigen::Index i = 0; i < chain.cols(); ++i) {
        if (!(chain.col(i).cwiseAbs().maxCoeff() <= std::numeric_limits<float>::max())) {
          Fail(r.source(), key("file"),
               file + ": point " + std::to_string(i + 1) + " is too large for single precision");
        }
        tube.points.push_back(chain.col(i).cast<float>());
      }
    }
    if (tube.points.size() < 2) Fail(r.source(), path, "a chain needs at least 2 points");
    tube.radius = static_cast<float>(r.Positive(r.Required(s, path, "radius"), key("radius")));
    if (s.contains("bead_radius")) {
      tube.bead_radius = static_cast<float>(r.Positive(s.at("bead_radius"), key("bead_radius")));
    }
    if (s.contains("segment_colors")) {
      const json& cs = s.at("segment_colors");
      if (!cs.is_array() || cs.size() != tube.points.size() - 1) {
        Fail(r.source(), key("segment_colors"),
             "expected one colour per segment (" + std::to_string(tube.points.size() - 1) + ")");
      }
      for (size_t i = 0; i < cs.size(); ++i) {
        tube.segment_colors.push_back(
            r.Color(cs[i], key("segment_colors") + "[" + std::to_string(i) + "]"));
      }
    }
    scene->tubes.push_back(std::move(tube));
  } else if (type == "lines") {
    r.OnlyKeys(s, path, {"type", "points", "color", "width", "strip"});
    render::Lines lines;
    const json& pts = r.Required(s, path, "points");
    if (!pts.is_array() || pts.size() < 2) {
      Fail(r.source(), key("points"), "expected at least 2 points [x, y, z]");
    }
    budget->AddPoints(pts.size(), key("points"));
    for (size_t i = 0; i < pts.size(); ++i) {
      lines.points.push_back(r.Vec3(pts[i], key("points") + "[" + std::to_string(i) + "]"));
    }
    if (s.contains("color")) lines.rgba = r.Color(s.at("color"), key("color"));
    if (s.contains("width"))
      lines.width = static_cast<float>(r.Positive(s.at("width"), key("width")));
    if (s.contains("strip")) lines.strip = r.Bool(s.at("strip"), key("strip"));
    scene->lines.push_back(std::move(lines));
  } else {
    Fail(r.source(), key("type"),
         "unknown shape type '" + type +
             "' (expected sphere, box, capsule, cylinder, mesh, chain or lines)");
  }
}

render::Camera ParseCamera(const Reader& r, const json& c, const std::string& path) {
  r.ExpectObject(c, path);
  r.OnlyKeys(c, path, {"eye", "target", "up", "fovy_deg"});
  render::Camera cam;
  cam.eye = r.Vec3(r.Required(c, path, "eye"), path + ".eye");
  cam.target = r.Vec3(r.Required(c, path, "target"), path + ".target");
  if (c.contains("up")) cam.up = r.Vec3(c.at("up"), path + ".up");
  if (c.contains("fovy_deg")) {
    cam.fovy_deg = static_cast<float>(r.Number(c.at("fovy_deg"), path + ".fovy_deg"));
    if (!(cam.fovy_deg > 0.0f && cam.fovy_deg < 180.0f)) {
      Fail(r.source(), path + ".fovy_deg", "must be in (0, 180) degrees");
    }
  }
  if (!((cam.target - cam.eye).norm() > 0.0f)) {
    Fail(r.source(), path + ".target", "must differ from eye");
  }
  if ((cam.target - cam.eye).normalized().cross(cam.up).norm() < 1e-6f) {
    Fail(r.source(), path + ".up", "must not be parallel to the view direction");
  }
  return cam;
}

}  // namespace

render::Camera ParseCameraJson(const nlohmann::json& j, const std::string& source,
                               const std::string& path) {
  return ParseCamera(Reader(source, "."), j, path);
}

std::array<float, 4> ParseColorJson(const nlohmann::json& j, const std::string& source,
                                    const std::string& path) {
  return Reader(source, ".").Color(j, path);
}

SceneDocument ParseSceneJson(const nlohmann::json& doc, const std::string& source,
                             const std::string& base_dir) {
  const Reader r(source, base_dir);
  r.ExpectObject(doc, "");
  r.OnlyKeys(doc, "", {"camera", "background", "ambient", "size", "grid", "lights", "shapes"});
  SceneDocument out;
  if (doc.contains("camera")) {
    out.camera = ParseCamera(r, doc.at("camera"), "camera");
    out.has_camera = true;
  }
  if (doc.contains("background")) {
    const auto c = r.Color(doc.at("background"), "background");
    out.scene.background = {c[0], c[1], c[2]};
  }
  if (doc.contains("ambient")) {
    const auto c = r.Color(doc.at("ambient"), "ambient");
    out.scene.ambient = {c[0], c[1], c[2]};
  }
  if (doc.contains("size")) {
    const std::vector<double> s = r.Numbers(doc.at("size"), "size", 2, 2);
    for (int k = 0; k < 2; ++k) {
      if (s[k] < 16 || s[k] > 8192 || s[k] != std::floor(s[k])) {
        Fail(source, "size[" + std::to_string(k) + "]", "expected an integer in [16, 8192]");
      }
    }
    out.width = static_cast<int>(s[0]);
    out.height = static_cast<int>(s[1]);
  }
  if (doc.contains("grid")) {
    const json& g = doc.at("grid");
    render::Grid& grid = out.scene.grid;
    if (g.is_boolean()) {
      grid.enabled = g.get<bool>();
    } else {
      r.ExpectObject(g, "grid");
      r.OnlyKeys(g, "grid", {"center", "height", "extent", "spacing", "color", "line_color"});
      grid.enabled = true;
      if (g.contains("center")) {
        const std::vector<double> c = r.Numbers(g.at("center"), "grid.center", 2, 2);
        grid.center = Eigen::Vector2f(static_cast<float>(c[0]), static_cast<float>(c[1]));
      }
      if (g.contains("height"))
        grid.height = static_cast<float>(r.Number(g.at("height"), "grid.height"));
      if (g.contains("extent"))
        grid.extent = static_cast<float>(r.Positive(g.at("extent"), "grid.extent"));
      if (g.contains("spacing")) {
        grid.spacing = static_cast<float>(r.Positive(g.at("spacing"), "grid.spacing"));
      }
      if (g.contains("color")) grid.plane_rgba = r.Color(g.at("color"), "grid.color");
      if (g.contains("line_color")) grid.line_rgba = r.Color(g.at("line_color"), "grid.line_color");
    }
  }
  if (doc.contains("lights")) {
    const json& ls = doc.at("lights");
    if (!ls.is_array() || ls.size() > 4)
      Fail(source, "lights", "expected an array of at most 4 lights");
    for (size_t i = 0; i < ls.size(); ++i) {
      const std::string path = "lights[" + std::to_string(i) + "]";
      r.ExpectObject(ls[i], path);
      r.OnlyKeys(ls[i], path, {"direction", "color"});
      render::Light light;
      light.direction = r.Vec3(r.Required(ls[i], path, "direction"), path + ".direction");
      if (!(light.direction.norm() > 0.0f)) Fail(source, path + ".direction", "must not be zero");
      if (ls[i].contains("color")) {
        const auto c = r.Color(ls[i].at("color"), path + ".color");
        light.rgb = {c[0], c[1], c[2]};
      }
      out.scene.lights.push_back(light);
    }
  }
  if (doc.contains("shapes")) {
    const json& shapes = doc.at("shapes");
    if (!shapes.is_array()) Fail(source, "shapes", "expected an array");
    if (shapes.size() > kMaxSceneShapes) {
      Fail(source, "shapes",
           std::to_string(shapes.size()) + " shapes, more than " + std::to_string(kMaxSceneShapes) +
               " (limit)");
    }
    SceneBudget budget(source);
    for (size_t i = 0; i < shapes.size(); ++i) {
      ParseShape(r, shapes[i], "shapes[" + std::to_string(i) + "]", &out.scene, &budget);
    }
  }
  return out;
}

SceneDocument LoadSceneFile(const std::string& path) {
  if (fs::is_directory(path)) throw std::invalid_argument(path + ": cannot open scene file");
  const json doc = base::ParseJsonFile(path, "scene");
  const fs::path parent = fs::path(path).parent_path();
  return ParseSceneJson(doc, path, parent.empty() ? "." : parent.string());
}

}  // namespace visualize
