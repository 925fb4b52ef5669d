// SPDX-License-Identifier: GPL-3.0-or-later
// The batched covariant Lyapunov vectors (hyperbolicity.hpp, covariant_vectors_batched), compiled with the kernel
// flags.  Each lane carries the point u (the plain kernel's map_step: the symbols are iterate::run<double>'s), the
// line of the first Ginelli vector e1 and, over the steps whose R is stored, the second e2, all unnormalised and
// rescaled by exact powers of two every few steps.
//
// One step, with M = P_s / r, m = M u, E_i = M e_i, mm = m . m (no division, no square root):
//   e1' = mm E1 - (m . E1) m     mm times E1 projected on m's complement (the line Ginelli's QR keeps);
//   e2' = m x E1                 orthogonal to m and to e1', oriented as u x e1 (det M > 0).
// In the frames (e1, e2) -> (e1', e2') the projective derivative D = Pi_w M / |M u^| is the triangular
// c [[1 / mm, b / N], [0, g mm / N]], c = |u| / |m|, N = e1' . e1', b = e1' . E2, g = e2' . E2.  Ginelli's backward
// step for the second CLV x e1 + y e2 in the ratio tau = x / y is then tau_k = A_k tau_{k+1} - B_k with
// A = g mm^2 / N and B = mm b / N (one division per stored step; a second in the window for c^2 = |u|^2 / mm), A
// times s1 / s2 where e1', e2' were rescaled by s1, s2.  Over the backward transient only the composition of these
// maps matters (tau at the window's end, from tau = 0 after the last step): it is composed forward as the steps come,
// t -> alpha t + beta with alpha <- alpha A, beta <- beta - alpha B, instead of storing A and B of every step and
// recursing back over them (the same value, with other roundings; Ginelli's start tau = 0 is arbitrary anyway, and
// the recursion contracts).  The angle between the CLVs is atan(1 / (|tau| sqrt(rho))),
// rho = |e1|^2 / |e2|^2, which is the previous step's mm (times (s1 / s2)^2).  The angles are kept as
// key = tau^2 rho (their order reversed) and an angle is computed from its key only where a value is reported:
// quantiles are order statistics.
//
// lambda1 = mean log |D g1| (g1 = e1 / |e1|) = mean of (1/2) log(|u|^2 N / (mm^3 |e1|^2)) telescopes, up to the
// rescaling exponents, into the logs of |u|^2 and |e1|^2 at the window's two ends and the sum of log mm (kept as a
// mantissa product and an exponent sum, exact); lambda1 + lambda2 = mean log det D = mean of log det M + 3 log c.
// The expanding flag s1 >= 1 of D: with F = s1^2 + s2^2 = |D g1|^2 + |D g2|^2 and Dt = s1 s2 = det M c^3,
// s1 >= 1 exactly when Dt >= 1 or F >= 1 + Dt^2 ((1 - s1^2)(1 - s2^2) = 1 - F + Dt^2).
#include "core/cancel.hpp"
#include "core/run.hpp"
#include "iterate/cocycle_impl.hpp"
#include "iterate/recorders.hpp"
#include "lyapunov/hyperbolicity.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace btob::lyapunov {
namespace {

using S = iterate::detail::Simd<double>;
using V = S::V;
using I = S::I;
// Vectors per batch.  The covariant-vector pass is bound by the coefficients it stores per step, not by the
// dependency chain, so 2 vectors do as well as 4 while keeping a batch's stored coefficients half as large.
// (CHANGELOG.md keeps the measurements behind the choice.)
constexpr int kVectors = 2;
constexpr int W = S::W, NV = kVectors, B = W * NV;
constexpr int bias = std::numeric_limits<double>::max_exponent - 1;
constexpr double ln2 = std::numbers::ln2;

// Steps between rescalings at r: over K steps from max-norms in [1, 2), |u| grows by at most 2^(K h), e1 by
// 2^(K (K + 2) h + 3 K) (e1' carries mm |E1|), h the larger of the map's log2 growth and shrinkage bounds; the
// squares and products of two such (N, b, g) stay within 2^+-980.  Rescaling is exact, so K changes no bit; it is a
// function of r only all the same.
int clv_interval(double r) {
  double grow = 0, shrink = 0;
  iterate::detail::step_log2_bounds(r, grow, shrink);
  const double h = std::max(grow, shrink);
  for (int K = 16; K >= 1; --K)
    if (2 * (K * (K + 2) * h + 3 * K) <= 980) return K;
  // A plain invalid_argument with InvalidField's message: constructing InvalidField here would emit its inline
  // constructor in a kernel unit (check_kernel_symbols).
  throw std::invalid_argument(
      fmt::format("r: got {}, expected r whose matrices keep the CLV frame in double's range", r));
}

struct Regs {
  V x[NV], y[NV], z[NV], ax[NV], ay[NV], az[NV], bx[NV], by[NV], bz[NV];
};
// Per vector over the window: rho and the inverse squared norms of e1, e2 for the next step, the mantissa product
// and exponent sum of mm, the counts of symbols 1 and 3 and of expanding steps, the exponents removed from u, e1.
// Over the backward transient: the composition t -> alpha t + beta of its steps' maps tau_k = A tau_{k+1} - B.
struct Sums {
  V rho[NV], iq1[NV], iq2[NV], pm[NV], em[NV], n13[NV], nexp[NV], eu[NV], ef[NV];
  V alpha[NV], beta[NV];
};
// A batch's stored steps: row j (B lanes) is step transient + j.
struct Store {
  double *A, *Bc, *rho;
  std::uint8_t *sym, *expd;         // window rows, only with keep_steps
  const core::CancelToken* cancel;  // polled every core::cancel_stride blocks of steps (clv_phase)
};

inline V one() { return V{} + 1; }
inline V pow2(I biased) { return (V)(biased << (std::numeric_limits<double>::digits - 1)); }

template <bool Stored, bool Window, bool Keep>
inline void clv_block(Regs& s, Sums& w, const V* r, const V* a, const V* k, int n, long j0, const Store& st) {
  for (int i = 0; i < n; ++i) {
    const long row = (j0 + i) * B;
#pragma GCC unroll 4
    for (int j = 0; j < NV; ++j) {
      I s1, s3;
      const V uu = s.x[j] * s.x[j] + s.y[j] * s.y[j] + s.z[j] * s.z[j];
      const auto m = iterate::detail::map_step<V, I>(s.x[j], s.y[j], s.z[j], r[j], a[j], k[j], s1, s3);
      V e1x = s.ax[j], e1y = s.ay[j], e1z = s.az[j];
      iterate::detail::tangent_step(e1x, e1y, e1z, r[j], a[j], k[j], s1, s3);
      const V mm = m.x * m.x + m.y * m.y + m.z * m.z;
      const V p1 = m.x * e1x + m.y * e1y + m.z * e1z;
      const V hx = mm * e1x - p1 * m.x, hy = mm * e1y - p1 * m.y, hz = mm * e1z - p1 * m.z;
      if constexpr (Stored) {
        V e2x = s.bx[j], e2y = s.by[j], e2z = s.bz[j];
        iterate::detail::tangent_step(e2x, e2y, e2z, r[j], a[j], k[j], s1, s3);
        const V cx = m.y * e1z - m.z * e1y, cy = m.z * e1x - m.x * e1z, cz = m.x * e1y - m.y * e1x;
        const V N = hx * hx + hy * hy + hz * hz;
        const V inv = one() / N;
        const V b = hx * e2x + hy * e2y + hz * e2z, g = cx * e2x + cy * e2y + cz * e2z;
        const V beta = b * inv, gam = g * mm * inv;  // coefficients of e1', e2' in Pi E2
        if constexpr (Window) {
          S::store(st.A + row + j * W, mm * gam);
          S::store(st.Bc + row + j * W, mm * beta);
          const V imm = one() / mm, c2 = uu * imm;
          const V det = (s1 | s3) ? r[j] : one();
          const V D2 = det * det * c2 * c2 * c2;
          const V F = c2 * (N * w.iq1[j] * imm * imm + (b * beta + g * gam) * w.iq2[j]);
          const I e = (D2 >= one()) | (F >= one() + D2);
          w.nexp[j] += e ? one() : V{};
          S::store(st.rho + row + j * W, w.rho[j]);
          w.rho[j] = mm;
          w.iq1[j] = inv;
          w.iq2[j] = mm * inv;
          const V p = w.pm[j] * mm;
          const I bits = (I)p;
          w.em[j] += __builtin_convertvector((bits >> 52) - bias, V);
          w.pm[j] = (V)((bits & ((I{} + 1) << 52) - 1) | (I)one());
          w.n13[j] += (s1 | s3) ? one() : V{};
          if constexpr (Keep) {
            const I code = s1 ? I{} + 1 : (s3 ? I{} + 3 : I{} + 2);
            for (int l = 0; l < W; ++l) {
              st.sym[row + j * W + l] = static_cast<std::uint8_t>(code[l]);
              st.expd[row + j * W + l] = e[l] != 0;
            }
          }
        } else {  // the backward transient: compose its map into t -> alpha t + beta
          w.beta[j] -= w.alpha[j] * (mm * beta);
          w.alpha[j] *= mm * gam;
        }
        s.bx[j] = cx, s.by[j] = cy, s.bz[j] = cz;
      }
      s.x[j] = m.x, s.y[j] = m.y, s.z[j] = m.z;
      s.ax[j] = hx, s.ay[j] = hy, s.az[j] = hz;
    }
  }
}

// Exact power-of-two rescaling of u, e1 (and e2) after a block whose last stored row is `last`.
template <bool Stored, bool Window> inline void clv_rescale(Regs& s, Sums& w, long last, const Store& st) {
  using iterate::detail::max_exponent;
  using iterate::detail::scale_for;
  for (int j = 0; j < NV; ++j) {
    const I eu = max_exponent<double, V, I>(s.x[j], s.y[j], s.z[j]);
    const I ef = max_exponent<double, V, I>(s.ax[j], s.ay[j], s.az[j]);
    const V su = scale_for<double, V, I>(eu), sf = scale_for<double, V, I>(ef);
    s.x[j] *= su, s.y[j] *= su, s.z[j] *= su;
    s.ax[j] *= sf, s.ay[j] *= sf, s.az[j] *= sf;
    if constexpr (Stored) {
      const I eg = max_exponent<double, V, I>(s.bx[j], s.by[j], s.bz[j]);
      const V sg = scale_for<double, V, I>(eg);
      s.bx[j] *= sg, s.by[j] *= sg, s.bz[j] *= sg;
      const V sigma = sf * pow2(eg);  // s1 / s2: the last step's A times sigma
      if constexpr (Window) {
        double* A = st.A + last * B + j * W;
        S::store(A, S::load(A) * sigma);
        w.rho[j] *= sigma * sigma;
        const V uf = pow2(ef), ug = pow2(eg);
        w.iq1[j] *= uf * uf;
        w.iq2[j] *= ug * ug;
        w.eu[j] += __builtin_convertvector(eu - bias, V);
        w.ef[j] += __builtin_convertvector(ef - bias, V);
      } else {
        w.alpha[j] *= sigma;
      }
    }
  }
}

template <bool Stored, bool Window, bool Keep>
void clv_phase(Regs& s_out, Sums& w_out, const V* r_in, const V* a_in, const V* k_in, long steps, long j0, int K,
               const Store& st) {
  // Local copies: the rows are stored through double pointers, which may alias the caller's vectors; GCC would
  // reload and store every state vector around each row's stores.
  Regs s = s_out;
  Sums w = w_out;
  V r[NV], a[NV], k[NV];
  for (int j = 0; j < NV; ++j) r[j] = r_in[j], a[j] = a_in[j], k[j] = k_in[j];
  for (long done = 0, blocks = 0; done < steps; ++blocks) {
    // Cancelled: the lanes are left where they are (the batch is dropped; the run throws after its region).
    if (core::cancel_due(st.cancel, blocks)) break;
    const int n = static_cast<int>(std::min<long>(K, steps - done));
    clv_block<Stored, Window, Keep>(s, w, r, a, k, n, j0 + done, st);
    done += n;
    clv_rescale<Stored, Window>(s, w, j0 + done - 1, st);
  }
  s_out = s;
  w_out = w;
}

// The angle of a key.
double angle_of(double key) { return std::atan2(1.0, std::sqrt(key)); }

// The smallest and largest of n keys, in vectors (a scalar min/max chain waits 4 cycles per key).
void min_max(const double* key, std::size_t n, double& lo, double& hi) {
  V vlo = V{} + key[0], vhi = vlo;
  std::size_t i = 0;
  for (; i + W <= n; i += W) {
    const V v = S::load(key + i);
    vlo = v < vlo ? v : vlo;
    vhi = v > vhi ? v : vhi;
  }
  lo = key[0], hi = key[0];
  for (int l = 0; l < W; ++l) lo = std::min(lo, vlo[l]), hi = std::max(hi, vhi[l]);
  for (; i < n; ++i) lo = std::min(lo, key[i]), hi = std::max(hi, key[i]);
}

// Adds the counts of n keys per bucket into four tables in turn (nb each, summed by the caller): runs of equal keys
// (a periodic orbit has a few values) would otherwise wait on the same counter's previous increment.
template <class Bucket>
void count_buckets(const double* key, std::size_t n, std::size_t nb, Bucket bucket, std::vector<std::uint32_t>& count) {
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4)
    for (std::size_t q = 0; q < 4; ++q) ++count[q * nb + bucket(key[i + q])];
  for (; i < n; ++i) ++count[bucket(key[i])];
}

