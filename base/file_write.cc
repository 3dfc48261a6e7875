#include "base/file_write.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace base {
namespace {

namespace fs = std::filesystem;

const char* ErrnoName(int err) {
  switch (err) {
    case ENOSPC: return "ENOSPC";
    case EDQUOT: return "EDQUOT";
    case EROFS: return "EROFS";
    case EACCES: return "EACCES";
    case EPERM: return "EPERM";
    case EIO: return "EIO";
    case EBADF: return "EBADF";
    case EPIPE: return "EPIPE";
    case ENOENT: return "ENOENT";
    case ENOTDIR: return "ENOTDIR";
    case EISDIR: return "EISDIR";
    case EXDEV: return "EXDEV";
    case EFBIG: return "EFBIG";
    case ENAMETOOLONG: return "ENAMETOOLONG";
    default: return nullptr;
  }
}

// What is at `path` (lstat: a symlink is reported as a symlink).
enum class Kind { kAbsent, kFile, kFolder, kSymlink, kDevice, kPipe, kSocket, kOther };

Kind KindOf(const std::string& path, bool follow, struct stat* st_out = nullptr) {
  struct stat st {};
  const int rc = follow ? ::stat(path.c_str(), &st) : ::lstat(path.c_str(), &st);
  if (rc != 0) return Kind::kAbsent;
  if (st_out != nullptr) *st_out = st;
  if (S_ISLNK(st.st_mode)) return Kind::kSymlink;
  if (S_ISREG(st.st_mode)) return Kind::kFile;
  if (S_ISDIR(st.st_mode)) return Kind::kFolder;
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return Kind::kDevice;
  if (S_ISFIFO(st.st_mode)) return Kind::kPipe;
  if (S_ISSOCK(st.st_mode)) return Kind::kSocket;
  return Kind::kOther;
}

const char* KindText(Kind k) {
  switch (k) {
    case Kind::kDevice: return "a device node";
    case Kind::kPipe: return "a named pipe";
    case Kind::kSocket: return "a socket";
    case Kind::kFolder: return "a folder";
    case Kind::kSymlink: return "a symlink";
    case Kind::kFile: return "a file";
    default: return "not a regular file";
  }
}

// Throws when `path` is the same file as one of `inputs`.
void CheckNotInput(const std::string& path, const std::string& flag,
                   const std::vector<std::string>& inputs) {
  struct stat out {};
  if (::stat(path.c_str(), &out) != 0) return;
  for (const std::string& in : inputs) {
    struct stat st {};
    if (!in.empty() && ::stat(in.c_str(), &st) == 0 && st.st_dev == out.st_dev &&
        st.st_ino == out.st_ino) {
      throw std::invalid_argument(flag + ": '" + path + "' is an input of this run (" + in +
                                  "); write the output elsewhere");
    }
  }
}

// The folder that would hold a new `dir` (its nearest existing ancestor) must be a writable
// folder.
void CheckCreatable(const fs::path& start, const std::string& shown, const std::string& flag) {
  std::error_code ec;
  fs::path p = fs::absolute(start, ec);
  if (ec) throw std::invalid_argument(flag + ": '" + shown + "': " + ec.message());
  while (!fs::exists(p, ec)) {
    if (!p.has_parent_path() || p.parent_path() == p) break;
    p = p.parent_path();
  }
  if (!fs::is_directory(p, ec)) {
    throw std::invalid_argument(flag + ": '" + shown + "': " + p.string() + " is not a folder");
  }
  if (::access(p.c_str(), W_OK | X_OK) != 0) {
    throw std::invalid_argument(flag + ": '" + shown + "': folder " + p.string() +
                                " is not writable");
  }
}

std::atomic<unsigned> g_temp_counter{0};

}  // namespace

std::string ErrnoText(int err) {
  const char* name = ErrnoName(err);
  return std::string(std::strerror(err)) + (name ? std::string(" (") + name + ")" : "");
}

