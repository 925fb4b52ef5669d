// The projective exponents of one orbit at the scalar limit (lyapunov/orbit.hpp): the frame is stepped by
// detail::advance (kernel_orbit.cpp, orbit_mpfr.cpp) between Gram-Schmidt steps, which happen here, every `len` steps.
//
// The interval.  Between two Gram-Schmidt steps the tangent vectors are stepped by M_s without projection, so each
// carries a component along the orbit vector u next to its projective part p (the component orthogonal to u).  Every
// rounding of a step is relative to the whole vector |v|, so after the projection p carries a relative error of at
// most about (len + 2) eps rho, rho = |v| / |p| (len steps of rounding and the cancellation of the projection; the
// second vector's Gram-Schmidt against the first likewise, with |v2| over its part orthogonal to u and p1).  rho is
// measured at every Gram-Schmidt step (free: both norms are computed there), and the next interval is chosen so that
// rho stays below 2^B, B = a sixth of T's bits (double: 8 bits, so the logs keep 45 of their 53 bits; MPFR at 50
// digits: 27 bits): with g = log2(rho) / len measured over the last interval, len = B / g, at least 1, at most the
// kernel's renormalisation interval K (iterate::renormalisation_interval: over K steps no vector of the frame
// leaves T's range, so no step tests a range either).  A worst-case bound from the matrices alone (rho <= the
// product of cond(M_s)) is useless at small r (cond(M_s) ~ 1 / r^2), hence the measured one.
// The arithmetic's error enters the error bar: each Gram-Schmidt step adds (len + 2) eps rho to the logs' worst-case
// error, and the reported error is at least that sum over the averaged steps divided by their number.
// A user interval (Options::reorthonormalise > 1) is kept fixed (at most K), as the QR route kept it.
#include "core/scalar.hpp"
#include "iterate/kernel.hpp"
#include "lyapunov/lyapunov_impl.hpp"
#include "lyapunov/orbit.hpp"

#include <array>
#include <cmath>

namespace btob::lyapunov::detail {
// Defined in orbit_mpfr.cpp (the mpfr_* C API): declared wherever the MPFR frame is stepped.
template <> void advance<core::mpfr_float>(OrbitFrame<core::mpfr_float>& f, long n, long first, std::uint8_t* ring);
}  // namespace btob::lyapunov::detail

namespace btob::lyapunov {
namespace detail {
namespace {

template <class T> T dot3(const T* p, const T* q) { return T(p[0] * q[0] + p[1] * q[1] + p[2] * q[2]); }

// One Gram-Schmidt step's output: the two logs of the projective growth since the previous one, and rho's log2.
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
      f.v[0][i] = V(i, 0);
      f.v[1][i] = V(i, 1);
    }
    f.r = r;
    f.a = (T(1) + r) / T(2);
    f.k = f.a / r;
    unorm = un;
  }

  // Project both tangent vectors on u^perp, Gram-Schmidt them, restart them as the orthonormal pair, and rescale u
  // by a power of two (exact: the orbit's bits do not change).  The projective tangent vector is p / |u| (the
  // derivative of u -> M u / |M u| at a unit u is (I - w w^T) M / |M u|), so a log of growth is log |p| - log |u|
  // + log |u_prev|, with p from a unit start.
  Growth gram_schmidt() {
    using std::sqrt;
    const T uu = dot3(f.u, f.u);
    T p[2][3];
    long double vlen[2];
    for (int j = 0; j < 2; ++j) {
      const T c = dot3(f.u, f.v[j]) / uu;
      for (int i = 0; i < 3; ++i) p[j][i] = f.v[j][i] - c * f.u[i];
      vlen[j] = std::sqrt(static_cast<long double>(dot3(f.v[j], f.v[j])));
    }
    const T n1 = sqrt(dot3(p[0], p[0]));
    for (int i = 0; i < 3; ++i) p[0][i] /= n1;
    const T c = dot3(p[0], p[1]);
    for (int i = 0; i < 3; ++i) p[1][i] -= c * p[0][i];
    const T n2 = sqrt(dot3(p[1], p[1]));
    for (int i = 0; i < 3; ++i) p[1][i] /= n2;
    const T un = sqrt(uu);
    const long double ratio = static_cast<long double>(unorm / un);
    const Growth g{{std::log(static_cast<long double>(n1) * ratio), std::log(static_cast<long double>(n2) * ratio)},
                   static_cast<double>(std::log2(std::max({vlen[0] / static_cast<long double>(n1),
                                                           vlen[1] / static_cast<long double>(n2), 1.0L})))};
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
      f.v[0][i] = p[0][i];
      f.v[1][i] = p[1][i];
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

template <class T> ProjectiveResult finish(const Accumulator<2>& acc, const Orbit<T>& o, long double loss,
                                           const Options& opt) {
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
  const double bits_allowed = std::max(2.0, -std::log2(static_cast<double>(eps)) / 6);  // B of the header comment
  const int cap = std::max(1, iterate::renormalisation_interval<T>({static_cast<double>(r)}));
  const bool fixed = opt.reorthonormalise > 1;
  int len = fixed ? std::min(opt.reorthonormalise, cap) : 1;
  long double loss = 0;  // worst-case error of the summed logs: sum of (len + 2) eps rho over the averaged steps
  const long total = sc.transient + sc.n;
  for (long done = 0; done < total;) {
    const long next = detail::next_stop(done, len, sc, acc.next_cp);
    detail::advance<T>(o.f, next - done, done + 1, ring.data());
    if ((next >> 8) != (done >> 8)) core::check_cancel(opt.cancel);  // about every core::cancel_stride steps
    const detail::Growth g = o.gram_schmidt();
    acc.add(next, g.logs);
    if (next > sc.transient)
      loss += static_cast<long double>(next - done + 2) * eps * std::exp2(static_cast<long double>(g.bits));
    if (!fixed) {
      const double per_step = g.bits / static_cast<double>(next - done);
      // At most doubling: an interval measured on a quiet stretch must not jump to K on a chaotic one.
      const int want = per_step > bits_allowed / cap ? std::max(1, static_cast<int>(bits_allowed / per_step)) : cap;
      len = std::min(want, 2 * static_cast<int>(next - done));
    }
    done = next;
  }
  ProjectiveResult res = detail::finish<T>(acc, o, loss, opt);
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
