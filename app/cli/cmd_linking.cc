// `topoplan linking`: the Gauss linking number of two closed chains, streamed (O(N) memory, both
// cores), rounded only when the error bound certifies it; and a batch mode for many small pairs.
#include <algorithm>
#include <charconv>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "app/cli/command.h"
#include "app/cli/io.h"
#include "base/enum_names.h"
#include "topology/linking_crossings.h"
#include "topology/polyline.h"
#include "topology/writhe_stream.h"

namespace app {
namespace {

struct LinkingArgs {
  std::string a_path, b_path, batch;
  bool json = false, close = false;
  int threads = 0;
  double tol = 0.0;  // > 0: Barnes–Hut far field with this approximation bound
  std::string method = "auto";
  // --method as parsed.
  topology::LinkingMethod Method() const {
    return base::ParseEnum<topology::LinkingMethod>(method, "linking method");
  }
};

// Appends the first point when the chain does not end on it (`--close`).
void CloseChain(topology::Chain* c) {
  if (c->cols() >= 2 && c->col(0) != c->col(c->cols() - 1)) {
    c->conservativeResize(Eigen::NoChange, c->cols() + 1);
    c->col(c->cols() - 1) = c->col(0);
  }
}

// Throws std::invalid_argument naming `source` when the chain is not closed.
void RequireClosed(const topology::Chain& c, const std::string& source, bool may_close) {
  if (topology::IsClosedChain(c)) return;
  std::string msg = source;
  msg.append(
      ": chain is not closed (its last point must repeat its first exactly, at least 3 "
      "segments); the linking number is defined only for closed curves");
  if (may_close) msg.append(" (--close appends the first point)");
  throw std::invalid_argument(msg);
}

nlohmann::ordered_json ResultJson(const topology::LinkingResult& r) {
  nlohmann::ordered_json j;
  const bool ok = r.status == topology::LinkingStatus::kCertified;
  j["linking_number"] = ok ? nlohmann::ordered_json(r.linking_number) : nlohmann::ordered_json();
  j["status"] = topology::LinkingStatusName(r.status);
  const bool crossings = r.method == topology::LinkingMethod::kCrossings;
  j["gauss_integral"] =
      crossings ? nlohmann::ordered_json() : nlohmann::ordered_json(r.gauss_integral);
  j["error_bound"] = r.error_bound;
  j["distance"] = r.distance;
  j["segments"] = {r.segments_a, r.segments_b};
  j["degenerate_pairs"] = r.degenerate_pairs;
  j["method"] = base::ToName(r.method);
  j["crossings"] = r.crossings;
  j["projection"] =
      r.projection.isZero()
          ? nlohmann::ordered_json()
          : nlohmann::ordered_json({r.projection.x(), r.projection.y(), r.projection.z()});
  return j;
}

// Why a result is not certified, for the message on stderr.
std::string Reason(const topology::LinkingResult& r) {
  char buf[320];
  if (r.method == topology::LinkingMethod::kCrossings) {
    return "no projection decides every crossing with certainty (in each of the three tried, "
           "a vertex projects onto the other curve, or two segments nearly meet); --method "
           "gauss gives the Gauss integral and its error bound";
  }
  switch (r.status) {
    case topology::LinkingStatus::kTouching:
      std::snprintf(buf, sizeof buf,
                    "%lld segment pairs touch or cross: the linking number is not defined",
                    r.degenerate_pairs);
      break;
    case topology::LinkingStatus::kNotInteger:
      std::snprintf(buf, sizeof buf,
                    "the Gauss integral %.17g is %.3g from the nearest integer, more than its "
                    "error bound %.3g: the curves cross or nearly touch",
                    r.gauss_integral, r.distance, r.error_bound);
      break;
    default:
      std::snprintf(buf, sizeof buf,
                    "the error bound %.3g is too large to single out one integer (Gauss "
                    "integral %.17g)",
                    r.error_bound, r.gauss_integral);
  }
  return buf;
}

// The fast path of ParseBatchLine for the common, plain form of a line: an object with the keys
// "id", "a", "b" (each at most once, any order, JSON whitespace anywhere), "a" and "b" arrays of
// [x,y,z] number triples (strict JSON number syntax, read by std::from_chars, which rounds
// correctly as nlohmann's strtod does: the same doubles). The id's value (anything but an object
// or array, and strings without escapes) is parsed by nlohmann from its own text. Returns false,
// having read nothing for sure, whenever the line is anything else (escapes, nesting, errors,
// out-of-range numbers): the general parser then decides and words the error.
class FastBatchLine {
 public:
  explicit FastBatchLine(const std::string& line) : p_(line.data()), end_(p_ + line.size()) {}