// Buckets of keys >= 0 by their bits (whose order is the keys'): at most 2^log2_cap equal spans of the bits between
// the smallest and the largest key, so that keys one ulp apart split as soon as keys many binades apart.
struct Buckets {
  std::uint64_t lo = 0;
  int shift = 0;
  std::size_t count = 1;
  Buckets(double min, double max, int log2_cap) : lo(std::bit_cast<std::uint64_t>(min)) {
    const std::uint64_t span = std::bit_cast<std::uint64_t>(max) - lo;
    shift = std::max(0, static_cast<int>(std::bit_width(span)) - log2_cap);
    count = static_cast<std::size_t>(span >> shift) + 1;
  }
  // Clamped: a NaN key (tau overflowed, an angle below 1e-150) lands in the last bucket instead of past the table.
  std::size_t operator()(double x) const {
    return std::min(count - 1, static_cast<std::size_t>((std::bit_cast<std::uint64_t>(x) - lo) >> shift));
  }
};

// The value of ascending rank k among n keys >= 0 (overwritten): while many, the keys of rank k's bucket are moved
// to the front and bucketed again; then nth_element.  The value nth_element gives, in passes of counting instead
// of its partitions (slow where keys repeat: a periodic orbit has a few values).
double select_in(double* v, std::size_t n, std::size_t k, std::vector<std::uint32_t>& count) {
  while (n > 2048) {
    double lo = 0, hi = 0;
    min_max(v, n, lo, hi);
    if (lo == hi) return lo;
    const Buckets bucket(lo, hi, 12);
    count.assign(4 * bucket.count, 0);
    count_buckets(v, n, bucket.count, bucket, count);
    for (std::size_t c = 0; c < bucket.count; ++c)
      count[c] += count[bucket.count + c] + count[2 * bucket.count + c] + count[3 * bucket.count + c];
    std::size_t b = 0, below = 0;
    while (below + count[b] <= k) below += count[b++];
    std::size_t m = 0;
    for (std::size_t i = 0; i < n; ++i) {  // without a branch: the buckets come in no order
      v[m] = v[i];
      m += bucket(v[i]) == b;
    }
    n = m, k -= below;
  }
  std::nth_element(v, v + k, v + n);
  return v[k];
}

