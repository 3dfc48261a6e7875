// Small output helpers for commands: atomic file writes and vector flag parsing.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace app {

// Writes `contents` to `path` atomically: a temporary file in the same folder, then rename, so a
// failure never leaves a half-written output. Creates missing parent folders. Throws
// std::runtime_error naming the path on failure.
void WriteFileAtomic(const std::string& path, const std::string& contents);

// Parses "v1,v2,...,vn" into doubles. Throws std::invalid_argument naming `flag` when a field is
// not a finite number or, if expected_size >= 0, when the count differs.
std::vector<double> ParseNumberList(const std::string& text, const std::string& flag,
                                    int expected_size = -1);

}  // namespace app
