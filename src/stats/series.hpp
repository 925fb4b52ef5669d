// SPDX-License-Identifier: GPL-3.0-or-later
// SeriesRecorder: the unit states and symbols of a window of consecutive steps of every orbit (Section 8.1 (2)).
#pragma once

#include "iterate/ensemble.hpp"

#include <cmath>
#include <cstdint>
#include <vector>

namespace btob::stats {

using iterate::checked_bytes;
using iterate::Ensemble;
using iterate::Vec3;

// Keeps, for steps from..from+count-1 of every orbit, the state normalised to a unit vector (in double,
// whatever the kernel's T) and the symbol 1/2/3 of the step that produced it:
//     x[o * count + j], y[...], z[...], symbol[...]  for state k = from + j  (k >= 1: steps done).
// Every observable of Section 8.1 (theta, phi, the strip, cos phi, symbol indicators, user functions of
// the state) is a function of these, so one run serves them all.  Storage: 25 bytes per point.
struct SeriesRecorder {
  static constexpr bool needs_symbols = true;
  long from, count;
  std::vector<double> x, y, z;
  std::vector<std::uint8_t> symbol;
  SeriesRecorder(std::size_t orbits, long from_, long count_)
      : from(from_),
        count(count_),
        x(checked_bytes(orbits * static_cast<std::size_t>(count_), 3 * sizeof(double) + 1, "series") /
          (3 * sizeof(double) + 1)),
        y(x.size()),
        z(x.size()),
        symbol(x.size()) {}
  long first_step() const { return from; }
  template <class T>
  void record(std::size_t o0, int lanes, long k, const T* px, const T* py, const T* pz, const std::uint8_t* sym) {
    if (k >= from + count) return;
    const std::size_t j = static_cast<std::size_t>(k - from);
    for (int l = 0; l < lanes; ++l) {
      // The kernel's states are rescaled by powers of two only; the unit vector is taken in double.
      const double a = static_cast<double>(px[l]), b = static_cast<double>(py[l]), c = static_cast<double>(pz[l]);
      const double inv = 1.0 / std::sqrt(a * a + b * b + c * c);
      const std::size_t i = (o0 + static_cast<std::size_t>(l)) * static_cast<std::size_t>(count) + j;
      x[i] = a * inv;
      y[i] = b * inv;
      z[i] = c * inv;
      symbol[i] = sym[l];
    }
  }
};

}  // namespace btob::stats
