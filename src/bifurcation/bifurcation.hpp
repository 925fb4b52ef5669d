// SPDX-License-Identifier: GPL-3.0-or-later
// Bifurcation diagrams (Figures 4.1-4.7 and 6.1-6.8 of the paper): the tails of theta, log10 theta, phi, w1 or w2
// of every orbit of an ensemble (r values x initial conditions), binned on the fly into a density image, with the
// points outside the range and the orbits the precision could not follow counted, never dropped silently.
#pragma once

#include "core/request.hpp"
#include "core/result.hpp"
#include "core/sweep.hpp"
#include "iterate/ensemble.hpp"
#include "reference/reference.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace btob::bifurcation {

struct Request {
  core::Decimal r_min = 0.0717, r_max = 0.1717;  // r range, each in (0, 1), kept as given (read in the precision)
  long r_count = 5000;                           // evenly spaced r values
  long iterations = 5000;                        // map iterations per orbit
  long tail = 100;                               // last iterations binned per orbit, 1..iterations
  std::string coord = "theta";                   // theta, phi, w1 or w2 (radians for the angles)
  bool log = false;                              // log10 theta
  std::string grid = "paper";                    // paper, strip:NxM[:w1min:w1max], random:N, or x,y,z;...
  std::uint64_t seed = 1;                        // seed of random grids
  std::string precision = "double";              // float, double, long-double, float128 or mpfr:D
  long bins = 800;                               // bins of the coordinate axis, 1..100000
  std::vector<double> range;         // lo hi of the coordinate axis (log10 units with log); default per coord
  std::vector<double> vline;         // r values drawn as vertical lines (presentation)
  std::vector<std::string> overlay;  // named overlays (presentation; the command line resolves them)
  std::string algorithm = "linear";  // linear (Theorem 3.3, batched kernel) or trig (Appendix A.1)
  bool raw = false;                  // also keep the raw tails (r x initial condition x tail)
  // Also classify every orbit (`btob classify` with transient iterations - tail, iterations tail, in double): what
  // extras::of adds after the run (src/extras), so the diagram's run and its speed are the same without it.
  bool attractors = false;

  void validate() const;
  std::size_t work_items() const { return static_cast<std::size_t>(r_count); }  // a sweep over r (core/sweep.hpp)
  double map_steps() const;  // r values x initial conditions x iterations (core::StepCounted)
  template <class V> void fields(V&& v) {
    v("r-min", r_min, "smallest r, in (0,1)");
    v("r-max", r_max, "largest r, in (0,1)");
    v("r-count", r_count, "number of evenly spaced r values");
    v("iterations", iterations, "map iterations per orbit");
    v("tail", tail, "last iterations kept per orbit");
    v("coord", coord, "theta, phi, w1 or w2");
    v("log", log, "log10 scale for theta");
    v("grid", grid, "initial conditions: paper, strip:NxM[:w1min:w1max], random:N, or x,y,z;...");
    v("seed", seed, "seed of random grids");
    v("precision", precision, "float, double, long-double, float128 or mpfr:<digits> (10..10000)");
    v("bins", bins, "bins of the coordinate axis");
    v("range", range, "lo hi of the coordinate axis (log10 units with --log)");
    v("vline", vline, "r values drawn as vertical lines");
    v("overlay", overlay, "named overlays (thresholds, windows, stripes)");
    v("algorithm", algorithm, "linear (Theorem 3.3, batched kernel) or trig (Appendix A.1, per collision)");
    v("raw", raw, "also store the raw tails in the HDF5 file");
    v("attractors", attractors, "also record each orbit's attractor (classify over the tail)");
  }
};

struct Result {
  iterate::Ensemble ensemble;                      // the r values and initial conditions iterated (the orbits, r-major)
  double r_min = 0, r_max = 0;                     // the requested r range
  std::string coord;                               // the binned coordinate: theta, log10_theta, phi, w1, w2
  double lo = 0, hi = 0;                           // the axis range
  std::size_t bins = 0;                            // bins of the density along the coordinate
  std::vector<double> bin_centre;                  // [bins]: lo + (i + 1/2) (hi - lo) / bins, the density's coordinates
  std::vector<std::uint32_t> density;              // [r, bin]: tail points per bin
  std::vector<std::uint64_t> underflow, overflow;  // [r]: tail points below lo / above hi (or NaN)
  std::vector<std::uint64_t> broken;  // [r]: orbits the trigonometric algorithm lost (acos out of its domain)
  std::vector<double> tail;           // [r, initial condition, tail] when raw
  bool raw = false;                   // the request kept the raw tails (`tail` is described even when the MPI ranks
                                      // write its rows themselves and it is empty here)
  reference::MatlabTrigImage matlab;  // trig only: what the paper's MATLAB code draws (complex continuation past
                                      // acos's domain, Figure 4.7), over [0, pi]
  std::vector<double> vlines;         // the request's vertical lines
  std::string scalar_type,
      algorithm;  // the arithmetic that ran (float, double, ...) and the request's algorithm (linear or trig)
  long iterations = 0, tail_length = 0,
       renormalisation_interval =
           0;                    // map iterations per orbit, of them the tail binned, steps between renormalisations
  std::uint64_t degenerate = 0;  // orbits whose final state was not a finite non-zero vector
  double iteration_seconds = 0;  // wall time of the iteration (without plotting or writing), seconds

  std::uint64_t points_below() const;
  std::uint64_t points_above() const;
  void describe(core::Contents& c) const;
};

// Some of the r values (items, ascending indices into linspace(r-min, r-max, r-count)): their rows only.
struct Part {
  std::vector<std::size_t> items;
  std::vector<std::uint32_t> density;                      // [items, bins]
  std::vector<std::uint64_t> underflow, overflow, broken;  // [items]
  std::vector<double> tail;                                // [items, initial condition, tail] when raw
  reference::MatlabTrigImage matlab;                       // trig only: [items, bins] and [items]
  std::uint64_t degenerate = 0;
  double iteration_seconds = 0;
  template <class A> void members(A& a) {
    a(items, density, underflow, overflow, broken, tail, matlab.counts, matlab.complex_orbits, matlab.nan_points,
      matlab.outside, matlab.stalled, degenerate, iteration_seconds);
  }
  // The bulk, written by each MPI rank itself (core::HasRows): the density's rows and the raw tails (when kept).
  template <class A> void rows(A& a) {
    a("density", density);
    a("tail", tail);
  }
};
Part run_part(const Request& req, const std::vector<std::size_t>& items, const core::RunControl& control = {});
Result merge(const Request& req, std::vector<Part> parts);
// merge(req, {run_part(req, every item)}).
Result run(const Request& req, const core::RunControl& control = {});

}  // namespace btob::bifurcation
