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
  for (int guard = 0; std::stod(s) < x && guard < 4; ++guard) {  // the product or the text rounded below x
    m += 1;
    s = fmt::format("{:.1e}", m * unit);
  }
  return s;
}

}  // namespace

ValueWithError with_error(double value, double error) {
  if (!std::isfinite(value) || !std::isfinite(error) || error < 0)
    throw std::invalid_argument(fmt::format("with_error: value {} and error {} (a finite value, an error >= 0)", value, error));
  if (error < std::numeric_limits<double>::min())  // no scale to print at: every digit, and the error as given
    return {fmt::format("{:.17g}", value), error == 0 ? std::string("0") : two_digits_up(error)};
  // The value's last printed digit: one below the error's second significant digit.
  const int unit_exp = static_cast<int>(std::floor(std::log10(error))) - 2;
  const int lead = value == 0 ? unit_exp : static_cast<int>(std::floor(std::log10(std::fabs(value))));
  const int significant = std::clamp(lead - unit_exp + 1, 1, 17);
  const std::string v = fmt::format("{:.{}e}", value, significant - 1);
  const double shown = std::stod(v);
  // The bar grows by the rounding of the printed value (exact in double: both are within a factor 2 here), and a
  // relative 4 eps for the subtraction itself; then rounded up to two digits.
  const double widened = error + std::fabs(value - shown) * (1 + 4 * std::numeric_limits<double>::epsilon());
  return {significant == 17 ? fmt::format("{:.17g}", value) : fmt::format("{:.{}g}", value, significant),
          two_digits_up(widened)};
}

}  // namespace btob::core
