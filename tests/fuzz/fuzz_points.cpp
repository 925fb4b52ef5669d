// Fuzz harness: core::parse_point ("x,y,z", the --point flag of lyapunov, stats, classify).  A parse either
// throws a std::logic_error (invalid_argument or domain_error, naming the field) or returns a finite, non-zero
// point of the domain x*z <= 0 with x, z not both zero (eq. 3.2).
//
// core::parse_point(std::string_view, const char* field) is being moved into core from the command line; until
// it exists the fallback declared below is chosen by overload resolution and the harness does nothing (a
// non-template function beats this template on an exact match, so the real parser wins as soon as it exists).
#include "core/coords.hpp"
#include "core/map.hpp"
#include "core/scalar.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string_view>
#include <type_traits>

namespace btob::core {
struct NoParsePointYet {};
template <class... A> NoParsePointYet parse_point(A&&...);  // never defined: only its return type is looked at
}  // namespace btob::core

namespace {
// A template, so that the discarded branch is not compiled while only the fallback exists.
template <class Text> void check_point(Text text) {
  const char* field = "point";
  using Parsed = decltype(btob::core::parse_point(text, field));
  if constexpr (!std::is_same_v<Parsed, btob::core::NoParsePointYet>) {
    try {
      const auto p = btob::core::parse_point(text, field);
      const double x = p[0], y = p[1], z = p[2];
      if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) std::abort();
      if (x * z > 0 || (x == 0 && z == 0)) std::abort();
    } catch (const std::logic_error&) {
    }
  }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 4096) return 0;
  check_point(std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
