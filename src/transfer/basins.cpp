// SPDX-License-Identifier: GPL-3.0-or-later
// Stage 9 of `btob transfer` (stages.hpp): basins from the Ulam graph.  The targets (the boxes of each stable
// cycle, the P2 region), then the absorption probability of every box into each target and the Lebesgue measure
// each target absorbs.
#include "transfer/detail.hpp"
#include "transfer/stages.hpp"

#include "core/cancel.hpp"
#include "core/map.hpp"

#include <Eigen/IterativeLinearSolvers>

#include <algorithm>
#include <cmath>
#include <limits>

namespace btob::transfer {

using detail::at;

namespace detail {
double p2_level(double r) {
  const double al = core::alpha(r);
  return 2 - al * al / r;
}
}  // namespace detail

std::vector<double> lebesgue(const Partition& p, Domain d, const std::vector<double>& w1_range) {
  // On the strip, uniform in w1: a column [u0, u1] of atan(w1) weighs |[tan u0, tan u1] cap [a, b]|.
  std::vector<double> m(at(p.size()), 0);
  const double h1 = (p.hi1 - p.lo1) / static_cast<double>(p.n1);
  for (long i1 = 0; i1 < p.n1; ++i1) {
    double w = 1.0 / static_cast<double>(p.n1);
    if (d == Domain::strip) {
      const double u0 = p.lo1 + h1 * static_cast<double>(i1), u1 = u0 + h1;
      const double t0 = i1 == 0 ? -std::numeric_limits<double>::infinity() : std::tan(u0);
      const double t1 = i1 == p.n1 - 1 ? std::numeric_limits<double>::infinity() : std::tan(u1);
      w = std::max(0.0, std::min(t1, w1_range[1]) - std::max(t0, w1_range[0])) / (w1_range[1] - w1_range[0]);
    }
    for (long i2 = 0; i2 < p.n2; ++i2) m[at(i1 * p.n2 + i2)] = w / static_cast<double>(p.n2);
  }
  return m;
}

namespace {

// The Lebesgue measure of the P2 region R = {I < c}, c = 2 - alpha^2 / r, inside the request's rectangle
// w1 in [w1a, w1b] x w2 in [-1, 1], as a fraction of the rectangle: the chord of R at w1 has length
// sqrt(8 c - (32 r - 16 alpha^2) w1^2) / 2 (R lies within |w2| <= 1: it is tangent to w2 = +-1); midpoint rule
// on 2^17 points (the chord's square-root ends: error ~ N^-1.5, below 1e-7).
double p2_region_fraction(double r, double w1a, double w1b) {
  const double al = core::alpha(r), cm = detail::p2_level(r), k = 32 * r - 16 * al * al;
  if (!(cm > 0 && k > 0)) return 0;
  const double half = std::sqrt(8 * cm / k), lo = std::max(w1a, -half), hi = std::min(w1b, half);
  if (!(hi > lo)) return 0;
  const long N = 1L << 17;
  const double dw = (hi - lo) / static_cast<double>(N);
  double s = 0;
  for (long i = 0; i < N; ++i) {
    const double w = lo + (static_cast<double>(i) + 0.5) * dw;
    s += std::sqrt(std::max(0.0, 8 * cm - k * w * w)) / 2;
  }
  return s * dw / (2 * (w1b - w1a));
}

// The P2 region's target: the boxes inside R, all four corners (R is convex in (w1, w2), and a box of either chart
// is a rectangle in (atan w1, w2) or (theta, phi); on the strip a box is a rectangle in (w1, w2) too, so the test
// is exact there), among the boxes no earlier target holds.
void add_p2_region(const Partition& part, Domain dom, const TransferRequest& q, BasinTargets& t) {
  const double al = core::alpha(q.r), cmax = detail::p2_level(q.r);
  if (!(cmax > 0)) return;
  BasinInfo b;
  b.attractor = "P2 region";
  b.kind = "neutral";  // the P2 invariant curves: elliptic, neither attracting nor repelling
  const auto id = static_cast<std::uint32_t>(t.basins.size() + 1);
  const double h1 = (part.hi1 - part.lo1) / static_cast<double>(part.n1),
               h2 = (part.hi2 - part.lo2) / static_cast<double>(part.n2);
  const auto I = [&](double a, double bb) {  // the conserved quantity of P2 at the chart point (a, bb)
    double x, y, z;
    chart_to_vector(dom, a, bb, x, y, z);
    const double s = x + z, d = x - z;
    return d > 0 ? (2 * s * s - 4 * al * s * y + 4 * q.r * y * y) / (d * d) : std::numeric_limits<double>::infinity();
  };
  for (long i1 = 0; i1 < part.n1; ++i1)
    for (long i2 = 0; i2 < part.n2; ++i2) {
      const double a0 = part.lo1 + static_cast<double>(i1) * h1, b0 = part.lo2 + static_cast<double>(i2) * h2;
      if (I(a0, b0) < cmax && I(a0 + h1, b0) < cmax && I(a0, b0 + h2) < cmax && I(a0 + h1, b0 + h2) < cmax &&
          t.of_box[at(i1 * part.n2 + i2)] == 0)
        t.of_box[at(i1 * part.n2 + i2)] = id, ++b.target_boxes;
    }
  if (dom == Domain::strip) b.exact = p2_region_fraction(q.r, q.w1_range[0], q.w1_range[1]);
  if (b.target_boxes > 0) t.basins.push_back(b);
}

}  // namespace

BasinTargets basin_targets(const std::vector<CycleCheck>& cycles, const Partition& part, Domain dom,
                           const TransferRequest& q) {
  BasinTargets t;
  t.of_box.assign(at(part.size()), 0);
  for (const auto& cc : cycles) {
    if (cc.outcome != "stable orbit") continue;  // an unstable or absent cycle attracts nothing
    BasinInfo b;
    b.attractor = cc.word;
    b.kind = "stable";  // an attracting cycle (the verdict words of docs/ARCHITECTURE.md)
    const auto id = static_cast<std::uint32_t>(t.basins.size() + 1);
    for (long box : cc.boxes)
      if (box >= 0 && t.of_box[at(box)] == 0) t.of_box[at(box)] = id, ++b.target_boxes;
    if (b.target_boxes > 0) t.basins.push_back(b);
  }
  add_p2_region(part, dom, q, t);
  return t;
}

namespace {

// The boxes from which a target can be reached (reverse breadth-first search on the transposed graph); the others
// are absorbed by none.
std::vector<char> reaching_boxes(const UlamMatrix& P, const std::vector<std::uint32_t>& target) {
  const std::size_t n = at(P.n);
  std::vector<int> in_ptr(n + 1, 0), in_col(P.col.size());
  for (int j : P.col) ++in_ptr[at(j + 1)];
  for (std::size_t j = 0; j < n; ++j) in_ptr[j + 1] += in_ptr[j];
  std::vector<int> fill(in_ptr.begin(), in_ptr.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    for (int e = P.row_ptr[i]; e < P.row_ptr[i + 1]; ++e) in_col[at(fill[at(P.col[at(e)])]++)] = static_cast<int>(i);
  std::vector<char> reach(n, 0);
  std::vector<long> queue;
  for (std::size_t i = 0; i < n; ++i)
    if (target[i]) reach[i] = 1, queue.push_back(static_cast<long>(i));
  for (std::size_t k = 0; k < queue.size(); ++k)
    for (int e = in_ptr[at(queue[k])]; e < in_ptr[at(queue[k] + 1)]; ++e)
      if (!reach[at(in_col[at(e)])]) reach[at(in_col[at(e)])] = 1, queue.push_back(in_col[at(e)]);
  return reach;
}

using RowMat = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

// The absorption problem (I - Q) h_k = P 1_k on the unknowns (boxes that reach a target and are none).
struct AbsorptionSystem {
  std::vector<int> unknown;  // per box: its row among the unknowns, -1 for none
  int m = 0;                 // number of unknowns
  RowMat A;                  // I - Q
  Eigen::MatrixXd B;         // column k: P 1_k
};

// A in compressed rows, built directly: P's columns are sorted in each row and the unknowns' numbering is
// increasing, so the columns of A's rows are sorted; the diagonal 1 is merged in at its place.
AbsorptionSystem absorption_system(const UlamMatrix& P, const std::vector<std::uint32_t>& target,
                                   const std::vector<char>& reach, std::size_t targets) {
  AbsorptionSystem s;
  s.unknown.assign(at(P.n), -1);
  for (std::size_t i = 0; i < s.unknown.size(); ++i)
    if (reach[i] && !target[i]) s.unknown[i] = s.m++;
  std::vector<int> a_ptr{0}, a_col;
  std::vector<double> a_val;
  s.B = Eigen::MatrixXd::Zero(s.m, static_cast<long>(targets));
  for (std::size_t i = 0; i < s.unknown.size(); ++i) {
    const int u = s.unknown[i];
    if (u < 0) continue;
    bool diag = false;
    for (int e = P.row_ptr[i]; e < P.row_ptr[i + 1]; ++e) {
      const std::size_t j = at(P.col[at(e)]);
      if (target[j]) {
        s.B(u, target[j] - 1) += P.val[at(e)];
        continue;
      }
      const int v = s.unknown[j];
      if (v < 0) continue;
      if (!diag && v >= u) {
        diag = true;
        if (v > u) a_col.push_back(u), a_val.push_back(1.0);
        else {
          a_col.push_back(u), a_val.push_back(1.0 - P.val[at(e)]);
          continue;
        }
      }
      a_col.push_back(v), a_val.push_back(-P.val[at(e)]);
    }
    if (!diag) a_col.push_back(u), a_val.push_back(1.0);
    a_ptr.push_back(static_cast<int>(a_col.size()));
  }
  s.A = Eigen::Map<const RowMat>(s.m, s.m, static_cast<int>(a_col.size()), a_ptr.data(), a_col.data(), a_val.data());
  return s;
}

// Target k's absorption probabilities spread over the boxes: the Lebesgue measure it absorbs, and the boxes where
// it is the most probable target so far.
double spread_target(std::uint32_t k, const Eigen::VectorXd& h, const AbsorptionSystem& s,
                     const std::vector<std::uint32_t>& target, const std::vector<double>& mu, Basins& out) {
  double fraction = 0;
  for (std::size_t i = 0; i < target.size(); ++i) {
    const double p =
        target[i] ? (target[i] == k ? 1.0 : 0.0) : (s.unknown[i] >= 0 ? std::clamp(h(s.unknown[i]), 0.0, 1.0) : 0.0);
    fraction += mu[i] * p;
    if (!target[i] && p > out.basin_probability[i]) out.basin_probability[i] = p, out.basin_of_box[i] = k;
  }
  return fraction;
}

// BiCGSTAB's diagonal preconditioner, polling the run's cancellation token at each application (twice per BiCGSTAB
// iteration, outside Eigen's parallel products): the same numbers as Eigen::DiagonalPreconditioner, and the
// iteration (up to 20000 sparse products) stops within one iteration of a request.
struct CancellableDiagonal : Eigen::DiagonalPreconditioner<double> {
  const core::CancelToken* cancel = nullptr;
  template <class Rhs> auto solve(const Eigen::MatrixBase<Rhs>& b) const {
    core::check_cancel(cancel);
    return Eigen::DiagonalPreconditioner<double>::solve(b);
  }
};

}  // namespace

Basins absorb(const UlamMatrix& P, BasinTargets targets, const std::vector<double>& mu,
              const core::CancelToken* cancel) {
  Basins out;
  out.basins = std::move(targets.basins);
  if (out.basins.empty()) return out;
  const std::vector<std::uint32_t>& target = targets.of_box;
  const AbsorptionSystem s = absorption_system(P, target, reaching_boxes(P, target), out.basins.size());
  out.basin_of_box.assign(target.size(), 0);
  out.basin_probability.assign(target.size(), 0);
  for (std::size_t i = 0; i < target.size(); ++i)
    if (target[i]) out.basin_of_box[i] = target[i], out.basin_probability[i] = 1;
  Eigen::BiCGSTAB<RowMat, CancellableDiagonal> solver;  // diagonal preconditioner
  solver.preconditioner().cancel = cancel;
  // 1e-12 relative residual: the fractions are reported to 1e-6 and the absorption probabilities lie in [0, 1].
  solver.setTolerance(1e-12);
  solver.setMaxIterations(20000);
  if (s.m > 0) solver.compute(s.A);
  double absorbed = 0;
  for (std::size_t k = 0; k < out.basins.size(); ++k) {
    Eigen::VectorXd h = Eigen::VectorXd::Zero(s.m);
    if (s.m > 0) {
      h = solver.solve(s.B.col(static_cast<long>(k)));
      out.iterations += solver.iterations();
      out.residual = std::max(out.residual, solver.error());
    }
    out.basins[k].fraction = spread_target(static_cast<std::uint32_t>(k + 1), h, s, target, mu, out);
    absorbed += out.basins[k].fraction;
  }
  out.unabsorbed = 1 - absorbed;
  return out;
}

}  // namespace btob::transfer