  bool Parse(nlohmann::json* id, topology::Chain* a, topology::Chain* b) {
    bool seen[3] = {false, false, false};
    *id = nlohmann::json();
    if (!Eat('{')) return false;
    if (Eat('}')) return false;  // no "a", "b": the general parser words the error
    do {
      std::string_view key;
      if (!String(&key) || !Eat(':')) return false;
      const int k = key == "id" ? 0 : key == "a" ? 1 : key == "b" ? 2 : -1;
      if (k < 0 || seen[k]) return false;
      seen[k] = true;
      if (k == 0 ? !Id(id) : !Points(k == 1 ? a : b)) return false;
    } while (Eat(','));
    if (!Eat('}')) return false;
    Space();
    return p_ == end_ && seen[1] && seen[2];
  }

 private:
  void Space() {
    while (p_ < end_ && (*p_ == ' ' || *p_ == '\t' || *p_ == '\n' || *p_ == '\r')) ++p_;
  }
  bool Eat(char c) {
    Space();
    if (p_ < end_ && *p_ == c) {
      ++p_;
      return true;
    }
    return false;
  }
  // A string without escapes or control characters.
  bool String(std::string_view* out) {
    if (!Eat('"')) return false;
    const char* start = p_;
    while (p_ < end_ && *p_ != '"') {
      if (*p_ == '\\' || static_cast<unsigned char>(*p_) < 0x20) return false;
      ++p_;
    }
    if (p_ == end_) return false;
    *out = std::string_view(start, static_cast<size_t>(p_ - start));
    ++p_;
    return true;
  }
  bool Id(nlohmann::json* id) {
    Space();
    const char* start = p_;
    if (p_ < end_ && *p_ == '"') {
      std::string_view text;
      if (!String(&text)) return false;
    } else {
      while (p_ < end_ && *p_ != ',' && *p_ != '}' && *p_ != '{' && *p_ != '[' && *p_ != '"') ++p_;
    }
    *id = nlohmann::json::parse(start, p_, nullptr, /*allow_exceptions=*/false);
    return !id->is_discarded();
  }
  // Strict JSON number syntax: -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)?
  bool Number(double* value) {
    Space();
    const char* start = p_;
    auto digits = [&] {
      const char* d = p_;
      while (p_ < end_ && *p_ >= '0' && *p_ <= '9') ++p_;
      return p_ > d;
    };
    if (p_ < end_ && *p_ == '-') ++p_;
    if (p_ < end_ && *p_ == '0') {
      ++p_;
    } else if (!digits()) {
      return false;
    }
    bool integer = true;
    if (p_ < end_ && *p_ == '.') {
      ++p_;
      integer = false;
      if (!digits()) return false;
    }
    if (p_ < end_ && (*p_ == 'e' || *p_ == 'E')) {
      ++p_;
      integer = false;
      if (p_ < end_ && (*p_ == '+' || *p_ == '-')) ++p_;
      if (!digits()) return false;
    }
    const auto [ptr, ec] = std::from_chars(start, p_, *value);
    // nlohmann reads an integer literal as an integer: "-0" is +0.0 there.
    if (integer && *value == 0.0) *value = 0.0;
    return ec == std::errc() && ptr == p_;
  }
  bool Points(topology::Chain* chain) {
    if (!Eat('[')) return false;
    coords_.clear();
    if (!Eat(']')) {
      do {
        double x, y, z;
        if (!Eat('[') || !Number(&x) || !Eat(',') || !Number(&y) || !Eat(',') || !Number(&z) ||
            !Eat(']')) {
          return false;
        }
        coords_.insert(coords_.end(), {x, y, z});
        if (coords_.size() > 3 * static_cast<size_t>(topology::kMaxChainPoints)) return false;
      } while (Eat(','));
      if (!Eat(']')) return false;
    }
    const Eigen::Index n = static_cast<Eigen::Index>(coords_.size() / 3);
    chain->resize(3, n);
    std::copy(coords_.begin(), coords_.end(), chain->data());
    return true;
  }

