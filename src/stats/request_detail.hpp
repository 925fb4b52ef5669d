// SPDX-License-Identifier: GPL-3.0-or-later
// What the stats requests' files share (validate.cpp, run.cpp): the observables a request names.
#pragma once

#include "stats/stats.hpp"

#include <string>
#include <utility>

namespace btob::stats::detail {

// The observables phi and psi of "phi[,psi]" (psi = phi when one is named), else core::InvalidField naming
// "observable" and the accepted names.
std::pair<Observable, Observable> observables(const std::string& spec);

}  // namespace btob::stats::detail
