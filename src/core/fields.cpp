// SPDX-License-Identifier: GPL-3.0-or-later
// Field parsers of requests (core/fields.hpp).
#include "core/fields.hpp"

#include "core/scalar.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdlib>

namespace btob::core {

namespace {
std::string quoted(std::string_view t) { return fmt::format("'{}'", t); }

std::string_view trim(std::string_view t) {
  while (!t.empty() && (t.front() == ' ' || t.front() == '\t')) t.remove_prefix(1);
  while (!t.empty() && (t.back() == ' ' || t.back() == '\t')) t.remove_suffix(1);
  return t;
}

std::vector<std::string> split_items(const std::vector<std::string>& items) {
  std::vector<std::string> out;
  for (const auto& it : items) {
    std::string cur;
    for (char c : it) {
      if (c == ',' || c == ' ' || c == ';') {
        if (!cur.empty()) out.push_back(cur);
        cur.clear();
      } else {
        cur += c;
      }
    }
    if (!cur.empty()) out.push_back(cur);
  }
  return out;
}

const std::string& single(const std::vector<std::string>& items, const std::string& field) {
  if (items.size() != 1) throw InvalidField(field, fmt::format("{} values", items.size()), "exactly one value");
  return items[0];
}
}  // namespace

bool parse_bool(std::string_view text, const std::string& field) {
  const std::string_view t = trim(text);
  if (t == "true" || t == "1" || t == "yes" || t == "on") return true;
  if (t == "false" || t == "0" || t == "no" || t == "off") return false;
  throw InvalidField(field, quoted(text), "true or false");
}

namespace {
// An integer written in decimal, optionally in scientific notation whose value is an exact integer: "1000000",
// "1e6", "2.5e3", "-3E2".  Parsed with integer arithmetic only (no rounding through double): the digits of the
// mantissa form D, f of them after the point, and the value is D * 10^(e - f), which must have no fractional
// part ("1.5e0", "1e-3" are refused).  `magnitude` gets |value|; false when the text is not such an integer or
// |value| >= 2^64.
bool exact_integer(const std::string& s, bool& negative, std::uint64_t& magnitude) {
  std::size_t i = 0;
  negative = false;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) negative = s[i++] == '-';
  std::string digits;  // mantissa digits, the point removed
  long frac = 0;       // how many of them were after the point
  bool point = false;
  for (; i < s.size() && (std::isdigit(static_cast<unsigned char>(s[i])) || (s[i] == '.' && !point)); ++i) {
    if (s[i] == '.') point = true;
    else {
      digits += s[i];
      frac += point ? 1 : 0;
    }
  }
  if (digits.empty()) return false;
  long exponent = 0;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    bool eneg = false;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) eneg = s[i++] == '-';
    if (i == s.size()) return false;
    for (; i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])); ++i)
      if ((exponent = exponent * 10 + (s[i] - '0')) > 100000) return false;
    if (eneg) exponent = -exponent;
  } else if (point && frac == 0) {
    return false;  // "12." is not written as an integer
  }
  if (i != s.size()) return false;
  long shift = exponent - frac;  // value = digits * 10^shift
  while (shift < 0) {            // drop trailing zeros; a non-zero one is a fractional part
    if (digits.back() != '0') return false;
    digits.pop_back();
    ++shift;
    if (digits.empty()) digits = "0";
  }
  unsigned __int128 v = 0;
  const unsigned __int128 limit = static_cast<unsigned __int128>(UINT64_MAX);
  for (char c : digits)
    if ((v = v * 10 + static_cast<unsigned>(c - '0')) > limit) return false;
  for (long k = 0; k < shift && v != 0; ++k)
    if ((v *= 10) > limit) return false;
  magnitude = static_cast<std::uint64_t>(v);
  return true;
}
constexpr const char* integer_forms = "(1000000, or exactly in scientific notation: 1e6, 2.5e3)";
}  // namespace

