#include "planning/grasp/grasp.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <locale>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "base/file_write.h"
#include "base/json_reader.h"
#include "topology/winding.h"
#include "topology/writhe.h"

namespace planning {
namespace {

// {"xyz": [x, y, z], "rpy": [r, p, y]} (both required).
Eigen::Isometry3d ReadPose(const base::JsonNode& n) {
  n.CheckKeys({"xyz", "rpy"});
  return PoseFromXyzRpy(n.At("xyz").Vec3(), n.At("rpy").Vec3());
}

nlohmann::json PoseJson(const Eigen::Isometry3d& pose) {
  Eigen::Vector3d xyz, rpy;
  PoseToXyzRpy(pose, &xyz, &rpy);
  auto round = [](double v) { return std::round(v * 1e9) / 1e9; };
  return nlohmann::json{{"xyz", {round(xyz.x()), round(xyz.y()), round(xyz.z())}},
                        {"rpy", {round(rpy.x()), round(rpy.y()), round(rpy.z())}}};
}

// Every link in the subtree rooted at `link` (including it), in index order.
std::vector<char> LinkSubtree(const Robot& robot, int link) {
  std::vector<char> in(robot.links.size(), 0);
  in[link] = 1;
  for (size_t i = 0; i < robot.links.size(); ++i) {  // topological order: parents first
    const int pj = robot.links[i].parent_joint;
    if (pj >= 0 && in[robot.joints[pj].parent_link]) in[i] = 1;
  }
  return in;
}

void AddSpheresAlongZ(int link, const Eigen::Isometry3d& t, double z0, double z1, double r,
                      double spacing, HandSpheres* out) {
  const int n = std::max(1, static_cast<int>(std::ceil((z1 - z0) / spacing)) + 1);
  for (int k = 0; k < n; ++k) {
    const double z = n == 1 ? 0.5 * (z0 + z1) : z0 + (z1 - z0) * k / (n - 1);
    out->link.push_back(link);
    out->radius.push_back(r);
    const int c = static_cast<int>(out->center_local.cols());
    out->center_local.conservativeResize(3, c + 1);
    out->center_local.col(c) = t * Eigen::Vector3d(0, 0, z);
  }
}

}  // namespace

const std::vector<std::string>& HumanFingers() {
  static const std::vector<std::string> kFingers = {"thumb", "index", "middle", "ring", "little"};
  return kFingers;
}

const std::vector<std::string>& SdhFingers() {
  static const std::vector<std::string> kFingers = {"thumb", "finger_1", "finger_2"};
  return kFingers;
}

HumanGrasp LoadHumanGrasp(const std::string& path) {
  const nlohmann::json doc = base::ParseJsonFile(path, "grasp");
  const base::JsonNode root(doc, path);
  root.CheckKeys({"name", "type", "description", "object", "object_pose", "palm_pose", "joints",
                  "sdh_spread", "close"});
  HumanGrasp g;
  g.source = path;
  // A grasp's name names its output folders (frames/<name>_<method>): one plain file name, so
  // that nothing an input file says can write outside the output folder.
  g.name = base::Located(root.At("name"),
                         [&] { return base::SafeFileName(root.At("name").String(), ""); });
  g.object = root.At("object").String();
  g.type = root.String("type", "");
  g.description = root.String("description", "");
  g.world_from_object = ReadPose(root.At("object_pose"));
  g.world_from_palm = ReadPose(root.At("palm_pose"));
  for (const auto& [name, value] : root.At("joints").Members()) g.joints[name] = value.Number();
  if (root.Has("sdh_spread")) {
    const base::JsonNode sn = root.At("sdh_spread");
    g.sdh_spread = sn.Number();
    if (!(g.sdh_spread >= 0 && g.sdh_spread <= 1.5707963268)) sn.Fail("must be in [0, pi/2]");
  }
  if (root.Has("close")) g.close = root.At("close").Strings();
  return g;
}

std::string HumanGraspToJson(const HumanGrasp& g) {
  nlohmann::json j;
  j["name"] = g.name;
  j["type"] = g.type;
  j["description"] = g.description;
  j["object"] = g.object;
  j["object_pose"] = PoseJson(g.world_from_object);
  j["palm_pose"] = PoseJson(g.world_from_palm);
  j["sdh_spread"] = g.sdh_spread;
  nlohmann::json joints = nlohmann::json::object();
  for (const auto& [name, v] : g.joints) joints[name] = std::round(v * 1e6) / 1e6;
  j["joints"] = joints;
  if (!g.close.empty()) j["close"] = g.close;
  return j.dump(1) + "\n";
}

std::vector<int> AddGraspChains(bool human, Robot* robot) {
  const std::string palm = human ? "hand_palm" : "sdh_palm";
  const Eigen::Vector3d palm_point =
      human ? Eigen::Vector3d(0, -0.014, 0.045) : Eigen::Vector3d(0, 0, 0.0745);
  const int palm_link = FindLink(*robot, palm);
  std::vector<int> out;
  for (const std::string& f : human ? HumanFingers() : SdhFingers()) {
    const ChainSpec src = robot->chains[FindChain(*robot, human ? f : "sdh_" + f)];
    ChainSpec c;
    c.name = "grasp_" + f;
    c.closed = false;
    c.point_link.push_back(palm_link);
    c.point_link.insert(c.point_link.end(), src.point_link.begin(), src.point_link.end());
    c.point_local.resize(3, src.point_local.cols() + 1);
    c.point_local.col(0) = palm_point;
    c.point_local.rightCols(src.point_local.cols()) = src.point_local;
    robot->chains.push_back(c);
    out.push_back(static_cast<int>(robot->chains.size()) - 1);
  }
  return out;
}

Eigen::VectorXd HumanConfiguration(const Robot& human, const HumanGrasp& grasp) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(num_dofs(human));
  const std::vector<std::string> names = DofNames(human);
  auto set = [&](const std::string& name, double v) {
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end()) {
      throw std::invalid_argument(grasp.source + ": joints." + name +
                                  ": not a joint of the human hand model");
    }
    const int k = static_cast<int>(it - names.begin());
    const JointLimits& lim = human.joints[human.dof_joints[k]].limits;
    if (v < lim.lower - 1e-6 || v > lim.upper + 1e-6) {
      std::ostringstream msg;
      msg.imbue(std::locale::classic());  // "0.5" whatever the global locale
      msg << grasp.source << ": joints." << name << " = " << v << " is outside [" << lim.lower
          << ", " << lim.upper << "]";
      throw std::invalid_argument(msg.str());
    }
    q[k] = v;
  };
  Eigen::Vector3d xyz, rpy;
  PoseToXyzRpy(grasp.world_from_palm, &xyz, &rpy);
  set("hand_tx", xyz.x());
  set("hand_ty", xyz.y());
  set("hand_tz", xyz.z());
  set("hand_rz", rpy.z());
  set("hand_ry", rpy.y());
  set("hand_rx", rpy.x());
  for (const auto& [name, v] : grasp.joints) set(name, v);
  return q;
}

