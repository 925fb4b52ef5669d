// SPDX-License-Identifier: GPL-3.0-or-later
// Attractors of P_r-hat (Section 8.1 (1)): per-orbit classification, attractor identity, basins over grids
// with frequencies and confidence intervals, basin fractions across r (Table 6.1 with many orbits).
#pragma once

#include "attractors/boundary.hpp"
#include "core/grid.hpp"
#include "core/map.hpp"
#include "iterate/ensemble.hpp"
#include "iterate/kernel.hpp"
#include "patterns/patterns.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace btob::attractors {

using core::Vec3;

// Conventions.
//  * Iterations are map iterations of P_r (one symbol 1, 2 or 3 each).  Points are unit vectors in
//    Q = {x >= 0, z <= 0}; strip coordinates (w1, w2) are those of eq. (6.4).
//  * Pass 1 (every orbit, batched kernel, no tangent): `transient` steps, then a window of `window`
//    steps in which the return to the window's first point (period <= max_period), the symbols and
//    the counts of symbols 1 / 3 are recorded.  Pass 2 (orbits without a period): Lyapunov exponent
//    lambda1 (the fused cocycle kernel, batch means) and, for the orbits whose lambda1 is zero within its bar,
//    from a plain run of the same orbits, the weighted Birkhoff rotation number about the P2
//    centre (1, 0, -1) with the P2 invariant I (attractors/recorders.hpp).  Refinement: orbits
//    still undecided are continued from where they stopped with `refine_factor` times the transient.
//  * Types: periodic (a stable periodic orbit, the pattern tool's verdict attached), collapse
//    (three-particle collapse, z -> 0 with symbol 1 or x -> 0 with symbol 3; r <= 7 - 4 sqrt(3)),
//    quasi-periodic (lambda1 = 0 within its error bar and a converged rotation number), chaotic
//    (lambda1 > 0 beyond its error bar), undecided (the budget ran out; `detail` says why).

enum class Type : std::uint8_t { undecided = 0, collapse = 1, periodic = 2, quasi_periodic = 3, chaotic = 4 };
const char* type_name(Type t);

struct Options {
  long transient = 5000;  // steps before the window (paper: 5000 iterations), >= 1
  long window = 1000;     // window of pass 1, >= max_period
  int max_period = 256;   // longest period searched (132^67312^67 has 138 symbols), 1 .. 1024
  // Return tolerance on unit vectors (max norm): a stable orbit contracts by e^(lambda2 p) per period, so
  // after the transient its returns are ~1e-15; quasi-periodic orbits do not return closer than ~1e-6
  // within 256 steps at the grid sizes we use.  In (0, 1e-3].
  double return_tol = 1e-9;
  // A periodic point must lie within this distance (max norm, unit vectors) of the pattern tool's exact
  // periodic point: it confirms that the numerical cycle is the stable orbit of its word.  In (0, 1e-2].
  double point_tol = 1e-7;
  // theta (or pi/2 - theta) below this at the end of the window, with symbol 1 (3) throughout, is a
  // three-particle collapse (theta shrinks geometrically, like (r^2 / lambda_P1)^n).  In (0, 0.1].
  double collapse_theta = 1e-6;
  long lyap_transient = 500;    // pass 2: steps aligning the tangent vector before averaging, >= 1
  long lyap_iterations = 4000;  // pass 2: averaged steps (also the Birkhoff window), >= 10 * lyap_blocks
  int lyap_blocks = 10;         // batch-means blocks, 2 .. 1000
  // |rotation(full record) - rotation(first half)| below this (turns) counts as converged: the weighted
  // average converges faster than any power of 1/n on a smooth invariant curve (Das-Yorke), to ~1e-10
  // at n = 4000; chaotic orbits differ by ~1e-2.  In (0, 0.1].
  double rotation_tol = 1e-6;
  int refine_factor = 10;   // refinement pass: transient multiplied by this for undecided orbits, 0 = off, <= 1000
  iterate::RunOptions run;  // threads (results never depend on them), progress
};
// Throws std::invalid_argument "field: got X, expected Y" naming the option.
void validate(const Options& opt);

