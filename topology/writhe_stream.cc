#include "topology/writhe_stream.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "topology/gauss_far_field.h"
#include "topology/internal/compensated_sum.h"
#include "topology/internal/writhe_rows.h"
#include "topology/internal/writhe_tile.h"

namespace topology {
namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;
constexpr double kUnitRoundoff = std::numeric_limits<double>::epsilon() / 2.0;  // u = 2⁻⁵³
constexpr long long kParallelMinPairs = 200000;

using internal::CompensatedSum;

int ThreadCount(const WritheStreamOptions& o, long long pairs, int tasks) {
  // Small sums first: hardware_concurrency() reads /sys on every call (~10 µs, more than a
  // 32×32 Gauss integral; linking --batch calls this once per pair).
  if (pairs < kParallelMinPairs) return 1;
  const int n = o.threads > 0 ? o.threads : static_cast<int>(std::thread::hardware_concurrency());
  return std::max(1, std::min(n, tasks));
}

// Runs task(t, ws) for t in [0, tasks) on `threads` threads (the caller is one). Tasks are taken
// in order from a shared counter; each must write only its own outputs. progress(pairs done) is
// called on the calling thread after each of its tasks; if it (or a task) throws, the remaining
// tasks are skipped and the first exception is rethrown after every thread has joined.
template <typename Task>
void RunTasks(int tasks, int threads, const std::function<void(long long, long long)>& progress,
              long long pairs_per_task_total, const std::vector<long long>& task_pairs,
              Task&& task) {
  std::atomic<int> next{0};
  std::atomic<long long> done{0};
  std::atomic<bool> abort{false};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&](bool caller) {
    WritheWorkspace ws;
    try {
      for (;;) {
        if (abort.load(std::memory_order_relaxed)) return;
        const int t = next.fetch_add(1);
        if (t >= tasks) return;
        task(t, &ws);
        const long long d = done.fetch_add(task_pairs[t]) + task_pairs[t];
        if (caller && progress) progress(d, pairs_per_task_total);
      }
    } catch (...) {
      abort = true;
      const std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(static_cast<size_t>(threads - 1));
  for (int k = 1; k < threads; ++k) pool.emplace_back(work, false);
  work(true);
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

// Per row: the sum (four interleaved partial sums in a fixed order, added at the end), Σ|w|,
// Σ_j 1/|Z_j| for the kernel bound, and the degenerate pairs. Far pairs (|Z|² ≥ 1, almost all)
// take 1/|Z| ≤ 1 without a square root; the few near pairs their exact 1/|Z|.
class RowSumSink : public internal::WritheRowSink {
 public:
  RowSumSink(double* sum, double* abs_sum, double* bound, long long* degenerate)
      : sum_(sum), abs_sum_(abs_sum), bound_(bound), degenerate_(degenerate) {}
  void Row(int i, const double* w, const double* x, const double* y, int cols) override {
    double s[4] = {0.0, 0.0, 0.0, 0.0}, a[4] = {0.0, 0.0, 0.0, 0.0};
    int j = 0;
    for (; j + 3 < cols; j += 4) {
      for (int k = 0; k < 4; ++k) {
        s[k] += w[j + k];
        a[k] += std::abs(w[j + k]);
      }
    }
    for (; j < cols; ++j) {
      s[0] += w[j];
      a[0] += std::abs(w[j]);
    }
    double inv_mag = 0.0;
    long long degenerate = 0;
    for (j = 0; j < cols; ++j) {
      const double m2 = x[j] * x[j] + y[j] * y[j];
      if (m2 >= 1.0) {
        inv_mag += 1.0;
        if (x[j] == 1.0 && y[j] == 0.0) ++degenerate;
      } else {
        inv_mag += 1.0 / std::sqrt(m2);
      }
    }
    sum_[i] = (s[0] + s[1]) + (s[2] + s[3]);
    abs_sum_[i] = (a[0] + a[1]) + (a[2] + a[3]);
    // e_ij = u (1024/|Z| + 16)/(2π), summed; ×1.01 covers the rounding of these sums themselves.
    bound_[i] = 1.01 * kUnitRoundoff * (1024.0 * inv_mag + 16.0 * cols) / kTwoPi;
    degenerate_[i] = degenerate;
  }

 private:
  double *sum_, *abs_sum_, *bound_;
  long long* degenerate_;
};

// Rows [begin, end) by the SIMD kernel: per row the same four lane sums (j mod 4, the tail in
// lane 0) as RowSumSink, so the row sums are bitwise those of the scalar path given equal entries.
void SimdRowSums(const Chain& a, const std::vector<std::uint8_t>& a_degenerate,
                 const std::vector<double>& soa_b, int stride, const WritheOptions& opt, int begin,
                 int end, int cols, WritheWorkspace* ws, double* sum, double* abs_sum,
                 double* bound, long long* degenerate) {
  const int n = end - begin;
  ws->simd_scratch.assign(internal::TileScratchSize() + 12 * static_cast<size_t>(n), 0.0);
  internal::TileArgs t;
  t.a = a.data();
  t.a_degenerate = a_degenerate.data();
  t.SetB(soa_b, stride);
  t.row_begin = begin;
  t.row_end = end;
  t.col_end = t.cols = cols;
  t.degenerate_length = opt.degenerate_length;
  t.unsigned_variant = opt.variant == WritheVariant::kUnsignedSolidAngle;
  t.scratch = ws->simd_scratch.data();
  double* lanes = t.scratch + internal::TileScratchSize();
  t.out.lane_sum = lanes;
  t.out.lane_abs = lanes + 4 * n;
  t.out.lane_inv_mag = lanes + 8 * n;
  for (int i = begin; i < end; ++i) degenerate[i] = 0;
  t.out.degenerate = degenerate + begin;
  internal::WritheTile(t);
  for (int r = 0; r < n; ++r) {
    const double* s = t.out.lane_sum + 4 * r;
    const double* m = t.out.lane_abs + 4 * r;
    const double* v = t.out.lane_inv_mag + 4 * r;
    sum[begin + r] = (s[0] + s[1]) + (s[2] + s[3]);
    abs_sum[begin + r] = (m[0] + m[1]) + (m[2] + m[3]);
    const double inv_mag = (v[0] + v[1]) + (v[2] + v[3]);
    bound[begin + r] = 1.01 * kUnitRoundoff * (1024.0 * inv_mag + 16.0 * cols) / kTwoPi;
  }
}

}  // namespace

WritheSums StreamWritheSums(const Chain& a, const Chain& b, const WritheStreamOptions& options) {
  internal::CheckWritheChain(a, "A");
  internal::CheckWritheChain(b, "B");
  WritheSums out;
  out.rows = static_cast<int>(a.cols()) - 1;
  out.cols = static_cast<int>(b.cols()) - 1;
  if (options.far_field_tol != 0.0) {
    if (options.row_sums || options.writhe.variant != WritheVariant::kSigned) {
      throw std::invalid_argument(
          "far field (--tol): only for the signed total, not with row sums or the unsigned "
          "variant");
    }
    FarFieldOptions f;
    f.tol = options.far_field_tol;
    f.threads = options.threads;
    f.degenerate_length = options.writhe.degenerate_length;
    f.progress = options.progress;
    const FarFieldSums r = FarFieldGaussIntegral(a, b, f);
    out.total = r.total;
    out.error_bound = r.error_bound;
    out.degenerate_pairs = r.degenerate_pairs;
    out.abs_total = std::numeric_limits<double>::quiet_NaN();
    return out;
  }
  const long long pairs = static_cast<long long>(out.rows) * out.cols;
  const bool simd = out.cols >= internal::kMinSimdCols &&
                    internal::ActiveSimdLevel() != internal::SimdLevel::kScalar;
  // Units of work of ~2.6·10⁵ pairs (a few ms) so that progress and Ctrl-C respond quickly. The
  // SIMD kernel walks column tiles inside a unit and recomputes one row of directions per unit and
  // tile, so its units have at least 8 rows (~10⁶ pairs, ≤ 256 rows), and at least 4 per thread.
  int rows_per_task = std::max(1, std::min(out.rows, (1 << 18) / out.cols));
  if (simd) {
    const int threads = ThreadCount(options, pairs, out.rows);
    rows_per_task = std::clamp((1 << 20) / out.cols, 8, 256);
    if (threads > 1) rows_per_task = std::min(rows_per_task, out.rows / (4 * threads));
    rows_per_task = std::max(1, std::min(rows_per_task, out.rows));
  }
  const int tasks = (out.rows + rows_per_task - 1) / rows_per_task;
  std::vector<double> sum(out.rows), abs_sum(out.rows), bound(out.rows);
  std::vector<long long> degenerate(out.rows), task_pairs(tasks);
  for (int t = 0; t < tasks; ++t) {
    task_pairs[t] =
        static_cast<long long>(std::min(rows_per_task, out.rows - t * rows_per_task)) * out.cols;
  }
  std::vector<double> soa_b;
  std::vector<std::uint8_t> a_degenerate;
  int stride = 0;
  if (simd) {
    stride = internal::FillSoaChain(b, options.writhe.degenerate_length, &soa_b);
    internal::FillDegenerateSegments(a, options.writhe.degenerate_length, &a_degenerate);
  }
  RunTasks(tasks, ThreadCount(options, pairs, tasks), options.progress, pairs, task_pairs,
           [&](int t, WritheWorkspace* ws) {
             const int begin = t * rows_per_task;
             const int end = std::min(out.rows, begin + rows_per_task);
             if (simd) {
               SimdRowSums(a, a_degenerate, soa_b, stride, options.writhe, begin, end, out.cols, ws,
                           sum.data(), abs_sum.data(), bound.data(), degenerate.data());
               return;
             }
             RowSumSink sink(sum.data(), abs_sum.data(), bound.data(), degenerate.data());
             internal::WritheRows(a, b, options.writhe, begin, end, ws, &sink);
           });
  CompensatedSum total;
  double abs_total = 0.0, kernel_bound = 0.0;
  for (int i = 0; i < out.rows; ++i) {
    total.Add(sum[i]);
    abs_total += abs_sum[i];
    kernel_bound += bound[i];
    out.degenerate_pairs += degenerate[i];
  }
  out.total = total.Value();
  out.abs_total = abs_total;
  if (options.writhe.variant == WritheVariant::kUnsignedSolidAngle) kernel_bound *= 2.0 * kTwoPi;
  // Row sums: four recursive partial sums of ≤ ⌈cols/4⌉ + 2 terms, error ≤ (cols/4 + 2) u Σ|w|;
  // the rows: Neumaier, ≤ 3u Σ|r_i| ≤ 3u Σ|w|.
  const double sum_bound = (out.cols / 4.0 + 5.0) * kUnitRoundoff * abs_total;
  out.error_bound = 1.01 * (kernel_bound + sum_bound);
  if (options.row_sums) out.row_sums = Eigen::Map<const Eigen::VectorXd>(sum.data(), out.rows);
  return out;
}

namespace {

// Accumulates rows into one row of block sums: cells[q] += Σ_{j ∈ J_q} w[j].
class BlockRowSink : public internal::WritheRowSink {
 public:
  BlockRowSink(double* cells, int col_block) : cells_(cells), col_block_(col_block) {}
  void Row(int /*i*/, const double* w, const double*, const double*, int cols) override {
    for (int q = 0, j0 = 0; j0 < cols; ++q, j0 += col_block_) {
      const int j1 = std::min(cols, j0 + col_block_);
      double s = 0.0;
      for (int j = j0; j < j1; ++j) s += w[j];
      cells_[q] += s;
    }
  }

 private:
  double* cells_;
  int col_block_;
};

// Rows [begin, end) into one row of block sums by the SIMD kernel, in column chunks: the same
// additions in the same order as BlockRowSink (per row and block a sum from 0 in increasing j,
// then added to the cell, rows in order), the open block's partial sum carried across chunks.
void SimdBlockRow(const Chain& a, const std::vector<std::uint8_t>& a_degenerate,
                  const std::vector<double>& soa_b, int stride, const WritheOptions& opt, int begin,
                  int end, int cols, int col_block, WritheWorkspace* ws, double* cells) {
  constexpr int kChunk = 2 * internal::kTileCols;
  const int n = end - begin;
  ws->simd_scratch.resize(internal::TileScratchSize() + static_cast<size_t>(n) * (kChunk + 1));
  internal::TileArgs t;
  t.a = a.data();
  t.a_degenerate = a_degenerate.data();
  t.SetB(soa_b, stride);
  t.row_begin = begin;
  t.row_end = end;
  t.cols = cols;
  t.degenerate_length = opt.degenerate_length;
  t.unsigned_variant = opt.variant == WritheVariant::kUnsignedSolidAngle;
  t.scratch = ws->simd_scratch.data();
  double* w = t.scratch + internal::TileScratchSize();  // n × kChunk, column-major
  double* open = w + static_cast<size_t>(n) * kChunk;   // per row: the open block's partial sum
  std::fill(open, open + n, 0.0);
  t.out.dense = w;
  t.out.ld = n;
  t.out.dense_row0 = begin;
  for (int c0 = 0; c0 < cols; c0 += kChunk) {
    const int c1 = std::min(cols, c0 + kChunk);
    t.col_begin = c0;
    t.col_end = c1;
    t.out.dense_col0 = c0;
    internal::WritheTile(t);
    for (int r = 0; r < n; ++r) {
      for (int j0 = c0; j0 < c1;) {
        const int q = j0 / col_block;
        const int block_end = std::min(cols, (q + 1) * col_block);
        const int j1 = std::min(c1, block_end);
        double s = open[r];
        for (int j = j0; j < j1; ++j) s += w[r + static_cast<size_t>(j - c0) * n];
        if (j1 == block_end) {
          cells[q] += s;
          s = 0.0;
        }
        open[r] = s;
        j0 = j1;
      }
    }
  }
}

}  // namespace

WritheBlockSums BlockWritheSums(const Chain& a, const Chain& b, int max_rows, int max_cols,
                                const WritheStreamOptions& options) {
  internal::CheckWritheChain(a, "A");
  internal::CheckWritheChain(b, "B");
  if (max_rows < 1 || max_cols < 1) {
    throw std::invalid_argument("BlockWritheSums: at most " + std::to_string(max_rows) + "x" +
                                std::to_string(max_cols) + " blocks; both must be >= 1");
  }
  const int rows = static_cast<int>(a.cols()) - 1, cols = static_cast<int>(b.cols()) - 1;
  WritheBlockSums out;
  out.row_block = (rows + max_rows - 1) / max_rows;
  out.col_block = (cols + max_cols - 1) / max_cols;
  const int block_rows = (rows + out.row_block - 1) / out.row_block;
  const int block_cols = (cols + out.col_block - 1) / out.col_block;
  // Row-major scratch (one contiguous row of cells per task), copied into `sums` at the end.
  std::vector<double> cells(static_cast<size_t>(block_rows) * block_cols, 0.0);
  std::vector<long long> task_pairs(block_rows);
  for (int p = 0; p < block_rows; ++p) {
    task_pairs[p] =
        static_cast<long long>(std::min(out.row_block, rows - p * out.row_block)) * cols;
  }
  const long long pairs = static_cast<long long>(rows) * cols;
  const bool simd =
      cols >= internal::kMinSimdCols && internal::ActiveSimdLevel() != internal::SimdLevel::kScalar;
  std::vector<double> soa_b;
  std::vector<std::uint8_t> a_degenerate;
  int stride = 0;
  if (simd) {
    stride = internal::FillSoaChain(b, options.writhe.degenerate_length, &soa_b);
    internal::FillDegenerateSegments(a, options.writhe.degenerate_length, &a_degenerate);
  }
  RunTasks(block_rows, ThreadCount(options, pairs, block_rows), options.progress, pairs, task_pairs,
           [&](int p, WritheWorkspace* ws) {
             double* row_cells = cells.data() + static_cast<size_t>(p) * block_cols;
             const int begin = p * out.row_block;
             const int end = std::min(rows, begin + out.row_block);
             if (simd) {
               SimdBlockRow(a, a_degenerate, soa_b, stride, options.writhe, begin, end, cols,
                            out.col_block, ws, row_cells);
               return;
             }
             BlockRowSink sink(row_cells, out.col_block);
             internal::WritheRows(a, b, options.writhe, begin, end, ws, &sink);
           });
  out.sums =
      Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
          cells.data(), block_rows, block_cols);
  return out;
}

bool IsClosedChain(const Chain& c) {
  if (c.cols() < 4 || !c.allFinite()) return false;
  const double size = (c.rowwise().maxCoeff() - c.rowwise().minCoeff()).norm();
  return (c.col(c.cols() - 1) - c.col(0)).norm() <= kClosedGap * size;
}

namespace internal {

const Chain& CheckClosedSnapped(const Chain& c, const char* name, Chain* copy) {
  CheckWritheChain(c, name);
  if (!IsClosedChain(c)) {
    std::string msg = "linking number: chain ";
    msg.append(name).append(
        " is not closed (a closed chain has >= 4 points and repeats its first point as its "
        "last, up to 1e-9 of its size); the linking number is defined only for closed curves");
    throw std::invalid_argument(msg);
  }
  if (c.col(0) == c.col(c.cols() - 1)) return c;
  *copy = c;
  copy->col(c.cols() - 1) = c.col(0);
  return *copy;
}

}  // namespace internal

LinkingResult LinkingNumber(const Chain& a, const Chain& b, const WritheStreamOptions& options) {
  // A last point within the closing gap of the first is moved onto it (copies only then).
  Chain snapped_a, snapped_b;
  const Chain& ca = internal::CheckClosedSnapped(a, "A", &snapped_a);
  const Chain& cb = internal::CheckClosedSnapped(b, "B", &snapped_b);
  WritheStreamOptions o = options;
  o.writhe.variant = WritheVariant::kSigned;
  o.row_sums = false;
  const WritheSums s = StreamWritheSums(ca, cb, o);
  LinkingResult r;
  r.gauss_integral = s.total;
  r.error_bound = s.error_bound;
  const double nearest = std::nearbyint(s.total);
  r.distance = std::abs(s.total - nearest);
  r.linking_number = static_cast<long long>(nearest);
  r.degenerate_pairs = s.degenerate_pairs;
  r.segments_a = s.rows;
  r.segments_b = s.cols;
  if (s.degenerate_pairs > 0) {
    r.status = LinkingStatus::kTouching;
  } else if (!(s.error_bound < 0.5)) {
    r.status = LinkingStatus::kUncertain;
  } else if (r.distance > s.error_bound) {
    r.status = LinkingStatus::kNotInteger;
  } else {
    r.status = LinkingStatus::kCertified;
  }
  return r;
}

}  // namespace topology
