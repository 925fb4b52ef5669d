// `btob hyperbolicity` (singular values of the one-step derivative over a strip grid, as an image) and
// `btob hyperbolicity-orbits` (per r: fraction of expanding steps and CLV angles along orbits, beside lambda1):
// the (non-)hyperbolicity of Section 8.1 (3).
#include "cli/app.hpp"
#include "cli/common.hpp"
#include "core/map.hpp"
#include "io/io.hpp"
#include "iterate/ensemble.hpp"
#include "lyapunov/hyperbolicity.hpp"
#include "lyapunov/maps.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>
#include <regex>

namespace btob::cli {
namespace {

void check_r(double r, const char* field) {
  if (!(r > 0 && r < 1)) throw UsageError(fmt::format("{}: got {}, expected a value in the open interval (0, 1)", field, r));
}

// ---- btob hyperbolicity ----
struct StripArgs {
  double r = 0;
  std::string grid = "strip:400x200";
  std::string w1_range = "-2,2";
  std::string out = "results/hyperbolicity";
  std::string name, title;
  bool no_plot = false, quiet = false;
};

std::pair<long, long> parse_strip_size(const std::string& spec) {
  static const std::regex re(R"(strip:([0-9]{1,9})x([0-9]{1,9}))");
  std::smatch m;
  const auto bad = [&] { return UsageError(fmt::format("grid: got '{}', expected strip:NxM with N, M >= 1", spec)); };
  if (!std::regex_match(spec, m, re)) throw bad();
  const long n1 = std::stol(m[1]), n2 = std::stol(m[2]);
  if (n1 < 1 || n2 < 1) throw bad();
  return {n1, n2};
}

std::pair<double, double> parse_range(const std::string& s) {
  const auto bad = [&] { return UsageError(fmt::format("w1-range: got '{}', expected two finite numbers a,b with a < b", s)); };
  const auto comma = s.find(',');
  if (comma == std::string::npos) throw bad();
  double a = 0, b = 0;
  try {
    std::size_t ua = 0, ub = 0;
    a = std::stod(s.substr(0, comma), &ua);
    b = std::stod(s.substr(comma + 1), &ub);
    if (ua != comma || ub != s.size() - comma - 1) throw bad();
  } catch (const std::logic_error&) {
    throw bad();
  }
  if (!std::isfinite(a) || !std::isfinite(b) || !(a < b)) throw bad();
  return {a, b};
}

void hyperbolicity_strip(StripArgs a) {
  check_r(a.r, "r");
  const auto [n1, n2] = parse_strip_size(a.grid);
  const auto [lo, hi] = parse_range(a.w1_range);
  if (a.name.empty()) a.name = fmt::format("hyperbolicity_strip_r{}", a.r);
  const auto t0 = std::chrono::steady_clock::now();
  lyapunov::StripSingularValues img;
  try {
    img = lyapunov::strip_singular_values(a.r, n1, n2, lo, hi);
  } catch (const std::length_error& e) {
    throw UsageError(e.what());
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const io::fs::path out(a.out);
  io::ensure_dir(out);
  io::Attrs at = io::provenance(invocation());
  at["kind"] = std::string("hyperbolicity-strip");
  at["name"] = a.name;
  at["title"] = a.title;
  at["r"] = a.r;
  at["alpha"] = core::alpha(a.r);
  at["grid"] = fmt::format("strip:{}x{}:{}:{}", n1, n2, lo, hi);
  at["w1_min"] = lo;
  at["w1_max"] = hi;
  at["metric"] = std::string("round metric of the unit sphere (tangent planes u^perp)");
  at["expanding_fraction"] = img.expanding_fraction;
  at["scalar_type"] = std::string("double");
  at["seconds"] = secs;
  const io::fs::path h5 = out / (a.name + ".h5");
  {
    io::H5Writer w(h5);
    w.attrs(at);
    const std::vector<std::size_t> dims = {static_cast<std::size_t>(n1), static_cast<std::size_t>(n2)};
    w.dataset("s1", img.s1, dims);
    w.dataset("s2", img.s2, dims);
    w.dataset("symbol", img.symbol, dims);
    w.dataset("w1", img.w1, dims);
    w.dataset("w2", img.w2, dims);
    w.commit();
  }
  io::write_manifest(out / (a.name + ".json"), at);
  const auto [mn, mx] = std::minmax_element(img.s1.begin(), img.s1.end());
  std::cout << "r,cells,expanding_fraction,s1_min,s1_max\n"
            << fmt::format("{},{},{:.6f},{:.6g},{:.6g}\n", a.r, img.s1.size(), img.expanding_fraction, *mn, *mx);
  if (!a.quiet) std::cerr << fmt::format("btob: {} cells in {:.3f} s; wrote {}\n", img.s1.size(), secs, h5.string());
  if (!a.no_plot) io::run_plot("hyperbolicity_strip.py", {h5.string(), (out / (a.name + ".png")).string()});
}

// ---- btob hyperbolicity-orbits ----
struct OrbitsArgs {
  double r_min = 0.0717, r_max = 0.6;
  long r_count = 100;
  std::string grid = "paper";
  std::uint64_t seed = 1;
  long iterations = 10000, transient = 10000, backward = 10000;
  int bins = 90, threads = 0;
  std::string out = "results/hyperbolicity";
  std::string name = "hyperbolicity_orbits", title;
  bool no_plot = false, quiet = false;
};

void hyperbolicity_orbits(const OrbitsArgs& a) {
  check_r(a.r_min, "r-min");
  check_r(a.r_max, "r-max");
  if (a.r_count < 1 || a.r_count > 1000000)
    throw UsageError(fmt::format("r-count: got {}, expected 1 <= r-count <= 1000000", a.r_count));
  // lambda1 comes from lyapunov::map_exponents with 10 batch-means blocks, which needs iterations >= 10.
  if (a.iterations < 10) throw UsageError(fmt::format("iterations: got {}, expected at least 10", a.iterations));
  if (a.threads < 0) throw UsageError(fmt::format("threads: got {}, expected at least 1", a.threads));
  lyapunov::ClvOptions co;
  co.transient = a.transient;
  co.window = a.iterations;
  co.backward_transient = a.backward;
  co.bins = a.bins;
  try {
    lyapunov::validate(co);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  iterate::Ensemble ens;
  try {
    ens.r = iterate::linspace_r(a.r_min, a.r_max, a.r_count);
    ens.initial = iterate::parse_grid(a.grid, a.seed, "grid");
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  ens.grid_description = a.grid;
  ens.seed = a.seed;
  const std::size_t R = ens.r.size(), I = ens.initial.size(), B = static_cast<std::size_t>(a.bins);
  iterate::checked_bytes(I * static_cast<std::size_t>(a.iterations), sizeof(double) + 2, "iterations");
  const int nt = a.threads > 0 ? a.threads : omp_get_max_threads();
  const io::fs::path out(a.out);
  io::ensure_dir(out);

  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> o_frac(R * I), o_med(R * I), o_q05(R * I), o_l1(R * I), o_l2(R * I);
  std::vector<std::uint8_t> o_deg(R * I);
  std::vector<double> frac(R), med(R, nan), q05(R, nan), amin(R, nan), fdeg(R), hist(R * B, 0.0), l1qr(R);
  io::Progress progress("hyperbolicity-orbits");
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t ir = 0; ir < R; ++ir) {
    std::vector<lyapunov::ClvResult> res(I);
    const double r = ens.r[ir];
#pragma omp parallel for schedule(static) num_threads(nt)
    for (long i = 0; i < static_cast<long>(I); ++i) {
      res[static_cast<std::size_t>(i)] = lyapunov::covariant_vectors<double>(ens.initial[static_cast<std::size_t>(i)], r, co);
      res[static_cast<std::size_t>(i)].symbols = {};  // only the angles are pooled below
    }
    // Pooled in orbit order (deterministic for any thread count); angles only from non-degenerate orbits.
    std::vector<double> pooled, l1s;
    double f = 0;
    long deg = 0;
    for (std::size_t i = 0; i < I; ++i) {
      const auto& c = res[i];
      const std::size_t o = ir * I + i;
      o_frac[o] = c.expanding_fraction;
      o_med[o] = c.degenerate ? nan : c.median_angle;
      o_q05[o] = c.degenerate ? nan : c.q05_angle;
      o_l1[o] = c.lambda[0];
      o_l2[o] = c.lambda[1];
      o_deg[o] = c.degenerate;
      l1s.push_back(c.lambda[0]);
      f += c.expanding_fraction;
      deg += c.degenerate;
      if (c.degenerate) continue;
      pooled.insert(pooled.end(), c.angle.begin(), c.angle.end());
      for (std::size_t b = 0; b < B; ++b) hist[ir * B + b] += c.histogram[b];
    }
    frac[ir] = f / static_cast<double>(I);
    fdeg[ir] = static_cast<double>(deg) / static_cast<double>(I);
    l1qr[ir] = lyapunov::median(l1s);  // as lyapunov-map's median column
    if (!pooled.empty()) {
      med[ir] = lyapunov::quantile(pooled, 0.5);
      q05[ir] = lyapunov::quantile(pooled, 0.05);
      amin[ir] = *std::min_element(pooled.begin(), pooled.end());
    }
    if (!a.quiet) progress.update(ir + 1, R);
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  // lambda1 beside them, from the colleague's batched tangent recorder on the same orbits (same r, same grid).
  lyapunov::MapOptions mo;
  mo.transient = a.transient;
  mo.iterations = a.iterations;
  mo.blocks = 10;
  mo.run.threads = a.threads;
  const lyapunov::OrbitExponents ex = lyapunov::map_exponents(ens, mo);
  const lyapunov::RSummary sm = lyapunov::summarise(ex, R, I);

  io::Attrs at = io::provenance(invocation());
  at["kind"] = std::string("hyperbolicity-orbits");
  at["name"] = a.name;
  at["title"] = a.title;
  at["r_min"] = a.r_min;
  at["r_max"] = a.r_max;
  at["r_count"] = a.r_count;
  at["grid"] = ens.grid_description;
  at["initial_conditions"] = static_cast<long>(I);
  at["seed"] = static_cast<long>(a.seed);
  at["iterations"] = a.iterations;
  at["transient"] = a.transient;
  at["backward_transient"] = a.backward;
  at["bins"] = static_cast<long>(a.bins);
  at["angle_units"] = std::string("radians, in [0, pi/2], between the two CLVs in the round metric of the sphere");
  at["degenerate"] = std::string("lambda1 - lambda2 < 10 / iterations (forward QR): CLV angle undefined, left out");
  at["lambda1_source"] = std::string("lyapunov::map_exponents (batched tangent recorder), 10 blocks");
  at["scalar_type"] = std::string("double");
  at["threads"] = static_cast<long>(nt);
  at["clv_seconds"] = secs;
  const io::fs::path h5 = out / (a.name + ".h5");
  {
    io::H5Writer w(h5);
    w.attrs(at);
    w.dataset("r", ens.r, {R});
    for (auto [n, v] : {std::pair<const char*, const std::vector<double>*>{"frac_expanding", &frac}, {"angle_median", &med}, {"angle_q05", &q05},
                        {"angle_min", &amin}, {"frac_degenerate", &fdeg}, {"lambda1_median", &sm.median},
                        {"lambda1_frac_positive", &sm.frac_positive}, {"lambda1_qr_median", &l1qr}})
      w.dataset(n, *v, {R});
    w.dataset("angle_histogram", hist, {R, B});
    for (auto [n, v] : {std::pair<const char*, const std::vector<double>*>{"orbit_frac_expanding", &o_frac}, {"orbit_angle_median", &o_med},
                        {"orbit_angle_q05", &o_q05}, {"orbit_lambda1_qr", &o_l1}, {"orbit_lambda2_qr", &o_l2},
                        {"orbit_lambda1", &ex.lambda1}})
      w.dataset(n, *v, {R, I});
    w.dataset("orbit_degenerate", o_deg, {R, I});
    w.commit();
  }
  std::string csv =
      "r,frac_expanding,angle_median,angle_q05,angle_min,frac_degenerate,lambda1_median,lambda1_frac_positive,"
      "lambda1_qr_median\n";
  for (std::size_t i = 0; i < R; ++i)
    csv += fmt::format("{:.9f},{:.5f},{:.6g},{:.6g},{:.6g},{:.4f},{:.6g},{:.4f},{:.6g}\n", ens.r[i], frac[i], med[i],
                       q05[i], amin[i], fdeg[i], sm.median[i], sm.frac_positive[i], l1qr[i]);
  io::write_text_atomic(out / (a.name + "_summary.csv"), csv);
  io::write_manifest(out / (a.name + ".json"), at);
  if (!a.quiet)
    std::cerr << fmt::format("btob: {} orbits x {} steps with CLVs in {:.3f} s; wrote {}\n", ens.orbits(),
                             a.transient + a.iterations + a.backward, secs, h5.string());
  if (!a.no_plot) io::run_plot("hyperbolicity_orbits.py", {h5.string(), (out / (a.name + ".png")).string()});
}

Register reg([](CLI::App& app) {
  auto s = std::make_shared<StripArgs>();
  CLI::App* c = app.add_subcommand("hyperbolicity",
                                   "Singular values of the one-step derivative of the projective map over a strip grid");
  c->add_option("--r", s->r, "restitution coefficient, in (0,1)")->required();
  c->add_option("--grid", s->grid, "strip:NxM cells along w1 x w2")->capture_default_str();
  c->add_option("--w1-range", s->w1_range, "w1 range a,b of the image")->capture_default_str();
  c->add_option("--out", s->out, "output directory")->capture_default_str();
  c->add_option("--name", s->name, "file stem of the outputs (default hyperbolicity_strip_r<r>)");
  c->add_option("--title", s->title, "figure title (r, grid are added)");
  c->add_flag("--no-plot", s->no_plot, "write data only");
  c->add_flag("--quiet", s->quiet, "no summary on stderr");
  c->callback([s] { hyperbolicity_strip(*s); });

  auto o = std::make_shared<OrbitsArgs>();
  CLI::App* co = app.add_subcommand(
      "hyperbolicity-orbits", "Per r: fraction of expanding steps and CLV angles (Ginelli) along orbits, beside lambda1");
  co->add_option("--r-min", o->r_min, "smallest r, in (0,1)")->capture_default_str();
  co->add_option("--r-max", o->r_max, "largest r, in (0,1)")->capture_default_str();
  co->add_option("--r-count", o->r_count, "number of evenly spaced r values")->capture_default_str();
  co->add_option("--grid", o->grid, "initial conditions: paper, strip:NxM[:w1min:w1max], random:N, or x,y,z;...")
      ->capture_default_str();
  co->add_option("--seed", o->seed, "seed of random grids")->capture_default_str();
  co->add_option("--iterations", o->iterations, "window: steps with CLV angles and expanding flags")->capture_default_str();
  co->add_option("--transient", o->transient, "forward steps before the window")->capture_default_str();
  co->add_option("--backward", o->backward, "forward steps after the window, iterated back first")->capture_default_str();
  co->add_option("--bins", o->bins, "angle histogram bins over [0, pi/2]")->capture_default_str();
  co->add_option("--threads", o->threads, "OpenMP threads (default: all cores)");
  co->add_option("--out", o->out, "output directory")->capture_default_str();
  co->add_option("--name", o->name, "file stem of the outputs")->capture_default_str();
  co->add_option("--title", o->title, "figure title (r range, grid and iterations are added)");
  co->add_flag("--no-plot", o->no_plot, "write data only");
  co->add_flag("--quiet", o->quiet, "no progress or summary on stderr");
  co->callback([o] { hyperbolicity_orbits(*o); });
});

}  // namespace
}  // namespace btob::cli
