// Bounded, checked reading of input text: one helper for every file reader (chain CSV, JSON,
// viewer scripts, ...) and one number parser for every text field and flag.
//
// Limits are checked before any work starts, so that a hostile input (`/dev/zero`, a 10^10-line
// file) stops with a clear message instead of reading gigabytes.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

namespace topology {

// Largest input file read as text (bytes): 64 MiB.
inline constexpr std::size_t kMaxInputFileBytes = std::size_t{64} << 20;

// Reads a whole file (regular file, pipe or device) into memory, at most `max_bytes` bytes.
// Throws std::invalid_argument "<path>: cannot open <what> file" when it cannot be opened (or is
// a folder) and "<path>: <what> file is larger than <max_bytes> bytes (limit)" when there is more:
// a regular file is refused on its size before any read (a huge sparse file costs nothing), a
// pipe or device once max_bytes + 1 bytes have arrived. A named pipe that no process writes to
// reads as empty (it is opened without blocking).
std::string ReadFileBounded(const std::string& path, const std::string& what,
                            std::size_t max_bytes = kMaxInputFileBytes);

// The whole of `text` as a finite double (strtod syntax; leading/trailing spaces not allowed).
// Subnormal values such as 1e-310 are numbers; "nan", "inf", overflow (1e400), empty text and
// trailing characters give std::nullopt.
std::optional<double> ParseFiniteDouble(const std::string& text);

}  // namespace topology
