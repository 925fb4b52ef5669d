// SPDX-License-Identifier: GPL-3.0-or-later
// Non-template parts of the Lyapunov module and the explicit instantiations (double, long double).
#include "lyapunov/lyapunov_impl.hpp"

#include "core/request.hpp"

#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include <complex>
#include <numeric>

namespace btob::lyapunov {

void validate(const Options& o) {
  if (o.iterations < 1) throw core::InvalidField("iterations", fmt::format("{}", o.iterations), "at least 1");
  if (o.transient < 0) throw core::InvalidField("transient", fmt::format("{}", o.transient), "at least 0");
  if (o.reorthonormalise < 1)
    throw core::InvalidField("reorthonormalise", fmt::format("{}", o.reorthonormalise), "at least 1");
  if (o.blocks < 2) throw core::InvalidField("blocks", fmt::format("{}", o.blocks), "at least 2");
  if (o.blocks > o.iterations)
    throw core::InvalidField("blocks", fmt::format("{}", o.blocks),
                             fmt::format("at most iterations = {}", o.iterations));
}

namespace detail {
Estimate batch_means(const std::vector<double>& cum, const std::vector<long>& block_end) {
  const std::size_t B = cum.size();
  Estimate e;
  if (B == 0) return e;
  std::vector<double> mean(B);
  for (std::size_t j = 0; j < B; ++j) {
    const double prev = j ? cum[j - 1] : 0.0;
    const long len = block_end[j] - (j ? block_end[j - 1] : 0);
    mean[j] = (cum[j] - prev) / static_cast<double>(len);
  }
  const double m = std::accumulate(mean.begin(), mean.end(), 0.0) / static_cast<double>(B);
  double ss = 0;
  for (double x : mean) ss += (x - m) * (x - m);
  e.value = cum.back() / static_cast<double>(block_end.back());
  e.error = B > 1 ? std::sqrt(ss / static_cast<double>(B - 1) / static_cast<double>(B)) : 0.0;
  return e;
}
}  // namespace detail

FiniteDifference finite_difference_exponent(const Vec3<double>& u0, double r, double delta, const Options& opt) {
  validate(opt);
  detail::check_start(u0, r);
  if (!(delta > 0 && delta < 1)) throw core::InvalidField("delta", fmt::format("{}", delta), "0 < delta < 1");
  // The reference orbit is kept scaled by powers of two (detail::pow2_scaled), never divided by its norm: its
  // branches are those of the user's point to the last bit; distances are measured between unit vectors.
  Vec3<double> u = detail::pow2_scaled<double>(core::to_quadrant<double>(u0));
  Vec3<double> unit = u.normalized();
  Vec3<double> v = (unit + delta * tangent_basis(unit).col(0)).normalized();
  FiniteDifference fd;
  double sum = 0;
  const long total = opt.transient + opt.iterations;
  for (long k = 1; k <= total; ++k) {
    core::poll_cancel(opt.cancel, k);
    const int s = core::branch(u, r), s2 = core::branch(v, r);
    u = detail::pow2_scaled<double>(detail::apply(s, u, r));
    unit = u.normalized();
    v = detail::apply(s2, v, r).normalized();
    const Vec3<double> d = v - unit;
    const double dist = d.norm();
    if (k > opt.transient) {
      sum += std::log(dist / delta);
      fd.straddles += (s != s2);
    }
    v = (unit + delta * d / dist).normalized();  // re-place the partner at distance ~delta along the separation
  }
  fd.lambda1 = sum / static_cast<double>(opt.iterations);
  return fd;
}

std::array<double, 2> periodic_exponents(const std::vector<int>& period_symbols, double r) {
  core::validate_r(r);
  if (period_symbols.empty()) throw core::InvalidField("period", "an empty word", "symbols 1, 2, 3");
  Mat3<double> M = Mat3<double>::Identity();
  double log_det = 0;
  for (int s : period_symbols) {
    M = core::P<double>(s, r) * M;              // P_{s_p} ... P_{s_1}
    log_det += (s == 2 ? 3 : 4) * std::log(r);  // det P1 = det P3 = r^4, det P2 = r^3 (Section 5.1)
  }
  const Eigen::EigenSolver<Mat3<double>> es(M, false);
  std::array<std::complex<double>, 3> ev = {es.eigenvalues()(0), es.eigenvalues()(1), es.eigenvalues()(2)};
  std::sort(ev.begin(), ev.end(), [](auto a, auto b) { return std::abs(a) > std::abs(b); });
  const double l1 = std::log(std::abs(ev[0]));
  // A complex pair below the dominant eigenvalue: |l2| = |l3| = sqrt(det / |l1|).  Else l2 from the solver.
  const bool pair = ev[1].imag() != 0 && ev[2].imag() != 0;
  const double l2 = pair ? (log_det - l1) / 2 : std::log(std::abs(ev[1]));
  const double l3 = log_det - l1 - l2;
  const double p = static_cast<double>(period_symbols.size());
  return {(l2 - l1) / p, (l3 - l1) / p};
}

double median(std::vector<double> v) {
  const std::size_t n = v.size();
  if (n == 0) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int detect_period(const std::vector<int>& s, int max_period, int check) {
  const long n = static_cast<long>(s.size());
  for (int p = 1; p <= max_period; ++p) {
    if (n < check + p) return 0;
    bool ok = true;
    for (long i = n - check; i < n && ok; ++i) ok = s[i] == s[i - p];
    if (ok) return p;
  }
  return 0;
}

template Eigen::Matrix<double, 3, 2> tangent_basis<double>(const Vec3<double>&);
template Eigen::Matrix<long double, 3, 2> tangent_basis<long double>(const Vec3<long double>&);
template Mat3<double> projective_derivative<double>(const Mat3<double>&, const Vec3<double>&);
template Mat3<long double> projective_derivative<long double>(const Mat3<long double>&, const Vec3<long double>&);
template ProjectiveResult projective_exponents<double>(const Vec3<double>&, const double&, const Options&);
template ProjectiveResult projective_exponents<long double>(const Vec3<long double>&, const long double&,
                                                            const Options&);
template ProjectiveResult projective_exponents_qr<double>(const Vec3<double>&, const double&, const Options&);
template ProjectiveResult projective_exponents_qr<long double>(const Vec3<long double>&, const long double&,
                                                               const Options&);
template LinearResult linear_exponents<double>(const Vec3<double>&, const double&, const Options&);
template LinearResult linear_exponents<long double>(const Vec3<long double>&, const long double&, const Options&);

}  // namespace btob::lyapunov