long parse_long(std::string_view text, const std::string& field) {
  const std::string s(trim(text));
  bool negative = false;
  std::uint64_t m = 0;
  const std::uint64_t max = static_cast<std::uint64_t>(LONG_MAX);
  if (!exact_integer(s, negative, m) || m > max + (negative ? 1 : 0))
    throw InvalidField(field, quoted(text), fmt::format("an integer {}", integer_forms));
  if (negative) return m == max + 1 ? LONG_MIN : -static_cast<long>(m);
  return static_cast<long>(m);
}

std::uint64_t parse_u64(std::string_view text, const std::string& field) {
  const std::string s(trim(text));
  bool negative = false;
  std::uint64_t m = 0;
  if (!exact_integer(s, negative, m) || (negative && m != 0))
    throw InvalidField(field, quoted(text), fmt::format("a non-negative integer below 2^64 {}", integer_forms));
  return m;
}

double parse_double(std::string_view text, const std::string& field) {
  const std::string s(trim(text));
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  // strtod sets ERANGE on underflow too: a subnormal (or a tiny value rounded to 0) is a number, an overflow
  // to infinity is not.
  if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(v))
    throw InvalidField(field, quoted(text), "a finite number");
  return v;
}

Decimal::Decimal(double v) : value(v), text(fmt::format("{}", v)) {}

Decimal Decimal::parse(std::string_view text, const std::string& field) {
  Decimal d;
  d.value = parse_double(text, field);
  d.text = std::string(trim(text));
  return d;
}

std::vector<double> values(const std::vector<Decimal>& v) { return {v.begin(), v.end()}; }

template <class T> void set_field(T& value, const std::vector<std::string>& items, const std::string& field) {
  if constexpr (std::is_same_v<T, bool>) {
    value = items.empty() ? true : parse_bool(single(items, field), field);  // a flag given alone means true
  } else if constexpr (std::is_same_v<T, int>) {
    const long v = parse_long(single(items, field), field);
    if (v < -2147483647L || v > 2147483647L) throw InvalidField(field, std::to_string(v), "an integer below 2^31");
    value = static_cast<int>(v);
  } else if constexpr (std::is_same_v<T, long>) {
    value = parse_long(single(items, field), field);
  } else if constexpr (std::is_same_v<T, std::uint64_t>) {
    value = parse_u64(single(items, field), field);
  } else if constexpr (std::is_same_v<T, double>) {
    value = parse_double(single(items, field), field);
  } else if constexpr (std::is_same_v<T, Decimal>) {
    value = Decimal::parse(single(items, field), field);
  } else if constexpr (std::is_same_v<T, std::vector<Decimal>>) {
    value.clear();
    for (const auto& s : split_items(items)) value.push_back(Decimal::parse(s, field));
  } else if constexpr (std::is_same_v<T, std::string>) {
    value = single(items, field);
  } else if constexpr (std::is_same_v<T, std::vector<double>>) {
    value.clear();
    for (const auto& s : split_items(items)) value.push_back(parse_double(s, field));
  } else {
    static_assert(std::is_same_v<T, std::vector<std::string>>);
    value = items;
  }
}

template <class T> std::vector<std::string> field_text(const T& value) {
  if constexpr (std::is_same_v<T, bool>) return {value ? "true" : "false"};
  else if constexpr (std::is_same_v<T, double>) return {fmt::format("{}", value)};  // shortest round-trip form
  else if constexpr (std::is_same_v<T, std::string>) return {value};
  else if constexpr (std::is_same_v<T, Decimal>) return {value.text};
  else if constexpr (std::is_same_v<T, std::vector<Decimal>>) {
    std::vector<std::string> out;
    for (const Decimal& v : value) out.push_back(v.text);
    return out;
  } else if constexpr (std::is_same_v<T, std::vector<double>>) {
    std::vector<std::string> out;
    for (double v : value) out.push_back(fmt::format("{}", v));
    return out;
  } else if constexpr (std::is_same_v<T, std::vector<std::string>>) return value;
  else return {std::to_string(value)};
}

#define BTOB_FIELD_TYPE(T)                                                             \
  template void set_field<T>(T&, const std::vector<std::string>&, const std::string&); \
  template std::vector<std::string> field_text<T>(const T&);