GraspEncoding EncodeGrasp(const Robot& robot, const KinematicsData& kin,
                          const std::vector<int>& chains, const ReferenceCurve& reference,
                          Eigen::MatrixXd* jacobian) {
  const int n = num_dofs(robot);
  GraspEncoding enc;
  enc.finger.resize(static_cast<int>(chains.size()));
  if (jacobian) jacobian->setZero(static_cast<int>(chains.size()), n);
  Eigen::Matrix3Xd points, grad;
  Eigen::MatrixXd dP;
  for (size_t c = 0; c < chains.size(); ++c) {
    ChainPoints(robot, kin, chains[c], &points);
    const int np = static_cast<int>(points.cols());
    if (reference.kind == ReferenceCurve::Kind::kAxis) {
      enc.phalanx.push_back(topology::SegmentWindings(points, reference.axis));
      enc.finger[c] = enc.phalanx.back().sum();
      if (jacobian) topology::WindingNumber(points, reference.axis, {}, &grad);
    } else {
      Eigen::MatrixXd w;
      topology::WritheJacobian wj;
      topology::WritheWorkspace ws;
      topology::WritheMatrixWithJacobian(points, reference.loop, {}, &w, &wj, &ws);
      enc.phalanx.push_back(w.rowwise().sum());
      enc.finger[c] = w.sum();
      if (jacobian) {
        Eigen::Matrix3Xd grad_b;
        topology::WeightedWritheGradient(wj, Eigen::MatrixXd(), &grad, &grad_b);
      }
    }
    if (jacobian) {
      dP.resize(3 * np, n);
      ChainJacobian(robot, kin, chains[c], dP);
      for (int k = 0; k < np; ++k) {
        jacobian->row(c) += grad.col(k).transpose() * dP.middleRows(3 * k, 3);
      }
    }
  }
  return enc;
}

