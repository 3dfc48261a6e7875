// The SIMD writhe kernel (topology/internal/writhe_tile.h) against the scalar per-row kernel, the
// oracle: AVX2 (when the CPU has it) and SSE2 paths, dense matrix and streamed sums, on random
// chains of awkward sizes (not multiples of 4, more than one column tile) and degenerate input.
#include "topology/internal/writhe_tile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "tests/topology/test_chains.h"
#include "topology/writhe.h"
#include "topology/writhe_stream.h"

namespace topology {
namespace {

using internal::SimdLevel;

// Restores automatic dispatch when a test ends.
class LevelGuard {
 public:
  explicit LevelGuard(SimdLevel level) { internal::SetSimdLevel(level); }
  ~LevelGuard() { internal::SetSimdLevel(SimdLevel::kAuto); }
};

std::vector<SimdLevel> SimdLevels() {
  std::vector<SimdLevel> levels = {SimdLevel::kSse2};
  if (__builtin_cpu_supports("avx2")) levels.push_back(SimdLevel::kAvx2);
  return levels;
}

const char* Name(SimdLevel level) { return level == SimdLevel::kAvx2 ? "avx2" : "sse2"; }

Eigen::MatrixXd MatrixAt(SimdLevel level, const Chain& a, const Chain& b, const WritheOptions& o) {
  const LevelGuard guard(level);
  return WritheMatrix(a, b, o);
}

// A random walk with some repeated points (zero-length segments), one point of B placed on a
// segment of A (a touching pair) and one B segment crossing an A segment in a common plane.
void AddDegeneracies(Chain* a, Chain* b) {
  if (a->cols() > 6) a->col(4) = a->col(3);
  if (b->cols() > 6) b->col(2) = b->col(1);
  if (a->cols() > 3 && b->cols() > 9) b->col(8) = 0.5 * (a->col(1) + a->col(2));
}

TEST(WritheTileTest, DenseMatrixMatchesScalarKernelPerEntry) {
  std::mt19937 rng(7);
  const std::pair<int, int> sizes[] = {{2, 2},    {2, 3},    {3, 4},     {5, 6},     {9, 8},
                                       {17, 258}, {40, 257}, {130, 513}, {300, 300}, {7, 1100}};
  for (const auto& [na, nb] : sizes) {
    for (int degenerate = 0; degenerate < 2; ++degenerate) {
      Chain a = testing::RandomChain(na, 0.1, {0, 0, 0}, &rng);
      Chain b = testing::RandomChain(nb, 0.1, {0.05, 0.02, 0}, &rng);
      if (degenerate) AddDegeneracies(&a, &b);
      for (WritheVariant v : {WritheVariant::kSigned, WritheVariant::kUnsignedSolidAngle}) {
        WritheOptions o;
        o.variant = v;
        const Eigen::MatrixXd ref = MatrixAt(SimdLevel::kScalar, a, b, o);
        for (SimdLevel level : SimdLevels()) {
          const Eigen::MatrixXd w = MatrixAt(level, a, b, o);
          ASSERT_EQ(w.rows(), ref.rows());
          ASSERT_EQ(w.cols(), ref.cols());
          double worst = 0.0;
          for (Eigen::Index k = 0; k < w.size(); ++k) {
            const double d = std::abs(w.data()[k] - ref.data()[k]);
            const double scale = std::abs(ref.data()[k]);
            if (ref.data()[k] == 0.0) {
              EXPECT_EQ(w.data()[k], 0.0) << Name(level) << " " << na << "x" << nb << " " << k;
            } else {
              worst = std::max(worst, d / scale);
            }
          }
          EXPECT_LE(worst, 1e-12) << Name(level) << " " << na << "x" << nb;
        }
      }
    }
  }
}

TEST(WritheTileTest, JacobianMatchesScalarKernel) {
  std::mt19937 rng(5);
  const std::pair<int, int> sizes[] = {{2, 2}, {3, 6}, {21, 2}, {33, 259}, {120, 97}};
  for (const auto& [na, nb] : sizes) {
    Chain a = testing::RandomChain(na, 0.1, {0, 0, 0}, &rng);
    Chain b = testing::RandomChain(nb, 0.1, {0.05, 0.02, 0}, &rng);
    AddDegeneracies(&a, &b);
    for (WritheVariant v : {WritheVariant::kSigned, WritheVariant::kUnsignedSolidAngle}) {
      WritheOptions o;
      o.variant = v;
      Eigen::MatrixXd w_ref, w;
      WritheJacobian jac_ref, jac;
      WritheWorkspace ws;
      {
        const LevelGuard guard(SimdLevel::kScalar);
        WritheMatrixWithJacobian(a, b, o, &w_ref, &jac_ref, &ws);
      }
      for (SimdLevel level : SimdLevels()) {
        const LevelGuard guard(level);
        WritheMatrixWithJacobian(a, b, o, &w, &jac, &ws);
        ASSERT_EQ(jac.pair.cols(), jac_ref.pair.cols());
        EXPECT_EQ(jac.rows, jac_ref.rows);
        EXPECT_EQ(jac.cols, jac_ref.cols);
        EXPECT_LE((w - w_ref).cwiseAbs().maxCoeff(), 1e-12 * w_ref.cwiseAbs().maxCoeff());
        for (Eigen::Index k = 0; k < jac.pair.cols(); ++k) {
          const double scale = jac_ref.pair.col(k).cwiseAbs().maxCoeff();
          ASSERT_LE((jac.pair.col(k) - jac_ref.pair.col(k)).cwiseAbs().maxCoeff(), 1e-12 * scale)
              << Name(level) << " " << na << "x" << nb << " pair " << k;
        }
      }
    }
  }
}

TEST(WritheTileTest, StreamedSumsMatchScalarKernel) {
  std::mt19937 rng(11);
  const std::pair<int, int> sizes[] = {{2, 2}, {3, 7}, {65, 258}, {600, 501}, {1001, 1003}};
  for (const auto& [na, nb] : sizes) {
    Chain a = testing::RandomChain(na, 0.1, {0, 0, 0}, &rng);
    Chain b = testing::RandomChain(nb, 0.1, {0.05, 0, 0}, &rng);
    AddDegeneracies(&a, &b);
    for (WritheVariant v : {WritheVariant::kSigned, WritheVariant::kUnsignedSolidAngle}) {
      WritheStreamOptions o;
      o.writhe.variant = v;
      o.row_sums = true;
      o.threads = 1;
      WritheSums ref;
      {
        const LevelGuard guard(SimdLevel::kScalar);
        ref = StreamWritheSums(a, b, o);
      }
      for (SimdLevel level : SimdLevels()) {
        for (int threads : {1, 2, 3}) {
          o.threads = threads;
          const LevelGuard guard(level);
          const WritheSums s = StreamWritheSums(a, b, o);
          const std::string what = std::string(Name(level)) + " " + std::to_string(na) + "x" +
                                   std::to_string(nb) + " threads " + std::to_string(threads);
          EXPECT_LE(std::abs(s.total - ref.total), 1e-12 * ref.abs_total) << what;
          EXPECT_LE(std::abs(s.abs_total - ref.abs_total), 1e-12 * ref.abs_total) << what;
          EXPECT_LE(std::abs(s.error_bound - ref.error_bound), 1e-12 * ref.error_bound) << what;
          EXPECT_EQ(s.degenerate_pairs, ref.degenerate_pairs) << what;
          ASSERT_EQ(s.row_sums.size(), ref.row_sums.size());
          EXPECT_LE((s.row_sums - ref.row_sums).cwiseAbs().maxCoeff(), 1e-12 * ref.abs_total)
              << what;
        }
      }
    }
  }
}

TEST(WritheTileTest, BlockSumsMatchScalarKernel) {
  std::mt19937 rng(13);
  struct Case {
    int na, nb, max_rows, max_cols;
  };
  const Case cases[] = {{9, 8, 3, 2},      {40, 1100, 7, 9},   {300, 517, 256, 256},
                        {120, 2050, 1, 1}, {65, 700, 64, 700}, {33, 4, 5, 3}};
  for (const Case& c : cases) {
    Chain a = testing::RandomChain(c.na, 0.1, {0, 0, 0}, &rng);
    Chain b = testing::RandomChain(c.nb, 0.1, {0.05, 0, 0}, &rng);
    AddDegeneracies(&a, &b);
    WritheStreamOptions o;
    o.threads = 2;
    WritheBlockSums ref;
    {
      const LevelGuard guard(SimdLevel::kScalar);
      ref = BlockWritheSums(a, b, c.max_rows, c.max_cols, o);
    }
    for (SimdLevel level : SimdLevels()) {
      const LevelGuard guard(level);
      const WritheBlockSums s = BlockWritheSums(a, b, c.max_rows, c.max_cols, o);
      ASSERT_EQ(s.sums.rows(), ref.sums.rows());
      ASSERT_EQ(s.sums.cols(), ref.sums.cols());
      EXPECT_EQ(s.row_block, ref.row_block);
      EXPECT_EQ(s.col_block, ref.col_block);
      const double scale = std::max(1.0, ref.sums.cwiseAbs().maxCoeff());
      EXPECT_LE((s.sums - ref.sums).cwiseAbs().maxCoeff(), 1e-12 * scale)
          << Name(level) << " " << c.na << "x" << c.nb;
    }
  }
}

TEST(WritheTileTest, SumsAreBitwiseIndependentOfThreads) {
  std::mt19937 rng(3);
  const Chain a = testing::RandomChain(700, 0.1, {0, 0, 0}, &rng);
  const Chain b = testing::RandomChain(903, 0.1, {0.05, 0, 0}, &rng);
  WritheStreamOptions o;
  o.row_sums = true;
  o.threads = 1;
  const WritheSums one = StreamWritheSums(a, b, o);
  for (int threads : {2, 3, 5}) {
    o.threads = threads;
    const WritheSums s = StreamWritheSums(a, b, o);
    EXPECT_EQ(s.total, one.total) << threads;
    EXPECT_EQ(s.error_bound, one.error_bound) << threads;
    EXPECT_TRUE(s.row_sums == one.row_sums) << threads;
  }
}

TEST(WritheTileTest, LinkingNumbersAgreeAcrossKernels) {
  for (int k : {1, 3}) {
    const Chain a = testing::TorusLinkComponent(k, 0, 333);
    const Chain b = testing::TorusLinkComponent(k, 1, 517);
    for (SimdLevel level : {SimdLevel::kScalar, SimdLevel::kSse2, SimdLevel::kAvx2}) {
      if (level == SimdLevel::kAvx2 && !__builtin_cpu_supports("avx2")) continue;
      const LevelGuard guard(level);
      const LinkingResult r = LinkingNumber(a, b);
      EXPECT_EQ(r.status, LinkingStatus::kCertified);
      EXPECT_EQ(std::llabs(r.linking_number), k);  // the sign depends on orientation
    }
  }
}

}  // namespace
}  // namespace topology
