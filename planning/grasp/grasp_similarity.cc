// Encoding-independent grasp similarity (planning/grasp/grasp_similarity.h).
#include "planning/grasp/grasp_similarity.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace planning {

std::optional<double> RegionIoU(const CellSet& a, const CellSet& b) {
  if (a.empty() && b.empty()) return std::nullopt;
  int inter = 0;
  for (const SurfaceCell& c : a) inter += b.count(c) ? 1 : 0;
  const int uni = static_cast<int>(a.size() + b.size()) - inter;
  return static_cast<double>(inter) / static_cast<double>(uni);
}

std::vector<CellSet> FingerContactRegions(const Robot& robot, const KinematicsData& kin,
                                          const std::vector<std::vector<std::string>>& groups,
                                          const GraspObject& object,
                                          const Eigen::Isometry3d& world_from_object,
                                          const ContactRegionOptions& o) {
  if (!(o.cell > 0) || !(o.spacing > 0)) {
    throw std::invalid_argument("contact regions: cell and spacing must be > 0");
  }
  std::vector<CellSet> out(groups.size());
  const Eigen::Isometry3d object_from_world = world_from_object.inverse();
  for (size_t g = 0; g < groups.size(); ++g) {
    std::vector<int> links;
    for (size_t i = 0; i < robot.links.size(); ++i) {
      for (const std::string& prefix : groups[g]) {
        if (robot.links[i].name.rfind(prefix, 0) == 0) {
          links.push_back(static_cast<int>(i));
          break;
        }
      }
    }
    if (links.empty()) continue;
    const HandSpheres s = SampleHandSpheres(robot, links, o.spacing);
    for (size_t k = 0; k < s.link.size(); ++k) {
      const Eigen::Vector3d c =
          object_from_world * (kin.world_from_link[s.link[k]] * s.center_local.col(k));
      Eigen::Vector3d grad;
      const double d = SignedDistance(object, c, &grad);
      if (d - s.radius[k] >= o.tolerance) continue;
      const Eigen::Vector3d p = c - d * grad;
      out[g].insert({static_cast<int>(std::floor(p.x() / o.cell)),
                     static_cast<int>(std::floor(p.y() / o.cell)),
                     static_cast<int>(std::floor(p.z() / o.cell))});
    }
  }
  return out;
}

const std::vector<std::vector<std::string>>& HumanGroupsForSdh() {
  static const std::vector<std::vector<std::string>> g = {
      {"thumb_"}, {"ring_", "little_"}, {"index_", "middle_"}};
  return g;
}

const std::vector<std::vector<std::string>>& SdhGroups() {
  static const std::vector<std::vector<std::string>> g = {
      {"sdh_thumb"}, {"sdh_finger_1"}, {"sdh_finger_2"}};
  return g;
}

bool ChainThreadsLoop(const Eigen::Matrix3Xd& chain, const Eigen::Matrix3Xd& loop) {
  const int m = static_cast<int>(loop.cols()) - 1;  // distinct loop points
  if (m < 3) throw std::invalid_argument("threading: a loop needs at least 4 points");
  const Eigen::Vector3d centre = loop.leftCols(m).rowwise().mean();
  Eigen::Vector3d n = Eigen::Vector3d::Zero();  // Newell's normal
  for (int i = 0; i < m; ++i) n += loop.col(i).cross(loop.col(i + 1));
  if (n.norm() < 1e-12) throw std::invalid_argument("threading: degenerate loop plane");
  n.normalize();
  const Eigen::Vector3d u = n.unitOrthogonal(), v = n.cross(u);
  std::vector<Eigen::Vector2d> poly(m);
  for (int i = 0; i < m; ++i) {
    const Eigen::Vector3d d = loop.col(i) - centre;
    poly[i] = Eigen::Vector2d(d.dot(u), d.dot(v));
  }
  auto inside = [&poly, m](const Eigen::Vector2d& p) {
    bool in = false;
    for (int i = 0, j = m - 1; i < m; j = i++) {
      const Eigen::Vector2d &a = poly[i], &b = poly[j];
      if ((a.y() > p.y()) != (b.y() > p.y()) &&
          p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
        in = !in;
      }
    }
    return in;
  };
  for (int k = 0; k + 1 < chain.cols(); ++k) {
    const double s0 = n.dot(chain.col(k) - centre), s1 = n.dot(chain.col(k + 1) - centre);
    if ((s0 > 0) == (s1 > 0) || s0 == s1) continue;
    const Eigen::Vector3d x = chain.col(k) + (s0 / (s0 - s1)) * (chain.col(k + 1) - chain.col(k));
    const Eigen::Vector3d d = x - centre;
    if (inside(Eigen::Vector2d(d.dot(u), d.dot(v)))) return true;
  }
  return false;
}

std::vector<bool> FingersThreading(const Robot& robot, const KinematicsData& kin,
                                   const std::vector<int>& chains, const Eigen::Matrix3Xd& loop) {
  std::vector<bool> out;
  Eigen::Matrix3Xd points;
  for (int c : chains) {
    ChainPoints(robot, kin, c, &points);
    out.push_back(ChainThreadsLoop(points, loop));
  }
  return out;
}

std::vector<bool> HumanThreadingForSdh(const std::vector<bool>& h) {
  if (h.size() != 5) throw std::invalid_argument("threading: 5 human fingers expected");
  // HumanFingers order: thumb, index, middle, ring, little.
  return {h[0], h[3] || h[4], h[1] || h[2]};
}

ThreadPreservation CompareThreading(const std::vector<bool>& demo,
                                    const std::vector<bool>& transfer) {
  if (demo.size() != transfer.size()) {
    throw std::invalid_argument("threading: demonstration and transfer differ in fingers");
  }
  ThreadPreservation t;
  for (size_t f = 0; f < demo.size(); ++f) {
    if (!demo[f]) continue;
    ++t.demo;
    if (transfer[f]) ++t.preserved;
  }
  return t;
}

}  // namespace planning
