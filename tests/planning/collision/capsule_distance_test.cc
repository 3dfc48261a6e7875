// Closed-form capsule–capsule distance (CollisionOptions::analytic_capsules) against an independent
// reference (ternary search over the first segment) and against FCL's GJK/EPA answer, on random
// poses and on the degenerate cases: parallel, collinear, crossing and coaxial segments, and
// zero-length capsules; separated and penetrating.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "planning/collision/collision.h"
#include "planning/robot/kinematics.h"

namespace planning {
namespace {

struct Capsule {
  double radius;
  double length;
  Eigen::Isometry3d pose;  // world from capsule; core segment along local z, centred
};

Geometry CapsuleGeometry(const Capsule& c) {
  Geometry g;
  g.kind = Geometry::Kind::kCapsule;
  g.size = Eigen::Vector3d(c.radius, c.length, 0.0);
  return g;
}

Eigen::Vector3d End(const Capsule& c, double sign) {
  return c.pose * Eigen::Vector3d(0, 0, sign * 0.5 * c.length);
}

// Distance from x to the segment [p0, p1].
double PointSegment(const Eigen::Vector3d& x, const Eigen::Vector3d& p0,
                    const Eigen::Vector3d& p1) {
  const Eigen::Vector3d d = p1 - p0;
  const double dd = d.squaredNorm();
  const double s = dd > 0 ? std::clamp((x - p0).dot(d) / dd, 0.0, 1.0) : 0.0;
  return (p0 + s * d - x).norm();
}

// Reference segment–segment distance: the distance from a(s) to segment b is convex in s, so a
// ternary search over s converges to the minimum.
double SegmentDistance(const Capsule& a, const Capsule& b) {
  const Eigen::Vector3d a0 = End(a, -1), a1 = End(a, 1), b0 = End(b, -1), b1 = End(b, 1);
  const auto f = [&](double s) { return PointSegment(a0 + s * (a1 - a0), b0, b1); };
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 200; ++i) {
    const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
    (f(m1) < f(m2) ? hi : lo) = f(m1) < f(m2) ? m2 : m1;
  }
  return f(0.5 * (lo + hi));
}

// Robot = capsule a (pose set directly in the kinematics), environment = capsule b.
ProximityPair Query(const Capsule& a, const Capsule& b, bool analytic, std::int64_t* calls) {
  const Robot robot = MakePrimitiveObject("a", CapsuleGeometry(a));
  Environment env;
  AddObject(MakePrimitiveObject("b", CapsuleGeometry(b)), b.pose, "b", &env);
  CollisionOptions options;
  options.analytic_capsules = analytic;
  CollisionData coll(robot, env, options);
  KinematicsData kin(robot);
  ForwardKinematics(robot, Eigen::VectorXd(0), &kin);
  kin.world_from_link[0] = a.pose;
  std::vector<ProximityPair> pairs;
  ComputeProximity(robot, kin, 100.0, &coll, &pairs);
  EXPECT_EQ(pairs.size(), 1u);
  if (calls) *calls = coll.narrow_phase_calls;
  return pairs.empty() ? ProximityPair{} : pairs[0];
}

// Properties every answer of the closed form has: signed distance = reference, unit normal,
// witness points on the surfaces, separated pairs' witnesses |p_a − p_b| = distance along the
// normal, penetrating pairs' witnesses coincide.
void CheckAnalytic(const Capsule& a, const Capsule& b, const ProximityPair& p) {
  const double ref = SegmentDistance(a, b) - a.radius - b.radius;
  EXPECT_NEAR(p.distance, ref, 1e-9);
  EXPECT_NEAR(p.normal.norm(), 1.0, 1e-12);
  if (p.distance > 0) {
    EXPECT_NEAR(PointSegment(p.point_a, End(a, -1), End(a, 1)), a.radius, 1e-9);
    EXPECT_NEAR(PointSegment(p.point_b, End(b, -1), End(b, 1)), b.radius, 1e-9);
    EXPECT_NEAR((p.point_a - p.point_b).norm(), p.distance, 1e-9);
    EXPECT_TRUE((p.point_a - p.point_b).isApprox(p.distance * p.normal, 1e-9));
  } else {
    EXPECT_TRUE(p.point_a.isApprox(p.point_b, 1e-12));
  }
}

// The closed-form answer for a and b, checked by CheckAnalytic.
ProximityPair Checked(const Capsule& a, const Capsule& b) {
  const ProximityPair p = Query(a, b, true, nullptr);
  CheckAnalytic(a, b, p);
  return p;
}

Capsule At(double r, double len, const Eigen::Vector3d& xyz, const Eigen::Vector3d& axis) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis).matrix();
  pose.translation() = xyz;
  return {r, len, pose};
}

