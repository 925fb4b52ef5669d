// SPDX-License-Identifier: GPL-3.0-or-later
// The batched kernel instantiated for double (compiled with the kernel flags, cmake/KernelFlags.cmake).
#include "iterate/kernel_instances.hpp"
namespace btob::iterate {
BTOB_INSTANTIATE_KERNEL(double)

core::Step<double> kernel_step(const core::Vec3<double>& u, double r) {
  const core::Vec3<double> q = core::to_quadrant<double>(u);
  const double a = (1.0 + r) / 2.0, k = a / r;  // as run() computes them per lane
  bool s1 = false, s3 = false;
  const detail::StepResult<double> o = detail::map_step<double, bool>(q(0), q(1), q(2), r, a, k, s1, s3);
  return {core::Vec3<double>(o.x, o.y, o.z), s1 ? 1 : (s3 ? 3 : 2)};
}
}  // namespace btob::iterate