// The verdict on one orbit, with its evidence.
struct OrbitVerdict {
  Type type = Type::undecided;
  int period = 0;          // in map iterations (periodic; 1 for collapse)
  patterns::Word word;     // periodic: the symbols of one period from the window's first point
  std::string key;         // attractor identity key (see attractor_key)
  double residual = 0;     // periodic: return distance |u_p - u_0|; else the closest return up to max_period
  int closest_return = 0;  // j of that closest return
  // pass 2: lambda1 and err1 its batch-means standard error (lyapunov's method, floored at 4 eps max(1, |lambda1|));
  // periodic / collapse: the exact exponent log|l2/l1|/p in double, err1 that floor (its rounding)
  double lambda1 = 0, err1 = 0;
  // Pass 2, for the orbits they decide (lambda1 zero within its bar, r > 3 - 2 sqrt(2)); 0 for the others:
  double rotation = 0, rotation_delta = 0;     // turns per iteration, and |full - half| of the weighted averages
  double invariant = 0, invariant_spread = 0;  // weighted mean of I and (max - min) / mean over the record
  bool p2_region = false;                      // no symbol 1 or 3 in the window (an orbit of the P2 parallelogram)
  long iterations = 0;                         // map iterations spent on this orbit
  Vec3<double> point;                          // a point on the attractor (the window's first point, unit, in Q)
  std::string detail;                          // why undecided, or extra evidence
  template <class A> void members(A& a) {      // core/pack.hpp
    a(type, period, word.s, key, residual, closest_return, lambda1, err1, rotation, rotation_delta, invariant,
      invariant_spread, p2_region, iterations, point, detail);
  }
};

// Identity of the attractor an orbit reached, as a string key that sorts deterministically:
//   "C1" / "C3"  collapse on z = 0 / x = 0;   "P<digits>"  periodic, word rotated to its smallest rotation
//   (order 1 < 3 < 2; J-mirrors are different attractors);   "Q2" quasi-periodic invariant curves of the P2
//   parallelogram (a continuum: one family);   "Q" other quasi-periodic;   "X" chaotic;   "" undecided.
std::string attractor_key(const OrbitVerdict& v);
// Same attractor at r: same key and, for periodic orbits, b's point lies on a's cycle (within point_tol);
// for quasi-periodic curves, same rotation number (turns) and same invariant I (relative), within `curve_tol`.
bool same_attractor(const OrbitVerdict& a, const OrbitVerdict& b, double r, double point_tol = 1e-7,
                    double curve_tol = 1e-6);

// Classifies every orbit of a one-r ensemble (ens.r.size() == 1), in ensemble order.
std::vector<OrbitVerdict> classify(const iterate::Ensemble& ens, const Options& opt);
// One orbit (the batched path with one lane).
OrbitVerdict classify_point(const Vec3<double>& u0, double r, const Options& opt);

// An attractor found at one r.
struct Attractor {
  int id = 0;  // 1-based, by sorted key (0 is reserved for undecided points)
  Type type = Type::undecided;
  std::string key;
  std::string pattern;    // paper notation (132^3312^3; 312^2 for the J-mirror of 132^2; "1" / "3" collapse)
  std::string canonical;  // patterns::canonical in paper notation (mirrors share it)
  int period = 0;
  int collisions = 0;     // letters a, b, c per period (Table 6.1's last column)
  std::string letters;    // collision letters from the exact periodic point (acb / cab resolved)
  std::string stability;  // periodic: the pattern tool's outcome at r, and its reason if not stable
  double lyapunov2 = 0;   // periodic: the pattern tool's projective exponent log|l2/l1|/p
  Vec3<double> point;     // representative: the exact periodic point (periodic) or the point of the
                          // lowest-index orbit of the basin
  std::size_t count = 0;  // basin size (orbits)
  double rotation_min = 0, rotation_max = 0, invariant_min = 0, invariant_max = 0;  // quasi-periodic ranges
  template <class A> void members(A& a) {                                           // core/pack.hpp
    a(id, type, key, pattern, canonical, period, collisions, letters, stability, lyapunov2, point, count, rotation_min,
      rotation_max, invariant_min, invariant_max);
  }
};

