// Ferrari–Canny ε (L1, 8-edge friction pyramid, torque / radius of gyration) and the Wilson score
// interval.
#include "planning/grasp/grasp_quality.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <stdexcept>

namespace planning {
namespace {

GraspContact Contact(const Eigen::Vector3d& p, const Eigen::Vector3d& n) {
  GraspContact c;
  c.position = p;
  c.normal = n;
  return c;
}

EpsilonOptions Rho(double rho) {
  EpsilonOptions o;
  o.radius_of_gyration = rho;
  return o;
}

// Six contacts at the face centres ±R e_a of a cube (or a sphere of radius R), inward normals.
std::vector<GraspContact> SixFaces(double r, const Eigen::Vector3d& centre) {
  std::vector<GraspContact> contacts;
  for (int a = 0; a < 3; ++a) {
    for (double s : {1.0, -1.0}) {
      const Eigen::Vector3d p = s * r * Eigen::Vector3d::Unit(a);
      contacts.push_back(Contact(centre + p, -p.normalized()));
    }
  }
  return contacts;
}

// Antipodal pair: p1 = (R, 0, 0) with n1 = −e_x and p2 = −p1 with n2 = e_x, centre 0. Each edge
// carries a unit normal force plus μ·d, d a unit tangent in the y–z plane, so (force; torque/ρ)
//   w1(d) = (−1, μ d_y, μ d_z; 0, −k μ d_z,  k μ d_y),
//   w2(d) = ( 1, μ d_y, μ d_z; 0,  k μ d_z, −k μ d_y),   k = R/ρ.
// The torque about the grasp axis (τ_x) is 0 for every primitive wrench: the hull is flat in ℝ⁶,
// the origin is not strictly inside, and ε = 0 (point contacts cannot resist torsion about the
// line joining them) for every μ.
TEST(GraspQualityTest, AntipodalPairHandComputedWrenchesAndZeroEpsilon) {
  const double r = 0.03, rho = 0.02, mu = 0.7, k = r / rho;
  const std::vector<GraspContact> pair = {Contact({r, 0, 0}, {-1, 0, 0}),
                                          Contact({-r, 0, 0}, {1, 0, 0})};
  const auto w = PrimitiveWrenches(pair, Eigen::Vector3d::Zero(), mu, Rho(rho));
  ASSERT_EQ(w.cols(), 16);
  for (int j = 0; j < 16; ++j) {
    const double sign = j < 8 ? -1.0 : 1.0;  // contact 1, then contact 2
    const double dy = w(1, j) / mu, dz = w(2, j) / mu;
    EXPECT_NEAR(w(0, j), sign, 1e-12);
    EXPECT_NEAR(dy * dy + dz * dz, 1.0, 1e-12);  // unit tangent
    EXPECT_NEAR(w(3, j), 0.0, 1e-12);
    EXPECT_NEAR(w(4, j), sign * k * mu * dz, 1e-12);
    EXPECT_NEAR(w(5, j), -sign * k * mu * dy, 1e-12);
  }
  EXPECT_EQ(EpsilonQuality(pair, Eigen::Vector3d::Zero(), mu, Rho(rho)), 0.0);
}

// Six face contacts, ρ = R. Contact at s R e_a with n = −s e_a: w = (−s e_a + μ d; μ s e_a × d),
// d over the 8 pyramid directions in the tangent plane: the axes ±e_b, ±e_c and the diagonals
// (±e_b ± e_c)/√2. Along the pure-torque direction u = (0; 1, 1, 1)/√3 the support
// h(u) = max_j u·w_j is reached by the diagonal torques, e.g. e_x × (e_y − e_z)/√2 =
// (e_y + e_z)/√2: h(u) = μ · 2/√6 = μ √(2/3) (the axis torques give only μ/√3). The hyperplane
// u·w = μ√(2/3) supports a facet of the hull, so ε ≤ μ√(2/3); by the cube's symmetry no facet is
// closer (the force directions are bounded by the unit normal forces, ≥ 1 > μ√(2/3) for μ < 1):
// ε = μ √(2/3) = 0.8165 μ.
TEST(GraspQualityTest, SixFaceGraspHandComputedValue) {
  for (double mu : {0.25, 0.5, 0.9}) {
    const double eps = EpsilonQuality(SixFaces(0.04, Eigen::Vector3d::Zero()),
                                      Eigen::Vector3d::Zero(), mu, Rho(0.04));
    EXPECT_NEAR(eps, mu * std::sqrt(2.0 / 3.0), 1e-9) << "mu " << mu;
  }
}

TEST(GraspQualityTest, ZeroWithoutForceClosure) {
  const EpsilonOptions o = Rho(0.03);
  const Eigen::Vector3d c = Eigen::Vector3d::Zero();
  EXPECT_EQ(EpsilonQuality({}, c, 1.0, o), 0.0);
  EXPECT_EQ(EpsilonQuality({Contact({0.03, 0, 0}, {-1, 0, 0})}, c, 1.0, o), 0.0);
  // All normals parallel (a hand pushing from one side): the object can always escape along +z.
  std::vector<GraspContact> parallel;
  for (double x : {-0.02, 0.0, 0.02}) {
    for (double y : {-0.02, 0.02}) parallel.push_back(Contact({x, y, -0.03}, {0, 0, 1}));
  }
  EXPECT_EQ(EpsilonQuality(parallel, c, 0.5, o), 0.0);
  // Frictionless contacts on a sphere: every normal passes through the centre, no torque.
  EXPECT_EQ(EpsilonQuality(SixFaces(0.03, c), c, 0.0, o), 0.0);
}

TEST(GraspQualityTest, InvariantToContactOrderAndRigidMotion) {
  const Eigen::Vector3d c(0.1, -0.2, 0.3);
  std::vector<GraspContact> contacts = SixFaces(0.04, c);
  contacts[0].position += Eigen::Vector3d(0, 0.01, 0.005);  // break the symmetry a little
  contacts[3].normal = Eigen::Vector3d(0.1, -1, 0.05).normalized();
  const double eps = EpsilonQuality(contacts, c, 0.6, Rho(0.035));
  ASSERT_GT(eps, 0.0);
  std::vector<GraspContact> reversed(contacts.rbegin(), contacts.rend());
  EXPECT_NEAR(EpsilonQuality(reversed, c, 0.6, Rho(0.035)), eps, 1e-9);
  std::swap(contacts[1], contacts[4]);
  EXPECT_NEAR(EpsilonQuality(contacts, c, 0.6, Rho(0.035)), eps, 1e-9);
  // A translation of everything (rotations change the pyramid's orientation about the normals).
  std::vector<GraspContact> moved = contacts;
  const Eigen::Vector3d t(0.5, 0.25, -1.0);
  for (GraspContact& g : moved) g.position += t;
  EXPECT_NEAR(EpsilonQuality(moved, c + t, 0.6, Rho(0.035)), eps, 1e-9);
}

TEST(GraspQualityTest, ScalingBehaviour) {
  const Eigen::Vector3d c = Eigen::Vector3d::Zero();
  const double mu = 0.5;
  const double eps = EpsilonQuality(SixFaces(0.04, c), c, mu, Rho(0.04));
  // Geometry and ρ scaled together: ε unchanged (torque / ρ is scale-free).
  EXPECT_NEAR(EpsilonQuality(SixFaces(0.4, c), c, mu, Rho(0.4)), eps, 1e-9);
  // Only ρ doubled: every torque halves; here the torque facets are the nearest, so ε halves.
  EXPECT_NEAR(EpsilonQuality(SixFaces(0.04, c), c, mu, Rho(0.08)), eps / 2, 1e-9);
  // More friction never lowers ε (the pyramids grow).
  EXPECT_GT(EpsilonQuality(SixFaces(0.04, c), c, 0.8, Rho(0.04)), eps);
}

TEST(GraspQualityTest, RejectsBadInput) {
  const std::vector<GraspContact> six = SixFaces(0.04, Eigen::Vector3d::Zero());
  const Eigen::Vector3d c = Eigen::Vector3d::Zero();
  EXPECT_THROW(EpsilonQuality(six, c, -0.1, Rho(0.04)), std::invalid_argument);
  EXPECT_THROW(EpsilonQuality(six, c, 0.5, Rho(0.0)), std::invalid_argument);
  EpsilonOptions few = Rho(0.04);
  few.friction_edges = 2;
  EXPECT_THROW(EpsilonQuality(six, c, 0.5, few), std::invalid_argument);
  std::vector<GraspContact> bad = six;
  bad[2].normal = Eigen::Vector3d::Zero();
  EXPECT_THROW(EpsilonQuality(bad, c, 0.5, Rho(0.04)), std::invalid_argument);
}

// Wilson: centre = (p̂ + z²/2n)/(1 + z²/n), half = z/(1 + z²/n)·sqrt(p̂(1−p̂)/n + z²/4n²).
// n = 10, z = 1.959964: z² = 3.841459, 1 + z²/n = 1.3841459, z²/4n² = 0.0096036.
//   0/10: centre = 0.1920730/1.3841459 = 0.138766, half = 1.416009·sqrt(0.0096036) = 0.138766
//         → [0, 0.277533].
//   5/10: centre = 0.5, half = 1.416009·sqrt(0.025 + 0.0096036) = 0.263407 → [0.236593, 0.763407].
//  10/10: mirror of 0/10 → [0.722467, 1].
TEST(GraspQualityTest, WilsonIntervalKnownValues) {
  const Eigen::Vector2d none = WilsonInterval(0, 10);
  EXPECT_NEAR(none[0], 0.0, 1e-12);
  EXPECT_NEAR(none[1], 0.277533, 1e-5);
  const Eigen::Vector2d half = WilsonInterval(5, 10);
  EXPECT_NEAR(half[0], 0.236593, 1e-5);
  EXPECT_NEAR(half[1], 0.763407, 1e-5);
  const Eigen::Vector2d all = WilsonInterval(10, 10);
  EXPECT_NEAR(all[0], 0.722467, 1e-5);
  EXPECT_NEAR(all[1], 1.0, 1e-12);
  // 1/1 with z = 1: p̂ = 1, centre = 1.5/2 = 0.75, half = 0.5·sqrt(0.25) = 0.25 → [0.5, 1].
  const Eigen::Vector2d one = WilsonInterval(1, 1, 1.0);
  EXPECT_NEAR(one[0], 0.5, 1e-12);
  EXPECT_NEAR(one[1], 1.0, 1e-12);
  EXPECT_THROW(WilsonInterval(3, 2), std::invalid_argument);
  EXPECT_THROW(WilsonInterval(0, 0), std::invalid_argument);
  EXPECT_THROW(WilsonInterval(-1, 5), std::invalid_argument);
}

// Spearman: without ties ρ = 1 − 6 Σd² / (n(n² − 1)); x = 1..5, y = (2, 1, 4, 3, 5): d = (1, 1, 1,
// 1, 0), Σd² = 4, ρ = 1 − 24/120 = 0.8. With ties (ε against stable): x = (0.1, 0.5, 0.5, 0.9)
// has ranks (1, 2.5, 2.5, 4), y = (0, 1, 0, 1) ranks (1.5, 3.5, 1.5, 3.5), mean rank 2.5:
// Σ dx·dy = 1.5 + 0 + 0 + 1.5 = 3, Σ dx² = 4.5, Σ dy² = 4 → ρ = 3 / sqrt(18) = 0.7071068.
TEST(GraspQualityTest, SpearmanCorrelationKnownValues) {
  const std::optional<double> plain = SpearmanCorrelation({1, 2, 3, 4, 5}, {2, 1, 4, 3, 5});
  ASSERT_TRUE(plain.has_value());
  EXPECT_NEAR(*plain, 0.8, 1e-12);
  const std::optional<double> ties = SpearmanCorrelation({0.1, 0.5, 0.5, 0.9}, {0, 1, 0, 1});
  ASSERT_TRUE(ties.has_value());
  EXPECT_NEAR(*ties, 0.7071068, 1e-7);
  // Ranks only: a monotone transform of x changes nothing; reversing y flips the sign.
  EXPECT_NEAR(*SpearmanCorrelation({1, 20, 300, 4000, 50000}, {2, 1, 4, 3, 5}), 0.8, 1e-12);
  EXPECT_NEAR(*SpearmanCorrelation({1, 2, 3}, {3, 2, 1}), -1.0, 1e-12);
  EXPECT_FALSE(SpearmanCorrelation({1, 2, 3}, {1, 1, 1}).has_value());  // constant outcome
  EXPECT_FALSE(SpearmanCorrelation({1}, {1}).has_value());
  EXPECT_THROW(SpearmanCorrelation({1, 2}, {1}), std::invalid_argument);
  EXPECT_THROW(SpearmanCorrelation({1, std::nan("")}, {1, 2}), std::invalid_argument);
}

}  // namespace
}  // namespace planning
