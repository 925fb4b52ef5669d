// SPDX-License-Identifier: GPL-3.0-or-later
// The batched iterator of P_r: structure-of-arrays SIMD kernel, OpenMP driver, and its scalar reference.
#pragma once

#include "core/map.hpp"
#include "core/request.hpp"
#include "iterate/ensemble.hpp"

#include <concepts>
#include <cstddef>
#include <cstdint>

namespace btob::iterate {

// A Recorder says what a run keeps.  The kernel calls, for every recorded state k (k steps done,
// first_step() <= k <= iterations), once per batch of `lanes` consecutive orbits starting at `orbit0`:
//     rec.record(orbit0, lanes, k, x, y, z, sym)
// x, y, z hold the (unnormalised, power-of-two-rescaled) state of each lane, in the quadrant Q, and
// sym[l] the symbol 1/2/3 of step k (only when Rec::needs_symbols; else sym is null).  Calls for
// different batches may come from different threads at once: a recorder writes only its orbits' slice
// (or a per-thread buffer indexed by thread).  Required members:
//     static constexpr bool needs_symbols;
//     long first_step() const;

// The recorder concept: what the kernel needs of any recorder, which the analysis that owns it defines (in its own
// folder) and instantiates in the kernel in its own kernel_*.cpp (docs/ARCHITECTURE.md, "Adding an analysis").
template <class R>
concept Recorder = requires(R& rec, const R& crec, std::size_t orbit0, int lanes, long k, const double* v,
                            const std::uint8_t* symbols) {
  { R::needs_symbols } -> std::convertible_to<bool>;
  { crec.first_step() } -> std::convertible_to<long>;
  rec.record(orbit0, lanes, k, v, v, v, symbols);
};

// Run options.  threads <= 0 means OpenMP's default.  Results never depend on `threads`.
using core::ProgressSink;
struct RunOptions {
  int threads = 0;
  ProgressSink* progress = nullptr;
  // Checked before every batch and inside one (every renormalisation block of the unrecorded steps, every
  // core::cancel_stride recorded steps); a cancelled run throws core::Cancelled after the parallel region.
  const core::CancelToken* cancel = nullptr;
  // When set, receives the number of orbits whose final state is not a finite non-zero vector (the
  // precision could not cope, e.g. float at extreme r); 0 on healthy runs.
  std::size_t* degenerate = nullptr;
  // run_cocycle only (iterate/cocycle.hpp): receives how many (orbit, block) pairs were redone with a projection
  // after every step.
  std::size_t* redone = nullptr;
};

// Number of steps between renormalisations for scalar type T that keeps every state normal and finite
// for all r in the ensemble (from operator-norm bounds of the branch matrices, see kernel_impl.hpp).
template <class T> int renormalisation_interval(const std::vector<double>& r);

// Iterates every orbit of the ensemble `iterations` times with the batched kernel (T = float or
// double with SIMD; long double, float128, MPFR per lane).  Each orbit starts from its initial vector
// scaled by a power of two (exact), in the quadrant Q.
template <class T, Recorder Rec>
void run(const Ensemble& ensemble, long iterations, Rec& rec, const RunOptions& opt = {});

// One step of the double kernel from one point, bit for bit a lane of the batched step (compiled in the kernel's
// unit with its instruction set): u brought into Q, then M_s u = P_s u / r (not normalised) and the branch s.
// A point and the same point times 2^k (no underflow) give images that differ by 2^k exactly.
core::Step<double> kernel_step(const core::Vec3<double>& u, double r);

// The scalar reference: one orbit at a time, the paper's matrices P1/P2/P3 chosen with branches and
// the vector normalised every step (Appendix A.2).  Same recorder interface, lanes = 1.
template <class T, Recorder Rec> void run_scalar(const Ensemble& ensemble, long iterations, Rec& rec);

}  // namespace btob::iterate
