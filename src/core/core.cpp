// SPDX-License-Identifier: GPL-3.0-or-later
// Non-template parts of btob::core: validation and precision names.
#include "core/map.hpp"
#include "core/scalar.hpp"

#include "core/request.hpp"

#include <cmath>

#include <fmt/format.h>

namespace btob::core {

std::string detail::shortest(double v) { return fmt::format("{}", v); }

void detail::refuse_r(double r, const char* field) {
  throw InvalidField(field, shortest(r), "a value in the open interval (0, 1)");
}

void validate_point(double x, double y, double z, const char* field) {
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
    throw InvalidField(field, fmt::format("({}, {}, {})", x, y, z), "finite coordinates x,y,z");
  if (x == 0 && y == 0 && z == 0) throw InvalidField(field, "the zero vector", "a non-zero normal vector x,y,z");
  if (x == 0 && z == 0)
    throw InvalidField(field, fmt::format("({}, {}, {}) with x = z = 0", x, y, z),
                       "x or z non-zero (x = z = 0 puts all four particles in contact)");
  if (x * z > 0 || (x != 0 && z != 0 && std::signbit(x) == std::signbit(z)))
    throw InvalidField(field, fmt::format("({}, {}, {}) with x*z > 0", x, y, z),
                       "a point of the domain x*z <= 0 (eq. 3.4)");
}

std::string Precision::name() const {
  switch (kind) {
    case Kind::f32: return "float";
    case Kind::f64: return "double";
    case Kind::f80: return "long-double";
    case Kind::f128: return "float128";
    case Kind::mpfr: return fmt::format("mpfr:{}", mpfr_digits);
  }
  return "?";
}

Precision parse_precision(std::string_view text, const char* field) {
  Precision p;
  if (text == "float") p.kind = Precision::Kind::f32;
  else if (text == "double") p.kind = Precision::Kind::f64;
  else if (text == "long-double" || text == "long double" || text == "longdouble") p.kind = Precision::Kind::f80;
  else if (text == "float128") p.kind = Precision::Kind::f128;
  else if (text.starts_with("mpfr")) {
    p.kind = Precision::Kind::mpfr;
    std::string_view digits = text.substr(4);
    if (!digits.empty() && digits.front() == ':') digits.remove_prefix(1);
    int d = 0;
    bool ok = !digits.empty();
    for (char c : digits) {
      if (c < '0' || c > '9' || d > 100000) {
        ok = false;
        break;
      }
      d = d * 10 + (c - '0');
    }
    if (!ok || d < 10 || d > 10000)
      throw InvalidField(field, fmt::format("'{}'", text), "mpfr:<digits> with 10 <= digits <= 10000");
    p.mpfr_digits = d;
  } else {
    throw InvalidField(field, fmt::format("'{}'", text), "one of float, double, long-double, float128, mpfr:<digits>");
  }
  return p;
}

}  // namespace btob::core
