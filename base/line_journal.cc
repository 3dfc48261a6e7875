// The append-only journal (base/line_journal.h).
#include "base/line_journal.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "base/file_read.h"
#include "base/file_write.h"
#include "base/str_cat.h"

namespace base {
namespace {

namespace fs = std::filesystem;

constexpr const char* kHeaderPrefix = "# topoplan journal 1: ";

std::string Hex16(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof(buf), "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

// Whether `line` (no '\n') is "<payload>\t<checksum of payload>"; sets *payload.
bool IntactRecord(const std::string& line, std::string* payload) {
  const std::size_t tab = line.rfind('\t');
  if (tab == std::string::npos || line.size() - tab - 1 != 16) return false;
  *payload = line.substr(0, tab);
  return line.compare(tab + 1, 16, Hex16(Fnv1a64(*payload))) == 0;
}

std::vector<std::string> Words(const std::string& text) {
  std::vector<std::string> out;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    std::size_t end = text.find(' ', pos);
    if (end == std::string::npos) end = text.size();
    out.push_back(text.substr(pos, end - pos));
    pos = end + 1;
  }
  return out;
}

// "journal: 'seed=0'; this run: 'seed=1'": the space-separated words that differ when both
// configurations have as many, else both in full.
std::string ConfigurationDifference(const std::string& theirs, const std::string& ours) {
  const std::vector<std::string> a = Words(theirs), b = Words(ours);
  if (a.size() != b.size()) return StrCat("journal: '", theirs, "'; this run: '", ours, "'");
  std::string x, y;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i] == b[i]) continue;
    x.append(x.empty() ? "" : " ").append(a[i]);
    y.append(y.empty() ? "" : " ").append(b[i]);
  }
  return StrCat("journal: '", x, "'; this run: '", y, "'");
}

void WriteAll(int fd, const std::string& bytes, const std::string& path) {
  const char* p = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw WriteError(StrCat(path, ": cannot write: ", ErrnoText(errno)));
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}

void Sync(int fd, const std::string& path) {
  if (::fsync(fd) != 0) throw WriteError(StrCat(path, ": cannot sync: ", ErrnoText(errno)));
}

// Makes the folder entry of `path` durable (a new file survives a power loss).
void SyncFolder(const std::string& path) {
  fs::path folder = fs::path(path).parent_path();
  if (folder.empty()) folder = ".";
  const int dfd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd < 0) return;  // best effort: some file systems do not open folders
  ::fsync(dfd);
  ::close(dfd);
}

}  // namespace

std::uint64_t Fnv1a64(const std::string& bytes) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

LineJournal::LineJournal(const std::string& path, const std::string& configuration) : path_(path) {
  if (configuration.find('\n') != std::string::npos) {
    throw std::invalid_argument(StrCat(path, ": a journal configuration is one line"));
  }
  CheckOutputFile(path, path);
  const std::string header = StrCat(kHeaderPrefix, configuration, "\n");
  std::error_code ec;
  const bool existed = fs::exists(path, ec);
  std::string text;
  if (existed) text = ReadFileBounded(path, "journal");
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw WriteError(StrCat(path, ": cannot write: ", ErrnoText(errno)));
  // The length of the file that stays: the header and the intact records before any torn line.
  std::size_t keep = 0;
  const std::size_t header_end = text.find('\n');
  if (header_end == std::string::npos) {
    // Absent, empty, or a header torn by a kill: start afresh (nothing was recorded yet).
    if (!text.empty() && header.compare(0, text.size(), text) != 0) {
      ::close(fd_);
      fd_ = -1;
      throw std::invalid_argument(StrCat(path, ": not a topoplan journal; remove it"));
    }
    if (::ftruncate(fd_, 0) != 0) {
      throw WriteError(StrCat(path, ": cannot write: ", ErrnoText(errno)));
    }
    WriteAll(fd_, header, path);
    Sync(fd_, path);
    SyncFolder(path);
  } else {
    const std::string first = text.substr(0, header_end);
    std::string theirs;
    if (first.rfind(kHeaderPrefix, 0) == 0)
      theirs = first.substr(std::string(kHeaderPrefix).size());
    if (first.rfind(kHeaderPrefix, 0) != 0 || theirs != configuration) {
      ::close(fd_);
      fd_ = -1;
      if (first.rfind(kHeaderPrefix, 0) != 0) {
        throw std::invalid_argument(StrCat(path, ": not a topoplan journal; remove it"));
      }
      throw std::invalid_argument(StrCat(path, ": was written by another configuration (",
                                         ConfigurationDifference(theirs, configuration),
                                         "); remove it or use another output folder"));
    }
    keep = header_end + 1;
    std::size_t pos = keep;
    int line_no = 1;
    bool torn = false;
    int torn_line = 0;
    while (pos < text.size()) {
      const std::size_t end = text.find('\n', pos);
      ++line_no;
      if (end == std::string::npos) {  // no newline: the last write was cut short
        torn = true;
        break;
      }
      std::string payload;
      if (IntactRecord(text.substr(pos, end - pos), &payload)) {
        if (torn) {
          ::close(fd_);
          fd_ = -1;
          throw std::invalid_argument(
              StrCat(path, ":", std::to_string(torn_line),
                     ": damaged record (checksum mismatch) before intact ones; the journal was "
                     "changed by something else: remove it"));
        }
        records_.push_back(payload);
        keep = end + 1;
      } else if (!torn) {
        torn = true;
        torn_line = line_no;
      }
      pos = end + 1;
    }
    dropped_torn_line_ = keep < text.size();
    if (dropped_torn_line_) {
      if (::ftruncate(fd_, static_cast<off_t>(keep)) != 0) {
        throw WriteError(StrCat(path, ": cannot write: ", ErrnoText(errno)));
      }
      Sync(fd_, path);
    }
  }
  if (::lseek(fd_, 0, SEEK_END) < 0) {
    throw WriteError(StrCat(path, ": cannot write: ", ErrnoText(errno)));
  }
}

LineJournal::~LineJournal() {
  if (fd_ >= 0) ::close(fd_);
}

void LineJournal::Append(const std::string& payload) {
  if (payload.find_first_of("\n\t") != std::string::npos) {
    throw std::invalid_argument(StrCat(path_, ": a journal record holds no newline or tab"));
  }
  if (fd_ < 0) throw std::invalid_argument(StrCat(path_, ": journal already removed"));
  WriteAll(fd_, StrCat(payload, "\t", Hex16(Fnv1a64(payload)), "\n"), path_);
  Sync(fd_, path_);
}

void LineJournal::Remove() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  std::error_code ec;
  fs::remove(path_, ec);
}

}  // namespace base
