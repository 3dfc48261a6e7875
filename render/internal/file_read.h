// Bounded reading of input files inside render/ (PNG images, fonts): render/ sits beside the
// topology and planning readers and cannot use them, so it has this one small reader.
#pragma once

#include <cstddef>
#include <string>

namespace render::internal {

// Reads the file at `path` (regular file, pipe or device) into *bytes, at most max_bytes + 1
// bytes: a caller refuses the file as too large when bytes->size() > max_bytes, without an
// endless read of `/dev/zero` or of a huge (even sparse) file. The file is opened without
// blocking, so a named pipe that no process writes to reads as empty instead of blocking for
// ever. Returns false (and leaves *bytes empty) when the file cannot be opened or read, or is a
// folder.
bool ReadFileUpTo(const std::string& path, std::size_t max_bytes, std::string* bytes);

}  // namespace render::internal