// Attractors of a set of verdicts: one per key, ids by sorted key, counts; `labels` (same order as the
// verdicts) gets the ids (0: undecided).  Periodic keys are checked against patterns::analyse at r.
std::vector<Attractor> collect(const std::vector<OrbitVerdict>& v, double r, std::vector<std::uint32_t>* labels);

// A binomial proportion with its two-sided 95% Clopper-Pearson interval (boost::math::binomial_distribution).
struct Fraction {
  double value = 0, low = 0, high = 0;
  template <class A> void members(A& a) { a(value, low, high); }
};
Fraction fraction(std::size_t successes, std::size_t trials, double confidence = 0.95);

// A grid of initial conditions (core/grid.hpp), cell centres shifted by (du, dv) cells (|du|, |dv| <= 1/2; replicate
// grids):
//   "sphere:NxM"  theta in [0, pi/2] x y in [-1, 1] (the equal-area chart, core::from_height): every cell holds the
//                 same solid angle, so a fraction of the points is a fraction of the uniform measure on the sphere
//                 of directions restricted to the domain (the quarter-sphere Q, solid angle pi);
//   "strip:NxM"   w1 in [w1_min, w1_max] x w2 in [-1, 1]: Lebesgue measure on that rectangle of the plane x - z = 1
//                 (its points are far from uniform on the sphere: a cell holds the solid angle dw1 dw2 / (2|u|^3));
//   "angles:NxM"  theta in [0, pi/2] x phi in [0, pi]: the measure dtheta dphi (the sphere's is sin(phi) dtheta dphi).
// parse_grid throws core::InvalidField naming `field` for an empty or malformed grid, "w1-range" for a bad range.
using Grid = core::Grid;
// The measure whose fractions a grid's counts estimate, in words (every output names it).
std::string measure_name(const Grid& g);
// The share of the sphere measure of the domain (uniform on the directions of Q) that the grid's region holds: 1 for
// sphere and angles grids (they cover Q), for a strip w1 in [a, b] (2/pi) (F(b) - F(a)), F(w) = asin(w/sqrt(1+2w^2))
// (the integral over theta of the height interval |y| <= w c/sqrt(1+w^2c^2), c = cos(theta) + sin(theta)).
double sphere_share(const Grid& g);
// The same share for a strip w1 in [a, b] x w2 in [-1, 1], and that strip's measure in words.
double strip_sphere_share(double a, double b);
std::string strip_measure_name(double a, double b);
Grid parse_grid(const std::string& spec, double w1_min, double w1_max, const char* field = "grid");
std::vector<Vec3<double>> grid_points(const Grid& g, double du = 0, double dv = 0);

// Basins at one r over a grid and K replicate grids shifted by seeded random fractions of a cell.
struct Basins {
  double r = 0;
  Grid grid;
  std::vector<Attractor> attractors;  // union over the main grid and the replicates, ids by key
  std::vector<std::uint32_t> labels;  // main grid, index i2 * n1 + i1 (row-major, w2 rows)
  std::vector<Fraction> fractions;    // per attractor (main grid); undecided last
  Fraction undecided;
  std::vector<std::vector<double>> replicate_fractions;  // [attractor][replicate]; undecided appended last
  std::size_t undecided_first_pass = 0;                  // before refinement
  long iterations_total = 0;  // map iterations of the grids' orbits (all passes, all grids; not the
                              // early exit's probe and checks)
  std::size_t certified = 0;  // orbits decided early (all grids): see basin_rows
  // Basin entropies on boxes of entropy_box cells (main and replicate grids), the uncertainty exponent and the Wada
  // test of the main grid (attractors/boundary.hpp).
  BoundaryGeometry boundary;
  double seconds = 0;
};
Basins basins(double r, const Grid& g, int replicates, std::uint64_t seed, const Options& opt, int entropy_box = 5);

