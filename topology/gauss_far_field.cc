#include "topology/gauss_far_field.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "topology/internal/compensated_sum.h"
#include "topology/internal/writhe_rows.h"
#include "topology/internal/writhe_tile.h"

namespace topology {
namespace {

constexpr double kPi = 3.141592653589793238462643383279;
constexpr double kUnitRoundoff = std::numeric_limits<double>::epsilon() / 2.0;

using Eigen::Matrix3d;
using Eigen::Vector3d;

// One node of a chain's tree: segments [lo, hi) (lo a multiple of 4), centre c, radius r ≥ |x − c|
// for every point x of its segments, length L and the moments about c (header): T = Σ t,
// m(k, j) = M_k,j = Σ ∫ α_k dx_j, q[k](l, j) = Q_kl,j = Σ ∫ α_k α_l dx_j.
struct Node {
  int lo = 0, hi = 0, left = -1, right = -1;
  Vector3d c = Vector3d::Zero(), box_min, box_max;
  double r = 0.0, len = 0.0;
  Vector3d t = Vector3d::Zero();
  Matrix3d m = Matrix3d::Zero();
  Matrix3d q[3] = {Matrix3d::Zero(), Matrix3d::Zero(), Matrix3d::Zero()};
};

int Build(const Chain& p, int lo, int hi, int leaf, std::vector<Node>* nodes) {
  const int id = static_cast<int>(nodes->size());
  nodes->emplace_back();
  Node n;
  n.lo = lo;
  n.hi = hi;
  if (hi - lo <= leaf) {
    n.box_min = n.box_max = p.col(lo);
    for (int i = lo + 1; i <= hi; ++i) {
      n.box_min = n.box_min.cwiseMin(p.col(i));
      n.box_max = n.box_max.cwiseMax(p.col(i));
    }
    n.c = 0.5 * (n.box_min + n.box_max);
    for (int i = lo; i <= hi; ++i) n.r = std::max(n.r, (p.col(i) - n.c).norm());
    for (int i = lo; i < hi; ++i) {
      const Vector3d t = p.col(i + 1) - p.col(i);
      const Vector3d alpha = 0.5 * (p.col(i) + p.col(i + 1)) - n.c;  // midpoint − c
      n.len += t.norm();
      n.t += t;
      n.m += alpha * t.transpose();
      // ∫ (α + u t)_k (α + u t)_l t_j du over u ∈ [−1/2, 1/2] = (α_k α_l + t_k t_l / 12) t_j.
      const Matrix3d aa = alpha * alpha.transpose() + t * t.transpose() / 12.0;
      for (int k = 0; k < 3; ++k) n.q[k] += aa.col(k) * t.transpose();
    }
  } else {
    const int mid = ((lo + hi) / 2) & ~3;  // keeps every node's first segment a multiple of 4
    n.left = Build(p, lo, mid, leaf, nodes);
    n.right = Build(p, mid, hi, leaf, nodes);
    const Node& a = (*nodes)[n.left];
    const Node& b = (*nodes)[n.right];
    n.box_min = a.box_min.cwiseMin(b.box_min);
    n.box_max = a.box_max.cwiseMax(b.box_max);
    n.c = 0.5 * (n.box_min + n.box_max);
    for (const Node* child : {&a, &b}) {
      // Moments about the new centre: α = α_child + e.
      const Vector3d e = child->c - n.c;
      n.r = std::max(n.r, e.norm() + child->r);
      n.len += child->len;
      n.t += child->t;
      n.m += child->m + e * child->t.transpose();
      for (int k = 0; k < 3; ++k) {
        for (int l = 0; l < 3; ++l) {
          n.q[k].row(l) += child->q[k].row(l) + e(k) * child->m.row(l) + e(l) * child->m.row(k) +
                           e(k) * e(l) * child->t.transpose();
        }
      }
    }
  }
  (*nodes)[id] = n;
  return id;
}

// 4π × the node pair's contribution to T, from the moments (second-order expansion of K(r₀ + δ),
// δ = α − β): K·(T_A × T_B) + Σ_k ∂_k K · V_k + ½ Σ_kl ∂_k ∂_l K · V_kl with
// V_k = M_A,k × T_B − T_A × M_B,k and V_kl = Q_A,kl × T_B − M_A,k × M_B,l − M_A,l × M_B,k +
// T_A × Q_B,kl.
double FarPair(const Node& a, const Node& b) {
  const Vector3d r = a.c - b.c;
  const double d2 = r.squaredNorm(), d = std::sqrt(d2);
  const double inv3 = 1.0 / (d2 * d), inv5 = inv3 / d2, inv7 = inv5 / d2;
  double sum = (r * inv3).dot(a.t.cross(b.t));
  for (int k = 0; k < 3; ++k) {
    const Vector3d v = Vector3d(a.m.row(k)).cross(b.t) - a.t.cross(Vector3d(b.m.row(k)));
    // ∂_k K_j = δ_jk / d³ − 3 r_j r_k / d⁵
    sum += v(k) * inv3 - 3.0 * r(k) * inv5 * r.dot(v);
  }
  double second = 0.0;
  for (int k = 0; k < 3; ++k) {
    for (int l = 0; l < 3; ++l) {
      const Vector3d mak(a.m.row(k)), mal(a.m.row(l)), mbk(b.m.row(k)), mbl(b.m.row(l));
      const Vector3d v = Vector3d(a.q[k].row(l)).cross(b.t) - mak.cross(mbl) - mal.cross(mbk) +
                         a.t.cross(Vector3d(b.q[k].row(l)));
      // ∂_k ∂_l K_j = −3 (δ_jk r_l + δ_jl r_k + δ_kl r_j) / d⁵ + 15 r_j r_k r_l / d⁷
      const double rv = r.dot(v);
      second += -3.0 * inv5 * (v(k) * r(l) + v(l) * r(k) + (k == l ? rv : 0.0)) +
                15.0 * inv7 * r(k) * r(l) * rv;
    }
  }
  return sum + 0.5 * second;
}

using internal::CompensatedSum;

// What one task (an A node against the whole of B) accumulates besides the per-row lane sums.
struct TaskResult {
  CompensatedSum far;
  double approximation = 0.0, far_rounding = 0.0;
  long long exact_pairs = 0, far_node_pairs = 0;
};

struct Context {
  const std::vector<Node>* ta;
  const std::vector<Node>* tb;
  double accept;  // tol / (L_A L_B): a far pair is used when s³/(π (d − s)⁵) ≤ accept
  internal::TileArgs tile;  // chains, flags and lane outputs; the rectangle is set per leaf pair
};

void Interact(const Context& ctx, int ia, int ib, double* scratch, TaskResult* out) {
  const Node& a = (*ctx.ta)[ia];
  const Node& b = (*ctx.tb)[ib];
  const double d = (a.c - b.c).norm(), s = a.r + b.r;
  if (d > s) {
    const double gap = d - s;
    const double e = s * s * s / (kPi * gap * gap * gap * gap * gap);
    if (e <= ctx.accept) {
      out->far.Add(FarPair(a, b) / (4.0 * kPi));
      out->approximation += e * a.len * b.len;
      // Rounding of the moments (sums over ≤ 10⁵ segments) and of the expansion (terms of at
      // most ~10² L_A L_B / d²): generously 10⁵ u of the pair's scale L_A L_B / (d − s)².
      out->far_rounding += 1e5 * kUnitRoundoff * a.len * b.len / (gap * gap);
      ++out->far_node_pairs;
      return;
    }
  }
  const bool leaf_a = a.left < 0, leaf_b = b.left < 0;
  if (leaf_a && leaf_b) {
    // ctx.tile's outputs are for row 0; the kernel indexes them from row_begin.
    internal::TileArgs tile = ctx.tile;
    tile.row_begin = a.lo;
    tile.row_end = a.hi;
    tile.col_begin = b.lo;
    tile.col_end = b.hi;
    tile.scratch = scratch;
    tile.out.lane_sum += 4 * static_cast<size_t>(a.lo);
    tile.out.lane_abs += 4 * static_cast<size_t>(a.lo);
    tile.out.lane_inv_mag += 4 * static_cast<size_t>(a.lo);
    tile.out.degenerate += a.lo;
    internal::WritheTile(tile);
    out->exact_pairs += static_cast<long long>(a.hi - a.lo) * (b.hi - b.lo);
  } else if (leaf_b || (!leaf_a && a.r >= b.r)) {
    Interact(ctx, a.left, ib, scratch, out);
    Interact(ctx, a.right, ib, scratch, out);
  } else {
    Interact(ctx, ia, b.left, scratch, out);
    Interact(ctx, ia, b.right, scratch, out);
  }
}

}  // namespace

FarFieldSums FarFieldGaussIntegral(const Chain& a, const Chain& b, const FarFieldOptions& options) {
  internal::CheckWritheChain(a, "A");
  internal::CheckWritheChain(b, "B");
  if (!(options.tol > 0.0) || !std::isfinite(options.tol)) {
    throw std::invalid_argument("far field: tol must be a positive number, got " +
                                std::to_string(options.tol));
  }
  FarFieldSums out;
  out.rows = static_cast<int>(a.cols()) - 1;
  out.cols = static_cast<int>(b.cols()) - 1;
  const int leaf = std::max(8, (options.leaf_segments + 3) & ~3);
  std::vector<Node> ta, tb;
  ta.reserve(4 * (out.rows / leaf + 1));
  tb.reserve(4 * (out.cols / leaf + 1));
  Build(a, 0, out.rows, leaf, &ta);
  Build(b, 0, out.cols, leaf, &tb);

  // Tasks: A nodes of a fixed frontier (≥ 64 nodes or leaves), each against all of B; they own
  // disjoint rows, so their lane sums never collide. Independent of the thread count.
  std::vector<int> frontier = {0};
  while (static_cast<int>(frontier.size()) < 64) {
    std::vector<int> next;
    for (int id : frontier) {
      if (ta[id].left < 0) {
        next.push_back(id);
      } else {
        next.push_back(ta[id].left);
        next.push_back(ta[id].right);
      }
    }
    if (next.size() == frontier.size()) break;
    frontier.swap(next);
  }

  std::vector<double> soa_b;
  std::vector<std::uint8_t> a_degenerate;
  const int stride = internal::FillSoaChain(b, options.degenerate_length, &soa_b);
  internal::FillDegenerateSegments(a, options.degenerate_length, &a_degenerate);
  std::vector<double> lanes(12 * static_cast<size_t>(out.rows), 0.0);
  std::vector<long long> degenerate(out.rows, 0);

  Context ctx;
  ctx.ta = &ta;
  ctx.tb = &tb;
  ctx.accept = options.tol / (ta[0].len * tb[0].len);
  if (!std::isfinite(ctx.accept)) ctx.accept = 0.0;  // a zero-length chain: exact everywhere
  internal::TileArgs& t = ctx.tile;
  t.a = a.data();
  t.a_degenerate = a_degenerate.data();
  t.SetB(soa_b, stride);
  t.cols = out.cols;
  t.degenerate_length = options.degenerate_length;
  t.out.lane_sum = lanes.data();
  t.out.lane_abs = lanes.data() + 4 * static_cast<size_t>(out.rows);
  t.out.lane_inv_mag = lanes.data() + 8 * static_cast<size_t>(out.rows);
  t.out.degenerate = degenerate.data();
  const int tasks = static_cast<int>(frontier.size());
  std::vector<TaskResult> results(tasks);
  std::atomic<int> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  std::atomic<long long> done{0};
  const long long all_pairs = static_cast<long long>(out.rows) * out.cols;
  auto work = [&](bool caller) {
    try {
      std::vector<double> scratch(internal::TileScratchSize());
      for (;;) {
        const int k = next.fetch_add(1);
        if (k >= tasks) return;
        Interact(ctx, frontier[k], 0, scratch.data(), &results[k]);
        const Node& n = ta[frontier[k]];
        const long long d = done.fetch_add(static_cast<long long>(n.hi - n.lo) * out.cols) +
                            static_cast<long long>(n.hi - n.lo) * out.cols;
        if (caller && options.progress) options.progress(d, all_pairs);
      }
    } catch (...) {
      next = tasks;
      const std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
    }
  };
  int threads =
      options.threads > 0 ? options.threads : static_cast<int>(std::thread::hardware_concurrency());
  threads = std::max(1, std::min(threads, tasks));
  std::vector<std::thread> pool;
  for (int k = 1; k < threads; ++k) pool.emplace_back(work, false);
  work(true);
  for (std::thread& th : pool) th.join();
  if (error) std::rethrow_exception(error);

  CompensatedSum total;
  double abs_total = 0.0, kernel_bound = 0.0;
  const double* ls = lanes.data();
  const double* la = ls + 4 * static_cast<size_t>(out.rows);
  const double* li = ls + 8 * static_cast<size_t>(out.rows);
  for (int i = 0; i < out.rows; ++i) {
    total.Add((ls[4 * i] + ls[4 * i + 1]) + (ls[4 * i + 2] + ls[4 * i + 3]));
    abs_total += (la[4 * i] + la[4 * i + 1]) + (la[4 * i + 2] + la[4 * i + 3]);
    kernel_bound += (li[4 * i] + li[4 * i + 1]) + (li[4 * i + 2] + li[4 * i + 3]);
    out.degenerate_pairs += degenerate[i];
  }
  double far_rounding = 0.0;
  for (const TaskResult& r : results) {
    total.Add(r.far.Value());
    out.approximation_bound += r.approximation;
    far_rounding += r.far_rounding;
    out.exact_pairs += r.exact_pairs;
    out.far_node_pairs += r.far_node_pairs;
  }
  out.total = total.Value();
  // Exact part as in StreamWritheSums: e_ij = u (1024/|Z| + 16)/(2π) per pair, the lane sums
  // (≤ cols/4 + 5 terms each) and the compensated sums.
  const double exact_bound =
      kUnitRoundoff * (1024.0 * kernel_bound + 16.0 * out.exact_pairs) / (2.0 * kPi) +
      (out.cols / 4.0 + 5.0) * kUnitRoundoff * abs_total;
  out.rounding_bound = 1.01 * (exact_bound + far_rounding) + 4.0 * kUnitRoundoff * abs_total;
  out.error_bound = out.approximation_bound + out.rounding_bound;
  return out;
}

}  // namespace topology
