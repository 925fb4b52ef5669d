// SPDX-License-Identifier: GPL-3.0-or-later
// What the attractors requests' files share (validate.cpp, run.cpp): the check of the Table 6.1 a sweep compares with.
#pragma once

#include "attractors/requests.hpp"

namespace btob::attractors::detail {

// With `table`, the reference CSV (q.reference_csv, read from q.reference) must hold Table 6.1's rows, else
// core::InvalidField naming "reference".
void require_table(const BasinsRRequest& q);

}  // namespace btob::attractors::detail
