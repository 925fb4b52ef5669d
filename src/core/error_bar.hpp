// SPDX-License-Identifier: GPL-3.0-or-later
// A value printed with its error bar: the one rule every command that prints "value, error" or "value +- error"
// follows (lyapunov, classify), so that the printed interval [value - error, value + error] contains the value the
// result stores (docs/reference/numbers.md).
//   - the error is printed with two significant digits, rounded up (never down);
//   - the value is printed to the unit one digit below the error's second significant digit (three digits at the
//     error's scale), at most 17 significant digits (then it reads back as the same double);
//   - the printed error covers the printed value's rounding too: it is the bar plus |value - printed value|,
//     rounded up, and checked by reading both texts back.
#pragma once

#include <string>

namespace btob::core {

struct ValueWithError {
  std::string value, error;
};

// value and error (>= 0, finite) as texts by the rule above; a zero or subnormal error prints the value with 17
// significant digits (the bar then covers their rounding); a value 0 is exact ("0"); a bar below 1e-300 prints as
// 1.0e-300.  Throws std::invalid_argument on a non-finite value or error, or a negative error.
ValueWithError with_error(double value, double error);

}  // namespace btob::core
