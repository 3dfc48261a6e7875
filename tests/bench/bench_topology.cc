// Writhe matrix and winding throughput. Reports ns per segment pair (the README targets:
// ≤ 20 ns per pair for values, ≤ 100 ns with the gradient, per core). The writhe benchmarks take
// a kernel argument: 0 the scalar per-row kernel (the pre-SIMD path), 1 SSE2, 2 automatic (AVX2
// where the CPU has it); see topology/internal/writhe_tile.h.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "topology/gauss_far_field.h"
#include "topology/internal/writhe_tile.h"
#include "topology/linking_crossings.h"
#include "topology/winding.h"
#include "topology/writhe.h"
#include "topology/writhe_stream.h"

namespace {

// Selects the kernel for one benchmark run and restores automatic dispatch afterwards.
class KernelScope {
 public:
  explicit KernelScope(int64_t arg) {
    using topology::internal::SimdLevel;
    topology::internal::SetSimdLevel(arg == 0   ? SimdLevel::kScalar
                                     : arg == 1 ? SimdLevel::kSse2
                                                : SimdLevel::kAuto);
  }
  ~KernelScope() { topology::internal::SetSimdLevel(topology::internal::SimdLevel::kAuto); }
};

topology::Chain Random(int points, unsigned seed, double offset) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  topology::Chain c(3, points);
  c.col(0) << offset, 0, 0;
  for (int i = 1; i < points; ++i) {
    Eigen::Vector3d d(g(rng), g(rng), g(rng));
    c.col(i) = c.col(i - 1) + 0.1 * d.normalized();
  }
  return c;
}

