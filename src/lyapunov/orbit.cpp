// SPDX-License-Identifier: GPL-3.0-or-later
// The projective exponents of one orbit at the scalar limit (lyapunov/orbit.hpp): the frame is stepped by
// detail::advance (kernel_orbit.cpp, orbit_mpfr.cpp) between Gram-Schmidt steps, which happen here, every `len` steps.
//
// The interval.  Between two projections the tangent vector is stepped by M_s without projection, so it carries a
// component along the orbit vector u next to its projective part p (the component orthogonal to u).  Every rounding
// of a step is relative to the whole vector |v|, so after the projection p carries a relative error of at most about
// (len + 2) eps rho, rho = |v| / |p| (len steps of rounding and the cancellation of the projection).  rho is
// measured at every Gram-Schmidt step (free: both norms are computed there), and the next interval is chosen so that
// rho stays below 2^B, B = a sixth of the bits of T or of the trace's type if fewer (weighted.hpp; double: 8 bits, so
// the logs keep 45 of their 53 bits; MPFR: 10, a sixth of long double's 64): with g = log2(rho) / len measured over the
// last interval, len = B / g, at least 1, at most the kernel's renormalisation interval K
// (iterate::renormalisation_interval: over K steps no vector of the frame leaves T's range, so no step tests a range
// either).  A worst-case bound from the matrices alone (rho <= the product of cond(M_s)) is useless at small r
// (cond(M_s) ~ 1 / r^2), hence the measured one.  rho grows only where lambda1 < 0 (u outgrows the tangent vector): on
// a chaotic orbit len stays at K.  lambda2 comes from the area growth (Orbit::gram_schmidt), so no second vector has to
// be kept apart from the first: a Gram-Schmidt pair loses (lambda1 - lambda2) / ln 2 bits per step to each other (2.4
// on the chaotic orbit at r = 0.12), which would force len ~ 3 there. The arithmetic's error enters the error bar: each
// Gram-Schmidt step adds (len + 2) eps rho to the logs' worst-case error, and the reported error is at least that sum
// over the averaged steps divided by their number. A user interval (Options::reorthonormalise > 1) is kept fixed (at
// most K), as the QR route kept it.
#include "lyapunov/orbit.hpp"
#include "core/scalar.hpp"
#include "iterate/kernel.hpp"
#include "lyapunov/lyapunov_impl.hpp"
#include "lyapunov/weighted.hpp"

#include <array>
#include <cmath>
#include <vector>

namespace btob::lyapunov::detail {
// Defined in orbit_mpfr.cpp (the mpfr_* C API): declared wherever the MPFR frame is stepped.
template <>
void advance<core::mpfr_float>(OrbitFrame<core::mpfr_float>& f, long n, long first, std::uint8_t* ring,
                               Trace<long double> tr);
}  // namespace btob::lyapunov::detail