void CheckOutputFile(const std::string& path, const std::string& flag,
                     const std::vector<std::string>& inputs) {
  if (path.empty()) throw std::invalid_argument(flag + ": empty output path");
  const Kind kind = KindOf(path, /*follow=*/false);
  if (kind == Kind::kSymlink) {
    // Followed only inside its own folder, and only to a regular file (or to nothing yet).
    std::error_code ec;
    const fs::path target = fs::read_symlink(path, ec);
    const fs::path folder = fs::absolute(fs::path(path), ec).parent_path();
    const fs::path resolved = fs::weakly_canonical(folder / target, ec);
    const fs::path canonical_folder = fs::weakly_canonical(folder, ec);
    const Kind to = KindOf(resolved.string(), true);
    if (ec || resolved.parent_path() != canonical_folder ||
        (to != Kind::kFile && to != Kind::kAbsent)) {
      throw std::invalid_argument(flag + ": '" + path + "' is a symlink to " + target.string() +
                                  ", outside its folder or not a regular file; give a plain file "
                                  "name");
    }
  } else if (kind != Kind::kAbsent && kind != Kind::kFile) {
    throw std::invalid_argument(flag + ": '" + path + "' is " + KindText(kind) +
                                (kind == Kind::kFolder ? ", expected a file name"
                                                       : "; outputs are regular files only"));
  }
  CheckNotInput(path, flag, inputs);
  const fs::path parent = fs::path(path).parent_path();
  CheckCreatable(parent.empty() ? fs::path(".") : parent, path, flag);
}

void CheckOutputDir(const std::string& dir, const std::string& flag,
                    const std::vector<std::string>& inputs) {
  if (dir.empty()) throw std::invalid_argument(flag + ": empty output path");
  const Kind kind = KindOf(dir, /*follow=*/true);  // a symlink to a folder is a folder
  if (kind != Kind::kAbsent && kind != Kind::kFolder) {
    throw std::invalid_argument(flag + ": '" + dir + "' is " + KindText(kind) +
                                ", expected a folder (or a name for a new one)");
  }
  if (KindOf(dir, false) == Kind::kSymlink && kind == Kind::kAbsent) {
    throw std::invalid_argument(flag + ": '" + dir + "' is a dangling symlink");
  }
  CheckNotInput(dir, flag, inputs);
  CheckCreatable(fs::path(dir), dir, flag);
}

std::string SafeFileName(const std::string& name, const std::string& what) {
  auto refuse = [&](const std::string& why) {
    std::string shown;
    for (char c : name.substr(0, 64)) {
      shown += (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) ? '?' : c;
    }
    throw std::invalid_argument((what.empty() ? "" : what + ": ") + "'" + shown +
                                "' cannot be a file name (" + why + ")");
  };
  if (name.empty()) refuse("empty");
  if (name == "." || name == "..") refuse("a path step, not a name");
  if (name.size() > 128) refuse("longer than 128 bytes");
  for (char c : name) {
    if (c == '/' || c == '\\') refuse("holds a path separator");
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) refuse("holds a control character");
  }
  return name;
}

void WriteFileAtomic(const std::string& path, const std::string& contents) {
  const fs::path target(path);
  std::error_code ec;
  if (target.has_parent_path() && !fs::exists(target.parent_path(), ec)) {
    fs::create_directories(target.parent_path(), ec);
    if (ec) throw WriteError(path + ": cannot create its folder: " + ErrnoText(ec.value()));
  }
  // The rules of CheckOutputFile again, at the moment of writing (a pipe may have appeared).
  const Kind kind = KindOf(path, false);
  if (kind != Kind::kAbsent && kind != Kind::kFile && kind != Kind::kSymlink) {
    throw std::invalid_argument(path + ": is " + std::string(KindText(kind)) +
                                "; outputs are regular files only");
  }
  fs::path final_path = target;
  if (kind == Kind::kSymlink) {  // CheckOutputFile allowed it: write the file it names
    CheckOutputFile(path, path);
    final_path = fs::weakly_canonical(target, ec);
  }
  std::string tmp_name(1, '.');  // hidden, next to the target (same file system)
  tmp_name.append(final_path.filename().string());
  tmp_name.append(".tmp-");
  tmp_name.append(std::to_string(::getpid()));
  tmp_name.push_back('-');
  tmp_name.append(std::to_string(g_temp_counter++));
  const fs::path tmp = final_path.parent_path() / tmp_name;
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) throw WriteError(path + ": cannot write: " + ErrnoText(errno));
  const char* p = contents.data();
  std::size_t left = contents.size();
  int err = 0;
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      err = errno;
      break;
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0 && err == 0) err = errno;
  if (err != 0) {
    ::unlink(tmp.c_str());
    throw WriteError(path + ": cannot write: " + ErrnoText(err));
  }
  if (::rename(tmp.c_str(), final_path.c_str()) != 0) {
    err = errno;
    ::unlink(tmp.c_str());
    throw WriteError(path + ": cannot move the written file into place: " + ErrnoText(err));
  }
}

}  // namespace base
