// SPDX-License-Identifier: GPL-3.0-or-later
// The matrix-vector steps this thread's orbit walks took so far (the power iterations that carry a saddle's or the
// smallest eigenvalue's eigenvector along the word, whole periods until it converges, at most 64, and the forward
// walks of the others): with the word's length, what a verdict's time is proportional to (its cost model,
// patterns/cost.cpp).  The number of periods follows the word's eigenvalue ratios, not its length, so a prefix of a
// word is no sample of the word's cost.  Per thread: a scan's OpenMP threads each count their own.
#pragma once

#include <cstdint>

namespace btob::patterns {

std::uint64_t orbit_walk_steps();
void add_orbit_walk_steps(std::uint64_t steps);

}  // namespace btob::patterns
