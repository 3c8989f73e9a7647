/// \file
/// The names of an enumeration's values as scene files, output headers and the command line
/// spell them: one table of {value, name} pairs per enumeration, beside the enumeration, and
/// two functions over any table, so that a name and its parse cannot disagree.
#pragma once

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace boxsim {

/// One value of an enumeration and its name.
template <typename Enum>
struct EnumName {
  Enum value;             ///< the value
  std::string_view name;  ///< its name: lower case, words joined by '_'
};

/// A table of names: every value of an enumeration once, in the order of the enumeration.
template <typename Enum, std::size_t N>
using EnumNames = std::array<EnumName<Enum>, N>;

/// The name of `value` in `table`. Throws std::invalid_argument when the table does not hold
/// the value (a number cast to the enumeration outside its values).
template <typename Enum, std::size_t N>
std::string enumName(const EnumNames<Enum, N>& table, Enum value) {
  for (const EnumName<Enum>& entry : table)
    if (entry.value == value) return std::string(entry.name);
  throw std::invalid_argument("enumName: a value outside the table of names");
}

/// The names of `table` as a sentence lists them: "a", "a or b", "a, b or c".
template <typename Enum, std::size_t N>
std::string enumNameList(const EnumNames<Enum, N>& table) {
  std::string list;
  for (std::size_t i = 0; i < N; ++i) {
    if (i > 0) list += i + 1 == N ? " or " : ", ";
    list += table[i].name;
  }
  return list;
}

/// The value called `name` in `table`. Throws std::invalid_argument for any other name, reading
/// "unknown WHAT 'NAME'; use A, B or C" with `what` the kind of value ("integrator").
template <typename Enum, std::size_t N>
Enum parseEnum(const EnumNames<Enum, N>& table, const std::string& name, std::string_view what) {
  for (const EnumName<Enum>& entry : table)
    if (entry.name == name) return entry.value;
  throw std::invalid_argument("unknown " + std::string(what) + " '" + name + "'; use " +
                              enumNameList(table));
}

}  // namespace boxsim
