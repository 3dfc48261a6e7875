// Paired statistics of a grasp-transfer study: outcomes of two methods on the same trials
// (object, demonstration), McNemar's exact test on the discordant pairs and Wilson intervals.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace planning {

// 2 × 2 table of paired binary outcomes of methods A and B on the same trials:
//   both    A and B succeed,   only_a  A succeeds, B fails,
//   only_b  B succeeds, A fails,   neither  both fail.
struct PairedTable {
  int both = 0;
  int only_a = 0;
  int only_b = 0;
  int neither = 0;
  int trials() const { return both + only_a + only_b + neither; }
};

// The table of two outcome vectors of equal length (a[i], b[i]: trial i). Throws
// std::invalid_argument for different lengths.
PairedTable MakePairedTable(const std::vector<bool>& a, const std::vector<bool>& b);

// McNemar's exact test (McNemar 1947; the exact conditional form, Agresti 2013 §11.1.4): under
// H0 (the methods succeed equally often) the discordant count only_a is Binomial(n, ½) given
// n = only_a + only_b. Two-sided p-value p = min(1, 2 · P[X ≤ min(only_a, only_b)]),
// X ~ Binomial(n, ½); 1 for n = 0. Throws std::invalid_argument for a negative count.
double McNemarExactP(int only_a, int only_b);
inline double McNemarExactP(const PairedTable& t) { return McNemarExactP(t.only_a, t.only_b); }

// Binomial(n, ½) lower tail P[X ≤ k] (0 for k < 0, 1 for k ≥ n), summed in log space so that
// n up to 10⁶ does not underflow. Throws std::invalid_argument for n < 0.
double BinomialHalfCdf(int k, int n);

}  // namespace planning