// Rows of keys (>= 0), each `len` long: one orbit's window, or every non-degenerate orbit's of an r, with the
// smallest and the largest key among them (from the backward pass).
struct KeyRows {
  std::vector<const double*> row;
  std::size_t len = 0;
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  std::size_t size() const { return row.size() * len; }
  template <class F> void each(F f) const {
    for (const double* r : row)
      for (std::size_t i = 0; i < len; ++i) f(r[i]);
  }
};

// The keys of ascending ranks k0, k1 (left as they are): one pass counting per bucket, one gathering the two
// ranks' buckets, select_in within each.
void select_keys(const KeyRows& keys, std::size_t k0, std::size_t k1, double& v0, double& v1,
                 std::vector<std::uint32_t>& count, std::vector<double>& gather) {
  const Buckets bucket(keys.lo, keys.hi, 12);
  count.assign(4 * bucket.count, 0);
  for (const double* r : keys.row) count_buckets(r, keys.len, bucket.count, bucket, count);
  for (std::size_t b = 0; b < bucket.count; ++b)
    count[b] += count[bucket.count + b] + count[2 * bucket.count + b] + count[3 * bucket.count + b];
  std::size_t b0 = 0, b1 = 0, below0 = 0, below1 = 0, seen = 0;
  for (std::size_t b = 0; b < bucket.count; ++b) {
    const std::size_t c = count[b];
    if (seen <= k0 && k0 < seen + c) b0 = b, below0 = seen;
    if (seen <= k1 && k1 < seen + c) b1 = b, below1 = seen;
    seen += c;
  }
  const std::size_t n0 = count[b0], n1 = count[b1];
  gather.resize(n0 + n1 + 2);  // each part one longer: the branch-free stores below write one past its end
  std::size_t g0 = 0, g1 = n0 + 1;
  keys.each([&](double k) {
    const std::size_t b = bucket(k);
    gather[g0] = k;
    g0 += b == b0;
    gather[g1] = k;
    g1 += b == b1;
  });
  v0 = select_in(gather.data(), n0, k0 - below0, count);
  v1 = select_in(gather.data() + n0 + 1, n1, k1 - below1, count);
}

