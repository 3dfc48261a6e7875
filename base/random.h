// Portable random draws from std::mt19937.
//
// std::uniform_real_distribution and std::uniform_int_distribution are not specified bit for bit:
// libstdc++, libc++ and MSVC map the same generator output to different numbers. The planners
// therefore map the raw 32-bit outputs of std::mt19937 (which *is* fully specified) themselves,
// so a seed gives the same samples with every standard library:
//
//   UniformUnit: two outputs a, b; u = ((a >> 5) · 2^26 + (b >> 6)) / 2^53 ∈ [0, 1) — the
//                53-bit mantissa draw of Matsumoto and Nishimura's genrand_res53.
//   UniformIndex(n): Lemire's multiply-shift with rejection (Lemire 2019, "Fast random integer
//                generation in an interval"): x = output, m = x · n (64 bit); while the low
//                32 bits of m are < (2^32 − n) mod n draw again; the result is m >> 32 ∈ [0, n),
//                exactly uniform.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>

namespace base {

// A double uniform in [0, 1) with 53 random bits; consumes two generator outputs.
inline double UniformUnit(std::mt19937* rng) {
  const std::uint32_t a = (*rng)() >> 5;  // 27 bits
  const std::uint32_t b = (*rng)() >> 6;  // 26 bits
  return (static_cast<double>(a) * 67108864.0 + static_cast<double>(b)) *
         (1.0 / 9007199254740992.0);
}

// A direction uniform on the unit sphere (Archimedes: z uniform in [−1, 1), the azimuth uniform in
// [0, 2π)); consumes two UniformUnit draws, z first.
inline Eigen::Vector3d UniformUnitVector(std::mt19937* rng) {
  const double z = 2.0 * UniformUnit(rng) - 1.0;
  const double phi = 2.0 * M_PI * UniformUnit(rng);
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return Eigen::Vector3d(r * std::cos(phi), r * std::sin(phi), z);
}

// An integer uniform in [0, n), 1 <= n <= 2^32 − 1; consumes one or more generator outputs.
inline std::uint32_t UniformIndex(std::mt19937* rng, std::uint32_t n) {
  if (n == 0) throw std::invalid_argument("UniformIndex: n must be >= 1");
  std::uint64_t m = static_cast<std::uint64_t>((*rng)()) * n;
  auto low = static_cast<std::uint32_t>(m);
  if (low < n) {
    const std::uint32_t threshold = (0u - n) % n;  // 2^32 mod n
    while (low < threshold) {
      m = static_cast<std::uint64_t>((*rng)()) * n;
      low = static_cast<std::uint32_t>(m);
    }
  }
  return static_cast<std::uint32_t>(m >> 32);
}

}  // namespace base