TEST(CapsuleDistance, ParallelSideBySideTakesTheMiddleOfTheOverlap) {
  const Capsule a = At(0.05, 0.4, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d::UnitZ());
  const Capsule b = At(0.03, 0.4, Eigen::Vector3d(0.3, 0, 0.1), Eigen::Vector3d::UnitZ());
  const ProximityPair p = Checked(a, b);
  EXPECT_NEAR(p.distance, 0.22, 1e-12);
  EXPECT_TRUE(p.point_a.isApprox(Eigen::Vector3d(0.05, 0, 0.05), 1e-12));
  EXPECT_TRUE(p.point_b.isApprox(Eigen::Vector3d(0.27, 0, 0.05), 1e-12));
  EXPECT_TRUE(p.normal.isApprox(Eigen::Vector3d(-1, 0, 0), 1e-12));
  // Anti-parallel gives the same answer.
  const Capsule c = At(0.03, 0.4, Eigen::Vector3d(0.3, 0, 0.1), -Eigen::Vector3d::UnitZ());
  const ProximityPair q = Query(a, c, true, nullptr);
  EXPECT_NEAR(q.distance, 0.22, 1e-12);
  EXPECT_TRUE(q.point_a.isApprox(p.point_a, 1e-12));
}

TEST(CapsuleDistance, CollinearEndToEnd) {
  const Capsule a = At(0.05, 0.2, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d::UnitZ());
  const Capsule b = At(0.05, 0.2, Eigen::Vector3d(0, 0, 0.4), Eigen::Vector3d::UnitZ());
  const ProximityPair p = Checked(a, b);
  EXPECT_NEAR(p.distance, 0.1, 1e-12);
  EXPECT_TRUE(p.normal.isApprox(Eigen::Vector3d(0, 0, -1), 1e-12));
  EXPECT_TRUE(p.point_a.isApprox(Eigen::Vector3d(0, 0, 0.15), 1e-12));
}

TEST(CapsuleDistance, CrossingAxesPenetrateByBothRadiiAlongTheCrossProduct) {
  const Capsule a = At(0.05, 0.4, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX());
  const Capsule b = At(0.03, 0.4, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitY());
  const ProximityPair p = Checked(a, b);
  EXPECT_NEAR(p.distance, -0.08, 1e-12);
  EXPECT_NEAR(std::abs(p.normal.z()), 1.0, 1e-12);
}

