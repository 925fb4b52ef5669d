// SPDX-License-Identifier: GPL-3.0-or-later
// Template bodies of the fused cocycle kernel (iterate/cocycle.hpp); included only by kernel units (kernel flags).
#pragma once

#include "core/run.hpp"
#include "iterate/cocycle.hpp"
#include "iterate/kernel_impl.hpp"

#include <stdexcept>
#include <utility>

namespace btob::iterate {
namespace detail {

// Vectors in flight of the cocycle kernel.  Each carries 10 live values (u, v, r, alpha, alpha / r, the symbol
// count); with 4 vectors r, alpha and alpha / r are read from the stack as memory operands.  One step's dependency
// chain (a y - x, the compare, the selections, the FMA for y', and v's behind them) is ~25 cycles, so fewer vectors
// leave the pipes idle between steps, and more spill the state out of the 32 vector registers.  Per 8-lane
// vector-step the loop issues ~41 instructions, 33 of them on the FP pipes (against 12 for the plain step), and a
// block's end (projection, rescales, the loss test, the sums) adds ~8: on four 512-bit FP pipes the cocycle cannot
// run faster than ~10 cycles per vector-step, against ~3 for the plain kernel.  (CHANGELOG.md keeps the
// measurements behind the choice of 4.)
inline constexpr int kCocycleVectors = 4;

// NV vectors of W lanes: kCocycleVectors for a full batch, 1 for an ensemble of at most W orbits (one orbit's chain
// is latency-bound: three more vectors would add their issue cost and nothing else; each lane's arithmetic is the
// same whatever NV).
template <class T, int NV_ = kCocycleVectors> struct CocycleLanes {
  static constexpr int W = Simd<T>::W;
  static constexpr int NV = NV_;
  static constexpr int B = W * NV;
  alignas(64) T x[B], y[B], z[B], vx[B], vy[B], vz[B];
};

// v <- M_s v with the masks of the point's step (kernel_impl.hpp, map_step): the same three matrices written with
// selections, since the signs of a y - x and a y - z along v are not those along u:
//   M1 v = (d1, k (d1 + r vz) - vy, r vz),  M3 v = (r vx, k (r vx + d3) - vy, d3),  M2 v = (-d1, k (-d1 - d3) + vy,
//   -d3)
// with d1 = a vy - vx, d3 = a vy - vz (the identities of map_step: k r = a).  12 operations per lane.
template <class V, class M> inline void tangent_step(V& vx, V& vy, V& vz, V r, V a, V k, M s1, M s3) {
  const V ay = a * vy;
  const V d1 = ay - vx, d3 = ay - vz;
  const V tx = s3 ? V(r * vx) : (s1 ? d1 : V(-d1));
  const V tz = s1 ? V(r * vz) : (s3 ? d3 : V(-d3));
  const V sy = (s1 | s3) ? V(-vy) : vy;
  vx = tx;
  vz = tz;
  vy = k * (tx + tz) + sy;
}

// v <- v - u (u . v) / (u . u): the orthogonal projection onto u's complement.
template <class V> inline void project_out(V x, V y, V z, V& vx, V& vy, V& vz) {
  const V f = (x * vx + y * vy + z * vz) / (x * x + y * y + z * z);
  vx -= f * x;
  vy -= f * y;
  vz -= f * z;
}

// Biased binary exponent of max(|x|, |y|, |z|) and the exact power of two that brings that maximum into [1, 2).
template <class T, class V, class I> inline I max_exponent(V x, V y, V z) {
  constexpr int mant = std::numeric_limits<T>::digits - 1;
  const V ax = abs_of(x), ay = abs_of(y), az = abs_of(z);
  const V mxy = ax > ay ? ax : ay;
  const V m = mxy > az ? mxy : az;
  return (I)m >> mant;
}
template <class T, class V, class I> inline V scale_for(I e) {
  constexpr int mant = std::numeric_limits<T>::digits - 1;
  constexpr int two_bias = 2 * (std::numeric_limits<T>::max_exponent - 1);
  return (V)(((I{} + two_bias) - e) << mant);
}

// Loads and stores of a batch's state in registers.
template <class T, int NV> struct CocycleRegs {
  using S = Simd<T>;
  using V = typename S::V;
  static constexpr int W = S::W;
  V x[NV], y[NV], z[NV], vx[NV], vy[NV], vz[NV];
  void load(const CocycleLanes<T, NV>& m) {
    for (int j = 0; j < NV; ++j) {
      x[j] = S::load(m.x + j * W), y[j] = S::load(m.y + j * W), z[j] = S::load(m.z + j * W);
      vx[j] = S::load(m.vx + j * W), vy[j] = S::load(m.vy + j * W), vz[j] = S::load(m.vz + j * W);
    }
  }
  void store(CocycleLanes<T, NV>& m) const {
    for (int j = 0; j < NV; ++j) {
      S::store(m.x + j * W, x[j]), S::store(m.y + j * W, y[j]), S::store(m.z + j * W, z[j]);
      S::store(m.vx + j * W, vx[j]), S::store(m.vy + j * W, vy[j]), S::store(m.vz + j * W, vz[j]);
    }
  }
};

// One block of n steps of the point and of v for all vectors of a batch, in registers (the vectors interleaved:
// one step's dependency chain is ~20 cycles); then v is projected out of u's line (unless EveryStep: then after
// every step) and both are rescaled by exact powers of two.  Out, per lane: the exponents removed (eu, ev), the
// count of symbols 1 and 3 (cnt) and the bits lost to cancellation in the final projection (loss).  The point's
// arithmetic is the same code in both variants, so its bits are the same.
template <class T, int NV, bool EveryStep>
inline void cocycle_block(CocycleRegs<T, NV>& st, const typename Simd<T>::V* r, const typename Simd<T>::V* a,
                          const typename Simd<T>::V* k, int n, typename Simd<T>::V* eu, typename Simd<T>::V* ev,
                          typename Simd<T>::V* cnt, typename Simd<T>::I* loss) {
  using V = typename Simd<T>::V;
  using I = typename Simd<T>::I;
  constexpr int bias = std::numeric_limits<T>::max_exponent - 1;
  V c[NV];
#pragma GCC unroll 4
  for (int j = 0; j < NV; ++j) c[j] = V{};
  for (int s = 0; s < n; ++s) {
#pragma GCC unroll 4
    for (int j = 0; j < NV; ++j) {
      I s1, s3;
      const StepResult<V> o = map_step<V, I>(st.x[j], st.y[j], st.z[j], r[j], a[j], k[j], s1, s3);
      tangent_step(st.vx[j], st.vy[j], st.vz[j], r[j], a[j], k[j], s1, s3);
      c[j] += (s1 | s3) ? V{} + 1 : V{};
      st.x[j] = o.x, st.y[j] = o.y, st.z[j] = o.z;
      if constexpr (EveryStep) project_out(st.x[j], st.y[j], st.z[j], st.vx[j], st.vy[j], st.vz[j]);
    }
  }
#pragma GCC unroll 4
  for (int j = 0; j < NV; ++j) {
    const I before = max_exponent<T, V, I>(st.vx[j], st.vy[j], st.vz[j]);
    if constexpr (!EveryStep) project_out(st.x[j], st.y[j], st.z[j], st.vx[j], st.vy[j], st.vz[j]);
    const I e_u = max_exponent<T, V, I>(st.x[j], st.y[j], st.z[j]);
    const I e_v = max_exponent<T, V, I>(st.vx[j], st.vy[j], st.vz[j]);
    const V su = scale_for<T, V, I>(e_u), sv = scale_for<T, V, I>(e_v);
    st.x[j] *= su, st.y[j] *= su, st.z[j] *= su;
    st.vx[j] *= sv, st.vy[j] *= sv, st.vz[j] *= sv;
    eu[j] = __builtin_convertvector(e_u - bias, V);
    ev[j] = __builtin_convertvector(e_v - bias, V);
    cnt[j] = c[j];
    loss[j] = before - e_v;
  }
}

// Up to `steps` steps of a batch in blocks of K (the last one shorter when steps is not a multiple), the state kept
// in registers from block to block; after each block the removed exponents and the symbol counts are added to
// acc[0 .. B) (eu), acc[B .. 2B) (ev), acc[2B .. 3B) (counts), in T (exact integers: the caller bounds `steps`).
// Stops after the first block whose projection lost more than `budget` bits in some lane: then `pre` holds the state
// before that block, `st` after it, blk[] that block's own eu/ev/counts (layout of acc, not added to acc), loss[] its
// losses, and the return value is the number of steps before it.  Otherwise returns `steps` with failed = false.
template <class T, int NV>
inline long cocycle_blocks(CocycleLanes<T, NV>& st, CocycleLanes<T, NV>& pre, const T* rs, const T* as, const T* ks,
                           long steps, int K, int budget, T* acc, T* blk, std::int64_t* loss, bool& failed) {
  using S = Simd<T>;
  using V = typename S::V;
  using I = typename S::I;
  constexpr int W = S::W, B = CocycleLanes<T, NV>::B;
  CocycleRegs<T, NV> R;
  R.load(st);
  V r[NV], a[NV], k[NV];
  for (int j = 0; j < NV; ++j) r[j] = S::load(rs + j * W), a[j] = S::load(as + j * W), k[j] = S::load(ks + j * W);
  failed = false;
  long done = 0;
  while (done < steps) {
    const int n = static_cast<int>(std::min<long>(K, steps - done));
    R.store(pre);
    V eu[NV], ev[NV], cnt[NV];
    I loss_v[NV];
    I over{};
    cocycle_block<T, NV, false>(R, r, a, k, n, eu, ev, cnt, loss_v);
    for (int j = 0; j < NV; ++j) over |= loss_v[j] > budget;
    bool any = false;
    for (int l = 0; l < W; ++l) any |= over[l] != 0;
    if (any) {
      R.store(st);
      for (int j = 0; j < NV; ++j) {
        S::store(blk + j * W, eu[j]), S::store(blk + B + j * W, ev[j]), S::store(blk + 2 * B + j * W, cnt[j]);
        for (int l = 0; l < W; ++l) loss[j * W + l] = loss_v[j][l];
      }
      failed = true;
      return done;
    }
    for (int j = 0; j < NV; ++j) {
      S::store(acc + j * W, S::load(acc + j * W) + eu[j]);
      S::store(acc + B + j * W, S::load(acc + B + j * W) + ev[j]);
      S::store(acc + 2 * B + j * W, S::load(acc + 2 * B + j * W) + cnt[j]);
    }
    done += n;
  }
  R.store(st);
  return done;
}

// The failed block again with a projection after every step, from `pre`; lanes over budget take its tangent vector
// and its ev, the others keep the block's (a lane's bits never depend on its neighbours).  Returns lanes redone.
template <class T, int NV>
inline int cocycle_redo(CocycleLanes<T, NV>& st, const CocycleLanes<T, NV>& pre, const T* rs, const T* as, const T* ks,
                        int n, int budget, T* blk, const std::int64_t* loss, int lanes) {
  using S = Simd<T>;
  using V = typename S::V;
  using I = typename S::I;
  constexpr int W = S::W, B = CocycleLanes<T, NV>::B;
  CocycleRegs<T, NV> R;
  R.load(pre);
  alignas(64) T ev2[B];
  V r[NV], a[NV], k[NV], eu[NV], ev[NV], cnt[NV];
  I lo[NV];
  for (int j = 0; j < NV; ++j) r[j] = S::load(rs + j * W), a[j] = S::load(as + j * W), k[j] = S::load(ks + j * W);
  cocycle_block<T, NV, true>(R, r, a, k, n, eu, ev, cnt, lo);
  for (int j = 0; j < NV; ++j) S::store(ev2 + j * W, ev[j]);
  CocycleLanes<T, NV> again;
  R.store(again);
  int redone = 0;
  for (int l = 0; l < B; ++l)
    if (loss[l] > budget) {
      st.vx[l] = again.vx[l], st.vy[l] = again.vy[l], st.vz[l] = again.vz[l];
      blk[B + l] = ev2[l];
      if (l < lanes) ++redone;
    }
  return redone;
}

// The start of lane l: the orbit's start vector in Q with its largest component in [1, 2) (the plain kernel's),
// and v_0 (cocycle.hpp), both rounded to T.
template <class T> inline void cocycle_start(const Vec3<double>& u0, T& x, T& y, T& z, T& vx, T& vy, T& vz) {
  const Vec3<double> q = unit_start(u0);
  const Vec3<double> v = first_tangent(q);
  x = static_cast<T>(q(0)), y = static_cast<T>(q(1)), z = static_cast<T>(q(2));
  vx = static_cast<T>(v(0)), vy = static_cast<T>(v(1)), vz = static_cast<T>(v(2));
}

// One batch of B lanes in flight: the state and its copy before the block, r and the branch constants, the
// per-call sums and their double accumulators (log2 |u|, log2 |v|, symbols 1 and 3).
template <class T, int NV> struct CocycleBatchState {
  using L = CocycleLanes<T, NV>;
  static constexpr int B = L::B;
  L cur, pre;
  alignas(64) T r[B], a[B], k[B], acc[3 * B], blk[3 * B];
  alignas(64) std::int64_t loss[B];
  alignas(64) double lu[B], lv[B], n13[B];
  std::size_t o0 = 0;
  int lanes = 0;
};

// The batch of orbits o0..: every lane's start (a partial batch padded with its last orbit), r, alpha = (1 + r) / 2
// and alpha / r in T, the sums at zero.
template <class T, int NV>
void cocycle_batch_start(const Ensemble& ens, const T* r_t, std::size_t o0, CocycleBatchState<T, NV>& b) {
  constexpr int B = CocycleBatchState<T, NV>::B;
  const std::size_t n_orbits = ens.orbits(), n_ic = ens.initial.size();
  b.o0 = o0;
  b.lanes = static_cast<int>(std::min<std::size_t>(B, n_orbits - o0));
  for (int l = 0; l < B; ++l) {
    const std::size_t o = o0 + static_cast<std::size_t>(std::min(l, b.lanes - 1));  // pad with the last orbit
    CocycleLanes<T, NV>& c = b.cur;
    cocycle_start<T>(ens.initial[o % n_ic], c.x[l], c.y[l], c.z[l], c.vx[l], c.vy[l], c.vz[l]);
    b.r[l] = r_t[o / n_ic];
    b.a[l] = (T(1) + b.r[l]) / T(2);
    b.k[l] = b.a[l] / b.r[l];
    b.lu[l] = b.lv[l] = b.n13[l] = 0;
  }
  renormalise<T, B>(b.cur.x, b.cur.y, b.cur.z);  // float: rounding may have carried the largest to 2
}

// Adds T's per-call sums (exact integers) into the double accumulators.
template <class T, int NV> inline void cocycle_flush(CocycleBatchState<T, NV>& b, const T* s) {
  constexpr int B = CocycleBatchState<T, NV>::B;
#pragma omp simd
  for (int l = 0; l < B; ++l) {
    b.lu[l] += static_cast<double>(s[l]);
    b.lv[l] += static_cast<double>(s[B + l]);
    b.n13[l] += static_cast<double>(s[2 * B + l]);
  }
}

// The batch at a checkpoint, handed to the recorder.
template <class T, int NV, class Rec> inline void cocycle_record(Rec& rec, CocycleBatchState<T, NV>& b, long step) {
  CocycleBatch<T> v;
  v.orbit0 = b.o0, v.lanes = b.lanes, v.step = step;
  v.x = b.cur.x, v.y = b.cur.y, v.z = b.cur.z, v.vx = b.cur.vx, v.vy = b.cur.vy, v.vz = b.cur.vz;
  v.log2u = b.lu, v.log2v = b.lv, v.n13 = b.n13;
  rec.record(v);
}

// The batch's steps 1..iterations in calls of at most kFlush steps, each a run of blocks of K steps (cocycle_blocks)
// and, where a block lost more than the budget, that block redone per step for the lanes that lost
// (cocycle_redo); recorded at the recorder's checkpoints.  Polled once per call (about a millisecond): a cancelled
// run leaves the batch early.  Returns the lanes redone.
template <class T, int NV, class Rec>
std::size_t cocycle_batch(CocycleBatchState<T, NV>& b, long iterations, Rec& rec, const RunOptions& opt) {
  constexpr int B = CocycleBatchState<T, NV>::B;
  constexpr int K = cocycle_interval<T>();
  constexpr int budget = cocycle_loss_budget<T>();
  constexpr long kFlush = 1L << 16;
  const std::vector<long>& cps = rec.checkpoints();
  std::size_t ci = 0;
  if (ci < cps.size() && cps[ci] == 0) cocycle_record<T, NV>(rec, b, 0), ++ci;
  std::size_t redone = 0;
  long step = 0;
  while (step < iterations && !(opt.cancel && opt.cancel->cancelled())) {
    const long target = ci < cps.size() ? std::min(cps[ci], iterations) : iterations;
    // At most kFlush steps per call: T's sums of exponents (<= 2^6 per step) and counts stay exact integers.
    const long want = std::min<long>(target - step, kFlush);
    std::fill(b.acc, b.acc + 3 * B, T(0));
    bool failed = false;
    const long done = cocycle_blocks<T, NV>(b.cur, b.pre, b.r, b.a, b.k, want, K, budget, b.acc, b.blk, b.loss, failed);
    cocycle_flush<T, NV>(b, b.acc);
    step += done;
    if (failed) {
      const int n = static_cast<int>(std::min<long>(K, want - done));
      redone +=
          static_cast<std::size_t>(cocycle_redo<T, NV>(b.cur, b.pre, b.r, b.a, b.k, n, budget, b.blk, b.loss, b.lanes));
      cocycle_flush<T, NV>(b, b.blk);
      step += n;
    }
    if (ci < cps.size() && step == cps[ci]) cocycle_record<T, NV>(rec, b, step), ++ci;
  }
  return redone;
}

}  // namespace detail

namespace detail {
// Batches of B = W NV orbits over the threads (static schedule: each batch writes only its own lanes' records): start,
// step with the recorder at its checkpoints, tally (RunTally: progress, degenerate lanes, cancellation).
template <class T, int NV, CocycleRecorder Rec>
void cocycle_batches(const Ensemble& ens, long iterations, Rec& rec, const RunOptions& opt) {
  constexpr int B = CocycleLanes<T, NV>::B;
  const std::size_t n_orbits = ens.orbits();
  const std::size_t n_batches = (n_orbits + B - 1) / B;
  const int threads = static_cast<int>(std::min<std::size_t>(core::thread_count(opt.threads), n_batches));
  RunTally tally;
  std::atomic<std::size_t> redone{0};
  // r in T from the ensemble's decimal source, as iterate::run: float's r is the float nearest the request's decimal.
  std::vector<T> r_own;
  const T* r_t = r_values<T>(ens, r_own);

#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::size_t b = 0; b < n_batches; ++b) {
    if (opt.cancel && opt.cancel->cancelled()) continue;  // no exception may leave an OpenMP region
    CocycleBatchState<T, NV> st;
    cocycle_batch_start<T, NV>(ens, r_t, b * B, st);
    const std::size_t redone_here = cocycle_batch<T, NV>(st, iterations, rec, opt);
    if (redone_here) redone.fetch_add(redone_here, std::memory_order_relaxed);
    tally.batch_end(opt, n_batches, st.lanes, [&](int l) {
      return degenerate_vector(st.cur.x[l], st.cur.y[l], st.cur.z[l]) ||
             degenerate_vector(st.cur.vx[l], st.cur.vy[l], st.cur.vz[l]);
    });
  }
  tally.finish(opt, n_batches);
  if (opt.redone) *opt.redone = redone.load();
}
}  // namespace detail

// An ensemble of at most one vector's lanes runs as one vector (NV = 1: the scalar limit of the cocycle's chain, as
// iterate::run's few_lanes); a lane's bits are the same either way.  A block redone for one lane is redone for its
// batch, whose other lanes keep their values: a single orbit's batch is copies of it, so its bits do not change.
template <class T, CocycleRecorder Rec>
void run_cocycle(const Ensemble& ens, long iterations, Rec& rec, const RunOptions& opt) {
  static_assert(detail::has_simd<T>, "the cocycle kernel is written for float and double");
  if (ens.orbits() == 0 || iterations < 0) return;
  if (!cocycle_accepts<T>(ens.r))
    throw std::invalid_argument(
        "r: too small for the cocycle kernel in this precision (the state would leave the "
        "normal range within one projection interval)");
  if (ens.orbits() <= static_cast<std::size_t>(detail::Simd<T>::W))
    return detail::cocycle_batches<T, 1>(ens, iterations, rec, opt);
  detail::cocycle_batches<T, detail::kCocycleVectors>(ens, iterations, rec, opt);
}

}  // namespace btob::iterate