// Median, 5% quantile and minimum of the angles of the keys: the angle decreases as the key grows.
void angle_stats(const KeyRows& keys, double& median, double& q05, double& min, std::vector<std::uint32_t>& count,
                 std::vector<double>& gather) {
  const std::size_t n = keys.size();
  double km = 0, kq = 0;
  select_keys(keys, n - 1 - quantile_rank(0.5, n), n - 1 - quantile_rank(0.05, n), km, kq, count, gather);
  median = angle_of(km);
  q05 = angle_of(kq);
  min = angle_of(keys.hi);
}

// Adds the angles of n keys to a histogram of `bins` bins over [0, pi/2]: iterate::atan_fast (error < 2e-7) where
// the bin is certain (farther than twice that bound, 4e-7 rad, from both edges), angle_of and angle_bin elsewhere,
// so the counts are those of the angles angle_of gives.
void add_histogram(const double* key, std::size_t n, int bins, double* hist) {
  constexpr int chunk = 256;
  const double per = bins / (std::numbers::pi / 2), guard = 2 * iterate::kAtanFastError * per;
  alignas(64) std::int64_t bin[chunk];
  for (std::size_t i0 = 0; i0 < n; i0 += chunk) {
    const int c = static_cast<int>(std::min<std::size_t>(chunk, n - i0));
#pragma omp simd
    for (int i = 0; i < c; ++i) {
      const double x = iterate::atan_fast(1.0, std::sqrt(key[i0 + i])) * per;
      const double f = std::floor(x);
      const bool certain = x - f > guard && f + 1 - x > guard && f < bins;  // false for NaN (key inf)
      bin[i] = certain ? static_cast<std::int64_t>(f) : -1;
    }
    for (int i = 0; i < c; ++i) hist[bin[i] >= 0 ? bin[i] : angle_bin(angle_of(key[i0 + i]), bins)] += 1;
  }
}

