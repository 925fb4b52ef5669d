// SPDX-License-Identifier: GPL-3.0-or-later
// The batched kernel instantiated for float (compiled with the kernel flags, cmake/KernelFlags.cmake).
#include "iterate/kernel_instances.hpp"
namespace btob::iterate {
BTOB_INSTANTIATE_KERNEL(float)
}  // namespace btob::iterate
