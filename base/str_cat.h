// base::StrCat(a, b, ...): one std::string from string-like parts, by append. GCC 12 reports a
// false -Werror=restrict on "literal" + std::string; this is the project's one way around it.
#pragma once

#include <string>

namespace base {

template <typename... T>
std::string StrCat(const T&... parts) {
  std::string s;
  (s.append(parts), ...);
  return s;
}

}  // namespace base