// Early exit (basins only; classify() always runs the full length).  An orbit whose state at a checkpoint
// t < transient lies in a trapping cone of a stable cycle (a cone around the cycle's point, in the eigenvector
// coordinates of its monodromy, on which every branch of the word holds with margin and which the monodromy maps
// into itself) or on a P2 invariant ellipse inside the P2 region is given the verdict the full-length
// classification would give (periodic with the cycle's key; quasi-periodic "Q2"), with bounds that prove the
// full-length tests pass (return within return_tol at step `transient`, point within point_tol, for Q2: no return,
// |lambda1| below its bar, a converged rotation number).  The stable cycles are those that a fixed 16 x 16 sphere
// probe finds at r.  The values the table prints come from full-length verdicts: merge_basins classifies the first
// orbit of a non-periodic attractor when it was decided early, and the early Q2 orbits of smallest and largest I.
// As a check, per chunk of rows the first orbit decided early for each attractor is classified at full length too;
// a disagreement throws std::logic_error.
// The same in parts (core/sweep.hpp): item k * n2 + j is row j (w2 or phi) of grid k (0: the main grid, then the
// replicates).  A row's verdicts depend on the request and the row only: the replicate shifts are drawn for the
// whole request, then the grids are sliced.  basins() = merge_basins(..., {basin_rows(every item)}).
std::size_t basin_items(const Grid& g, int replicates);
// One attractor (type, key) as a part of a basin run saw it: what merging needs, without per-orbit verdicts.
// An orbit decided early whose full-length values the merged result needs: its start, index and invariant I at
// the checkpoint (index = npos: none).
struct Pending {
  Vec3<double> start = Vec3<double>::Zero();
  std::size_t index = static_cast<std::size_t>(-1);
  double I = 0;
  template <class A> void members(A& a) { a(start, index, I); }
};
struct BasinClass {
  OrbitVerdict first;              // the verdict of its lowest-index orbit (evidence text dropped)
  std::size_t first_index = 0;     // that orbit's index k n + i2 n1 + i1 over all grids
  std::vector<std::size_t> count;  // orbits per grid (main, then the replicates)
  // Over its orbits classified at full length (empty, min > max, when there were none).
  double rotation_min = 0, rotation_max = 0, invariant_min = 0, invariant_max = 0;
  // Decided early (non-periodic classes): the first orbit when it was, and the orbits of smallest and largest I;
  // merge_basins classifies them at full length (a periodic key's values are its own: rotation and invariant 0,
  // the exact cycle's point).
  Pending first_pending, lo, hi;
  template <class A> void members(A& a) {
    a(first, first_index, count, rotation_min, rotation_max, invariant_min, invariant_max, first_pending, lo, hi);
  }
};
// No rows(): the labels are numbered by the part's own classes (merge_basins renumbers them), and the boundary
// geometry reads them across neighbouring grid rows on rank 0, so they are gathered.
struct BasinRows {
  std::vector<std::size_t> items;        // ascending
  std::vector<std::uint32_t> labels;     // n1 per item, in item order: 1 + class, 0 undecided
  std::vector<BasinClass> classes;       // the attractors its orbits reached
  std::vector<std::size_t> undecided;    // undecided orbits per grid
  std::size_t undecided_first_pass = 0;  // main grid: undecided after the first pass (before refinement)
  long iterations = 0;                   // map iterations spent (all passes, all its grids)
  std::size_t certified = 0;             // orbits decided before the full length (early exit), all its grids
  double seconds = 0;
  int threads = 0;  // threads the part ran on (reported, not computed with)
  template <class A> void members(A& a) {
    a(items, labels, classes, undecided, undecided_first_pass, iterations, certified, seconds, threads);
  }
};
BasinRows basin_rows(double r, const Grid& g, int replicates, std::uint64_t seed, const Options& opt,
                     const std::vector<std::size_t>& items);
Basins merge_basins(double r, const Grid& g, int replicates, const Options& opt, std::vector<BasinRows> parts,
                    int entropy_box = 5);

}  // namespace btob::attractors
