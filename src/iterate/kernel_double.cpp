// The batched kernel instantiated for double (compiled with the kernel flags, cmake/KernelFlags.cmake).
#include "iterate/kernel_instances.hpp"
namespace btob::iterate {
BTOB_INSTANTIATE_KERNEL(double)
}  // namespace btob::iterate
