// SPDX-License-Identifier: GPL-3.0-or-later
// What the bifurcation request's roles share (validate.cpp, run.cpp): the binned coordinate and its range.
#pragma once

#include "bifurcation/bifurcation.hpp"
#include "iterate/recorders.hpp"

namespace btob::bifurcation::detail {

struct Axis {
  iterate::Coord coord;
  double lo, hi;
};

// The coordinate and its default range: theta in [0, pi/2], phi in [0, pi], log10 theta in [-16, 0.25],
// w1 in [-4, 4], w2 in [-1, 1]; a request's range replaces it.  Throws core::InvalidField for a bad coord or log.
Axis axis_of(const Request& req);

}  // namespace btob::bifurcation::detail
