// Package lookup for mesh URIs (planning/robot/internal/package_resolver.h).
#include "planning/robot/internal/package_resolver.h"

#include <algorithm>
#include <stdexcept>
#include <system_error>

#include "base/file_read.h"

namespace planning::internal {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void FailMesh(const std::string& source, const std::string& message) {
  throw std::invalid_argument(source + ": " + message);
}

// Folders below `dir` (depth levels, not hidden, not inside a package) whose package.xml names
// `pkg`.
void Crawl(const fs::path& dir, const std::string& pkg, int depth, std::vector<fs::path>* out) {
  std::error_code ec;
  fs::directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec);
  if (ec) return;
  for (const fs::directory_entry& e : it) {
    const std::string name = e.path().filename().string();
    if (name.empty() || name[0] == '.' || !e.is_directory(ec)) continue;
    const std::string manifest = PackageXmlName(e.path());
    if (manifest == pkg) out->push_back(e.path());
    // ROS does not look for packages inside a package.
    if (manifest.empty() && depth > 1) Crawl(e.path(), pkg, depth - 1, out);
  }
}

}  // namespace

std::string PackageXmlName(const fs::path& dir) {
  std::error_code ec;
  const fs::path manifest = dir / "package.xml";
  if (!fs::is_regular_file(manifest, ec)) return "";
  // An unreadable or oversized manifest names no package.
  base::FileBytes file = base::ReadFileLimited(manifest.string(), std::size_t{1} << 20);
  if (file.status != base::ReadStatus::kOk) return "";
  const std::string& text = file.bytes;
  const size_t open = text.find("<name>");
  const size_t close = open == std::string::npos ? open : text.find("</name>", open);
  if (close == std::string::npos) return "";
  std::string name = text.substr(open + 6, close - open - 6);
  const size_t b = name.find_first_not_of(" \t\r\n");
  const size_t e = name.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? "" : name.substr(b, e - b + 1);
}

const std::vector<fs::path>& MeshResolver::PackageRoots(const std::string& pkg) const {
  auto it = found.find(pkg);
  if (it != found.end()) return it->second;
  std::vector<fs::path> roots;
  std::error_code ec;
  auto add = [&](const fs::path& p) {
    if (fs::is_directory(p, ec) &&
        std::find(roots.begin(), roots.end(), p.lexically_normal()) == roots.end()) {
      roots.push_back(p.lexically_normal());
    }
  };
  for (const std::string& r : package_paths) {
    const fs::path root(r);
    if (root.filename() == pkg || PackageXmlName(root) == pkg) add(root);
    add(root / pkg);
  }
  for (const std::string& r : package_paths) {
    std::vector<fs::path> below;
    Crawl(fs::path(r), pkg, 3, &below);
    std::sort(below.begin(), below.end());  // directory order is not deterministic
    for (const fs::path& p : below) add(p);
  }
  for (fs::path d = fs::absolute(base_dir).lexically_normal(); !d.empty(); d = d.parent_path()) {
    if (d.filename() == pkg || PackageXmlName(d) == pkg) add(d);
    add(d / pkg);
    if (d == d.parent_path()) break;
  }
  return found.emplace(pkg, std::move(roots)).first->second;
}

std::string MeshResolver::Resolve(const std::string& uri) const {
  if (uri.starts_with("package://")) {
    std::string rest = uri.substr(10);
    // "package:///NAME/..." (an extra slash, seen in published URDFs) means the same.
    while (!rest.empty() && rest[0] == '/') rest.erase(0, 1);
    const size_t slash = rest.find('/');
    if (slash == std::string::npos || slash == 0) {
      FailMesh(source, "malformed mesh URI '" + uri + "'");
    }
    const std::string pkg = rest.substr(0, slash);
    const std::string rel = rest.substr(slash + 1);
    const fs::path rel_path = fs::path(rel).lexically_normal();
    if (rel_path.empty() || rel_path.is_absolute() || *rel_path.begin() == "..") {
      FailMesh(source, "mesh '" + uri + "' leaves its package '" + pkg + "'");
    }
    const std::vector<fs::path>& roots = PackageRoots(pkg);
    std::string missing;
    for (const fs::path& root : roots) {
      const fs::path file = root / rel_path;
      std::error_code ec;
      if (fs::is_regular_file(file, ec)) return file.lexically_normal().string();
      if (missing.size() < 400) {
        if (!missing.empty()) missing.append(", ");
        missing.append(file.lexically_normal().string());
      }
    }
    if (!missing.empty()) {
      FailMesh(source, "mesh '" + uri + "' not found: no file " + missing);
    }
    std::string tried;
    for (const std::string& r : package_paths) {
      if (tried.size() > 400) break;
      if (!tried.empty()) tried.append(", ");
      tried.append(r);
    }
    FailMesh(
        source,
        "mesh '" + uri + "' not found: no package '" + pkg +
            "' (a folder of that name or with a package.xml naming it) under the search roots (" +
            (tried.empty() ? std::string("none given") : tried) +
            ") or above the URDF; pass --package-path with the folder that holds it");
  }
  std::string path = uri;
  if (path.starts_with("file://")) path = path.substr(7);
  fs::path p(path);
  if (p.is_relative()) p = base_dir / p;
  if (!fs::is_regular_file(p))
    FailMesh(source, "mesh file '" + uri + "' not found (looked at " + p.string() + ")");
  return p.lexically_normal().string();
}

}  // namespace planning::internal