TEST(CapsuleDistance, CoaxialOverlapAndZeroLength) {
  const Capsule a = At(0.05, 0.4, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
  const Capsule b = At(0.03, 0.2, Eigen::Vector3d(0, 0, 0.1), Eigen::Vector3d::UnitZ());
  const ProximityPair p = Checked(a, b);
  EXPECT_NEAR(p.distance, -0.08, 1e-12);
  EXPECT_NEAR(p.normal.z(), 0.0, 1e-12);  // perpendicular to the common axis
  // Zero-length capsules are spheres.
  const Capsule s1 = At(0.1, 0.0, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
  const Capsule s2 = At(0.1, 0.0, Eigen::Vector3d(1, 0, 0), Eigen::Vector3d::UnitY());
  const ProximityPair q = Checked(s1, s2);
  EXPECT_NEAR(q.distance, 0.8, 1e-12);
  EXPECT_TRUE(q.normal.isApprox(Eigen::Vector3d(-1, 0, 0), 1e-12));
  // A sphere against a segment's middle.
  const Capsule s3 = At(0.1, 0.0, Eigen::Vector3d(0.3, 0, 0.05), Eigen::Vector3d::UnitX());
  const ProximityPair r = Checked(a, s3);
  EXPECT_NEAR(r.distance, 0.15, 1e-12);
}

// Random poses: the closed form matches the reference exactly, and FCL (GJK for separated pairs)
// within GJK's accuracy; for penetrating pairs FCL's depth is at least the exact one. One
// narrow-phase call per pair.
TEST(CapsuleDistance, RandomPosesMatchReferenceAndFcl) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const auto random_capsule = [&](double spread) {
    Eigen::Vector3d axis(unit(rng), unit(rng), unit(rng));
    if (axis.norm() < 1e-3) axis = Eigen::Vector3d::UnitZ();
    const double r = 0.02 + 0.05 * (unit(rng) + 1), len = 0.3 * (unit(rng) + 1);
    return At(r, len, spread * Eigen::Vector3d(unit(rng), unit(rng), unit(rng)), axis.normalized());
  };
  int separated = 0, penetrating = 0;
  double worst_sep = 0.0, worst_pen = 0.0, worst_point = 0.0;
  for (int i = 0; i < 400; ++i) {
    const Capsule a = random_capsule(0.0), b = random_capsule(i % 2 == 0 ? 0.4 : 0.15);
    std::int64_t calls_analytic = 0, calls_fcl = 0;
    const ProximityPair p = Query(a, b, true, &calls_analytic);
    const ProximityPair f = Query(a, b, false, &calls_fcl);
    CheckAnalytic(a, b, p);
    EXPECT_EQ(calls_analytic, 1);
    if (p.distance > 1e-3) {
      ++separated;
      worst_sep = std::max(worst_sep, std::abs(f.distance - p.distance));
      EXPECT_NEAR(f.distance, p.distance, 1e-4);
      // Witnesses are unique unless the axes are (nearly) parallel; GJK's are approximate.
      const Eigen::Vector3d ua = a.pose.linear().col(2), ub = b.pose.linear().col(2);
      if (ua.cross(ub).norm() > 0.1) {
        worst_point = std::max(worst_point, (f.point_a - p.point_a).norm());
        EXPECT_LT((f.point_a - p.point_a).norm(), 5e-3);
        EXPECT_LT((f.point_b - p.point_b).norm(), 5e-3);
      }
      EXPECT_GT(((f.point_a - f.point_b).normalized()).dot(p.normal), 0.99);
    } else if (p.distance < -1e-3) {
      ++penetrating;
      worst_pen = std::max(worst_pen, std::abs(f.distance - p.distance));
      // The exact depth is the smallest separating translation; FCL's contact depth (EPA on
      // curved shapes) only bounds it from above, sometimes loosely.
      EXPECT_LT(f.distance, 0.0);
      EXPECT_LE(f.distance, p.distance + 1e-3);
    }
  }
  EXPECT_GT(separated, 100);
  EXPECT_GT(penetrating, 100);
  RecordProperty("worst_separated_diff_m", std::to_string(worst_sep));
  RecordProperty("worst_penetrating_diff_m", std::to_string(worst_pen));
  RecordProperty("worst_witness_diff_m", std::to_string(worst_point));
  std::printf("separated %d (max |d - fcl| %.2e, witness %.2e), penetrating %d (max %.2e)\n",
              separated, worst_sep, worst_point, penetrating, worst_pen);
}

// Capsules against the other primitives still go through FCL (unchanged answers).
TEST(CapsuleDistance, OtherShapePairsUseFcl) {
  const Capsule a = At(0.05, 0.4, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
  Geometry box;
  box.kind = Geometry::Kind::kBox;
  box.size = Eigen::Vector3d(0.2, 0.2, 0.2);
  const Robot robot = MakePrimitiveObject("a", CapsuleGeometry(a));
  Environment env;
  AddObject(MakePrimitiveObject("box", box), Eigen::Isometry3d(Eigen::Translation3d(0.5, 0, 0)),
            "box", &env);
  CollisionData coll(robot, env);
  KinematicsData kin(robot);
  ForwardKinematics(robot, Eigen::VectorXd(0), &kin);
  std::vector<ProximityPair> pairs;
  ComputeProximity(robot, kin, 1.0, &coll, &pairs);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_NEAR(pairs[0].distance, 0.35, 1e-6);
}

}  // namespace
}  // namespace planning
