// `btob bifurcation`: tails of theta or phi against r (Figures 4.1-4.7, 6.1-6.8) as a density image.
#include "cli/app.hpp"
#include "cli/common.hpp"
#include "core/map.hpp"
#include "core/scalar.hpp"
#include "io/io.hpp"
#include "iterate/kernel.hpp"
#include "iterate/recorders.hpp"
#include "reference/reference.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <numbers>

namespace btob::cli {
namespace {

struct BifurcationArgs {
  double r_min = 0.0717, r_max = 0.1717;
  long r_count = 5000, iterations = 5000, tail = 100;
  std::string coord = "theta";
  bool log = false;
  std::string grid = "paper";
  std::uint64_t seed = 1;
  int threads = 0;
  std::string precision = "double";
  std::string out = "results/bifurcation";
  std::string name = "bifurcation";
  std::string title;
  long bins = 800;
  std::vector<double> range;   // lo, hi of the coordinate axis (log10 units with --log)
  std::vector<double> vlines;  // r values drawn as vertical lines
  std::vector<std::string> overlays;
  std::string algorithm = "linear";
  bool raw = false, no_plot = false, quiet = false;
};

template <class T>
void run_kernel(const iterate::Ensemble& ens, long iterations, iterate::DensityRecorder& dens,
                iterate::TailRecorder* raw, const iterate::RunOptions& opt) {
  if (raw) {
    iterate::Both<iterate::DensityRecorder, iterate::TailRecorder> both(dens, *raw);
    iterate::run<T>(ens, iterations, both, opt);
  } else {
    iterate::run<T>(ens, iterations, dens, opt);
  }
}

void bifurcation(const BifurcationArgs& a, const std::string& command_line) {
  using namespace btob::iterate;
  const auto t0 = std::chrono::steady_clock::now();
  // Validation at the edge: every error names the flag and the accepted range.
  if (a.iterations < 1) throw UsageError(fmt::format("iterations: got {}, expected at least 1", a.iterations));
  if (a.tail < 1 || a.tail > a.iterations)
    throw UsageError(fmt::format("tail: got {}, expected 1 <= tail <= iterations = {}", a.tail, a.iterations));
  if (a.bins < 1 || a.bins > 100000) throw UsageError(fmt::format("bins: got {}, expected 1..100000", a.bins));
  if (a.threads < 0) throw UsageError(fmt::format("threads: got {}, expected at least 1", a.threads));
  const core::Precision prec = core::parse_precision(a.precision, "precision");
  Coord coord = parse_coord(a.coord, "coord");
  if (a.log) {
    if (coord != Coord::theta) throw UsageError(fmt::format("log: got --log with coord {}, --log applies to theta", a.coord));
    coord = Coord::log10_theta;
  }
  double lo = 0, hi = std::numbers::pi / 2;
  if (coord == Coord::phi) hi = std::numbers::pi;
  if (coord == Coord::log10_theta) lo = -16, hi = 0.25;
  if (coord == Coord::w1) lo = -4, hi = 4;
  if (coord == Coord::w2) lo = -1, hi = 1;
  if (!a.range.empty()) {
    if (a.range.size() != 2 || !(a.range[0] < a.range[1]))
      throw UsageError(fmt::format("range: expected two numbers lo hi with lo < hi"));
    lo = a.range[0];
    hi = a.range[1];
  }
  if (a.algorithm != "linear" && a.algorithm != "trig")
    throw UsageError(fmt::format("algorithm: got '{}', expected linear (Theorem 3.3) or trig (Appendix A.1)", a.algorithm));
  if (a.algorithm == "trig" && (a.raw || (prec.kind != core::Precision::Kind::f64 && prec.kind != core::Precision::Kind::f80)))
    throw UsageError("algorithm: trig runs in double or long-double and keeps no raw tails");
  for (double v : a.vlines)
    if (!std::isfinite(v)) throw UsageError("vline: expected finite r values");

  Ensemble ens;
  ens.r = linspace_r(a.r_min, a.r_max, a.r_count);
  ens.initial = parse_grid(a.grid, a.seed, "grid");
  ens.grid_description = a.grid;
  ens.seed = a.seed;
  checked_bytes(ens.orbits(), 64, "r-count x grid");
  const std::vector<double> overlay_lines = overlay_values(a.overlays, a.r_min, a.r_max);

  const io::fs::path out(a.out);
  io::ensure_dir(out);
  io::Progress progress(fmt::format("bifurcation {}", a.name));
  RunOptions opt;
  std::size_t degenerate = 0;
  opt.degenerate = &degenerate;
  opt.threads = a.threads;
  opt.progress = a.quiet ? nullptr : &progress_adapter(progress);
  const int threads = a.threads > 0 ? a.threads : omp_get_max_threads();
  DensityRecorder dens(coord, ens, a.iterations, a.tail, static_cast<std::size_t>(a.bins), lo, hi, threads);
  std::unique_ptr<TailRecorder> raw;
  if (a.raw) raw = std::make_unique<TailRecorder>(coord, ens.orbits(), a.iterations, a.tail);

  const auto t1 = std::chrono::steady_clock::now();
  std::vector<std::uint64_t> broken(ens.r.size(), 0);  // trig algorithm: orbits that broke down, per r
  // trig: also what the paper's MATLAB code draws (complex continuation past acos's domain, Figure 4.7).
  reference::MatlabTrigImage matlab;
  if (a.algorithm == "trig") {
    broken = prec.kind == core::Precision::Kind::f80
                 ? reference::trig_density<long double>(ens, a.iterations, dens, threads)
                 : reference::trig_density<double>(ens, a.iterations, dens, threads);
    // Re acos lies in [0, pi]: the whole range, so that nothing MATLAB would draw falls outside.
    matlab = reference::trig_density_matlab(ens, a.iterations, a.tail, coord == Coord::phi, a.bins, 0.0,
                                            std::numbers::pi, threads);
  } else {
    switch (prec.kind) {
      case core::Precision::Kind::f32: run_kernel<float>(ens, a.iterations, dens, raw.get(), opt); break;
      case core::Precision::Kind::f80: run_kernel<long double>(ens, a.iterations, dens, raw.get(), opt); break;
      case core::Precision::Kind::f128: run_kernel<core::float128>(ens, a.iterations, dens, raw.get(), opt); break;
      case core::Precision::Kind::mpfr:
        core::mpfr_float::default_precision(static_cast<unsigned>(prec.mpfr_digits));
        run_kernel<core::mpfr_float>(ens, a.iterations, dens, raw.get(), opt);
        break;
      default: run_kernel<double>(ens, a.iterations, dens, raw.get(), opt); break;
    }
  }
  const auto t2 = std::chrono::steady_clock::now();
  const std::vector<std::uint32_t> img = dens.merge();

  io::Attrs attrs = io::provenance(command_line);
  attrs["kind"] = std::string("bifurcation");
  attrs["name"] = a.name;
  attrs["title"] = a.title;
  attrs["r_min"] = a.r_min;
  attrs["r_max"] = a.r_max;
  attrs["r_count"] = a.r_count;
  attrs["grid"] = a.grid;
  attrs["initial_conditions"] = static_cast<long>(ens.initial.size());
  attrs["seed"] = static_cast<long>(a.seed);
  attrs["iterations"] = a.iterations;
  attrs["tail"] = a.tail;
  attrs["coord"] = std::string(coord_name(coord));
  attrs["range_lo"] = lo;
  attrs["range_hi"] = hi;
  attrs["bins"] = a.bins;
  attrs["scalar_type"] = prec.name();
  attrs["algorithm"] = a.algorithm;
  attrs["threads"] = static_cast<long>(threads);
  {
    long k = 0;
    switch (prec.kind) {
      case core::Precision::Kind::f32: k = renormalisation_interval<float>(ens.r); break;
      case core::Precision::Kind::f80: k = renormalisation_interval<long double>(ens.r); break;
      case core::Precision::Kind::f128: k = renormalisation_interval<core::float128>(ens.r); break;
      case core::Precision::Kind::mpfr: k = renormalisation_interval<core::mpfr_float>(ens.r); break;
      default: k = renormalisation_interval<double>(ens.r); break;
    }
    attrs["renormalisation_interval"] = a.algorithm == "trig" ? 0L : k;  // trig normalises every collision
  }
  // Tail values outside the range.  On a log scale -inf means theta underflowed to 0: the small component of
  // the state fell below the precision's smallest number (float near 7-4*sqrt(3), Figures 4.3-4.6); the
  // diagram then lacks those points, which the user must be told.
  std::uint64_t under = 0, over = 0;
  for (auto v : dens.under) under += v;
  for (auto v : dens.over) over += v;
  const double tail_points = static_cast<double>(ens.orbits()) * static_cast<double>(a.tail);
  attrs["points_below_range"] = static_cast<long>(under);
  attrs["points_above_range"] = static_cast<long>(over);
  if (under + over > 0 && static_cast<double>(under + over) > 1e-3 * tail_points)
    std::cerr << fmt::format("btob: warning: {:.1f}% of the tail points fall outside [{}, {}] ({} below, {} above){}\n",
                             100.0 * static_cast<double>(under + over) / tail_points, lo, hi, under, over,
                             a.log && prec.kind == core::Precision::Kind::f32
                                 ? "; in float, theta underflows to 0 where double still resolves it: use double"
                                 : "; widen --range to see them");
  attrs["degenerate_orbits"] = static_cast<long>(degenerate);
  if (degenerate > 0)
    std::cerr << fmt::format("btob: warning: {} of {} orbits ended in a non-finite or zero state in {}: this precision "
                             "cannot cope at these r; use double or wider\n",
                             degenerate, ens.orbits(), prec.name());
  attrs["iteration_seconds"] = std::chrono::duration<double>(t2 - t1).count();

  const io::fs::path h5 = out / (a.name + ".h5");
  {
    io::H5Writer w(h5);
    w.attrs(attrs);
    w.dataset("density", img, {ens.r.size(), static_cast<std::size_t>(a.bins)});
    w.dataset("r", ens.r, {ens.r.size()});
    w.dataset("underflow", dens.under, {ens.r.size()});
    w.dataset("overflow", dens.over, {ens.r.size()});
    w.dataset("vlines", a.vlines, {a.vlines.size()});
    w.dataset("broken", broken, {broken.size()});
    w.dataset("overlay_lines", overlay_lines, {overlay_lines.size() / 2, 2});
    if (!matlab.counts.empty()) {
      w.dataset("density_matlab", matlab.counts, {ens.r.size(), static_cast<std::size_t>(a.bins)});
      w.dataset("complex_orbits", matlab.complex_orbits, {matlab.complex_orbits.size()});
      w.dataset("nan_points_matlab", matlab.nan_points, {matlab.nan_points.size()});
      w.dataset("outside_matlab", matlab.outside, {matlab.outside.size()});
      w.dataset("stalled_matlab", matlab.stalled, {matlab.stalled.size()});
    }
    if (raw) w.dataset("tail", raw->out, {ens.r.size(), ens.initial.size(), static_cast<std::size_t>(a.tail)});
    w.commit();
  }
  const auto t3 = std::chrono::steady_clock::now();
  attrs["total_seconds"] = std::chrono::duration<double>(t3 - t0).count();
  io::write_manifest(out / (a.name + ".json"), attrs);
  if (!a.quiet)
    std::cerr << fmt::format("btob: {} orbits x {} iterations = {:.3g} map iterations in {:.3f} s ({:.3g} it/s, {} threads); "
                             "wrote {}\n",
                             ens.orbits(), a.iterations, static_cast<double>(ens.orbits()) * a.iterations,
                             std::chrono::duration<double>(t2 - t1).count(),
                             static_cast<double>(ens.orbits()) * a.iterations / std::chrono::duration<double>(t2 - t1).count(),
                             threads, h5.string());
  if (!a.no_plot) io::run_plot("bifurcation.py", {h5.string(), (out / (a.name + ".png")).string()});
}

Register reg([](CLI::App& app) {
  auto a = std::make_shared<BifurcationArgs>();
  CLI::App* c = app.add_subcommand("bifurcation", "Tails of theta or phi against r, as a density image (Figures 4.x, 6.x)");
  c->add_option("--r-min", a->r_min, "smallest r, in (0,1)")->capture_default_str();
  c->add_option("--r-max", a->r_max, "largest r, in (0,1)")->capture_default_str();
  c->add_option("--r-count", a->r_count, "number of evenly spaced r values")->capture_default_str();
  c->add_option("--iterations", a->iterations, "map iterations per orbit")->capture_default_str();
  c->add_option("--tail", a->tail, "last iterations kept per orbit")->capture_default_str();
  c->add_option("--coord", a->coord, "theta, phi, w1 or w2")->capture_default_str();
  c->add_flag("--log", a->log, "log10 scale for theta");
  c->add_option("--grid", a->grid, "initial conditions: paper, strip:NxM[:w1min:w1max], random:N, or x,y,z;...")
      ->capture_default_str();
  c->add_option("--seed", a->seed, "seed of random grids")->capture_default_str();
  c->add_option("--threads", a->threads, "OpenMP threads (default: all cores)");
  c->add_option("--precision", a->precision, "float, double, long-double, float128 or mpfr:<digits> (10..10000)")
      ->capture_default_str();
  c->add_option("--out", a->out, "output directory")->capture_default_str();
  c->add_option("--name", a->name, "file stem of the outputs")->capture_default_str();
  c->add_option("--title", a->title, "figure title (r range, grid and iterations are added)");
  c->add_option("--bins", a->bins, "bins of the coordinate axis")->capture_default_str();
  c->add_option("--range", a->range, "lo hi of the coordinate axis (log10 units with --log)")->expected(2);
  c->add_option("--vline", a->vlines, "r values drawn as vertical lines")->expected(1, -1);
  c->add_option("--overlay", a->overlays, "named overlays: " + overlay_names())->expected(1, -1);
  c->add_option("--algorithm", a->algorithm, "linear (Theorem 3.3, batched kernel) or trig (Appendix A.1, per collision)")
      ->capture_default_str();
  c->add_flag("--raw", a->raw, "also store the raw tails in the HDF5 file");
  c->add_flag("--no-plot", a->no_plot, "write data only");
  c->add_flag("--quiet", a->quiet, "no progress or summary on stderr");
  c->callback([a, c] { bifurcation(*a, command_line_of(c)); });
});

}  // namespace
}  // namespace btob::cli
