// Nice tick values (see ticks.h).
#include "render/internal/ticks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace render::internal {

std::vector<Tick> NiceTicks(double lo, double hi, int target) {
  std::vector<Tick> ticks;
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return ticks;
  const double raw = (hi - lo) / std::max(1, target);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0}) {
    step = m * mag;
    if (step >= 0.75 * raw) break;
  }
  const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)) +
                                       (std::abs(step / mag - 2.5) < 1e-9 ? 1 : 0));
  const long first = static_cast<long>(std::ceil(lo / step - 1e-9));
  const long last = static_cast<long>(std::floor(hi / step + 1e-9));
  for (long k = first; k <= last; ++k) {
    const double v = k == 0 ? 0.0 : static_cast<double>(k) * step;
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%.*f", decimals, std::abs(v));
    std::string label = buf;
    if (v < 0.0) label = "\u2212" + label;
    ticks.push_back({v, label});
  }
  return ticks;
}

}  // namespace render::internal
