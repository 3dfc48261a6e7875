#include "base/json_reader.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <locale>
#include <sstream>
#include <stdexcept>

#include "base/file_read.h"

namespace base {
namespace {

using nlohmann::json;

std::string Join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

int EditDistance(const std::string& a, const std::string& b) {
  std::vector<int> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = static_cast<int>(j);
  for (size_t i = 1; i <= a.size(); ++i) {
    int diag = row[0];
    row[0] = static_cast<int>(i);
    for (size_t j = 1; j <= b.size(); ++j) {
      const int up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

// The JSON path of the value being parsed, tracked through the parser's callback events, so that
// a parse error (e.g. a number overflow) can name where it happened.
struct PathTracker {
  struct Frame {
    bool array = false;
    size_t index = 0;
    std::string key;
    std::vector<std::string> keys;  // the object's keys so far (duplicates are errors)
  };
  std::vector<Frame> frames;
  std::string duplicate;       // the first duplicate key found ("" while none)
  std::string duplicate_path;  // its object's JSON path

  void ValueDone() {
    if (!frames.empty() && frames.back().array) ++frames.back().index;
  }
  bool operator()(int /*depth*/, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
        frames.push_back({false, 0, "", {}});
        break;
      case json::parse_event_t::array_start:
        frames.push_back({true, 0, "", {}});
        break;
      case json::parse_event_t::key:
        if (!frames.empty()) {
          Frame& f = frames.back();
          f.key = parsed.get<std::string>();
          if (std::find(f.keys.begin(), f.keys.end(), f.key) != f.keys.end()) {
            f.key.clear();
            duplicate_path = Path();
            duplicate = parsed.get<std::string>();
            return false;  // ParseJsonText reports it
          }
          f.keys.push_back(f.key);
        }
        break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        if (!frames.empty()) frames.pop_back();
        ValueDone();
        break;
      case json::parse_event_t::value:
        ValueDone();
        break;
    }
    return true;
  }
  std::string Path() const {
    std::string p;
    for (const Frame& f : frames) {
      if (f.array) {
        p.push_back('[');
        p.append(std::to_string(f.index));
        p.push_back(']');
      } else if (!f.key.empty()) {
        if (!p.empty()) p.push_back('.');
        p.append(f.key);
      }
    }
    return p;
  }
};

}  // namespace

json ParseJsonText(const std::string& text, const std::string& source) {
  // The parser reads a NUL byte as the end of the text: what follows it would be dropped unread.
  if (const size_t nul = text.find('\0'); nul != std::string::npos) {
    throw std::invalid_argument(source + ": invalid JSON: a NUL byte at byte offset " +
                                std::to_string(nul) + " (JSON text holds none)");
  }
  PathTracker tracker;
  try {
    json j = json::parse(text, [&](int depth, json::parse_event_t event, json& parsed) {
      if (!tracker.duplicate.empty()) return false;
      return tracker(depth, event, parsed);
    });
    if (!tracker.duplicate.empty()) {
      // Last-one-wins would silently drop a value: the file is refused, naming the key.
      const std::string where = tracker.duplicate_path.empty() ? "(root)" : tracker.duplicate_path;
      throw std::invalid_argument(source + ": " + where + ": duplicate key '" + tracker.duplicate +
                                  "' (each key may appear once per object)");
    }
    return j;
  } catch (const json::exception& e) {
    const std::string path = tracker.Path();
    throw std::invalid_argument(source + ": invalid JSON" + (path.empty() ? "" : " at " + path) +
                                ": " + e.what());
  }
}

json ParseJsonFile(const std::string& path, const std::string& what) {
  return ParseJsonText(ReadFileBounded(path, what), path);
}

std::string DidYouMean(const std::string& word, const std::vector<std::string>& candidates) {
  const std::string* best = nullptr;
  int best_distance = std::numeric_limits<int>::max();
  for (const std::string& c : candidates) {
    const int d = EditDistance(word, c);
    if (d < best_distance) {
      best_distance = d;
      best = &c;
    }
  }
  const int limit = std::max(2, static_cast<int>(word.size()) / 3);
  if (best == nullptr || best_distance > limit) return "";
  return " (did you mean '" + *best + "'?)";
}

JsonNode::JsonNode(const nlohmann::json& j, std::string file, std::string path)
    : j_(&j), file_(std::move(file)), path_(std::move(path)) {}

std::string JsonNode::Where() const { return file_ + ": " + (path_.empty() ? "(root)" : path_); }

void JsonNode::Fail(const std::string& what) const {
  throw std::invalid_argument(Where() + ": " + what);
}

bool JsonNode::Has(const std::string& key) const { return j_->is_object() && j_->contains(key); }

JsonNode JsonNode::At(const std::string& key) const {
  if (!j_->is_object()) Fail("expected an object");
  if (!j_->contains(key)) {
    throw std::invalid_argument(file_ + ": " + Join(path_, key) + ": missing");
  }
  return {j_->at(key), file_, Join(path_, key)};
}

void JsonNode::CheckKeys(const std::vector<std::string>& allowed) const {
  if (!j_->is_object()) Fail("expected an object");
  for (auto it = j_->begin(); it != j_->end(); ++it) {
    if (std::find(allowed.begin(), allowed.end(), it.key()) != allowed.end()) continue;
    if (it.key().rfind("//", 0) == 0) continue;  // a comment key: "// note": "..."
    JsonNode(it.value(), file_, Join(path_, it.key()))
        .Fail("unknown key '" + it.key() + "'" + DidYouMean(it.key(), allowed));
  }
}

std::vector<std::pair<std::string, JsonNode>> JsonNode::Members() const {
  if (!j_->is_object()) Fail("expected an object");
  std::vector<std::pair<std::string, JsonNode>> out;
  for (auto it = j_->begin(); it != j_->end(); ++it) {
    out.emplace_back(it.key(), JsonNode(it.value(), file_, Join(path_, it.key())));
  }
  return out;
}

size_t JsonNode::Size() const {
  if (!j_->is_array()) Fail("expected an array");
  return j_->size();
}

JsonNode JsonNode::At(size_t i) const {
  if (i >= Size()) Fail("index " + std::to_string(i) + " out of range");
  return {(*j_)[i], file_, path_ + "[" + std::to_string(i) + "]"};
}

double JsonNode::Number() const {
  if (!j_->is_number()) Fail("expected a number");
  const double v = j_->get<double>();
  if (!std::isfinite(v)) Fail("not a finite number");
  return v;
}

double JsonNode::Number(const std::string& key, double fallback) const {
  return Has(key) ? At(key).Number() : fallback;
}

namespace {
std::string Shortest(double v) {
  std::ostringstream out;
  out.imbue(std::locale::classic());  // "0.5" whatever the global locale
  out << v;
  return out.str();
}
}  // namespace

double JsonNode::Number(double lo, double hi) const {
  const double v = Number();
  if (v < lo || v > hi) {
    Fail(Shortest(v) + " out of range [" + Shortest(lo) + ", " + Shortest(hi) + "]");
  }
  return v;
}

double JsonNode::Number(const std::string& key, double fallback, double lo, double hi) const {
  return Has(key) ? At(key).Number(lo, hi) : fallback;
}

float JsonNode::Float() const {
  const double v = Number();
  if (std::fabs(v) > static_cast<double>(std::numeric_limits<float>::max())) {
    Fail(Shortest(v) + " is too large for single precision");
  }
  return static_cast<float>(v);
}

long long JsonNode::Integer(long long lo, long long hi) const {
  if (!j_->is_number_integer()) Fail("expected an integer");
  const std::string range = " (expected " + std::to_string(lo) + ".." + std::to_string(hi) + ")";
  if (j_->is_number_unsigned()) {
    const auto u = j_->get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(std::numeric_limits<long long>::max()) ||
        static_cast<long long>(u) > hi || static_cast<long long>(u) < lo) {
      Fail("integer " + std::to_string(u) + " out of range" + range);
    }
    return static_cast<long long>(u);
  }
  const auto v = j_->get<std::int64_t>();
  if (v < lo || v > hi) Fail("integer " + std::to_string(v) + " out of range" + range);
  return v;
}

int JsonNode::Int() const {
  return static_cast<int>(
      Integer(std::numeric_limits<int>::min(), std::numeric_limits<int>::max()));
}

int JsonNode::Int(const std::string& key, int fallback) const {
  return Has(key) ? At(key).Int() : fallback;
}

bool JsonNode::Bool() const {
  if (!j_->is_boolean()) Fail("expected true or false");
  return j_->get<bool>();
}

bool JsonNode::Bool(const std::string& key, bool fallback) const {
  return Has(key) ? At(key).Bool() : fallback;
}

std::string JsonNode::String() const {
  if (!j_->is_string()) Fail("expected a string");
  return j_->get<std::string>();
}

std::string JsonNode::String(const std::string& key, const std::string& fallback) const {
  return Has(key) ? At(key).String() : fallback;
}

Eigen::VectorXd JsonNode::Vector(int expected) const {
  const size_t n = Size();
  if (expected >= 0 && static_cast<int>(n) != expected) {
    Fail("expected " + std::to_string(expected) + " numbers, got " + std::to_string(n));
  }
  Eigen::VectorXd v(static_cast<Eigen::Index>(n));
  for (size_t i = 0; i < n; ++i) v[static_cast<Eigen::Index>(i)] = At(i).Number();
  return v;
}

Eigen::Vector3d JsonNode::Vec3() const { return Eigen::Vector3d(Vector(3)); }

Eigen::Vector3d JsonNode::Vec3(const std::string& key, const Eigen::Vector3d& fallback) const {
  return Has(key) ? At(key).Vec3() : fallback;
}

std::vector<std::string> JsonNode::Strings() const {
  std::vector<std::string> out;
  for (size_t i = 0; i < Size(); ++i) out.push_back(At(i).String());
  return out;
}

}  // namespace base