namespace btob::lyapunov {
namespace detail {
namespace {

template <class T> T dot3(const T* p, const T* q) { return T(p[0] * q[0] + p[1] * q[1] + p[2] * q[2]); }

// One projection's output: the logs of the growth of lambda1 and of lambda2 since the previous one, and rho's log2.
struct Growth {
  std::array<long double, 2> logs;
  double bits;
};

template <class T> struct Orbit {
  OrbitFrame<T> f;
  T unorm;  // |u| right after the previous Gram-Schmidt step (u then scaled so that its largest component is in [1, 2))

  Orbit(const Vec3<T>& u0, const T& r) {
    using std::sqrt;
    const Vec3<T> u = pow2_scaled<T>(core::to_quadrant<T>(u0));  // the kernel's start (iterate's unit_start)
    const T un = sqrt(u.squaredNorm());
    const Eigen::Matrix<T, 3, 2> V = tangent_basis(Vec3<T>(u / un));
    for (int i = 0; i < 3; ++i) {
      f.u[i] = u(i);
      f.v[i] = V(i, 0);
    }
    f.r = r;
    f.a = (T(1) + r) / T(2);
    f.k = f.a / r;
    unorm = un;
  }

  // The state right after the previous projection, as the trace's state 0 (weighted.hpp).
  void start_trace(const Trace<TraceReal<T>>& tr) const {
    for (int c = 0; c < 3; ++c) {
      tr.at[c * tr.stride] = static_cast<TraceReal<T>>(f.u[c]);
      tr.at[(c + 3) * tr.stride] = static_cast<TraceReal<T>>(f.v[c]);
    }
  }

  // Project the tangent vector on u^perp, restart it as the unit vector there, and rescale u by a power of two
  // (exact: the orbit's bits do not change).  The projective tangent vector is p / |u| (the derivative of
  // u -> M u / |M u| at a unit u is (I - w w^T) M / |M u|), so lambda1's log of growth is log |p| - log |u| + log
  // |u_prev|, with p from a unit start.  lambda1 + lambda2 is the log of the area growth of the same map, whose
  // Jacobian on the sphere is |det M| / |M u|^3 at a unit u: over the interval, n13 log r - 3 log(|u| / |u_prev|) (det
  // M_s = det P_s / r^3 = r on branches 1 and 3, 1 on branch 2; Section 5.1's det P_i), exact up to rounding, without a
  // second vector.
  Growth gram_schmidt(long n13, long double log_r) {
    using std::sqrt;
    const T uu = dot3(f.u, f.u);
    const T c = dot3(f.u, f.v) / uu;
    T p[3];
    for (int i = 0; i < 3; ++i) p[i] = f.v[i] - c * f.u[i];
    const long double vlen = std::sqrt(static_cast<long double>(dot3(f.v, f.v)));
    const T n1 = sqrt(dot3(p, p));
    for (int i = 0; i < 3; ++i) p[i] /= n1;
    const T un = sqrt(uu);
    const long double log_ratio = std::log(static_cast<long double>(T(unorm / un)));  // log(|u_prev| / |u|)
    const long double log1 = std::log(static_cast<long double>(n1)) + log_ratio;
    const long double sum = static_cast<long double>(n13) * log_r + 3 * log_ratio;  // lambda1 + lambda2's log
    const Growth g{{log1, sum - log1},
                   static_cast<double>(std::log2(std::max(vlen / static_cast<long double>(n1), 1.0L)))};
    using std::fabs;
    using std::frexp;
    using std::ldexp;
    const T m = fabs(f.u[0]) > fabs(f.u[1]) ? (fabs(f.u[0]) > fabs(f.u[2]) ? T(fabs(f.u[0])) : T(fabs(f.u[2])))
                                            : (fabs(f.u[1]) > fabs(f.u[2]) ? T(fabs(f.u[1])) : T(fabs(f.u[2])));
    int e = 0;
    frexp(m, &e);  // u scaled by 2^(1 - e): largest component in [1, 2), as pow2_scaled and the kernel's renormalise
    unorm = T(ldexp(un, 1 - e));
    for (int i = 0; i < 3; ++i) {
      f.u[i] = T(ldexp(f.u[i], 1 - e));
      f.v[i] = p[i];
    }
    return g;
  }
};

// The next Gram-Schmidt step: `len` steps on, cut at the transient's end and at the next checkpoint (block ends and
// powers of two of the averaged length: the accumulator records there, as in the QR route).
long next_stop(long done, int len, const Schedule& sc, std::size_t next_cp) {
  long next = done + len;
  if (done < sc.transient) next = std::min(next, sc.transient);
  if (next_cp < sc.checkpoint.size()) next = std::min(next, sc.transient + sc.checkpoint[next_cp]);
  return std::min(next, sc.transient + sc.n);
}

// The symbols of the last `keep` steps, oldest first, from the ring.
std::vector<int> ring_tail(const std::array<std::uint8_t, kSymbolRing>& ring, long total, long keep) {
  std::vector<int> tail(static_cast<std::size_t>(keep));
  for (long i = 0; i < keep; ++i) tail[static_cast<std::size_t>(i)] = ring[(total - keep + 1 + i) & (kSymbolRing - 1)];
  return tail;
}

template <class T>
ProjectiveResult finish(const Accumulator<2>& acc, const Orbit<T>& o, long double loss, const Options& opt) {
  using std::sqrt;
  ProjectiveResult res;
  const double floor = static_cast<double>(loss / static_cast<long double>(opt.iterations));
  for (int i = 0; i < 2; ++i) {
    res.lambda[static_cast<std::size_t>(i)] = with_rounding_floor<T>(acc.estimate(i));
    res.lambda[static_cast<std::size_t>(i)].error = std::max(res.lambda[static_cast<std::size_t>(i)].error, floor);
    res.weighted[static_cast<std::size_t>(i)] = acc.weighted(i);
  }
  // lambda1 >= lambda2: the first vector's growth converges to the larger exponent, but where the two are equal (a
  // complex pair, an elliptic point) the finite-time estimates may come out in either order.
  if (res.lambda[0].value < res.lambda[1].value) {
    std::swap(res.lambda[0], res.lambda[1]);
    std::swap(res.weighted[0], res.weighted[1]);
  }
  res.iterations = opt.iterations;
  res.blocks = opt.blocks;
  res.convergence = acc.conv;
  const T un = sqrt(dot3(o.f.u, o.f.u));
  res.final_point = Vec3<double>(static_cast<double>(T(o.f.u[0] / un)), static_cast<double>(T(o.f.u[1] / un)),
                                 static_cast<double>(T(o.f.u[2] / un)));
  return res;
}

}  // namespace
}  // namespace detail

template <class T> ProjectiveResult projective_orbit(const Vec3<T>& u0, const T& r, const Options& opt) {
  validate(opt);
  detail::check_start(u0, r);
  const detail::Schedule sc(opt);
  detail::Accumulator<2> acc(sc);
  detail::Orbit<T> o(u0, r);
  std::array<std::uint8_t, detail::kSymbolRing> ring{};
  const long double eps = static_cast<long double>(std::numeric_limits<T>::epsilon());
  // B of the header comment, of T's bits and of the trace's: the weighted pass forms u x v from the trace's states
  // (weighted.hpp), where the projection's cancellation costs the same log2(rho) bits.  MPFR at 100 digits with B
  // from its own 332 bits (55) left long double's cross product 9 bits: its weighted lambda1 on the sink 1133 was off
  // by 4.9e-6.
  const double trace_eps = std::numeric_limits<detail::TraceReal<T>>::epsilon();
  const double bits_allowed = std::max(2.0, std::min(-std::log2(static_cast<double>(eps)), -std::log2(trace_eps)) / 6);
  // K of T, and of the trace's type (weighted.hpp squares the states in it: MPFR's range is wider than long double's).
  const std::vector<double> rv{static_cast<double>(r)};
  const int cap = std::max(1, std::min(iterate::renormalisation_interval<T>(rv),
                                       iterate::renormalisation_interval<detail::TraceReal<T>>(rv)));
  const long double log_r = std::log(static_cast<long double>(r));
  const bool fixed = opt.reorthonormalise > 1;
  int len = fixed ? std::min(opt.reorthonormalise, cap) : 1;
  long double loss = 0;  // worst-case error of the summed logs: sum of (len + 2) eps rho over the averaged steps
  const long total = sc.transient + sc.n;
  using W = detail::TraceReal<T>;
  std::vector<W> trace(6 * static_cast<std::size_t>(cap + 1));
  detail::WeightedSums ws;
  acc.weigh_intervals = false;  // weighed step by step below (weighted.hpp)
  for (long done = 0; done < total;) {
    const long next = detail::next_stop(done, len, sc, acc.next_cp);
    const detail::Trace<W> tr{opt.weighted && done >= sc.transient ? trace.data() : nullptr, cap + 1};
    if (tr.at) o.start_trace(tr);
    detail::advance<T>(o.f, next - done, done + 1, ring.data(), tr);
    if (tr.at) detail::weigh<W>(tr, next - done, ring.data(), done, done - sc.transient, sc.n, log_r, ws);
    if ((next >> 8) != (done >> 8)) core::check_cancel(opt.cancel);  // about every core::cancel_stride steps
    long n13 = 0;  // steps on branches 1 and 3 (det M = r) since the last projection
    for (long i = done + 1; i <= next; ++i) n13 += ring[i & (detail::kSymbolRing - 1)] != 2;
    const detail::Growth g = o.gram_schmidt(n13, log_r);
    acc.add(next, g.logs);
    if (next > sc.transient)
      loss += static_cast<long double>(next - done + 2) * eps * std::exp2(static_cast<long double>(g.bits));
    if (!fixed) {  // adapted all along: the weighted averages weigh every step whatever the intervals
      const double per_step = g.bits / static_cast<double>(next - done);
      const int want = per_step > bits_allowed / cap ? std::max(1, static_cast<int>(bits_allowed / per_step)) : cap;
      // At most doubling: an interval measured on a quiet stretch must not jump to K on a chaotic one.
      len = std::min(want, 2 * len);
    }
    done = next;
  }
  acc.wsum = {ws.lambda1, ws.area - ws.lambda1};
  acc.wnorm = ws.norm;
  ProjectiveResult res = detail::finish<T>(acc, o, loss, opt);
  res.has_weighted = opt.weighted;
  if (!opt.weighted) res.weighted = {0, 0};  // not computed: never read (describe and csv skip them)
  res.symbols_tail = detail::ring_tail(ring, total, std::min<long>(opt.iterations, 4096));
  return res;
}

template ProjectiveResult projective_orbit<float>(const Vec3<float>&, const float&, const Options&);
template ProjectiveResult projective_orbit<double>(const Vec3<double>&, const double&, const Options&);
template ProjectiveResult projective_orbit<long double>(const Vec3<long double>&, const long double&, const Options&);
template ProjectiveResult projective_orbit<core::float128>(const Vec3<core::float128>&, const core::float128&,
                                                           const Options&);
template ProjectiveResult projective_orbit<core::mpfr_float>(const Vec3<core::mpfr_float>&, const core::mpfr_float&,
                                                             const Options&);

}  // namespace btob::lyapunov
