#include "planning/grasp_object.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "planning/internal/json_read.h"

namespace planning {
namespace {

constexpr double kPi = 3.14159265358979323846;
using Json = nlohmann::json;

// Distance in the primitive's own frame (no gradient).
double LocalDistance(const GraspPrimitive& prim, const Eigen::Vector3d& p) {
  const Eigen::Vector3d& s = prim.size;
  switch (prim.kind) {
    case GraspPrimitive::Kind::kSphere:
      return p.norm() - s.x();
    case GraspPrimitive::Kind::kCylinder: {
      const double dx = std::hypot(p.x(), p.y()) - s.x();
      const double dz = std::abs(p.z()) - 0.5 * s.y();
      return std::min(std::max(dx, dz), 0.0) + std::hypot(std::max(dx, 0.0), std::max(dz, 0.0));
    }
    case GraspPrimitive::Kind::kBox: {
      const Eigen::Vector3d q = p.cwiseAbs() - 0.5 * s;
      return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
    }
    case GraspPrimitive::Kind::kCapsule: {
      const double z = std::clamp(p.z(), -0.5 * s.y(), 0.5 * s.y());
      return (p - Eigen::Vector3d(0, 0, z)).norm() - s.x();
    }
    case GraspPrimitive::Kind::kTorus: {
      const double half = s.z() > 0 ? std::min(s.z(), kPi) : kPi;
      const double phi = std::clamp(std::atan2(p.y(), p.x()), -half, half);
      const Eigen::Vector3d core(s.x() * std::cos(phi), s.x() * std::sin(phi), 0.0);
      return (p - core).norm() - s.y();
    }
  }
  return 0.0;
}

Eigen::Vector3d ReadVec3(const Json& j, const std::string& where) {
  return internal::ReadJsonVec3(j, where);
}

}  // namespace

Eigen::Isometry3d PoseFromXyzRpy(const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = xyz;
  t.linear() = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return t;
}

void PoseToXyzRpy(const Eigen::Isometry3d& pose, Eigen::Vector3d* xyz, Eigen::Vector3d* rpy) {
  *xyz = pose.translation();
  const Eigen::Matrix3d& r = pose.linear();
  const double pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  double roll, yaw;
  if (std::abs(std::cos(pitch)) > 1e-9) {
    roll = std::atan2(r(2, 1), r(2, 2));
    yaw = std::atan2(r(1, 0), r(0, 0));
  } else {
    roll = 0.0;
    yaw = std::atan2(-r(0, 1), r(1, 1));
  }
  *rpy = Eigen::Vector3d(roll, pitch, yaw);
}

double PrimitiveSignedDistance(const GraspPrimitive& prim, const Eigen::Vector3d& p,
                               Eigen::Vector3d* grad) {
  const Eigen::Vector3d local = prim.object_from_primitive.inverse() * p;
  const double d = LocalDistance(prim, local);
  if (grad) {
    // Central differences in the local frame: the distance is piecewise smooth and cheap.
    constexpr double h = 1e-6;
    Eigen::Vector3d g;
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d e = Eigen::Vector3d::Zero();
      e[k] = h;
      g[k] = (LocalDistance(prim, local + e) - LocalDistance(prim, local - e)) / (2 * h);
    }
    *grad = prim.object_from_primitive.linear() * g;
  }
  return d;
}

double SignedDistance(const GraspObject& object, const Eigen::Vector3d& p, Eigen::Vector3d* grad) {
  double best = std::numeric_limits<double>::infinity();
  int best_index = -1;
  for (size_t i = 0; i < object.primitives.size(); ++i) {
    const double d = PrimitiveSignedDistance(object.primitives[i], p, nullptr);
    if (d < best) {
      best = d;
      best_index = static_cast<int>(i);
    }
  }
  if (grad) {
    if (best_index < 0) {
      grad->setZero();
    } else {
      PrimitiveSignedDistance(object.primitives[best_index], p, grad);
    }
  }
  return best;
}

ReferenceCurve TransformReference(const ReferenceCurve& ref,
                                  const Eigen::Isometry3d& world_from_object) {
  ReferenceCurve out = ref;
  out.axis.point = world_from_object * ref.axis.point;
  out.axis.direction = world_from_object.linear() * ref.axis.direction;
  if (ref.loop.cols() > 0) {
    out.loop = (world_from_object.linear() * ref.loop).colwise() + world_from_object.translation();
  }
  return out;
}