// ---- the stages of covariant_vectors_batched --------------------------------------------------------------------

// One batch in registers: up to B consecutive orbits at one r, the frame and the sums of clv_phase.
struct Lanes {
  Regs s;
  Sums w;
  V r[NV], a[NV], k[NV];
};

// Per lane, |u|^2 and |e1|^2 at one end of the window.
struct NormsAt {
  alignas(64) double uu[B], q1[B];
};

// Per lane, at the window's end: the norms and the sums the exponents read (in the order of Sums: pm, em, n13,
// nexp, eu, ef, rho, iq1, iq2).
struct WindowEnd {
  NormsAt norms;
  alignas(64) double sums[9][B];
};

// Per lane, the smallest and largest key of the window.
struct KeyRange {
  alignas(64) double lo[B], hi[B];
};

// The lanes' starts: the unit point and the first tangent vector of orbits o0.., a partial batch padded with its
// last orbit (every lane steps like a full batch's).
void load_lanes(const std::vector<Vec3<double>>& initial, std::size_t o0, int lanes, double r, Lanes& b) {
  alignas(64) double L[9][B], rv[B], av[B], kv[B];
  for (int l = 0; l < B; ++l) {
    const Vec3<double> q = iterate::detail::unit_start(initial[o0 + static_cast<std::size_t>(std::min(l, lanes - 1))]);
    const Eigen::Matrix<double, 3, 2> f = tangent_basis<double>(q.normalized());
    for (int c = 0; c < 3; ++c) L[c][l] = q(c), L[3 + c][l] = f(c, 0);
    rv[l] = r, av[l] = (1 + r) / 2, kv[l] = av[l] / r;
  }
  Regs& s = b.s;
  for (int j = 0; j < NV; ++j) {
    s.x[j] = S::load(L[0] + j * W), s.y[j] = S::load(L[1] + j * W), s.z[j] = S::load(L[2] + j * W);
    s.ax[j] = S::load(L[3] + j * W), s.ay[j] = S::load(L[4] + j * W), s.az[j] = S::load(L[5] + j * W);
    b.r[j] = S::load(rv + j * W), b.a[j] = S::load(av + j * W), b.k[j] = S::load(kv + j * W);
  }
}