BTOB_FIELD_TYPE(bool)
BTOB_FIELD_TYPE(int)
BTOB_FIELD_TYPE(long)
BTOB_FIELD_TYPE(std::uint64_t)
BTOB_FIELD_TYPE(double)
BTOB_FIELD_TYPE(std::string)
BTOB_FIELD_TYPE(std::vector<double>)
BTOB_FIELD_TYPE(std::vector<std::string>)
BTOB_FIELD_TYPE(Decimal)
BTOB_FIELD_TYPE(std::vector<Decimal>)
#undef BTOB_FIELD_TYPE

Vec3<double> parse_point(std::string_view text, const std::string& field) {
  std::vector<double> v;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = text.find(',', start);
    const std::string_view item =
        text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    try {
      v.push_back(parse_double(item, field));
    } catch (const InvalidField&) {
      throw InvalidField(field, quoted(text), "three finite numbers x,y,z");
    }
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  if (v.size() != 3) throw InvalidField(field, quoted(text), "three finite numbers x,y,z");
  validate_point(v[0], v[1], v[2], field.c_str());
  // Exact rescaling by a power of two (ldexp of a double by an integer is exact unless it under- or overflows,
  // which the target range [1, 2) for the largest component rules out).
  int e = 0;
  std::frexp(std::max({std::abs(v[0]), std::abs(v[1]), std::abs(v[2])}), &e);
  return {std::ldexp(v[0], 1 - e), std::ldexp(v[1], 1 - e), std::ldexp(v[2], 1 - e)};
}

void require_r(double r, const std::string& field) {
  if (!(r > 0 && r < 1)) detail::refuse_r(r, field.c_str());
}

void require_r_range(double r_min, double r_max, long r_count) {
  require_r(r_min, "r-min");
  require_r(r_max, "r-max");
  if (!(r_min < r_max || (r_count == 1 && r_min == r_max)))
    throw InvalidField("r-max", fmt::format("{}", r_max),
                       fmt::format("a value in {}r-min = {}, 1)", r_count == 1 ? "[" : "(", r_min));
  require_distinct(r_min, r_max, r_count, "r-count", "r-min..r-max");
}

void require_r_values(const std::vector<double>& r, const std::string& field) {
  if (r.empty()) throw InvalidField(field, "no value", "one or more r values in (0, 1)");
  for (double v : r) require_r(v, field);
}

std::string threads_expected() { return fmt::format("0 (all cores) or 1..{}", RunControl::max_threads); }

void require_threads(long threads, const std::string& field) {
  if (threads < 0 || threads > RunControl::max_threads)
    throw InvalidField(field, std::to_string(threads), threads_expected());
}

void require_at_least(long value, long least, const std::string& field) {
  if (value < least) throw InvalidField(field, std::to_string(value), fmt::format("at least {}", least));
}

Precision require_precision(const std::string& text, const std::vector<std::string>& accepted,
                            const std::string& field) {
  if (std::find(accepted.begin(), accepted.end(), text) != accepted.end()) return parse_precision(text, field.c_str());
  const bool mpfr = std::find(accepted.begin(), accepted.end(), "mpfr") != accepted.end();
  if (mpfr && text.starts_with("mpfr")) return parse_precision(text, field.c_str());  // its digits checked there
  std::string names;
  for (std::size_t i = 0; i < accepted.size(); ++i)
    names += (i == 0                     ? ""
              : i + 1 == accepted.size() ? " or "
                                         : ", ") +
             (accepted[i] == "mpfr" ? std::string("mpfr:D with 10 <= D <= 10000") : accepted[i]);
  throw InvalidField(field, fmt::format("'{}'", text), names);
}

