#include "base/file_read.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <stdexcept>

namespace base {

FileBytes ReadFileLimited(const std::string& path, std::size_t max_bytes) {
  FileBytes out;
  // Non-blocking open: a named pipe without a writer would otherwise block here for ever (it then
  // reads as empty). Reads block again as usual.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    out.status = ReadStatus::kCannotOpen;
    return out;
  }
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    out.status = ReadStatus::kReadError;
    return out;
  }
  if (S_ISDIR(st.st_mode)) {
    out.status = ReadStatus::kIsFolder;
    return out;
  }
  out.pipe = S_ISFIFO(st.st_mode);
  // A regular file's size is known: a huge (even sparse) file is refused without reading it.
  if (S_ISREG(st.st_mode) && static_cast<std::size_t>(st.st_size) > max_bytes) {
    out.status = ReadStatus::kTooLarge;
    return out;
  }
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags < 0 || ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) != 0) {
    out.status = ReadStatus::kReadError;
    return out;
  }
  char buffer[1 << 16];
  for (;;) {
    const ssize_t got = ::read(fd, buffer, sizeof(buffer));
    if (got < 0) {
      if (errno == EINTR) continue;
      out.bytes.clear();
      out.status = ReadStatus::kReadError;
      return out;
    }
    if (got == 0) break;
    if (out.bytes.size() + static_cast<std::size_t>(got) > max_bytes) {
      out.bytes.clear();
      out.status = ReadStatus::kTooLarge;
      return out;
    }
    out.bytes.append(buffer, static_cast<std::size_t>(got));
  }
  out.status = ReadStatus::kOk;
  return out;
}

std::string ReadFileBounded(const std::string& path, const std::string& what,
                            std::size_t max_bytes) {
  FileBytes file = ReadFileLimited(path, max_bytes);
  switch (file.status) {
    case ReadStatus::kOk:
      if (file.pipe && file.bytes.empty()) {  // read as empty text it would pass for a bad file
        throw std::invalid_argument(
            path + ": " + what + " file is a named pipe that gave no data (nothing wrote to it)");
      }
      // Text: a UTF-8 byte-order mark (written by some editors) is not part of the content.
      if (file.bytes.size() >= 3 && file.bytes.compare(0, 3, "\xEF\xBB\xBF") == 0) {
        return file.bytes.substr(3);
      }
      return std::move(file.bytes);
    case ReadStatus::kCannotOpen:
      throw std::invalid_argument(path + ": cannot open " + what + " file");
    case ReadStatus::kIsFolder:
      throw std::invalid_argument(path + ": cannot open " + what + " file (it is a folder)");
    case ReadStatus::kTooLarge:
      throw std::invalid_argument(path + ": " + what + " file is larger than " +
                                  std::to_string(max_bytes) + " bytes (limit)");
    case ReadStatus::kReadError:
      break;
  }
  throw std::invalid_argument(path + ": cannot read " + what + " file");
}

}  // namespace base