// The window's start: e2 = u x e1, and the norms the window's sums start from.
NormsAt start_window(Lanes& b) {
  Regs& s = b.s;
  Sums& w = b.w;
  NormsAt start;
  for (int j = 0; j < NV; ++j) {
    s.bx[j] = s.y[j] * s.az[j] - s.z[j] * s.ay[j];
    s.by[j] = s.z[j] * s.ax[j] - s.x[j] * s.az[j];
    s.bz[j] = s.x[j] * s.ay[j] - s.y[j] * s.ax[j];
    const V q1 = s.ax[j] * s.ax[j] + s.ay[j] * s.ay[j] + s.az[j] * s.az[j];
    const V q2 = s.bx[j] * s.bx[j] + s.by[j] * s.by[j] + s.bz[j] * s.bz[j];
    const V uu = s.x[j] * s.x[j] + s.y[j] * s.y[j] + s.z[j] * s.z[j];
    w.rho[j] = q1 / q2, w.iq1[j] = one() / q1, w.iq2[j] = one() / q2;
    w.pm[j] = one(), w.em[j] = w.n13[j] = w.nexp[j] = w.eu[j] = w.ef[j] = V{};
    S::store(start.uu + j * W, uu), S::store(start.q1 + j * W, q1);
  }
  return start;
}

// The window's end: the norms and the window's sums, per lane.
WindowEnd end_window(const Lanes& b) {
  const Regs& s = b.s;
  const Sums& w = b.w;
  WindowEnd end;
  for (int j = 0; j < NV; ++j) {
    S::store(end.norms.uu + j * W, s.x[j] * s.x[j] + s.y[j] * s.y[j] + s.z[j] * s.z[j]);
    S::store(end.norms.q1 + j * W, s.ax[j] * s.ax[j] + s.ay[j] * s.ay[j] + s.az[j] * s.az[j]);
    const V* v[9] = {w.pm, w.em, w.n13, w.nexp, w.eu, w.ef, w.rho, w.iq1, w.iq2};
    for (int q = 0; q < 9; ++q) S::store(end.sums[q] + j * W, v[q][j]);
  }
  return end;
}

// Forward over transient, window and backward transient: the window's coefficients stored in st, the window's sums
// and ends, and in b.w.beta tau at the window's end (tau = 0 after the last step, where the second CLV is e2).
WindowEnd forward_pass(Lanes& b, long transient, long window, long backward, int K, bool keep_steps, const Store& st,
                       NormsAt& start) {
  clv_phase<false, false, false>(b.s, b.w, b.r, b.a, b.k, transient, 0, K, st);
  start = start_window(b);
  if (keep_steps) clv_phase<true, true, true>(b.s, b.w, b.r, b.a, b.k, window, 0, K, st);
  else clv_phase<true, true, false>(b.s, b.w, b.r, b.a, b.k, window, 0, K, st);
  const WindowEnd end = end_window(b);
  // The backward transient composes its steps' maps into t -> alpha t + beta.
  for (int j = 0; j < NV; ++j) b.w.alpha[j] = one(), b.w.beta[j] = V{};
  clv_phase<true, false, false>(b.s, b.w, b.r, b.a, b.k, backward, window, K, st);
  return end;
}

// Back over the window from tau = beta: the key of every step, written to keys[l * window + step] for the batch's
// lanes, and each lane's smallest and largest key.
KeyRange backward_keys(const Sums& w, const Store& st, long window, int lanes, double* keys) {
  const std::size_t Nz = static_cast<std::size_t>(window);
  V tau[NV], kmin[NV], kmax[NV];
  for (int v = 0; v < NV; ++v)
    tau[v] = w.beta[v], kmin[v] = V{} + std::numeric_limits<double>::infinity(), kmax[v] = V{};
  for (long j = window - 1; j >= 0; --j) {
    const long row = j * B;
    alignas(64) double kk[B];
    for (int v = 0; v < NV; ++v) {
      tau[v] = S::load(st.A + row + v * W) * tau[v] - S::load(st.Bc + row + v * W);
      const V key = tau[v] * tau[v] * S::load(st.rho + row + v * W);
      kmin[v] = key < kmin[v] ? key : kmin[v];
      kmax[v] = key > kmax[v] ? key : kmax[v];
      S::store(kk + v * W, key);
    }
    for (int l = 0; l < lanes; ++l) keys[static_cast<std::size_t>(l) * Nz + static_cast<std::size_t>(j)] = kk[l];
  }
  KeyRange range;
  for (int v = 0; v < NV; ++v) S::store(range.lo + v * W, kmin[v]), S::store(range.hi + v * W, kmax[v]);
  return range;
}

