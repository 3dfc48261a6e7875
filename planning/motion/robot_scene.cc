// Loading robots and scene JSON files for the robot commands and the renderer glue.
#include "planning/motion/robot_scene.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <locale>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "base/assets.h"
#include "base/file_read.h"
#include "base/json_reader.h"
#include "base/numbers.h"
#include "planning/motion/scenario.h"
#include "planning/robot/robot_io.h"

namespace planning {
namespace {

namespace fs = std::filesystem;

std::string Ext(const std::string& path) {
  std::string e = fs::path(path).extension().string();
  for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

// A file named in a scene: relative to the scene's folder first, then to the asset root.
std::string ResolveRelative(const std::string& name, const fs::path& base_dir) {
  const fs::path p(name);
  if (p.is_absolute()) return name;
  if (fs::exists(base_dir / p)) return (base_dir / p).string();
  const fs::path asset = fs::path(base::AssetRoot()) / p;
  if (fs::exists(asset)) return asset.string();
  return (base_dir / p).string();  // the loader reports it as missing
}

Eigen::Vector3d Vec3(const nlohmann::json& j, const std::string& src, const std::string& path) {
  if (!j.is_array() || j.size() != 3) {
    throw std::invalid_argument(src + ": " + path + ": expected [x, y, z]");
  }
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) {
    if (!j[i].is_number() || !std::isfinite(j[i].get<double>())) {
      throw std::invalid_argument(src + ": " + path + "[" + std::to_string(i) +
                                  "]: expected a finite number");
    }
    v[i] = j[i].get<double>();
  }
  return v;
}

Eigen::Isometry3d Pose(const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = xyz;
  t.linear() = (Eigen::AngleAxisd(rpy[2], Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(rpy[1], Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(rpy[0], Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return t;
}

}  // namespace

std::vector<std::string> PackagePaths(const std::vector<std::string>& extra) {
  std::vector<std::string> out = extra;
  if (const char* env = std::getenv("ROS_PACKAGE_PATH")) {
    std::stringstream ss(env);
    ss.imbue(std::locale::classic());  // "0.5" whatever the global locale
    std::string item;
    while (std::getline(ss, item, ':')) {
      if (!item.empty()) out.push_back(item);
    }
  }
  // ROS 2 installs packages as PREFIX/share/NAME (ament).
  if (const char* env = std::getenv("AMENT_PREFIX_PATH")) {
    std::stringstream ss(env);
    std::string item;
    while (std::getline(ss, item, ':')) {
      if (!item.empty()) out.push_back((fs::path(item) / "share").string());
    }
  }
  return out;
}

bool IsRobotSceneFile(const std::string& path) {
  const std::string ext = Ext(path);
  if (ext == ".urdf") return true;
  if (ext != ".json") return false;
  // Bounded like every reader; a file that cannot be read is not a robot scene (the scene loader
  // then names the problem).
  std::string text;
  try {
    text = base::ReadFileBounded(path, "scene");
  } catch (const std::invalid_argument&) {
    return false;
  }
  const nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
  return doc.is_object() && doc.contains("robot");
}

Eigen::VectorXd ParseQ(const Robot& robot, const std::string& text,
                       std::vector<std::string>* warnings) {
  const int n = num_dofs(robot);
  if (text.empty()) return Eigen::VectorXd::Zero(n);
  std::vector<double> v;
  try {
    v = base::ParseNumberList(text, "--q", n);
  } catch (const std::invalid_argument& e) {
    std::string names;
    for (const std::string& s : DofNames(robot)) names += (names.empty() ? "" : ",") + s;
    throw std::invalid_argument(std::string(e.what()) + " (robot '" + robot.name + "' takes " +
                                std::to_string(n) + " values: " + names + ")");
  }
  const Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXd>(v.data(), n);
  CheckJointValues(robot, q, "--q", warnings);
  return q;
}

void CheckJointValues(const Robot& robot, const Eigen::VectorXd& q, const std::string& where,
                      std::vector<std::string>* warnings) {
  const Eigen::VectorXd lo = LowerLimits(robot), hi = UpperLimits(robot);
  const std::vector<std::string> names = DofNames(robot);
  for (Eigen::Index k = 0; k < q.size(); ++k) {
    const std::string at = where + "[" + std::to_string(k) + "] (" + names[k] + ")";
    if (!std::isfinite(q[k]) || std::fabs(q[k]) > kMaxJointValue) {
      throw std::invalid_argument(at + ": " + base::FormatShortest(q[k]) +
                                  " is not a joint value (|q| <= 1e6)");
    }
    // A small tolerance keeps values printed at limited precision (e.g. 1.5708) usable.
    if (q[k] < lo[k] - 1e-6 || q[k] > hi[k] + 1e-6) {
      const std::string what = at + ": " + base::FormatShortest(q[k]) +
                               " is outside the joint limits [" + base::FormatShortest(lo[k]) +
                               ", " + base::FormatShortest(hi[k]) + "]";
      if (warnings == nullptr) throw std::invalid_argument(what);
      warnings->push_back(what);
    }
  }
}

void AddObjectSpec(const std::string& spec, RobotScene* scene) {
  const size_t at = spec.find('@');
  const std::string file = spec.substr(0, at);
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero(), rpy = Eigen::Vector3d::Zero();
  if (at != std::string::npos) {
    const std::vector<double> v = base::ParseNumberList(spec.substr(at + 1), "--object");
    if (v.size() != 3 && v.size() != 6) {
      throw std::invalid_argument("--object '" + spec + "': expected URDF@x,y,z[,roll,pitch,yaw]");
    }
    xyz = Eigen::Vector3d(v[0], v[1], v[2]);
    if (v.size() == 6) rpy = Eigen::Vector3d(v[3], v[4], v[5]);
  }
  const std::string path = ResolveRelative(file, fs::current_path());
  const Robot object = LoadRobot(path);
  std::string name = object.name;
  for (int k = 2; [&] {
         for (const auto& o : scene->env.objects) {
           if (o.name == name) return true;
         }
         return false;
       }();
       ++k) {
    name = object.name + "_" + std::to_string(k);
  }
  AddObject(object, Pose(xyz, rpy), name, &scene->env);
  scene->collides.push_back(true);
  if (scene->has_collision_env) {
    AddObject(object, Pose(xyz, rpy), name, &scene->collision_env);
  }
}

Environment CollisionEnvironment(const RobotScene& scene) {
  if (scene.has_collision_env) return scene.collision_env;
  Environment env;
  for (size_t i = 0; i < scene.env.objects.size(); ++i) {
    if (i >= scene.collides.size() || scene.collides[i])
      env.objects.push_back(scene.env.objects[i]);
  }
  return env;
}

namespace {

// Loads the SRDF at `srdf_path` (if not empty) for scene.robot and disables its pairs.
void AttachSrdf(const std::string& srdf_path, RobotScene* s) {
  if (srdf_path.empty()) return;
  s->srdf = LoadSrdf(srdf_path);
  const std::vector<std::string> base_warnings = ApplySrdfBase(*s->srdf, &s->robot);
  s->warnings.insert(s->warnings.end(), base_warnings.begin(), base_warnings.end());
  const std::vector<std::string> warnings = CheckSrdf(*s->srdf, s->robot);
  s->warnings.insert(s->warnings.end(), warnings.begin(), warnings.end());
  for (const auto& pair : DisabledPairs(*s->srdf, &s->robot)) {
    s->collision_options.disabled_pairs.push_back(pair);
  }
}

// Paths of a scene's "package_paths", relative to its folder.
std::vector<std::string> ScenePackagePaths(const nlohmann::json& doc, const std::string& path,
                                           const fs::path& base) {
  std::vector<std::string> out;
  if (!doc.contains("package_paths")) return out;
  const nlohmann::json& pp = doc["package_paths"];
  if (!pp.is_array()) throw std::invalid_argument(path + ": package_paths: expected an array");
  for (size_t i = 0; i < pp.size(); ++i) {
    if (!pp[i].is_string()) {
      throw std::invalid_argument(path + ": package_paths[" + std::to_string(i) +
                                  "]: expected a folder (string)");
    }
    const fs::path p(pp[i].get<std::string>());
    out.push_back(p.is_absolute() ? p.string() : (base / p).string());
  }
  return out;
}

RobotScene LoadRobotSceneImpl(const std::string& path, const std::vector<std::string>& flag_paths,
                              const std::string& srdf_flag, bool add_ros_paths) {
  RobotLoadOptions options;
  options.package_paths = add_ros_paths ? PackagePaths(flag_paths) : flag_paths;
  RobotScene s;
  s.source = path;
  const std::string ext = Ext(path);
  if (ext == ".urdf") {
    s.robot = LoadRobot(path, options);
    s.warnings = s.robot.warnings;
    s.q = Eigen::VectorXd::Zero(num_dofs(s.robot));
    const std::string srdf = srdf_flag.empty() ? FindSrdf(path, s.robot.name) : srdf_flag;
    if (srdf.empty()) {
      std::string note = "no SRDF found for robot '";
      note.append(s.robot.name).append("' (looked for ");
      note.append(fs::path(path).stem().string()).append(".srdf, ").append(s.robot.name);
      note.append(".srdf or an SRDF naming the robot next to the URDF and in ../srdf/); ");
      note.append("--srdf FILE gives one (disabled pairs, named poses)");
      s.notes.push_back(note);
    }
    AttachSrdf(srdf, &s);
    return s;
  }
  if (ext != ".json") {
    throw std::invalid_argument(path + ": expected a robot .urdf or a scene .json");
  }
  s.document = base::ParseJsonFile(path, "scene");
  const nlohmann::json& doc = s.document;
  const fs::path base = fs::path(path).parent_path();
  if (doc.is_object() && doc.contains("robot") && doc.contains("tasks")) {
    // A planning scenario: its own loader decides the start configuration and the collision set.
    ScenarioOverrides overrides;
    overrides.search_roots = {base::AssetRoot()};
    overrides.package_paths = options.package_paths;
    overrides.srdf = srdf_flag;
    const std::unique_ptr<const Scenario> sc = LoadScenarioArg(path, overrides);
    s.robot = sc->robot;
    s.warnings = sc->warnings;
    s.q = sc->initial.problem.q0;
    s.q_given = true;
    s.env = sc->initial.objects;
    s.collides.assign(s.env.objects.size(), true);
    s.has_collision_env = true;
    s.collision_env = sc->initial.env;
    s.collision_options = sc->collision;  // SRDF pairs included
    const std::string srdf = !srdf_flag.empty()       ? srdf_flag
                             : !sc->spec.srdf.empty() ? sc->spec.srdf
                                                      : FindSrdf(sc->spec.robot);
    if (!srdf.empty()) s.srdf = LoadSrdf(srdf);
    return s;
  }
  if (!doc.is_object() || !doc.contains("robot") || !doc["robot"].is_string()) {
    throw std::invalid_argument(path + ": robot: expected a URDF path (string)");
  }
  // Every key is known: a misspelt one ("postion") would otherwise be ignored silently and change
  // the scene (the object at the origin).
  const base::JsonNode root(doc, path);
  root.CheckKeys({"robot", "q", "base", "srdf", "package_paths", "objects", "camera", "size"});
  if (doc.contains("objects") && doc["objects"].is_array()) {
    for (size_t i = 0; i < doc["objects"].size(); ++i) {
      const base::JsonNode o = root.At("objects").At(i);
      if (o.IsObject()) o.CheckKeys({"name", "urdf", "position", "xyz", "rpy", "collide"});
    }
  }
  const std::vector<std::string> scene_paths = ScenePackagePaths(doc, path, base);
  options.package_paths.insert(options.package_paths.begin() + flag_paths.size(),
                               scene_paths.begin(), scene_paths.end());
  const std::string urdf = ResolveRelative(doc["robot"].get<std::string>(), base);
  s.robot = LoadRobot(urdf, options);
  s.warnings = s.robot.warnings;
  std::string srdf = srdf_flag;
  if (srdf.empty() && doc.contains("srdf")) {
    if (!doc["srdf"].is_string()) throw std::invalid_argument(path + ": srdf: expected a path");
    srdf = ResolveRelative(doc["srdf"].get<std::string>(), base);
  }
  AttachSrdf(srdf.empty() ? FindSrdf(urdf, s.robot.name) : srdf, &s);
  if (doc.contains("base")) {
    const nlohmann::json& b = doc["base"];
    std::vector<double> values;
    if (b.is_array()) {
      for (const nlohmann::json& v : b) {
        if (!v.is_number()) {
          values.clear();
          break;
        }
        values.push_back(v.get<double>());
      }
    }
    if (values.empty()) {
      throw std::invalid_argument(path + ": base: expected [x, y, z] or [x, y, z, qx, qy, qz, qw]");
    }
    s.robot.world_from_root = BasePoseFromValues(BaseType::kFloating, values, path + ": base");
  }
  const int n = num_dofs(s.robot);
  s.q = Eigen::VectorXd::Zero(n);
  if (doc.contains("q")) {
    s.q_given = true;
    const nlohmann::json& q = doc["q"];
    if (!q.is_array() || static_cast<int>(q.size()) != n) {
      throw std::invalid_argument(path + ": q: expected an array of " + std::to_string(n) +
                                  " numbers (robot '" + s.robot.name + "')");
    }
    for (int k = 0; k < n; ++k) {
      if (!q[k].is_number()) {
        throw std::invalid_argument(path + ": q[" + std::to_string(k) + "]: expected a number");
      }
      s.q[k] = q[k].get<double>();
    }
    CheckJointValues(s.robot, s.q, path + ": q");
  }
  if (doc.contains("objects")) {
    const nlohmann::json& objs = doc["objects"];
    if (!objs.is_array()) throw std::invalid_argument(path + ": objects: expected an array");
    for (size_t i = 0; i < objs.size(); ++i) {
      const std::string jp = "objects[" + std::to_string(i) + "]";
      const nlohmann::json& o = objs[i];
      if (!o.is_object() || !o.contains("urdf") || !o["urdf"].is_string()) {
        throw std::invalid_argument(path + ": " + jp + ".urdf: expected a URDF path");
      }
      const Robot object = LoadRobot(ResolveRelative(o["urdf"].get<std::string>(), base), options);
      const std::string name =
          o.contains("name") && o["name"].is_string() ? o["name"].get<std::string>() : object.name;
      // "xyz" is the scenario files' spelling (planning/motion/scenario.h), "position" ours.
      const std::string pos_key = o.contains("xyz") ? "xyz" : "position";
      const Eigen::Vector3d xyz = o.contains(pos_key) ? Vec3(o[pos_key], path, jp + "." + pos_key)
                                                      : Eigen::Vector3d::Zero();
      const Eigen::Vector3d rpy =
          o.contains("rpy") ? Vec3(o["rpy"], path, jp + ".rpy") : Eigen::Vector3d::Zero();
      if (o.contains("collide") && !o["collide"].is_boolean()) {
        throw std::invalid_argument(path + ": " + jp + ".collide: expected true or false");
      }
      s.collides.push_back(!o.contains("collide") || o["collide"].get<bool>());
      try {
        AddObject(object, Pose(xyz, rpy), name, &s.env);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(path + ": " + jp + ".name: " + e.what());
      }
    }
  }
  return s;
}

}  // namespace

RobotScene LoadRobotScene(const std::string& path, const std::vector<std::string>& package_paths) {
  return LoadRobotSceneImpl(path, package_paths, "", false);
}

RobotScene LoadRobotScene(const std::string& path, const RobotInputOptions& options) {
  return LoadRobotSceneImpl(path, options.package_paths, options.srdf, true);
}

Eigen::VectorXd DefaultQ(const RobotScene& scene, std::vector<std::string>* notes) {
  if (scene.srdf && !scene.srdf->poses.empty()) {
    const std::string& name = scene.srdf->poses.front().name;
    std::vector<std::string> warnings;  // a reference pose outside the limits: as --pose says
    Eigen::VectorXd q = NamedPose(scene.robot, *scene.srdf, name, &warnings);
    if (notes != nullptr) {
      std::string n = "no --q or --pose: the SRDF's first group_state '";
      notes->push_back(n.append(name).append("'"));
      for (std::string& w : warnings) notes->push_back(std::move(w));
    }
    return q;
  }
  const Eigen::VectorXd lo = LowerLimits(scene.robot), hi = UpperLimits(scene.robot);
  const std::vector<std::string> names = DofNames(scene.robot);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(num_dofs(scene.robot));
  std::string moved;
  for (Eigen::Index k = 0; k < q.size(); ++k) {
    if (lo[k] <= 0.0 && 0.0 <= hi[k]) continue;
    q[k] = 0.5 * (lo[k] + hi[k]);
    if (!moved.empty()) moved.append(", ");
    moved.append(names[k]).append(" = ").append(base::FormatShortest(q[k]));
  }
  if (notes != nullptr && !moved.empty()) {
    std::string n = "no --q or --pose: zeros, and the middle of the limits where zero is outside (";
    notes->push_back(n.append(moved).append(")"));
  }
  return q;
}

Eigen::VectorXd ChooseQ(const RobotScene& scene, const std::string& q_text, const std::string& pose,
                        std::vector<std::string>* warnings, std::vector<std::string>* notes) {
  if (!q_text.empty() && !pose.empty()) {
    throw std::invalid_argument("--q and --pose: give at most one of them");
  }
  if (!q_text.empty()) return ParseQ(scene.robot, q_text, warnings);
  if (pose.empty()) {
    if (scene.q_given) return scene.q;
    return DefaultQ(scene, notes);
  }
  if (!scene.srdf) {
    throw std::invalid_argument("--pose " + pose + ": robot '" + scene.robot.name +
                                "' has no SRDF (give --srdf FILE)");
  }
  return NamedPose(scene.robot, *scene.srdf, pose, warnings);
}

Eigen::Isometry3d ChooseBase(const RobotScene& scene, const std::string& base_text,
                             const std::string& pose) {
  if (!base_text.empty()) {
    return BasePoseFromValues(BaseType::kFloating, base::ParseNumberList(base_text, "--base"),
                              "--base");
  }
  if (!pose.empty() && scene.srdf) {
    if (const auto base = NamedBasePose(scene.robot, *scene.srdf, pose)) return *base;
  }
  return scene.robot.world_from_root;
}

}  // namespace planning
