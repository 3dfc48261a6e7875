// The exception for a broken environment (exit code 3): no GL context, a missing installed asset
// or font. Bad input is std::invalid_argument (exit code 2).
#pragma once

#include <stdexcept>

namespace base {

class EnvironmentError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace base