// Lane l's exponents, expanding fraction and degeneracy from the window's sums (the integer exponents added
// first: exact).
void lane_exponents(const NormsAt& start, const WindowEnd& end, int l, double r, long window, ClvResult& c) {
  const double(&sums)[9][B] = end.sums;
  const double n = static_cast<double>(window);
  // Sum of log r11 and of log det D over the window.
  const double e1 = -sums[4][l] + sums[5][l] - sums[1][l];
  const double s11 =
      0.5 * (std::log(start.uu[l]) - std::log(end.norms.uu[l]) + std::log(end.norms.q1[l]) - std::log(start.q1[l])) +
      e1 * ln2 - std::log(sums[0][l]);
  const double sdet =
      sums[2][l] * std::log(r) + 1.5 * (std::log(start.uu[l]) - std::log(end.norms.uu[l]) - 2 * ln2 * sums[4][l]);
  c.lambda = {s11 / n, (sdet - s11) / n};
  c.degenerate = c.lambda[0] - c.lambda[1] < 10.0 / n;  // as covariant_vectors
  c.expanding_fraction = sums[3][l] / n;
}

// Lane l's per-step angles, symbols and expanding flags (keep_steps).
void lane_steps(const double* key, const Store& st, int l, std::size_t window, ClvResult& c) {
  c.angle.resize(window);
  c.symbols.resize(window);
  c.expanding.resize(window);
  for (std::size_t j = 0; j < window; ++j) {
    c.angle[j] = angle_of(key[j]);
    c.symbols[j] = st.sym[j * B + static_cast<std::size_t>(l)];
    c.expanding[j] = st.expd[j * B + static_cast<std::size_t>(l)];
  }
}

// A thread's buffers: one batch's stored window (A, B and rho per step; symbols and flags with keep_steps) and the
// scratch of the order statistics.
struct ThreadStore {
  std::vector<double> A, Bc, rho;
  std::vector<std::uint8_t> sym, expd;
  std::vector<std::uint32_t> count;  // select_keys' buckets and gathered keys
  std::vector<double> gather;
  ThreadStore(std::size_t window, bool keep_steps)
      : A(window * B), Bc(A.size()), rho(window * B), sym(keep_steps ? window * B : 0), expd(sym.size()) {}
  const core::CancelToken* cancel = nullptr;
  Store store() { return {A.data(), Bc.data(), rho.data(), sym.data(), expd.data(), cancel}; }
};

// The keys of the r values in flight (r-major, then orbit-major, window keys each) and each orbit's extreme keys.
struct RoundKeys {
  std::size_t orbits = 0, window = 0;
  std::vector<double> key, lo, hi;
  RoundKeys(std::size_t rs, std::size_t orbits, std::size_t window)
      : orbits(orbits), window(window), key(rs * orbits * window), lo(rs * orbits), hi(rs * orbits) {}
  double* of(std::size_t ir, std::size_t o) { return key.data() + (ir * orbits + o) * window; }
};

