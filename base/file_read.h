// Bounded, checked reading of input files: the one reader under every file-reading path of the
// project (chain CSV, JSON, URDF/SRDF text, viewer scripts, PNG images, fonts). Numbers in text:
// base/numbers.h.
//
// Limits are checked before any work starts, so that a hostile input (`/dev/zero`, a 10^10-line
// file, a named pipe nobody writes to) stops at once with a clear message instead of reading
// gigabytes or blocking.
#pragma once

#include <cstddef>
#include <string>

namespace base {

// Largest input file read as text (bytes): 64 MiB.
inline constexpr std::size_t kMaxInputFileBytes = std::size_t{64} << 20;

// What ReadFileLimited found.
enum class ReadStatus {
  kOk,          // bytes holds the whole file
  kCannotOpen,  // missing, no permission, ...
  kIsFolder,
  kTooLarge,  // more than max_bytes (a regular file by its size, before reading)
  kReadError,
};

struct FileBytes {
  ReadStatus status = ReadStatus::kCannotOpen;
  std::string bytes;  // the file's bytes when status == kOk, else empty
  bool pipe = false;  // the file is a named pipe (FIFO)
};

// Reads a whole file (regular file, pipe or device) of at most `max_bytes` bytes. A regular file
// is refused on its size before any read (a huge sparse file costs nothing), a pipe or device once
// max_bytes + 1 bytes have arrived. The file is opened without blocking, so a named pipe that no
// process writes to reads as empty. Never throws for a file that cannot be read: the status says
// why.
FileBytes ReadFileLimited(const std::string& path, std::size_t max_bytes);

// ReadFileLimited for a text file (a leading UTF-8 byte-order mark is dropped), throwing
// std::invalid_argument for anything but kOk:
//   "<path>: cannot open <what> file" (also "... (it is a folder)"),
//   "<path>: <what> file is larger than <max_bytes> bytes (limit)", "<path>: cannot read <what>
//   file", "<path>: <what> file is a named pipe that gave no data (nothing wrote to it)".
std::string ReadFileBounded(const std::string& path, const std::string& what,
                            std::size_t max_bytes = kMaxInputFileBytes);

}  // namespace base