void BM_WritheMatrix(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const KernelScope kernel(state.range(1));
  const topology::Chain a = Random(n + 1, 1, 0.0), b = Random(n + 1, 2, 0.05);
  Eigen::MatrixXd w;
  topology::WritheWorkspace ws;
  for (auto _ : state) {
    topology::WritheMatrix(a, b, {}, &w, &ws);
    benchmark::DoNotOptimize(w.data());
  }
  const double pairs = static_cast<double>(n) * n;
  // Seconds per segment pair (printed with an SI prefix, e.g. "5.1n" = 5.1 ns).
  state.counters["s_per_pair"] = benchmark::Counter(
      pairs, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_WritheMatrix)
    ->ArgsProduct({{20, 100, 1000}, {0, 1, 2}})
    ->Unit(benchmark::kMicrosecond);

void BM_WritheMatrixWithJacobian(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const KernelScope kernel(state.range(1));
  const topology::Chain a = Random(n + 1, 1, 0.0), b = Random(n + 1, 2, 0.05);
  Eigen::MatrixXd w;
  topology::WritheJacobian jac;
  topology::WritheWorkspace ws;
  for (auto _ : state) {
    topology::WritheMatrixWithJacobian(a, b, {}, &w, &jac, &ws);
    benchmark::DoNotOptimize(jac.pair.data());
  }
  const double pairs = static_cast<double>(n) * n;
  // Seconds per segment pair (printed with an SI prefix, e.g. "5.1n" = 5.1 ns).
  state.counters["s_per_pair"] = benchmark::Counter(
      pairs, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_WritheMatrixWithJacobian)
    ->ArgsProduct({{20, 100, 1000}, {0, 1, 2}})
    ->Unit(benchmark::kMicrosecond);

// The unwrap task's shape: 20 arm links against one pole segment, with the chain rule to 20 dofs.
void BM_WritheArmPoleChainRule(benchmark::State& state) {
  const KernelScope kernel(state.range(0));
  const topology::Chain arm = Random(21, 3, 0.0);
  topology::Chain pole(3, 2);
  pole << -0.1, -0.1, -3, 0, 1.85, 1.85;
  std::mt19937 rng(4);
  std::normal_distribution<double> g(0, 1);
  Eigen::MatrixXd dp_dq(63, 20);
  for (int i = 0; i < dp_dq.size(); ++i) dp_dq.data()[i] = g(rng);
  Eigen::MatrixXd w, jq;
  topology::WritheJacobian jac;
  topology::WritheWorkspace ws;
  for (auto _ : state) {
    topology::WritheMatrixWithJacobian(arm, pole, {}, &w, &jac, &ws);
    topology::ChainWritheJacobian(jac, dp_dq, Eigen::MatrixXd(), &jq);
    benchmark::DoNotOptimize(jq.data());
  }
}
BENCHMARK(BM_WritheArmPoleChainRule)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

void BM_WindingWithGradient(benchmark::State& state) {
  const topology::Chain c = Random(static_cast<int>(state.range(0)), 5, 0.5);
  const topology::Axis axis{{0, 0, 0}, {0, 0, 1}};
  Eigen::Matrix3Xd grad;
  for (auto _ : state) {
    benchmark::DoNotOptimize(topology::WindingNumber(c, axis, {}, &grad));
  }
  state.SetItemsProcessed(state.iterations() * (state.range(0) - 1));
}
BENCHMARK(BM_WindingWithGradient)->Arg(21)->Arg(1001);

// Streaming total (topology/writhe_stream.h): Σ W and its error bound without the matrix, on
// range(1) threads. Args: segments per chain, threads, kernel. `topoplan writhe --total` and
// `linking`.
void BM_StreamWritheTotal(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const KernelScope kernel(state.range(2));
  const topology::Chain a = Random(n + 1, 1, 0.0), b = Random(n + 1, 2, 0.05);
  topology::WritheStreamOptions o;
  o.threads = static_cast<int>(state.range(1));
  for (auto _ : state) benchmark::DoNotOptimize(topology::StreamWritheSums(a, b, o).total);
  state.counters["s_per_pair"] =
      benchmark::Counter(static_cast<double>(n) * n, benchmark::Counter::kIsIterationInvariantRate |
                                                         benchmark::Counter::kInvert);
}
BENCHMARK(BM_StreamWritheTotal)
    ->ArgsProduct({{1000, 8000}, {1, 2}, {0, 1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_StreamWritheTotal)
    ->Args({100000, 1, 2})
    ->Args({100000, 2, 2})
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

// Barnes–Hut Gauss integral (topology/gauss_far_field.h) of the two components of the (2, 6)
// torus link (linking number 3 in magnitude), n segments each, tol = 10^−range(1), 2 threads;
// counters: the error bound and the exact pairs as a fraction of n².
topology::Chain TorusComponent(int k, int j, int n) {
  topology::Chain c(3, n + 1);
  for (int s = 0; s < n; ++s) {
    const double t = 6.283185307179586 * s / n;
    const double phi = t + 3.141592653589793 * j / k;  // the two components, half a turn apart
    const double rho = 2.0 + 0.7 * std::cos(k * phi);
    c.col(s) << rho * std::cos(t), rho * std::sin(t), 0.7 * std::sin(k * phi);
  }
  c.col(n) = c.col(0);
  return c;
}

void BM_FarFieldTorusLink(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const topology::Chain a = TorusComponent(3, 0, n), b = TorusComponent(3, 1, n);
  topology::FarFieldOptions o;
  o.tol = std::pow(10.0, -static_cast<double>(state.range(1)));
  o.threads = 2;
  topology::FarFieldSums s;
  for (auto _ : state) {
    s = topology::FarFieldGaussIntegral(a, b, o);
    benchmark::DoNotOptimize(&s);
    benchmark::ClobberMemory();
  }
  state.counters["T"] = s.total;
  state.counters["bound"] = s.error_bound;
  state.counters["exact_fraction"] = static_cast<double>(s.exact_pairs) / (double(n) * n);
}
BENCHMARK(BM_FarFieldTorusLink)
    ->ArgsProduct({{8000, 100000}, {1, 3, 6}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Growth with N for docs/benchmarks.md (tests/bench/plot_linking_scale.py): the Gauss integral of
// the (2, 6) torus link, N segments per component, one thread, CPU time. range(0): 0 the exact
// matrix stored and summed (WritheMatrix, N <= 4000: 128 MB), 1 the exact streamed total
// (StreamWritheSums), 2 and 3 the far field (FarFieldGaussIntegral) with tol 1e-3 and 1e-1, 4 the
// signed crossings of a projection (CrossingLinkingNumber; its linking number is the "T").
void BM_LinkingScale(benchmark::State& state) {
  const int method = static_cast<int>(state.range(0));
  const int n = static_cast<int>(state.range(1));
  const topology::Chain a = TorusComponent(3, 0, n), b = TorusComponent(3, 1, n);
  double total = 0.0;
  for (auto _ : state) {
    if (method == 0) {
      total = topology::WritheMatrix(a, b).sum();
    } else if (method == 1) {
      topology::WritheStreamOptions o;
      o.threads = 1;
      total = topology::StreamWritheSums(a, b, o).total;
    } else if (method == 4) {
      total = static_cast<double>(topology::CrossingLinkingNumber(a, b).linking_number);
    } else {
      topology::FarFieldOptions o;
      o.tol = method == 2 ? 1e-3 : 1e-1;
      o.threads = 1;
      total = topology::FarFieldGaussIntegral(a, b, o).total;
    }
    benchmark::DoNotOptimize(total);
  }
  state.counters["segments"] = n;
  state.counters["T"] = total;
}
BENCHMARK(BM_LinkingScale)
    ->ArgsProduct({{0}, {250, 500, 1000, 2000, 4000}})
    ->ArgsProduct({{1}, {250, 500, 1000, 2000, 4000, 8000, 16000, 32000}})
    ->ArgsProduct({{2, 3, 4}, {250, 500, 1000, 2000, 4000, 8000, 16000, 32000, 64000, 128000}})
    ->Unit(benchmark::kMillisecond);

}  // namespace
