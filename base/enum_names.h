// One enum <-> name mechanism: each enum has a constexpr table of {value, name} pairs, found by
// argument-dependent lookup as `EnumNames(E{})`; ToName / ParseEnum work on any such table.
//
//   inline constexpr EnumName<Color> kColorNames[] = {{Color::kRed, "red"}, ...};
//   constexpr std::span<const EnumName<Color>> EnumNames(Color) { return kColorNames; }
//   ToName(Color::kRed) == "red";  ParseEnum<Color>("red", "colour") == Color::kRed;
//   ParseEnum<Color>("blue", "colour") throws "unknown colour 'blue' (red, ...)".
#pragma once

#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

namespace base {

template <typename E>
struct EnumName {
  E value;
  const char* name;
};

// The name of `value` in its table; "?" if it is not listed.
template <typename E>
constexpr const char* ToName(E value) {
  for (const EnumName<E>& e : EnumNames(E{})) {
    if (e.value == value) return e.name;
  }
  return "?";
}

// "a, b, c": every name of E, in table order.
template <typename E>
std::string EnumNameList() {
  std::string out;
  for (const EnumName<E>& e : EnumNames(E{}))
    out += (out.empty() ? "" : ", ") + std::string(e.name);
  return out;
}

// The value named `name`; throws std::invalid_argument "unknown <what> '<name>' (a, b, c)".
template <typename E>
E ParseEnum(std::string_view name, const std::string& what) {
  for (const EnumName<E>& e : EnumNames(E{})) {
    if (name == e.name) return e.value;
  }
  throw std::invalid_argument("unknown " + what + " '" + std::string(name) + "' (" +
                              EnumNameList<E>() + ")");
}

}  // namespace base
