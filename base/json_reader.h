// Reading JSON input files with the file name and the JSON path in every error message.
//
// Every JSON loader of the project (scenarios, chain sidecars, grasp files, the grasp-object
// catalogue, render scene files) reads through JsonNode: a view of one value of a parsed document
// that knows its file and its JSON path ("tasks[0].feature.link"). All errors are
// std::invalid_argument with the message "<file>: <path>: <what>" ("(root)" for the document).
#pragma once

#include <Eigen/Core>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace base {

// Parses JSON text. Syntax errors and out-of-range numbers (e.g. 1e400) throw
// "<source>: invalid JSON at <path>: ..." where <path> is the JSON path being read. A NUL byte
// anywhere in the text is an error naming its byte offset ("<source>: invalid JSON: a NUL byte at
// byte offset 42 ...").
nlohmann::json ParseJsonText(const std::string& text, const std::string& source);
// Reads (at most kMaxInputFileBytes) and parses a file; "<path>: cannot open <what>
// file" when it cannot be read, "<path>: <what> file is larger than ..." beyond the limit.
nlohmann::json ParseJsonFile(const std::string& path, const std::string& what);

// " (did you mean 'x'?)" for the candidate closest to `word` in edit distance (at most 2 edits
// or a third of the word's length), or "" when none is close.
std::string DidYouMean(const std::string& word, const std::vector<std::string>& candidates);

class JsonNode {
 public:
  // `j` must outlive the node and every node derived from it.
  JsonNode(const nlohmann::json& j, std::string file, std::string path = "");

  const nlohmann::json& json() const { return *j_; }
  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  // "<file>: <path>" (the prefix of this node's error messages).
  std::string Where() const;
  [[noreturn]] void Fail(const std::string& what) const;

  bool IsObject() const { return j_->is_object(); }
  bool IsArray() const { return j_->is_array(); }
  bool IsString() const { return j_->is_string(); }
  bool IsNumber() const { return j_->is_number(); }

  // Objects. Has: the key is present (false for non-objects). At: required member.
  bool Has(const std::string& key) const;
  JsonNode At(const std::string& key) const;
  // Throws for a non-object and for any key outside `allowed` (with a did-you-mean hint). Keys
  // starting with "//" are comments and always allowed ({"// where": "edit me"}).
  void CheckKeys(const std::vector<std::string>& allowed) const;
  // The members of an object, in file order.
  std::vector<std::pair<std::string, JsonNode>> Members() const;

  // Arrays.
  size_t Size() const;
  JsonNode At(size_t i) const;

  // Typed reads; the (key, fallback) forms return the fallback when the key is absent.
  double Number() const;  // finite
  double Number(const std::string& key, double fallback) const;
  // A finite number in [lo, hi] ("<file>: <path>: 1e-07 out of range [1e-05, 10]").
  double Number(double lo, double hi) const;
  double Number(const std::string& key, double fallback, double lo, double hi) const;
  // A finite number that is also finite as a float (|v| <= FLT_MAX), for render data.
  float Float() const;
  // An integer in [lo, hi] (no silent truncation: 4294967297 is not an int).
  long long Integer(long long lo, long long hi) const;
  int Int() const;
  int Int(const std::string& key, int fallback) const;
  bool Bool() const;
  bool Bool(const std::string& key, bool fallback) const;
  std::string String() const;
  std::string String(const std::string& key, const std::string& fallback) const;
  // An array of finite numbers; `expected` >= 0 fixes its length.
  Eigen::VectorXd Vector(int expected = -1) const;
  Eigen::Vector3d Vec3() const;
  Eigen::Vector3d Vec3(const std::string& key, const Eigen::Vector3d& fallback) const;
  std::vector<std::string> Strings() const;  // an array of strings

 private:
  const nlohmann::json* j_;
  std::string file_;
  std::string path_;
};

// Calls f() and prefixes any std::invalid_argument it throws with `prefix` ("<prefix>: <what>"):
// the one way a caller adds its context (file and JSON path, a flag name) to a library error. A
// message that already starts with `prefix` (located by an inner PrefixErrors at or below the same
// place, e.g. "f.json: tasks[0].feature.chain: ..." inside "f.json: tasks[0].feature") is kept as
// it is, so no location is said twice.
template <typename F>
auto PrefixErrors(const std::string& prefix, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const std::invalid_argument& e) {
    if (std::string_view(e.what()).substr(0, prefix.size()) == prefix) throw;
    throw std::invalid_argument(prefix + ": " + e.what());
  }
}

// Calls f() and prefixes any std::invalid_argument it throws with the node's location.
template <typename F>
auto Located(const JsonNode& n, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const std::invalid_argument& e) {
    n.Fail(e.what());
  }
}

}  // namespace base
