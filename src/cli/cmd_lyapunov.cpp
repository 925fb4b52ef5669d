// `btob lyapunov` (one orbit), `btob lyapunov-map` (exponents over r x a grid), `btob lyapunov-strip` (one r, a
// strip grid drawn as an image): Lyapunov exponents of the projective derivative cocycle (Section 8.1 (3)).
#include "cli/app.hpp"
#include "cli/common.hpp"
#include "core/coords.hpp"
#include "core/map.hpp"
#include "core/scalar.hpp"
#include "io/io.hpp"
#include "iterate/ensemble.hpp"
#include "lyapunov/lyapunov.hpp"
#include "lyapunov/maps.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <omp.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <sstream>

namespace btob::cli {
namespace {

void check_r(double r, const char* field) {
  if (!(r > 0 && r < 1)) throw UsageError(fmt::format("{}: got {}, expected a value in the open interval (0, 1)", field, r));
}
void check_lengths(long iterations, long transient, int blocks) {
  if (iterations < 1) throw UsageError(fmt::format("iterations: got {}, expected at least 1", iterations));
  if (transient < 0) throw UsageError(fmt::format("transient: got {}, expected at least 0", transient));
  if (transient > iterations)
    throw UsageError(fmt::format("transient: got {}, expected at most iterations = {}", transient, iterations));
  if (blocks < 2 || blocks > iterations)
    throw UsageError(fmt::format("blocks: got {}, expected 2 <= blocks <= iterations = {}", blocks, iterations));
}

// ---- btob lyapunov ----
struct OrbitArgs {
  double r = 0;
  std::string point;
  long iterations = 100000, transient = 1000;
  int reorth = 1, blocks = 20;
  std::string precision = "double";
  std::string convergence;
  bool weighted = false;
};

core::Vec3<double> parse_point(const std::string& s) {
  std::vector<double> v;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) {
    try {
      std::size_t used = 0;
      v.push_back(std::stod(item, &used));
      if (used != item.size()) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw UsageError(fmt::format("point: got '{}', expected three numbers x,y,z", s));
    }
  }
  if (v.size() != 3) throw UsageError(fmt::format("point: got '{}', expected three numbers x,y,z", s));
  core::validate_point(v[0], v[1], v[2], "point");
  return {v[0], v[1], v[2]};
}

void lyapunov_orbit(const OrbitArgs& a) {
  check_r(a.r, "r");
  check_lengths(a.iterations, a.transient, a.blocks);
  if (a.reorth < 1) throw UsageError(fmt::format("reorthonormalise: got {}, expected at least 1", a.reorth));
  const core::Vec3<double> u = parse_point(a.point);
  lyapunov::Options o;
  o.iterations = a.iterations;
  o.transient = a.transient;
  o.reorthonormalise = a.reorth;
  o.blocks = a.blocks;
  // Every precision of the lab (issue 9); the orbit and the tangent frame are iterated in T, the sums of
  // log R_ii accumulated in long double and the exponents reported in double.
  const core::Precision prec = core::parse_precision(a.precision, "precision");
  const auto in = [&]<class T>(T*) {
    const core::Vec3<T> ut(T(u(0)), T(u(1)), T(u(2)));
    return lyapunov::projective_exponents<T>(ut, T(a.r), o);
  };
  lyapunov::ProjectiveResult res;
  switch (prec.kind) {
    case core::Precision::Kind::f32: res = in(static_cast<float*>(nullptr)); break;
    case core::Precision::Kind::f64: res = in(static_cast<double*>(nullptr)); break;
    case core::Precision::Kind::f80: res = in(static_cast<long double*>(nullptr)); break;
    case core::Precision::Kind::f128: res = in(static_cast<core::float128*>(nullptr)); break;
    case core::Precision::Kind::mpfr:
      core::mpfr_float::default_precision(static_cast<unsigned>(prec.mpfr_digits));
      res = in(static_cast<core::mpfr_float*>(nullptr));
      break;
  }
  if (a.weighted)  // weighted Birkhoff averages: super-polynomial on (quasi-)periodic orbits, no batch error
    std::cout << "lambda1_weighted,lambda2_weighted,lambda1,err1,lambda2,err2,iterations\n"
              << fmt::format("{:.15g},{:.15g},{:.12g},{:.3g},{:.12g},{:.3g},{}\n", res.weighted[0], res.weighted[1],
                             res.lambda[0].value, res.lambda[0].error, res.lambda[1].value, res.lambda[1].error,
                             res.iterations);
  else
    std::cout << "lambda1,err1,lambda2,err2,iterations\n"
              << fmt::format("{:.12g},{:.3g},{:.12g},{:.3g},{}\n", res.lambda[0].value, res.lambda[0].error,
                             res.lambda[1].value, res.lambda[1].error, res.iterations);
  if (!a.convergence.empty()) {
    std::string csv = "n,lambda1,lambda2\n";
    const auto& c = res.convergence;
    for (std::size_t j = 0; j < c.n.size(); ++j)
      csv += fmt::format("{},{:.12g},{:.12g}\n", c.n[j], c.exponents[0][j], c.exponents[1][j]);
    io::write_text_atomic(a.convergence, csv);
  }
}

// ---- btob lyapunov-map and lyapunov-strip ----
struct MapArgs {
  double r_min = 0.0717, r_max = 0.6;
  long r_count = 5000;
  double r = 0.3;                  // lyapunov-strip
  long strip_w1 = 200, strip_w2 = 100;  // lyapunov-strip
  double w1_min = -2, w1_max = 2;  // lyapunov-strip
  std::string grid = "paper";
  std::uint64_t seed = 1;
  long iterations = 10000, transient = 1000;
  int blocks = 10, threads = 0;
  std::string precision = "double";
  std::string out = "results/lyapunov";
  std::string name;
  std::string title;
  std::vector<std::string> overlays;  // lyapunov-map: named r overlays (default: thresholds, windows if built)
  bool no_plot = false, quiet = false;
};

lyapunov::MapOptions map_options(const MapArgs& a) {
  check_lengths(a.iterations, a.transient, a.blocks);
  if (a.threads < 0) throw UsageError(fmt::format("threads: got {}, expected at least 1", a.threads));
  lyapunov::MapOptions o;
  o.iterations = a.iterations;
  o.transient = a.transient;
  o.blocks = a.blocks;
  o.run.threads = a.threads;
  if (a.precision == "float") o.single_precision = true;
  else if (a.precision != "double")
    throw UsageError(fmt::format("precision: got '{}', expected float or double", a.precision));
  return o;
}

io::Attrs common_attrs(const MapArgs& a, const iterate::Ensemble& ens, const std::string& kind, double seconds) {
  io::Attrs at = io::provenance(invocation());
  at["kind"] = kind;
  at["name"] = a.name;
  at["title"] = a.title;
  at["grid"] = ens.grid_description;
  at["initial_conditions"] = static_cast<long>(ens.initial.size());
  at["seed"] = static_cast<long>(a.seed);
  at["iterations"] = a.iterations;
  at["transient"] = a.transient;
  at["blocks"] = static_cast<long>(a.blocks);
  at["error_estimate"] = fmt::format("batch means over {} blocks of the averaged steps", a.blocks);
  at["classification"] = std::string("positive if lambda1 > 3 err1 + 10/n, negative if < -(3 err1 + 10/n), else zero");
  at["scalar_type"] = a.precision;
  at["threads"] = static_cast<long>(a.threads > 0 ? a.threads : omp_get_max_threads());
  at["iteration_seconds"] = seconds;
  return at;
}

void lyapunov_map(MapArgs a) {
  if (a.name.empty()) a.name = "lyapunov_map";
  check_r(a.r_min, "r-min");
  check_r(a.r_max, "r-max");
  if (a.r_count < 1) throw UsageError(fmt::format("r-count: got {}, expected at least 1", a.r_count));
  lyapunov::MapOptions o = map_options(a);
  iterate::Ensemble ens;
  ens.r = iterate::linspace_r(a.r_min, a.r_max, a.r_count);
  ens.initial = iterate::parse_grid(a.grid, a.seed, "grid");
  ens.grid_description = a.grid;
  ens.seed = a.seed;
  const io::fs::path out(a.out);
  io::ensure_dir(out);
  io::Progress progress("lyapunov-map");
  if (!a.quiet) o.run.progress = &progress_adapter(progress);
  const auto t0 = std::chrono::steady_clock::now();
  const lyapunov::OrbitExponents e = lyapunov::map_exponents(ens, o);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::size_t R = ens.r.size(), I = ens.initial.size();
  const lyapunov::RSummary s = lyapunov::summarise(e, R, I);

  io::Attrs at = common_attrs(a, ens, "lyapunov-map", secs);
  at["r_min"] = a.r_min;
  at["r_max"] = a.r_max;
  at["r_count"] = a.r_count;
  std::vector<std::string> names = a.overlays;
  if (names.empty()) {
    names.push_back("thresholds");
    if (overlays().count("windows")) names.push_back("windows");
  }
  const std::vector<double> lines = overlay_values(names, a.r_min, a.r_max);
  at["overlays"] = fmt::format("{}", fmt::join(names, ","));
  const io::fs::path h5 = out / (a.name + ".h5");
  {
    io::H5Writer w(h5);
    w.attrs(at);
    w.dataset("r", ens.r, {R});
    w.dataset("overlay_lines", lines, {lines.size() / 2, 2});
    for (auto [n, v] : {std::pair{"lambda1", &e.lambda1}, {"err1", &e.err1}, {"lambda2", &e.lambda2}, {"err2", &e.err2},
                        {"chi1", &e.chi1}})
      w.dataset(n, *v, {R, I});
    for (auto [n, v] : {std::pair{"min", &s.min}, {"median", &s.median}, {"max", &s.max}, {"frac_positive", &s.frac_positive},
                        {"frac_zero", &s.frac_zero}, {"frac_negative", &s.frac_negative}})
      w.dataset(n, *v, {R});
    w.commit();
  }
  std::string csv = "r,lambda1_min,lambda1_median,lambda1_max,frac_positive,frac_zero,frac_negative\n";
  for (std::size_t i = 0; i < R; ++i)
    csv += fmt::format("{:.9f},{:.6g},{:.6g},{:.6g},{:.4f},{:.4f},{:.4f}\n", ens.r[i], s.min[i], s.median[i], s.max[i],
                       s.frac_positive[i], s.frac_zero[i], s.frac_negative[i]);
  io::write_text_atomic(out / (a.name + "_summary.csv"), csv);
  io::write_manifest(out / (a.name + ".json"), at);
  if (!a.quiet)
    std::cerr << fmt::format("btob: {} orbits x {} steps = {:.3g} map iterations with the tangent cocycle in {:.3f} s "
                             "({:.3g} it/s); wrote {}\n",
                             ens.orbits(), a.transient + a.iterations,
                             static_cast<double>(ens.orbits()) * static_cast<double>(a.transient + a.iterations), secs,
                             static_cast<double>(ens.orbits()) * static_cast<double>(a.transient + a.iterations) / secs,
                             h5.string());
  if (!a.no_plot) io::run_plot("lyapunov_map.py", {h5.string(), (out / (a.name + ".png")).string()});
}

void lyapunov_strip(MapArgs a) {
  if (a.name.empty()) a.name = "lyapunov_strip";
  check_r(a.r, "r");
  if (a.strip_w1 < 1 || a.strip_w2 < 1)
    throw UsageError(fmt::format("size: got {}x{}, expected positive numbers of cells", a.strip_w1, a.strip_w2));
  if (!(a.w1_min < a.w1_max)) throw UsageError(fmt::format("w1-range: got [{}, {}], expected w1-min < w1-max", a.w1_min, a.w1_max));
  lyapunov::MapOptions o = map_options(a);
  iterate::Ensemble ens;
  ens.r = {a.r};
  ens.initial = iterate::strip_grid(a.strip_w1, a.strip_w2, a.w1_min, a.w1_max);
  ens.grid_description = fmt::format("strip:{}x{}:{}:{}", a.strip_w1, a.strip_w2, a.w1_min, a.w1_max);
  const io::fs::path out(a.out);
  io::ensure_dir(out);
  const auto t0 = std::chrono::steady_clock::now();
  const lyapunov::OrbitExponents e = lyapunov::map_exponents(ens, o);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  io::Attrs at = common_attrs(a, ens, "lyapunov-strip", secs);
  at["r"] = a.r;
  at["w1_min"] = a.w1_min;
  at["w1_max"] = a.w1_max;
  at["alpha"] = core::alpha(a.r);
  const io::fs::path h5 = out / (a.name + ".h5");
  {
    io::H5Writer w(h5);
    w.attrs(at);
    // strip_grid is ordered w1-major (n1 x n2): image[i1, i2].
    const std::size_t n1 = static_cast<std::size_t>(a.strip_w1), n2 = static_cast<std::size_t>(a.strip_w2);
    w.dataset("lambda1", e.lambda1, {n1, n2});
    w.dataset("err1", e.err1, {n1, n2});
    w.dataset("lambda2", e.lambda2, {n1, n2});
    std::vector<double> w1(ens.initial.size()), w2(ens.initial.size());
    for (std::size_t i = 0; i < ens.initial.size(); ++i) std::tie(w1[i], w2[i]) = core::strip<double>(ens.initial[i]);
    w.dataset("w1", w1, {n1, n2});
    w.dataset("w2", w2, {n1, n2});
    w.commit();
  }
  io::write_manifest(out / (a.name + ".json"), at);
  if (!a.quiet) std::cerr << fmt::format("btob: {} orbits in {:.3f} s; wrote {}\n", ens.orbits(), secs, h5.string());
  if (!a.no_plot) io::run_plot("lyapunov_strip.py", {h5.string(), (out / (a.name + ".png")).string()});
}

void add_common(CLI::App* c, MapArgs& a) {
  c->add_option("--iterations", a.iterations, "averaged map iterations per orbit")->capture_default_str();
  c->add_option("--transient", a.transient, "iterations discarded first (orbit and tangent vector)")->capture_default_str();
  c->add_option("--blocks", a.blocks, "batch-means blocks for the error bars")->capture_default_str();
  c->add_option("--threads", a.threads, "OpenMP threads (default: all cores)");
  c->add_option("--precision", a.precision, "kernel precision: float or double (tangent arithmetic in double)")
      ->capture_default_str();
  c->add_option("--out", a.out, "output directory")->capture_default_str();
  c->add_option("--name", a.name, "file stem of the outputs");
  c->add_option("--title", a.title, "figure title (r range, grid and iterations are added)");
  c->add_flag("--no-plot", a.no_plot, "write data only");
  c->add_flag("--quiet", a.quiet, "no progress or summary on stderr");
}

Register reg([](CLI::App& app) {
  auto a = std::make_shared<OrbitArgs>();
  CLI::App* c = app.add_subcommand(
      "lyapunov",
      "Both Lyapunov exponents of one orbit (projective derivative cocycle, QR). Only the tangent cocycle is used: two "
      "nearby orbits straddle the branch boundaries of this piecewise-linear map and give wrong exponents.");
  c->add_flag("--weighted", a->weighted,
              "also print the weighted Birkhoff averages (first columns): 1e-8 or better on periodic and quasi-periodic "
              "orbits where the plain average converges like 1/n");
  c->add_option("--r", a->r, "restitution coefficient, in (0,1)")->required();
  c->add_option("--point", a->point, "initial point x,y,z (x*z <= 0)")->required();
  c->add_option("--iterations", a->iterations, "averaged map iterations")->capture_default_str();
  c->add_option("--transient", a->transient, "iterations discarded first (orbit and tangent frame)")->capture_default_str();
  c->add_option("--reorthonormalise", a->reorth, "QR every this many steps")->capture_default_str();
  c->add_option("--blocks", a->blocks, "batch-means blocks for the error bars")->capture_default_str();
  c->add_option("--precision", a->precision, "float, double, long-double, float128 or mpfr:D (D digits, 10..10000)")
      ->capture_default_str();
  c->add_option("--convergence", a->convergence, "also write exponent against n to this CSV file");
  c->callback([a] { lyapunov_orbit(*a); });

  auto m = std::make_shared<MapArgs>();
  CLI::App* cm = app.add_subcommand("lyapunov-map", "Lyapunov exponents of every orbit over r values x a grid, summarised per r");
  cm->add_option("--r-min", m->r_min, "smallest r, in (0,1)")->capture_default_str();
  cm->add_option("--r-max", m->r_max, "largest r, in (0,1)")->capture_default_str();
  cm->add_option("--r-count", m->r_count, "number of evenly spaced r values")->capture_default_str();
  cm->add_option("--grid", m->grid, "initial conditions: paper, strip:NxM[:w1min:w1max], random:N, or x,y,z;...")
      ->capture_default_str();
  cm->add_option("--seed", m->seed, "seed of random grids")->capture_default_str();
  cm->add_option("--overlay", m->overlays, "named r overlays: " + overlay_names())->expected(1, -1);
  add_common(cm, *m);
  cm->callback([m] { lyapunov_map(*m); });

  auto s = std::make_shared<MapArgs>();
  s->iterations = 5000;
  s->transient = 500;
  CLI::App* cs = app.add_subcommand("lyapunov-strip", "Lyapunov exponent at one r over a strip grid (w1, w2), as an image");
  cs->add_option("--r", s->r, "restitution coefficient, in (0,1)")->capture_default_str();
  cs->add_option("--n1", s->strip_w1, "cells along w1")->capture_default_str();
  cs->add_option("--n2", s->strip_w2, "cells along w2")->capture_default_str();
  cs->add_option("--w1-min", s->w1_min, "smallest w1")->capture_default_str();
  cs->add_option("--w1-max", s->w1_max, "largest w1")->capture_default_str();
  add_common(cs, *s);
  cs->callback([s] { lyapunov_strip(*s); });
});

}  // namespace
}  // namespace btob::cli
