// Paired statistics (planning/grasp/grasp_stats.h).
#include "planning/grasp/grasp_stats.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace planning {

PairedTable MakePairedTable(const std::vector<bool>& a, const std::vector<bool>& b) {
  if (a.size() != b.size()) {
    throw std::invalid_argument("paired table: outcome vectors of different lengths");
  }
  PairedTable t;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i] && b[i]) ++t.both;
    if (a[i] && !b[i]) ++t.only_a;
    if (!a[i] && b[i]) ++t.only_b;
    if (!a[i] && !b[i]) ++t.neither;
  }
  return t;
}

double BinomialHalfCdf(int k, int n) {
  if (n < 0) throw std::invalid_argument("binomial cdf: n must be >= 0");
  if (k < 0) return 0.0;
  if (k >= n) return 1.0;
  // log C(n, i) − n log 2, summed with the largest term factored out.
  const double log_half_n = -static_cast<double>(n) * std::log(2.0);
  std::vector<double> terms;
  terms.reserve(k + 1);
  for (int i = 0; i <= k; ++i) {
    terms.push_back(std::lgamma(n + 1.0) - std::lgamma(i + 1.0) - std::lgamma(n - i + 1.0) +
                    log_half_n);
  }
  const double top = *std::max_element(terms.begin(), terms.end());
  double sum = 0.0;
  for (double t : terms) sum += std::exp(t - top);
  return std::min(1.0, std::exp(top) * sum);
}

double McNemarExactP(int only_a, int only_b) {
  if (only_a < 0 || only_b < 0) {
    throw std::invalid_argument("McNemar test: discordant counts must be >= 0");
  }
  const int n = only_a + only_b;
  if (n == 0) return 1.0;
  return std::min(1.0, 2.0 * BinomialHalfCdf(std::min(only_a, only_b), n));
}

}  // namespace planning