Eigen::Vector2d OppositionPair(const Eigen::VectorXd& w, const Eigen::MatrixXd* jacobian,
                               Eigen::MatrixXd* pair_jacobian) {
  if (w.size() == 0) throw std::invalid_argument("OppositionPair: no finger values");
  if (jacobian && jacobian->rows() != w.size()) {
    throw std::invalid_argument("OppositionPair: jacobian rows != number of fingers");
  }
  int hi = 0, lo = 0;
  const Eigen::Vector2d o(w.maxCoeff(&hi), w.minCoeff(&lo));
  if (jacobian && pair_jacobian) {
    pair_jacobian->resize(2, jacobian->cols());
    pair_jacobian->row(0) = jacobian->row(hi);
    pair_jacobian->row(1) = jacobian->row(lo);
  }
  return o;
}

HandSpheres SampleHandSpheres(const Robot& robot, const std::vector<int>& links, double spacing) {
  HandSpheres out;
  out.center_local.resize(3, 0);
  std::vector<int> list = links;
  if (list.empty()) {
    for (size_t i = 0; i < robot.links.size(); ++i) list.push_back(static_cast<int>(i));
  }
  for (int li : list) {
    for (const Geometry& g : robot.links[li].collisions) {
      const Eigen::Isometry3d& t = g.link_from_geometry;
      const Eigen::Vector3d& s = g.size;
      switch (g.kind) {
        case Geometry::Kind::kSphere:
          AddSpheresAlongZ(li, t, 0, 0, s.x(), spacing, &out);
          break;
        case Geometry::Kind::kCapsule:
          AddSpheresAlongZ(li, t, -0.5 * s.y(), 0.5 * s.y(), s.x(), spacing, &out);
          break;
        case Geometry::Kind::kCylinder: {
          const double r = std::min(s.x(), 0.5 * s.y());
          if (s.y() >= 2 * s.x()) {
            AddSpheresAlongZ(li, t, -0.5 * s.y() + r, 0.5 * s.y() - r, r, spacing, &out);
          } else {
            // Flat disc: spheres of radius length/2 on rings inside radius − r.
            const double rr = s.x() - r;
            const int rings = std::max(0, static_cast<int>(std::ceil(rr / spacing)));
            AddSpheresAlongZ(li, t, 0, 0, r, spacing, &out);
            for (int ring = 1; ring <= rings; ++ring) {
              const double rad = rr * ring / rings;
              const int m = std::max(6, static_cast<int>(std::ceil(2 * M_PI * rad / spacing)));
              for (int k = 0; k < m; ++k) {
                const double a = 2 * M_PI * k / m;
                Eigen::Isometry3d tk = t;
                tk.translate(Eigen::Vector3d(rad * std::cos(a), rad * std::sin(a), 0));
                AddSpheresAlongZ(li, tk, 0, 0, r, spacing, &out);
              }
            }
          }
          break;
        }
        case Geometry::Kind::kBox: {
          // Spheres of radius = half the thinnest side on a grid in the box's mid-plane.
          int thin = 0;
          s.minCoeff(&thin);
          const double r = 0.5 * s[thin];
          const int u = (thin + 1) % 3, v = (thin + 2) % 3;
          const double hu = std::max(0.0, 0.5 * s[u] - r), hv = std::max(0.0, 0.5 * s[v] - r);
          const int nu = std::max(1, static_cast<int>(std::ceil(2 * hu / spacing)) + 1);
          const int nv = std::max(1, static_cast<int>(std::ceil(2 * hv / spacing)) + 1);
          for (int a = 0; a < nu; ++a) {
            for (int b = 0; b < nv; ++b) {
              Eigen::Vector3d c = Eigen::Vector3d::Zero();
              c[u] = nu == 1 ? 0.0 : -hu + 2 * hu * a / (nu - 1);
              c[v] = nv == 1 ? 0.0 : -hv + 2 * hv * b / (nv - 1);
              Eigen::Isometry3d tk = t;
              tk.translate(c);
              AddSpheresAlongZ(li, tk, 0, 0, r, spacing, &out);
            }
          }
          break;
        }
        case Geometry::Kind::kMesh:
          break;
      }
    }
  }
  return out;
}

