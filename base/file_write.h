// Writing outputs safely: whole files or nothing (a temporary file in the same folder, then
// rename), every write checked with the system's reason in the message, and output paths checked
// before any work so that a run never replaces what it must not (a device node, a pipe, its own
// input, a file reached through a symlink that leaves the folder).
#pragma once

#include <string>
#include <vector>

#include "base/errors.h"

namespace base {

// A write that failed although the path was fine: no space left, a read-only or vanished file
// system, an I/O error. Exit code 3 (environment). The message names the path and the reason:
// "out/report.json: cannot write: No space left on device (ENOSPC)".
class WriteError : public EnvironmentError {
 public:
  using EnvironmentError::EnvironmentError;
};

// "No space left on device (ENOSPC)": strerror and the errno name of `err`.
std::string ErrnoText(int err);

// Writes `contents` to `path` as a whole: a hidden temporary file next to it, written and closed
// with every call checked, then renamed over `path` (creating missing parent folders). A failed
// write leaves `path` as it was and no temporary file behind; messages name `path`, never the
// temporary file. Throws std::invalid_argument when `path` is not writable as a file
// (CheckOutputFile's rules, so a device or pipe is never replaced even if it appeared after the
// check), WriteError when the system refuses the write.
void WriteFileAtomic(const std::string& path, const std::string& contents);

// Checks, before any work, that `path` may be written as an output file:
//   - absent, or a regular file (replaced); a symlink only when it points to a regular file (or
//     nothing) in the same folder;
//   - never a folder, device node, named pipe or socket;
//   - not the same file (device and inode) as any of `inputs`, the input files of the same run;
//   - its folder exists (or can be created) and is writable.
// Throws std::invalid_argument "<flag>: '<path>' ..." saying which rule it breaks.
void CheckOutputFile(const std::string& path, const std::string& flag,
                     const std::vector<std::string>& inputs = {});

// Checks, before any work, that `dir` may be used as an output folder: absent (and creatable:
// its nearest existing ancestor is a writable folder) or a writable folder (a symlink to a folder
// is followed); never a file, device, pipe or socket, and not one of `inputs`. Throws
// std::invalid_argument naming `flag`.
void CheckOutputDir(const std::string& dir, const std::string& flag,
                    const std::vector<std::string>& inputs = {});

// `name` (taken from an input file, e.g. a grasp's "name") as one path component under an
// output folder: refused (std::invalid_argument "<what>: '<name>' cannot be a file name ...")
// when empty, "." or "..", longer than 128 bytes, or holding '/', '\\', NUL or control bytes, so
// that names from inputs never leave the output folder.
std::string SafeFileName(const std::string& name, const std::string& what);

}  // namespace base
