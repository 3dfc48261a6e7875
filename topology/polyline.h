// Polylines ("chains") as used by the topology features, and their CSV file format.
#pragma once

#include <Eigen/Core>
#include <istream>
#include <string>

namespace topology {

// A chain is a polyline stored as a 3×N matrix of points p_0..p_{N-1} (one point per column).
// It has N−1 segments; segment i runs from p_i to p_{i+1}. A closed curve repeats p_0 at the end.
using Chain = Eigen::Matrix3Xd;

// Largest chain read from a file (points).
inline constexpr int kMaxChainPoints = 100000;

// Largest |coordinate| the topology features accept (writhe, winding): squared distances of
// points up to 1e100 apart stay far from double overflow (1.8e308); beyond it they would
// silently become inf/NaN. Every physical chain is many orders of magnitude inside.
inline constexpr double kMaxCoordinate = 1e100;

// Reads a chain CSV: one point per line as `x,y,z` (spaces around fields allowed); blank lines and
// lines whose first non-blank character is `#` are ignored. Throws std::invalid_argument naming
// `source:line` for a malformed line, a non-finite number, more than kMaxChainPoints or fewer
// than 2 points; throws std::invalid_argument too when the file cannot be opened or is larger
// than kMaxInputFileBytes (topology/input_limits.h).
Chain ReadChainCsv(const std::string& path);
Chain ParseChainCsv(std::istream& in, const std::string& source_name);

// Writes `chain` as CSV with full double precision (round-trips through ReadChainCsv).
void WriteChainCsv(const Chain& chain, std::ostream& out);

// Number of segments (N−1, or 0 for fewer than 2 points).
inline int num_segments(const Chain& chain) {
  return chain.cols() < 2 ? 0 : static_cast<int>(chain.cols()) - 1;
}

}  // namespace topology
