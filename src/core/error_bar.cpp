// SPDX-License-Identifier: GPL-3.0-or-later
// core::with_error: the printed interval of a value and its error bar contains the value (core/error_bar.hpp).
#include "core/error_bar.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace btob::core {
namespace {

// x > 0 rounded up to two significant digits, as text that reads back to a double >= x.
std::string two_digits_up(double x) {
  const int e = static_cast<int>(std::floor(std::log10(x)));  // x in [10^e, 10^(e+1)) up to log10's rounding
  double unit = std::pow(10.0, e - 1);
  double m = std::ceil(x / unit);  // 10..100 digits at the unit
  std::string s = fmt::format("{:.1e}", m * unit);
  // The product or the text may have rounded below x.  The text's nearest double above x (strictly) puts the text
  // itself above x: it is nearer that double than x.
  for (int guard = 0; std::stod(s) <= x && guard < 4; ++guard) {
    m += 1;
    s = fmt::format("{:.1e}", m * unit);
  }
  return s;
}

}  // namespace

ValueWithError with_error(double value, double error) {
  if (!std::isfinite(value) || !std::isfinite(error) || error < 0)
    throw std::invalid_argument(
        fmt::format("with_error: value {} and error {} (a finite value, an error >= 0)", value, error));
  // Below 1e-300 a bar is printed as 1.0e-300 (rounded up: two digits of a subnormal have no double to hold them).
  const auto bar = [](double e) { return e == 0 ? std::string("0") : two_digits_up(std::max(e, 1e-300)); };
  if (value == 0) return {"0", bar(error)};  // exact
  // The value's last printed digit: one below the error's second significant digit (all 17 digits when the error
  // has no scale to print at: zero or subnormal).
  const int lead = static_cast<int>(std::floor(std::log10(std::fabs(value))));
  const int unit_exp =
      error >= std::numeric_limits<double>::min() ? static_cast<int>(std::floor(std::log10(error))) - 2 : lead - 16;
  const int significant = std::clamp(lead - unit_exp + 1, 1, 17);
  const std::string v = fmt::format("{:.{}e}", value, significant - 1);
  // The printed value is the value correctly rounded at its last digit (10^(E - significant + 1), E the printed
  // exponent, exact: log10 may be off by one near a power of ten), so it is within half that unit of the value:
  // the bar grows by that half unit (the double 10^k with a relative 4 eps for its own rounding), then is
  // rounded up to two digits.  With 17 digits the text reads back as the same double but is not its exact value.
  const int printed_exp = std::stoi(v.substr(v.find('e') + 1));
  const double half_unit =
      0.5 * std::pow(10.0, printed_exp - significant + 1) * (1 + 4 * std::numeric_limits<double>::epsilon());
  return {fmt::format("{:.{}g}", value, significant), two_digits_up(std::max(error + half_unit, 1e-300))};
}

}  // namespace btob::core
