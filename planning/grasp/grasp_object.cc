#include "planning/grasp/grasp_object.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <stdexcept>

#include "base/json_reader.h"

namespace planning {
namespace {

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
      const double half = s.z() > 0 ? std::min(s.z(), std::numbers::pi) : std::numbers::pi;
      const double phi = std::clamp(std::atan2(p.y(), p.x()), -half, half);
      const Eigen::Vector3d core(s.x() * std::cos(phi), s.x() * std::sin(phi), 0.0);
      return (p - core).norm() - s.y();
    }
  }
  return 0.0;
}

}  // namespace

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

namespace {

GraspPrimitive ReadPrimitive(const base::JsonNode& pj) {
  pj.CheckKeys({"type", "size", "xyz", "rpy"});
  GraspPrimitive prim;
  const base::JsonNode tn = pj.At("type");
  const std::string type = tn.String();
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
    tn.Fail("'" + type + "' is not sphere|cylinder|box|capsule|torus");
  }
  const base::JsonNode sn = pj.At("size");
  prim.size = sn.Vec3();
  if (prim.size.cwiseAbs().maxCoeff() > 10.0) sn.Fail("sizes must be at most 10 m");
  if (prim.size.x() <= 0 || (prim.kind != GraspPrimitive::Kind::kSphere &&
                             prim.kind != GraspPrimitive::Kind::kTorus && prim.size.y() < 0)) {
    sn.Fail("must be positive");
  }
  if (prim.kind == GraspPrimitive::Kind::kBox && (prim.size.array() <= 0).any()) {
    sn.Fail("box sides must be positive");
  }
  if (prim.kind == GraspPrimitive::Kind::kTorus && !(prim.size.y() > 0)) {
    sn.Fail("torus tube radius must be positive");
  }
  prim.object_from_primitive = PoseFromXyzRpy(pj.Vec3("xyz", Eigen::Vector3d::Zero()),
                                              pj.Vec3("rpy", Eigen::Vector3d::Zero()));
  return prim;
}

ReferenceCurve ReadReference(const base::JsonNode& r) {
  ReferenceCurve ref;
  const std::string type = r.String("type", "");
  if (type == "axis") {
    r.CheckKeys({"type", "point", "direction"});
    ref.kind = ReferenceCurve::Kind::kAxis;
    ref.axis.point = r.At("point").Vec3();
    ref.axis.direction = r.At("direction").Vec3();
    if (ref.axis.direction.norm() < 1e-9) r.At("direction").Fail("zero vector");
  } else if (type == "loop") {
    r.CheckKeys({"type", "points"});
    ref.kind = ReferenceCurve::Kind::kLoop;
    const base::JsonNode pts = r.At("points");
    if (pts.Size() < 3 || pts.Size() > 100000) pts.Fail("need 3 to 100000 points");
    ref.loop.resize(3, static_cast<int>(pts.Size()) + 1);
    for (size_t k = 0; k < pts.Size(); ++k) ref.loop.col(k) = pts.At(k).Vec3();
    ref.loop.col(pts.Size()) = ref.loop.col(0);
  } else if (type == "circle") {
    r.CheckKeys({"type", "center", "normal", "radius", "segments"});
    ref.kind = ReferenceCurve::Kind::kLoop;
    const Eigen::Vector3d c = r.At("center").Vec3();
    Eigen::Vector3d n = r.At("normal").Vec3();
    const double radius = r.Number("radius", 0.0, 0.0, 10.0);
    const int segments =
        r.Has("segments") ? static_cast<int>(r.At("segments").Integer(3, 100000)) : 24;
    if (n.norm() < 1e-9 || !(radius > 0)) {
      r.Fail("need a non-zero normal, radius > 0, segments >= 3");
    }
    n.normalize();
    const Eigen::Vector3d u = n.unitOrthogonal();
    const Eigen::Vector3d v = n.cross(u);
    ref.loop.resize(3, segments + 1);
    for (int k = 0; k <= segments; ++k) {
      const double a = 2 * std::numbers::pi * (k % segments) / segments;
      ref.loop.col(k) = c + radius * (std::cos(a) * u + std::sin(a) * v);
    }
  } else {
    r.At("type").Fail("'" + type + "' is not axis|loop|circle");
  }
  return ref;
}

}  // namespace

std::vector<GraspObject> LoadGraspObjects(const std::string& path) {
  const nlohmann::json doc = base::ParseJsonFile(path, "object catalogue");
  const base::JsonNode root(doc, path);
  root.CheckKeys({"objects"});
  const base::JsonNode list = root.At("objects");
  std::vector<GraspObject> objects;
  for (size_t i = 0; i < list.Size(); ++i) {
    const base::JsonNode o = list.At(i);
    o.CheckKeys({"name", "mass", "description", "primitives", "reference", "extra_references",
                 "main_reference_in_target"});
    GraspObject obj;
    obj.name = o.At("name").String();
    // Limits keep the ODE simulation in range: a hand holds objects of at most 1000 kg.
    obj.mass = o.At("mass").Number(0.0, 1000.0);
    if (!(obj.mass >= 1e-6)) o.At("mass").Fail("expected a mass in [1e-06, 1000] kg");
    obj.description = o.String("description", "");
    const base::JsonNode prims = o.At("primitives");
    if (prims.Size() == 0) prims.Fail("missing or empty");
    for (size_t k = 0; k < prims.Size(); ++k) obj.primitives.push_back(ReadPrimitive(prims.At(k)));
    obj.reference = ReadReference(o.At("reference"));
    if (o.Has("extra_references")) {
      const base::JsonNode extra = o.At("extra_references");
      for (size_t k = 0; k < extra.Size(); ++k) {
        obj.extra_references.push_back(ReadReference(extra.At(k)));
      }
    }
    obj.main_reference_in_target = o.Bool("main_reference_in_target", true);
    if (!obj.main_reference_in_target && obj.extra_references.empty()) {
      o.At("main_reference_in_target")
          .Fail("false needs extra_references (the winding target would be empty)");
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
