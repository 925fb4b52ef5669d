// SPDX-License-Identifier: GPL-3.0-or-later
// The kernel's generic lanes instantiated for float128 (quadmath) and MPFR (run-time digits), for the
// precision study.  MPFR: worker threads inherit the caller's precision (see kernel_impl.hpp).
#include "core/scalar.hpp"
#include "iterate/kernel_instances.hpp"
namespace btob::iterate {
BTOB_INSTANTIATE_KERNEL(core::float128)
BTOB_INSTANTIATE_KERNEL(core::mpfr_float)
}  // namespace btob::iterate
