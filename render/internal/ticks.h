// "Nice" axis ticks (1, 2, 5 x 10^k steps) with labels, for colour bars and plots.
#pragma once

#include <string>
#include <vector>

namespace render::internal {

struct Tick {
  double value;
  std::string label;  // shortest fixed-point form for the step; U+2212 minus sign
};

// Ticks inside [lo, hi] (lo < hi) with about `target` intervals. 0 is exact when in range.
std::vector<Tick> NiceTicks(double lo, double hi, int target);

}  // namespace render::internal
