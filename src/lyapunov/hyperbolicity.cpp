// SPDX-License-Identifier: GPL-3.0-or-later
// Non-template parts of hyperbolicity.hpp (strip images of the singular values, validation, quantiles) and the
// explicit instantiations (double, long double).
#include "lyapunov/hyperbolicity_impl.hpp"

#include "core/request.hpp"

#include <fmt/format.h>

#include <limits>

namespace btob::lyapunov {

void validate(const ClvOptions& o) {
  if (o.transient < 0) throw core::InvalidField("transient", fmt::format("{}", o.transient), "at least 0");
  if (o.window < 1) throw core::InvalidField("window", fmt::format("{}", o.window), "at least 1");
  if (o.backward_transient < 1)
    throw core::InvalidField("backward-transient", fmt::format("{}", o.backward_transient), "at least 1");
  if (o.bins < 1) throw core::InvalidField("bins", fmt::format("{}", o.bins), "at least 1");
}

StepSingularValues step_singular_values(const Vec3<double>& u, double r) {
  const Vec3<double> p = core::to_quadrant<double>(u);
  const int s = core::branch(p, r);  // of the point itself: its unit vector's rounding can cross a branch line
  const Vec3<double> q = detail::pow2_scaled<double>(p).normalized();
  const double det = s == 2 ? r * r * r : r * r * r * r;  // det P2 = r^3, det P1 = det P3 = r^4
  const auto sv = singular_values<double>(core::P<double>(s, r), det, q);
  return {sv[0], sv[1], s};
}

StripSingularValues strip_singular_values(double r, long n1, long n2, double w1_min, double w1_max) {
  core::validate_r(r);
  StripSingularValues out;
  const std::vector<Vec3<double>> grid = iterate::strip_grid(n1, n2, w1_min, w1_max);  // validates size and range
  out.n1 = n1;
  out.n2 = n2;
  out.w1_min = w1_min;
  out.w1_max = w1_max;
  const std::size_t n = grid.size();
  out.w1.resize(n);
  out.w2.resize(n);
  out.s1.resize(n);
  out.s2.resize(n);
  out.symbol.resize(n);
  long expanding = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::tie(out.w1[i], out.w2[i]) = core::strip<double>(grid[i]);
    const StepSingularValues sv = step_singular_values(grid[i], r);
    out.s1[i] = sv.s1;
    out.s2[i] = sv.s2;
    out.symbol[i] = static_cast<std::uint8_t>(sv.symbol);
    expanding += sv.s1 >= 1;
  }
  out.expanding_fraction = static_cast<double>(expanding) / static_cast<double>(n);
  return out;
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  const std::size_t k = quantile_rank(q, v.size());
  std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
  return v[k];
}

template std::array<double, 2> singular_values<double>(const Mat3<double>&, const double&, const Vec3<double>&);
template std::array<long double, 2> singular_values<long double>(const Mat3<long double>&, const long double&,
                                                                 const Vec3<long double>&);
template ClvResult covariant_vectors<double>(const Vec3<double>&, const double&, const ClvOptions&);
template ClvResult covariant_vectors<long double>(const Vec3<long double>&, const long double&, const ClvOptions&);

}  // namespace btob::lyapunov