double HandClearance(const Robot& robot, const KinematicsData& kin, const HandSpheres& spheres,
                     const GraspObject& object, const Eigen::Isometry3d& world_from_object,
                     std::vector<double>* per_link) {
  const Eigen::Isometry3d object_from_world = world_from_object.inverse();
  if (per_link) per_link->assign(robot.links.size(), std::numeric_limits<double>::infinity());
  double best = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < spheres.link.size(); ++k) {
    const int li = spheres.link[k];
    const Eigen::Vector3d p =
        object_from_world * (kin.world_from_link[li] * spheres.center_local.col(k));
    const double d = SignedDistance(object, p) - spheres.radius[k];
    best = std::min(best, d);
    if (per_link) (*per_link)[li] = std::min((*per_link)[li], d);
  }
  return best;
}

double SynthesizeGrasp(const Robot& human, const GraspObject& object, HumanGrasp* grasp,
                       double tolerance) {
  KinematicsData kin(human);
  Eigen::VectorXd q = HumanConfiguration(human, *grasp);
  const std::vector<std::string> names = DofNames(human);
  for (const std::string& jname : grasp->close) {
    const auto it = std::find(names.begin(), names.end(), jname);
    if (it == names.end()) {
      throw std::invalid_argument(grasp->source + ": close: '" + jname + "' is not a joint");
    }
    const int dof = static_cast<int>(it - names.begin());
    const Joint& joint = human.joints[human.dof_joints[dof]];
    const std::vector<char> moved = LinkSubtree(human, joint.child_link);
    std::vector<int> links;
    for (size_t i = 0; i < moved.size(); ++i) {
      if (moved[i]) links.push_back(static_cast<int>(i));
    }
    const HandSpheres spheres = SampleHandSpheres(human, links, 0.002);
    auto clearance = [&](double v) {
      q[dof] = v;
      ForwardKinematics(human, q, &kin);
      return HandClearance(human, kin, spheres, object, grasp->world_from_object);
    };
    const double lo_limit = joint.limits.lower, hi_limit = joint.limits.upper;
    double v = q[dof];
    // Already penetrating: open until free (or at the lower limit).
    while (clearance(v) < -tolerance && v > lo_limit) v = std::max(lo_limit, v - 0.01);
    // Close in small steps until penetration, then bisect onto the surface.
    double lo = v, hi = v;
    bool hit = false;
    while (hi < hi_limit) {
      hi = std::min(hi_limit, hi + 0.02);
      if (clearance(hi) < 0) {
        hit = true;
        break;
      }
      lo = hi;
    }
    if (hit) {
      for (int it2 = 0; it2 < 30; ++it2) {
        const double mid = 0.5 * (lo + hi);
        (clearance(mid) < 0 ? hi : lo) = mid;
      }
      v = clearance(hi) >= -tolerance ? hi : lo;
    } else {
      v = hi_limit;
    }
    q[dof] = v;
    grasp->joints[jname] = v;
  }
  ForwardKinematics(human, q, &kin);
  const HandSpheres all = SampleHandSpheres(human, {}, 0.002);
  return HandClearance(human, kin, all, object, grasp->world_from_object);
}

}  // namespace planning
