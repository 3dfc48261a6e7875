#include "topology/polyline.h"

#include <algorithm>
#include <cstdlib>
#include <iomanip>
#include <limits>
#include <locale>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "base/file_read.h"
#include "base/numbers.h"

namespace topology {
namespace {

// `s` without leading and trailing spaces, tabs and carriage returns.
std::string_view Trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

[[noreturn]] void Fail(const std::string& source, int line, const std::string& what) {
  throw std::invalid_argument(source + ":" + std::to_string(line) + ": " + what);
}

// The whole text of a chain file: lines split at '\n' (as std::getline: no empty last line after
// a final newline), fields at ',' (as std::getline: none after a final comma, which is refused).
// No stream per line: chains of 10⁵ points parse in milliseconds.
Chain ParseChainText(std::string_view text, const std::string& source_name) {
  std::vector<double> xyz;
  std::string field_text;  // ClassifyNumber's argument, reused
  int line_no = 0;
  size_t pos = 0;
  while (pos < text.size()) {
    const size_t eol = std::min(text.find('\n', pos), text.size());
    const std::string_view line = Trim(text.substr(pos, eol - pos));
    pos = eol + 1;
    ++line_no;
    if (line.empty() || line[0] == '#') continue;
    int count = 0;
    for (size_t f = 0; f < line.size();) {
      const size_t comma = std::min(line.find(',', f), line.size());
      const std::string_view field = Trim(line.substr(f, comma - f));
      f = comma + 1;
      if (++count > 3) Fail(source_name, line_no, "expected 3 comma-separated numbers x,y,z");
      field_text.assign(field);
      double v = 0.0;
      switch (base::ClassifyNumber(field_text, &v)) {
        case base::NumberKind::kFinite:
          break;
        case base::NumberKind::kNonFinite:
          Fail(source_name, line_no, "non-finite value '" + field_text + "'");
        case base::NumberKind::kNotANumber:
          Fail(source_name, line_no, "'" + field_text + "' is not a number");
      }
      xyz.push_back(v);
    }
    if (line.back() == ',') Fail(source_name, line_no, "trailing comma");
    if (count != 3) Fail(source_name, line_no, "expected 3 comma-separated numbers x,y,z");
    if (xyz.size() > 3 * static_cast<std::size_t>(kMaxChainPoints)) {
      Fail(source_name, line_no,
           "more than " + std::to_string(kMaxChainPoints) + " points (limit of a chain file)");
    }
  }
  const int n = static_cast<int>(xyz.size() / 3);
  if (n < 2) {
    throw std::invalid_argument(source_name + ": a chain needs at least 2 points, found " +
                                std::to_string(n));
  }
  return Eigen::Map<const Chain>(xyz.data(), 3, n);
}

}  // namespace

Chain ParseChainCsv(std::istream& in, const std::string& source_name) {
  std::ostringstream text;
  text << in.rdbuf();
  return ParseChainText(text.str(), source_name);
}

Chain ReadChainCsv(const std::string& path) {
  return ParseChainText(base::ReadFileBounded(path, "chain"), path);
}

void WriteChainCsv(const Chain& chain, std::ostream& out) {
  out << std::setprecision(std::numeric_limits<double>::max_digits10);
  for (Eigen::Index i = 0; i < chain.cols(); ++i) {
    out << chain(0, i) << ',' << chain(1, i) << ',' << chain(2, i) << '\n';
  }
}

}  // namespace topology