  const char* p_;
  const char* const end_;
  std::vector<double> coords_;
};

// One JSON line: {"id": ..., "a": [[x,y,z], ...], "b": [[x,y,z], ...]} → *id, *a, *b.
void ParseBatchLine(const std::string& line, nlohmann::json* id, topology::Chain* a,
                    topology::Chain* b) {
  if (FastBatchLine(line).Parse(id, a, b)) return;
  const nlohmann::json j = nlohmann::json::parse(line, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) throw std::invalid_argument("invalid JSON");
  if (!j.is_object()) throw std::invalid_argument("expected an object {\"a\": ..., \"b\": ...}");
  for (const auto& item : j.items()) {
    if (item.key() != "id" && item.key() != "a" && item.key() != "b") {
      throw std::invalid_argument("unknown key '" + item.key() + "' (expected id, a, b)");
    }
  }
  *id = j.contains("id") ? j["id"] : nlohmann::json();
  for (const auto& [key, chain] : {std::pair{"a", a}, std::pair{"b", b}}) {
    if (!j.contains(key) || !j[key].is_array()) {
      throw std::invalid_argument(std::string("\"") + key + "\": expected an array of [x,y,z]");
    }
    const nlohmann::json& pts = j[key];
    if (pts.size() > static_cast<size_t>(topology::kMaxChainPoints)) {
      throw std::invalid_argument(std::string("\"") + key + "\": more than " +
                                  std::to_string(topology::kMaxChainPoints) + " points");
    }
    chain->resize(3, static_cast<Eigen::Index>(pts.size()));
    for (size_t k = 0; k < pts.size(); ++k) {
      const nlohmann::json& p = pts[k];
      if (!p.is_array() || p.size() != 3 || !p[0].is_number() || !p[1].is_number() ||
          !p[2].is_number()) {
        throw std::invalid_argument(std::string("\"") + key + "\"[" + std::to_string(k) +
                                    "]: expected [x,y,z] numbers");
      }
      for (int d = 0; d < 3; ++d) (*chain)(d, static_cast<Eigen::Index>(k)) = p[d].get<double>();
    }
  }
}

// --batch: one result line per input line; stops with exit 2 at the first malformed line.
int RunBatch(const LinkingArgs& la, topology::LinkingMethod method) {
  std::ifstream file;
  if (la.batch != "-") {
    file.open(la.batch);
    if (!file) throw std::invalid_argument(la.batch + ": cannot open");
  }
  std::istream& in = la.batch == "-" ? std::cin : file;
  const std::string source = la.batch == "-" ? "stdin" : la.batch;
  topology::WritheStreamOptions options;
  options.threads = la.threads;
  options.far_field_tol = la.tol;
  const StopCheck stop(0.0);
  topology::Chain a, b;
  nlohmann::json id;
  std::string line;
  bool all_certified = true;
  for (long line_no = 1; std::getline(in, line); ++line_no) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    stop.Poll();
    topology::LinkingResult r;
    try {
      ParseBatchLine(line, &id, &a, &b);
      if (la.close) {
        CloseChain(&a);
        CloseChain(&b);
      }
      RequireClosed(a, "\"a\"", la.close);
      RequireClosed(b, "\"b\"", la.close);
      r = topology::LinkingNumberAuto(a, b, method, options);
    } catch (const std::invalid_argument& e) {
      std::fflush(stdout);
      std::string msg = source;
      msg.append(":").append(std::to_string(line_no)).append(": ").append(e.what());
      throw std::invalid_argument(msg);
    }
    nlohmann::ordered_json out;
    out["id"] = id;
    out.update(ResultJson(r));
    const std::string text = out.dump();
    std::fwrite(text.data(), 1, text.size(), stdout);
    std::fputc('\n', stdout);
    all_certified = all_certified && r.status == topology::LinkingStatus::kCertified;
  }
  return all_certified ? kExitOk : kExitFailed;
}

}  // namespace

