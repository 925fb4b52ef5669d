// SPDX-License-Identifier: GPL-3.0-or-later
// The type of a request field as the front ends name it: the command line's option type (CLI11's type_name, shown
// by --help and the command reference) and the Python annotation of the keyword (inspect.signature, help()).  One
// name per C++ field type of core/fields.hpp, so both front ends say the same thing about the same field.
#pragma once

#include "core/fields.hpp"

#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

namespace btob::core {

struct FieldTypeName {
  const char* cli;     // CLI11 adds " ..." itself to an option taking several values
  const char* python;  // a Python annotation (text: evaluated by nobody, read by help() and notebooks)
};

template <class T> constexpr FieldTypeName field_type_name() {
  static_assert(is_field_type_v<T>, "not a request field type (core/fields.hpp)");
  if constexpr (std::is_same_v<T, bool>) return {"", "bool"};
  // Signed or not (counts, seeds): the field's help and validate() state its range; "=" would read as a default.
  else if constexpr (std::is_same_v<T, int> || std::is_same_v<T, long> || std::is_same_v<T, std::uint64_t>)
    return {"INTEGER", "int"};
  else if constexpr (std::is_same_v<T, double>) return {"REAL", "float"};
  // A Decimal is a real number kept as the decimal text given (r = 0.1 is 0.1 in every precision): a str keeps it.
  else if constexpr (std::is_same_v<T, Decimal>) return {"DECIMAL", "float | str"};
  else if constexpr (std::is_same_v<T, std::string>) return {"TEXT", "str"};
  else if constexpr (std::is_same_v<T, std::vector<double>>) return {"REAL", "list[float] | str"};
  else if constexpr (std::is_same_v<T, std::vector<Decimal>>) return {"DECIMAL", "list[float | str] | str"};
  else return {"TEXT", "list[str] | str"};
}

// A field visitor listing each field's name and type names, in declaration order: req.fields(TypeLister{&out}).
struct FieldTypeDoc {
  std::string name;
  FieldTypeName type;
};
struct TypeLister {
  std::vector<FieldTypeDoc>* out;
  template <class T, class... Tag> void operator()(const std::string& name, T&, const std::string&, Tag...) {
    out->push_back(FieldTypeDoc{name, field_type_name<T>()});
  }
};

}  // namespace btob::core
