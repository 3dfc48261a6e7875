// Barnes–Hut Gauss integral (topology/gauss_far_field.h) against the exact streamed total.
#include "topology/gauss_far_field.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "tests/topology/test_chains.h"
#include "topology/writhe_stream.h"

namespace topology {
namespace {

// A random smooth closed curve: x(t) = c + Σ_{k=1..3} (p_k cos kt + q_k sin kt) / k, n segments.
Chain RandomSmoothCurve(int n, const Eigen::Vector3d& c, std::mt19937* rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::Vector3d p[3], q[3];
  for (int k = 0; k < 3; ++k) {
    p[k] = Eigen::Vector3d(g(*rng), g(*rng), g(*rng));
    q[k] = Eigen::Vector3d(g(*rng), g(*rng), g(*rng));
  }
  return testing::ClosedCurve(
      [&](double t) {
        Eigen::Vector3d x = c;
        for (int k = 0; k < 3; ++k)
          x += (p[k] * std::cos((k + 1) * t) + q[k] * std::sin((k + 1) * t)) / (k + 1);
        return x;
      },
      n);
}

double Exact(const Chain& a, const Chain& b) {
  WritheStreamOptions o;
  o.threads = 1;
  return StreamWritheSums(a, b, o).total;
}

TEST(GaussFarFieldTest, WithinTheBoundOnRandomSmoothCurves) {
  std::mt19937 rng(21);
  for (int trial = 0; trial < 4; ++trial) {
    const int na = 3000 + 700 * trial, nb = 2500 + 900 * trial;
    const Chain a = RandomSmoothCurve(na, {0, 0, 0}, &rng);
    const Chain b = RandomSmoothCurve(nb, {0.5, 0.2, 0}, &rng);
    const double exact = Exact(a, b);
    for (double tol : {1e-1, 1e-3, 1e-6}) {
      FarFieldOptions o;
      o.tol = tol;
      o.threads = 1 + trial % 2;
      const FarFieldSums s = FarFieldGaussIntegral(a, b, o);
      const std::string what = std::to_string(trial) + " tol " + std::to_string(tol);
      EXPECT_LE(s.approximation_bound, tol * (1 + 1e-12)) << what;
      EXPECT_LE(std::abs(s.total - exact), s.error_bound) << what;
      EXPECT_LE(s.exact_pairs, static_cast<long long>(na) * nb) << what;  // n segments each
      if (tol >= 1e-3) {
        EXPECT_GT(s.far_node_pairs, 0) << what;
        EXPECT_LT(s.exact_pairs, static_cast<long long>(na) * nb) << what;
      }
    }
  }
}

TEST(GaussFarFieldTest, WithinTheBoundOnRandomWalks) {
  // Compact, tangled walks: the bound's budget rarely admits far pairs, but whatever is used
  // must stay inside it.
  std::mt19937 rng(4);
  for (int trial = 0; trial < 3; ++trial) {
    const Chain a = testing::RandomChain(1500 + 200 * trial, 0.05, {0, 0, 0}, &rng);
    const Chain b = testing::RandomChain(1300, 0.05, {1.5 * trial, 0.1, 0}, &rng);
    FarFieldOptions o;
    o.tol = 0.2;
    const FarFieldSums s = FarFieldGaussIntegral(a, b, o);
    EXPECT_LE(std::abs(s.total - Exact(a, b)), s.error_bound) << trial;
    EXPECT_EQ(s.degenerate_pairs, 0);
  }
}

TEST(GaussFarFieldTest, SecondOrderExpansionOfOneFarPairIsAccurate) {
  // Two short chains far apart: with a loose tol the whole product is one far node pair.
  std::mt19937 rng(2);
  const Chain a = testing::RandomChain(20, 0.1, {0, 0, 0}, &rng);
  const Chain b = testing::RandomChain(20, 0.1, {20, 5, 3}, &rng);
  FarFieldOptions o;
  o.tol = 1.0;
  o.leaf_segments = 8;
  const FarFieldSums s = FarFieldGaussIntegral(a, b, o);
  EXPECT_EQ(s.exact_pairs, 0);  // every task's A node meets B as one far pair
  const double exact = Exact(a, b);
  EXPECT_LE(std::abs(s.total - exact), s.error_bound);
  EXPECT_LE(std::abs(s.total - exact), 1e-3 * std::abs(exact));  // third order in (size/d)
}

TEST(GaussFarFieldTest, LinkingNumberOfATorusLinkIsCertified) {
  const Chain a = testing::TorusLinkComponent(3, 0, 6000);
  const Chain b = testing::TorusLinkComponent(3, 1, 6000);
  WritheStreamOptions o;
  o.far_field_tol = 0.05;
  const LinkingResult far = LinkingNumber(a, b, o);
  const LinkingResult exact = LinkingNumber(a, b);
  EXPECT_EQ(far.status, LinkingStatus::kCertified);
  EXPECT_EQ(far.linking_number, exact.linking_number);
  EXPECT_LE(std::abs(far.gauss_integral - exact.gauss_integral), far.error_bound);
  EXPECT_LE(far.error_bound, 0.05 + 1e-6);
}

TEST(GaussFarFieldTest, ResultDoesNotDependOnThreads) {
  std::mt19937 rng(8);
  const Chain a = testing::RandomChain(3000, 0.05, {0, 0, 0}, &rng);
  const Chain b = testing::RandomChain(2500, 0.05, {0.2, 0, 0}, &rng);
  FarFieldOptions o;
  o.tol = 1e-4;
  o.threads = 1;
  const FarFieldSums one = FarFieldGaussIntegral(a, b, o);
  o.threads = 3;
  const FarFieldSums three = FarFieldGaussIntegral(a, b, o);
  EXPECT_EQ(one.total, three.total);
  EXPECT_EQ(one.error_bound, three.error_bound);
}

TEST(GaussFarFieldTest, RejectsBadTolerance) {
  std::mt19937 rng(1);
  const Chain a = testing::RandomChain(10, 0.1, {0, 0, 0}, &rng);
  for (double tol : {0.0, -1.0, std::nan("")}) {
    FarFieldOptions o;
    o.tol = tol;
    EXPECT_THROW(FarFieldGaussIntegral(a, a, o), std::invalid_argument);
  }
}

}  // namespace
}  // namespace topology