void AddLinkingCommand(CLI::App* root, CommandList* commands) {
  auto la = std::make_shared<LinkingArgs>();
  CLI::App* linking = root->add_subcommand(
      "linking", "Gauss linking number of two closed chains (streamed, certified rounding)");
  linking->add_option("A", la->a_path, "first closed chain CSV (last point = first point)");
  linking->add_option("B", la->b_path, "second closed chain CSV");
  linking->add_flag("--json", la->json,
                    "print {\"linking_number\", \"status\", \"gauss_integral\" (null for "
                    "crossings), \"error_bound\", \"distance\", \"segments\", "
                    "\"degenerate_pairs\", \"method\", \"crossings\", \"projection\"}");
  linking->add_flag("--close", la->close, "close an open chain by appending its first point");
  AddStreamThreadsFlag(linking, &la->threads);
  linking
      ->add_option("--tol", la->tol,
                   "approximate far segment pairs (Barnes-Hut, Qu & James 2021) with at most "
                   "this error in the Gauss integral, added to the error bound; e.g. 0.05 "
                   "(default: exact; at most 0.5, beyond which no integer can be certified)")
      ->check(FiniteIn(1e-12, 0.5));
  linking
      ->add_option("--method", la->method,
                   "auto (default): signed crossings of a projection, exact; the Gauss integral "
                   "when no projection tried is generic | crossings | gauss")
      ->check(CLI::IsMember({"auto", "crossings", "gauss"}));
  linking
      ->add_option("--batch", la->batch,
                   "many pairs from FILE (or - for stdin), one JSON object per line: "
                   "{\"id\": any, \"a\": [[x,y,z],...], \"b\": [[x,y,z],...]}; one JSON result "
                   "line each")
      ->check(NonEmpty());
  linking->footer(
      "Crossings: Lk = 1/2 sum of the signs of the crossings of A with B seen along a fixed\n"
      "generic direction, every sign certified by error-bounded predicates (docs/methods.md);\n"
      "near-linear time. Gauss: T = sum of the writhe matrix (see `topoplan writhe`), computed\n"
      "without storing the matrix, with an error bound B; round(T) is printed only when\n"
      "|T - round(T)| <= B < 1/2 and no segment pairs touch. --tol implies gauss. A result\n"
      "that is not certified prints its reason and exits 1.\n"
      "Open chains are refused (exit 2) unless --close. --batch stops at the first malformed\n"
      "line with exit 2, naming it (lines before it are answered); exit 1 if any pair is not\n"
      "certified. Long inputs show progress; Ctrl-C stops them (exit 130).");
  commands->push_back(
      {linking, [la]() -> int {
         const topology::LinkingMethod method = la->Method();
         if (la->tol > 0.0 && method == topology::LinkingMethod::kCrossings) {
           throw std::invalid_argument(
               "--tol: approximates the Gauss integral; not with --method crossings");
         }
         if (!la->batch.empty()) {
           if (!la->a_path.empty()) {
             throw std::invalid_argument("--batch: takes no chain files A, B");
           }
           return RunBatch(*la, method);
         }
         if (la->a_path.empty() || la->b_path.empty()) {
           throw std::invalid_argument("linking: needs two chain files A B (or --batch)");
         }
         topology::Chain a = topology::ReadChainCsv(la->a_path);
         topology::Chain b = topology::ReadChainCsv(la->b_path);
         if (la->close) {
           CloseChain(&a);
           CloseChain(&b);
         }
         RequireClosed(a, la->a_path, true);
         RequireClosed(b, la->b_path, true);
         const StopCheck stop(0.0);
         topology::WritheStreamOptions options;
         options.threads = la->threads;
         options.far_field_tol = la->tol;
         options.progress = PairProgress("linking", stop);
         const topology::LinkingResult r = topology::LinkingNumberAuto(a, b, method, options);
         EndProgress();
         const bool ok = r.status == topology::LinkingStatus::kCertified;
         if (la->json) {
           std::cout << ResultJson(r).dump() << "\n";
         } else if (ok && r.method == topology::LinkingMethod::kCrossings) {
           std::printf(
               "linking number %lld (%lld signed crossings in a projection; %d x %d segments)\n",
               r.linking_number, r.crossings, r.segments_a, r.segments_b);
         } else if (r.method == topology::LinkingMethod::kCrossings) {
           std::printf("linking number not certified (crossings: no generic projection)\n");
         } else if (ok) {
           std::printf(
               "linking number %lld (Gauss integral %.17g, error bound %.3g; "
               "%d x %d segments)\n",
               r.linking_number, r.gauss_integral, r.error_bound, r.segments_a, r.segments_b);
         } else {
           std::printf(
               "linking number not certified (%s): Gauss integral %.17g, "
               "error bound %.3g\n",
               topology::LinkingStatusName(r.status), r.gauss_integral, r.error_bound);
         }
         if (!ok) {
           std::fprintf(stderr, "topoplan linking: %s\n", Reason(r).c_str());
         }
         return ok ? kExitOk : kExitFailed;
       }});
}

}  // namespace app
