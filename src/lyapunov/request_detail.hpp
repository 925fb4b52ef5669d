// SPDX-License-Identifier: GPL-3.0-or-later
// What the Lyapunov requests' roles share (validate.cpp, run.cpp): the CLV options of hyperbolicity-orbits.
#pragma once

#include "lyapunov/hyperbolicity.hpp"
#include "lyapunov/hyperbolicity_requests.hpp"

namespace btob::lyapunov::detail {

// The covariant-vector run's options from the request: validated with it, used by its parts.
inline ClvOptions clv_options(const HyperbolicityOrbitsRequest& req) {
  ClvOptions co;
  co.transient = req.transient;
  co.window = req.iterations;
  co.backward_transient = req.backward;
  co.bins = req.bins;
  return co;
}

}  // namespace btob::lyapunov::detail