// One batch of orbits o0.. at r: forward, backward, then each lane's result; its keys go to keys (slot ir of the
// round) and the statistics of its own angles to its ClvResult.
void run_batch(const std::vector<Vec3<double>>& initial, std::size_t o0, double r, int K, const ClvOptions& opt,
               bool keep_steps, ThreadStore& ts, RoundKeys& keys, std::size_t ir, ClvRow& row) {
  const long N = opt.window;
  const std::size_t Nz = static_cast<std::size_t>(N), I0 = initial.size();
  const int lanes = static_cast<int>(std::min<std::size_t>(B, I0 - o0));
  const Store st = ts.store();
  Lanes b;
  load_lanes(initial, o0, lanes, r, b);
  NormsAt start;
  const WindowEnd end = forward_pass(b, opt.transient, N, opt.backward_transient, K, keep_steps, st, start);
  if (st.cancel && st.cancel->cancelled()) return;  // its lanes stopped part-way: nothing of them is kept
  const KeyRange range = backward_keys(b.w, st, N, lanes, keys.of(ir, o0));
  for (int l = 0; l < lanes; ++l) {
    const std::size_t o = o0 + static_cast<std::size_t>(l);
    ClvResult& c = row.orbit[o];
    lane_exponents(start, end, l, r, N, c);
    double* key = keys.of(ir, o);
    if (keep_steps) lane_steps(key, st, l, Nz, c);
    // A degenerate orbit's angles are undefined (hyperbolicity.hpp): nothing of them is kept.
    if (c.degenerate) {
      c.median_angle = c.q05_angle = c.min_angle = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    c.histogram.assign(static_cast<std::size_t>(opt.bins), 0.0);
    add_histogram(key, Nz, opt.bins, c.histogram.data());
    KeyRows own{{key}, Nz, range.lo[l], range.hi[l]};
    keys.lo[ir * I0 + o] = range.lo[l];
    keys.hi[ir * I0 + o] = range.hi[l];
    angle_stats(own, c.median_angle, c.q05_angle, c.min_angle, ts.count, ts.gather);
  }
}

// An r's statistics pooled over its non-degenerate orbits, in orbit order (their keys moved to the front).
void pool_row(RoundKeys& keys, std::size_t ir, std::size_t bins, ThreadStore& ts, ClvRow& row) {
  KeyRows pooled;
  pooled.len = keys.window;
  row.histogram.assign(bins, 0.0);
  for (std::size_t o = 0; o < keys.orbits; ++o) {
    const ClvResult& c = row.orbit[o];
    if (c.degenerate) continue;
    pooled.row.push_back(keys.of(ir, o));
    pooled.lo = std::min(pooled.lo, keys.lo[ir * keys.orbits + o]);
    pooled.hi = std::max(pooled.hi, keys.hi[ir * keys.orbits + o]);
    for (std::size_t b = 0; b < bins; ++b) row.histogram[b] += c.histogram[b];
  }
  if (!pooled.row.empty()) angle_stats(pooled, row.median_angle, row.q05_angle, row.min_angle, ts.count, ts.gather);
  else row.median_angle = row.q05_angle = row.min_angle = std::numeric_limits<double>::quiet_NaN();
}

// The inputs checked (r, points, the options) and the memory of the threads' windows refused when too large.
void check_batched(const std::vector<double>& rs, const std::vector<Vec3<double>>& initial, const ClvOptions& opt,
                   int threads) {
  validate(opt);
  for (double r : rs) core::validate_r(r);
  for (const auto& u : initial) core::validate_point(u(0), u(1), u(2), "point");
  const std::size_t Nz = static_cast<std::size_t>(opt.window);
  iterate::checked_bytes(static_cast<std::size_t>(threads) * B, sizeof(double) * 3 * Nz, "window");
  iterate::checked_bytes(initial.size(), sizeof(double) * Nz, "window");
}

}  // namespace

ClvRows covariant_vectors_batched(const std::vector<double>& rs, const std::vector<Vec3<double>>& initial,
                                  const ClvOptions& opt, const iterate::RunOptions& run, bool keep_steps) {
  const int threads = core::thread_count(run.threads);
  // r values in rounds of 4 per thread: the batches of a round's r values on every thread, then each r's pooled
  // statistics on one thread (in parallel; dynamic schedules: no bit depends on which thread runs what, and a
  // thread the machine delays holds the others less).
  const std::size_t G = 4 * static_cast<std::size_t>(threads);
  check_batched(rs, initial, opt, threads);
  const std::size_t I0 = initial.size(), n_batches = (I0 + B - 1) / B, Nz = static_cast<std::size_t>(opt.window);
  std::vector<int> K(rs.size());
  for (std::size_t i = 0; i < rs.size(); ++i) K[i] = clv_interval(rs[i]);
  iterate::checked_bytes(G * I0, sizeof(double) * Nz, "window");
  ClvRows rows(rs.size());
  RoundKeys keys(G, I0, Nz);
  bool stop = false;

#pragma omp parallel num_threads(threads)
  {
    ThreadStore ts(Nz, keep_steps);
    ts.cancel = run.cancel;
    for (std::size_t r0 = 0; r0 < rs.size(); r0 += G) {
      const std::size_t g = std::min(G, rs.size() - r0);
#pragma omp single
      {
        stop = run.cancel && run.cancel->cancelled();
        for (std::size_t i = 0; i < g; ++i) rows[r0 + i].orbit.resize(I0);
      }
      if (stop) break;  // read by every thread after the single's barrier: all leave at the same round
#pragma omp for schedule(dynamic)
      for (std::size_t t = 0; t < g * n_batches; ++t) {
        if (run.cancel && run.cancel->cancelled()) continue;  // no exception may leave an OpenMP region
        const std::size_t ir = r0 + t / n_batches;
        run_batch(initial, t % n_batches * B, rs[ir], K[ir], opt, keep_steps, ts, keys, ir - r0, rows[ir]);
      }
#pragma omp for schedule(dynamic)
      for (std::size_t i = 0; i < g; ++i)
        if (!(run.cancel && run.cancel->cancelled()))
          pool_row(keys, i, static_cast<std::size_t>(opt.bins), ts, rows[r0 + i]);
#pragma omp single nowait
      if (run.progress) run.progress->update(r0 + g, rs.size());
    }
  }
  core::check_cancel(run.cancel);
  return rows;
}

}  // namespace btob::lyapunov