std::vector<GraspObject> LoadGraspObjects(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument(path + ": cannot open object catalogue");
  Json root;
  try {
    root = Json::parse(in);
  } catch (const std::exception& e) {
    throw std::invalid_argument(path + ": invalid JSON: " + e.what());
  }
  if (!root.contains("objects") || !root["objects"].is_array()) {
    throw std::invalid_argument(path + ": expected {\"objects\": [...]}");
  }
  std::vector<GraspObject> objects;
  const Json& list = root["objects"];
  for (size_t i = 0; i < list.size(); ++i) {
    const Json& o = list[i];
    const std::string where = path + ": objects[" + std::to_string(i) + "]";
    GraspObject obj;
    if (!o.contains("name") || !o["name"].is_string()) {
      throw std::invalid_argument(where + ".name: missing or not a string");
    }
    obj.name = o["name"].get<std::string>();
    if (!o.contains("mass") || !o["mass"].is_number() || !(o["mass"].get<double>() > 0)) {
      throw std::invalid_argument(where + ".mass: missing or not a positive number");
    }
    obj.mass = o["mass"].get<double>();
    obj.description = o.value("description", "");
    if (!o.contains("primitives") || !o["primitives"].is_array() || o["primitives"].empty()) {
      throw std::invalid_argument(where + ".primitives: missing or empty");
    }
    for (size_t k = 0; k < o["primitives"].size(); ++k) {
      const Json& pj = o["primitives"][k];
      const std::string pw = where + ".primitives[" + std::to_string(k) + "]";
      GraspPrimitive prim;
      const std::string type = pj.value("type", "");
      if (type == "sphere") {
        prim.kind = GraspPrimitive::Kind::kSphere;
      } else if (type == "cylinder") {
        prim.kind = GraspPrimitive::Kind::kCylinder;
      } else if (type == "box") {
        prim.kind = GraspPrimitive::Kind::kBox;
      } else if (type == "capsule") {
        prim.kind = GraspPrimitive::Kind::kCapsule;
      } else if (type == "torus") {
        prim.kind = GraspPrimitive::Kind::kTorus;
      } else {
        throw std::invalid_argument(pw + ".type: '" + type +
                                    "' is not sphere|cylinder|box|capsule|torus");
      }
      if (!pj.contains("size")) throw std::invalid_argument(pw + ".size: missing");
      prim.size = ReadVec3(pj["size"], pw + ".size");
      if (prim.size.x() <= 0 || (prim.kind != GraspPrimitive::Kind::kSphere &&
                                 prim.kind != GraspPrimitive::Kind::kTorus && prim.size.y() < 0)) {
        throw std::invalid_argument(pw + ".size: must be positive");
      }
      if (prim.kind == GraspPrimitive::Kind::kBox && (prim.size.array() <= 0).any()) {
        throw std::invalid_argument(pw + ".size: box sides must be positive");
      }
      if (prim.kind == GraspPrimitive::Kind::kTorus && !(prim.size.y() > 0)) {
        throw std::invalid_argument(pw + ".size: torus tube radius must be positive");
      }
      const Eigen::Vector3d xyz =
          pj.contains("xyz") ? ReadVec3(pj["xyz"], pw + ".xyz") : Eigen::Vector3d::Zero();
      const Eigen::Vector3d rpy =
          pj.contains("rpy") ? ReadVec3(pj["rpy"], pw + ".rpy") : Eigen::Vector3d::Zero();
      prim.object_from_primitive = PoseFromXyzRpy(xyz, rpy);
      obj.primitives.push_back(prim);
    }
    if (!o.contains("reference")) throw std::invalid_argument(where + ".reference: missing");
    const Json& r = o["reference"];
    const std::string rw = where + ".reference";
    const std::string type = r.value("type", "");
    if (type == "axis") {
      obj.reference.kind = ReferenceCurve::Kind::kAxis;
      obj.reference.axis.point = ReadVec3(r.at("point"), rw + ".point");
      obj.reference.axis.direction = ReadVec3(r.at("direction"), rw + ".direction");
      if (obj.reference.axis.direction.norm() < 1e-9) {
        throw std::invalid_argument(rw + ".direction: zero vector");
      }
    } else if (type == "loop") {
      obj.reference.kind = ReferenceCurve::Kind::kLoop;
      const Json& pts = r.at("points");
      if (!pts.is_array() || pts.size() < 3) {
        throw std::invalid_argument(rw + ".points: need at least 3 points");
      }
      obj.reference.loop.resize(3, static_cast<int>(pts.size()) + 1);
      for (size_t k = 0; k < pts.size(); ++k) {
        obj.reference.loop.col(k) = ReadVec3(pts[k], rw + ".points[" + std::to_string(k) + "]");
      }
      obj.reference.loop.col(pts.size()) = obj.reference.loop.col(0);
    } else if (type == "circle") {
      obj.reference.kind = ReferenceCurve::Kind::kLoop;
      const Eigen::Vector3d c = ReadVec3(r.at("center"), rw + ".center");
      Eigen::Vector3d n = ReadVec3(r.at("normal"), rw + ".normal");
      const double radius = r.value("radius", 0.0);
      const int segments = r.value("segments", 24);
      if (n.norm() < 1e-9 || !(radius > 0) || segments < 3) {
        throw std::invalid_argument(rw + ": need a non-zero normal, radius > 0, segments >= 3");
      }
      n.normalize();
      const Eigen::Vector3d u = n.unitOrthogonal();
      const Eigen::Vector3d v = n.cross(u);
      obj.reference.loop.resize(3, segments + 1);
      for (int k = 0; k <= segments; ++k) {
        const double a = 2 * kPi * (k % segments) / segments;
        obj.reference.loop.col(k) = c + radius * (std::cos(a) * u + std::sin(a) * v);
      }
    } else {
      throw std::invalid_argument(rw + ".type: '" + type + "' is not axis|loop|circle");
    }
    objects.push_back(obj);
  }
  return objects;
}

const GraspObject& FindGraspObject(const std::vector<GraspObject>& objects,
                                   const std::string& name) {
  std::string known;
  for (const GraspObject& o : objects) {
    if (o.name == name) return o;
    known += (known.empty() ? "" : ", ") + o.name;
  }
  throw std::invalid_argument("unknown object '" + name + "' (known: " + known + ")");
}

}  // namespace planning

namespace planning::internal {

Eigen::Vector3d ReadJsonVec3(const nlohmann::json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 3) throw std::invalid_argument(where + ": expected [x, y, z]");
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) {
    if (!j[i].is_number()) throw std::invalid_argument(where + ": expected numbers");
    v[i] = j[i].get<double>();
    if (!std::isfinite(v[i])) throw std::invalid_argument(where + ": non-finite number");
  }
  return v;
}

}  // namespace planning::internal
