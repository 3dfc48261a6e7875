#include "topology/polyline.h"

#include <cstdlib>
#include <iomanip>
#include <limits>
#include <optional>
#include <locale>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "base/file_read.h"
#include "base/numbers.h"

namespace topology {
namespace {

std::string Trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

[[noreturn]] void Fail(const std::string& source, int line, const std::string& what) {
  throw std::invalid_argument(source + ":" + std::to_string(line) + ": " + what);
}

}  // namespace

Chain ParseChainCsv(std::istream& in, const std::string& source_name) {
  std::vector<double> xyz;
  std::string raw;
  int line_no = 0;
  while (std::getline(in, raw)) {
    ++line_no;
    const std::string line = Trim(raw);
    if (line.empty() || line[0] == '#') continue;
    std::stringstream fields(line);
    fields.imbue(std::locale::classic());  // "0.5" whatever the global locale
    std::string field;
    int count = 0;
    while (std::getline(fields, field, ',')) {
      field = Trim(field);
      if (++count > 3) Fail(source_name, line_no, "expected 3 comma-separated numbers x,y,z");
      double v = 0.0;
      switch (base::ClassifyNumber(field, &v)) {
        case base::NumberKind::kFinite:
          break;
        case base::NumberKind::kNonFinite:
          Fail(source_name, line_no, "non-finite value '" + field + "'");
        case base::NumberKind::kNotANumber:
          Fail(source_name, line_no, "'" + field + "' is not a number");
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

Chain ReadChainCsv(const std::string& path) {
  std::istringstream in(base::ReadFileBounded(path, "chain"));
  in.imbue(std::locale::classic());  // "0.5" whatever the global locale
  return ParseChainCsv(in, path);
}

void WriteChainCsv(const Chain& chain, std::ostream& out) {
  out << std::setprecision(std::numeric_limits<double>::max_digits10);
  for (Eigen::Index i = 0; i < chain.cols(); ++i) {
    out << chain(0, i) << ',' << chain(1, i) << ',' << chain(2, i) << '\n';
  }
}

}  // namespace topology
