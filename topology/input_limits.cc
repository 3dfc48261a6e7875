#include "topology/input_limits.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace topology {

std::string ReadFileBounded(const std::string& path, const std::string& what,
                            std::size_t max_bytes) {
  auto fail = [&](const std::string& why) {
    return std::invalid_argument(path + ": " + why + " " + what + " file");
  };
  auto too_large = [&] {
    return std::invalid_argument(path + ": " + what + " file is larger than " +
                                 std::to_string(max_bytes) + " bytes (limit)");
  };
  // Non-blocking open: a named pipe without a writer would otherwise block here for ever (it then
  // reads as empty). Reads block again as usual.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw fail("cannot open");
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw fail("cannot read");
  if (S_ISDIR(st.st_mode)) {
    throw std::invalid_argument(path + ": cannot open " + what + " file (it is a folder)");
  }
  // A regular file's size is known: a huge (even sparse) file is refused without reading it.
  if (S_ISREG(st.st_mode) && static_cast<std::size_t>(st.st_size) > max_bytes) throw too_large();
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags < 0 || ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) != 0) throw fail("cannot read");
  std::string out;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t got = ::read(fd, buffer, sizeof(buffer));
    if (got < 0) {
      if (errno == EINTR) continue;
      throw fail("cannot read");
    }
    if (got == 0) break;
    if (out.size() + static_cast<std::size_t>(got) > max_bytes) throw too_large();
    out.append(buffer, static_cast<std::size_t>(got));
  }
  return out;
}

std::optional<double> ParseFiniteDouble(const std::string& text) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(v)) return std::nullopt;
  // ERANGE also reports underflow to a subnormal or zero (1e-310), which is a number.
  if (errno == ERANGE && std::fabs(v) >= 1.0) return std::nullopt;
  return v;
}

}  // namespace topology