// The smallest r whose exponents precision p resolves.  One step of the derivative cocycle contracts the tangent
// plane by about r^2 relative to the orbit direction, and D(u) V = (P V - w (w . P V)) / |P u| recovers that
// part by cancellation from vectors of size ~1: its relative error is ~eps / r^2, so the per-step log-stretch
// errs by that much.  Asking eps / r^2 <= 1e-3 (exponents to about 1e-3 absolute) gives r >= sqrt(1e3 eps):
// 0.011 in float, 4.7e-7 in double, 1.0e-8 in long double, 4.4e-16 in float128, 10^-(D-3)/2 in mpfr:D.
// Below it the cancellation leaves nothing (r = 1e-20 in double gives lambda2 = NaN), so it is refused.
double smallest_r_exponents(const Precision& p) {
  double eps = 0;
  switch (p.kind) {
    case Precision::Kind::f32: eps = std::numeric_limits<float>::epsilon(); break;
    case Precision::Kind::f64: eps = std::numeric_limits<double>::epsilon(); break;
    case Precision::Kind::f80: eps = static_cast<double>(std::numeric_limits<long double>::epsilon()); break;
    case Precision::Kind::f128: eps = 0x1p-112; break;
    case Precision::Kind::mpfr: eps = std::pow(10.0, -p.mpfr_digits); break;
  }
  return std::sqrt(1e3 * eps);
}

void require_r_exponents(double r, const Precision& p, const std::string& field,
                         const std::vector<std::string>& accepted) {
  const double lo = smallest_r_exponents(p);
  if (r >= lo) return;
  // The narrowest accepted precision that resolves this r: the fixed sizes in order, then the MPFR digits D with
  // sqrt(1e3 10^-D) <= r, i.e. D >= 3 - 2 log10 r (one more for the rounding of the log), at most 10000.
  std::string fix;
  for (const char* name : {"float", "double", "long-double", "float128"})
    if (std::find(accepted.begin(), accepted.end(), name) != accepted.end() &&
        r >= smallest_r_exponents(parse_precision(name))) {
      fix = name;
      break;
    }
  const int digits = static_cast<int>(std::ceil(3 - 2 * std::log10(r))) + 1;
  if (fix.empty() && std::find(accepted.begin(), accepted.end(), "mpfr") != accepted.end() && digits <= 10000)
    fix = fmt::format("mpfr:{}", std::max(digits, 10));
  throw InvalidField(field, fmt::format("{}", r),
                     fmt::format("r >= {:.2g} in {} (the tangent plane's contraction r^2 is lost in rounding below){}",
                                 lo, p.name(), fix.empty() ? "" : "; use --precision " + fix));
}

namespace {
// The doubles' order as integers: x < y iff key(x) < key(y) for finite x, y (+0 and -0 share key 0).
std::int64_t order_key(double x) {
  const auto bits = std::bit_cast<std::int64_t>(x);
  return bits >= 0 ? bits : -(bits & INT64_MAX);
}
}  // namespace

double distinct_doubles(double lo, double hi) {
  // Unsigned: across zero the difference of the keys reaches 2^63 and overflows int64 ([-2, 2] counted -2^63); it is
  // below 2^64 for lo <= hi, exact in uint64 (the keys themselves, near 4.6e18, are not exact in double).
  return static_cast<double>(static_cast<std::uint64_t>(order_key(hi)) - static_cast<std::uint64_t>(order_key(lo))) + 1;
}

void require_distinct(double lo, double hi, long count, const std::string& count_field, const std::string& range) {
  if (count < 2 || !(std::isfinite(lo) && std::isfinite(hi) && lo <= hi)) return;  // the range's own checks say why
  const double held = distinct_doubles(lo, hi);
  if (static_cast<double>(count) > held)
    throw InvalidField(
        count_field, fmt::format("{} values over {} = [{}, {}]", count, range, lo, hi),
        fmt::format("at most {:.0f} (the distinct doubles in that range: more values would repeat)", held));
}

std::pair<long, long> parse_int_range(std::string_view text, long lo, long hi, const std::string& field) {
  const auto bad = [&] {
    return InvalidField(field, fmt::format("'{}'", text), fmt::format("A..B or A with {} <= A <= B <= {}", lo, hi));
  };
  const auto number = [&](std::string_view s) {
    long v = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty() || ec != std::errc() || end != s.data() + s.size()) throw bad();
    return v;
  };
  const auto dots = text.find("..");
  const long a = number(dots == std::string_view::npos ? text : text.substr(0, dots));
  const long b = dots == std::string_view::npos ? a : number(text.substr(dots + 2));
  if (a < lo || b < a || b > hi) throw bad();
  return {a, b};
}

}  // namespace btob::core
