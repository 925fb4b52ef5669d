// SPDX-License-Identifier: GPL-3.0-or-later
// The command line's words around a run (commands/spec.hpp: warn, print, report), and the few declarations that
// need code (prepare, attrs, also_write, validate).  Presentation only: nothing here is part of a result.
#include "commands/commands.hpp"
#include "core/csv.hpp"
#include "core/error_bar.hpp"
#include "io/io.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <variant>

namespace btob::commands {

// ---- bifurcation ----
// Tail points outside the range, and orbits the precision lost: said on stderr, recorded in the attributes.
void Spec<bifurcation::Request>::warn(const bifurcation::Request& req, const bifurcation::Result& res,
                                      const core::RunControl&) {
  const std::uint64_t under = res.points_below(), over = res.points_above();
  const double tail_points = static_cast<double>(res.ensemble.orbits()) * static_cast<double>(req.tail);
  // On a log scale -inf means theta underflowed to 0: the small component of the state fell below the
  // precision's smallest number (float near 7-4*sqrt(3), Figures 4.3-4.6); the diagram then lacks those points.
  if (under + over > 0 && static_cast<double>(under + over) > 1e-3 * tail_points)
    std::cerr << fmt::format("btob: warning: {:.1f}% of the tail points fall outside [{}, {}] ({} below, {} above){}\n",
                             100.0 * static_cast<double>(under + over) / tail_points, res.lo, res.hi, under, over,
                             req.log && req.precision == "float"
                                 ? "; in float, theta underflows to 0 where double still resolves it: use double"
                                 : "; widen --range to see them");
  if (res.degenerate > 0)
    std::cerr << fmt::format(
        "btob: warning: {} of {} orbits ended in a non-finite or zero state in {}: this precision "
        "cannot cope at these r; use double or wider\n",
        res.degenerate, res.ensemble.orbits(), res.scalar_type);
}

void Spec<bifurcation::Request>::report(const bifurcation::Request& req, const bifurcation::Result& res,
                                        const core::Contents&, const Written& w) {
  const double its = static_cast<double>(res.ensemble.orbits()) * static_cast<double>(req.iterations);
  if (!w.quiet)
    std::cerr << fmt::format(
        "btob: {} orbits x {} iterations = {:.3g} map iterations in {:.3f} s ({:.3g} it/s, {} threads); "
        "wrote {}\n",
        res.ensemble.orbits(), req.iterations, its, res.iteration_seconds, its / res.iteration_seconds, w.threads,
        w.listing());
}

// ---- lyapunov ----
void Spec<lyapunov::OrbitRequest>::print(const lyapunov::OrbitRequest&, const lyapunov::ProjectiveResult& res) {
  // With weighted the weighted Birkhoff averages first (super-polynomial on (quasi-)periodic orbits, no batch
  // error); each exponent printed with its bar by core::with_error.
  std::cout << res.csv();
}

// Float rounding can move an orbit off a weak sink: the same orbit in double, and a warning when the sign differs.
void Spec<lyapunov::OrbitRequest>::warn(const lyapunov::OrbitRequest& req, const lyapunov::ProjectiveResult& res,
                                        const core::RunControl& control) {
  if (req.precision != "float") return;
  const auto& l = res.lambda;
  lyapunov::OrbitRequest d = req;
  d.precision = "double";
  d.convergence.clear();
  const lyapunov::ProjectiveResult rd = lyapunov::run(d, control);
  const int cf = lyapunov::classify(l[0].value, l[0].error, res.iterations),
            cd = lyapunov::classify(rd.lambda[0].value, rd.lambda[0].error, rd.iterations);
  const auto name = [](int c) { return c > 0 ? "positive" : c < 0 ? "negative" : "zero"; };
  const core::ValueWithError dl = core::with_error(rd.lambda[0].value, rd.lambda[0].error);
  if (cf != cd)
    std::cerr << fmt::format(
        "btob: warning: in double this orbit has lambda1 = {} +- {} ({}), float {:.6g} "
        "({}): float rounding moves orbits off weakly contracting sinks; use --precision double\n",
        dl.value, dl.error, name(cd), l[0].value, name(cf));
}

void Spec<lyapunov::OrbitRequest>::also_write(const lyapunov::OrbitRequest& req,
                                              const lyapunov::ProjectiveResult& res) {
  if (req.convergence.empty()) return;
  core::CsvTable csv("n,lambda1,lambda2");
  const auto& c = res.convergence;
  for (std::size_t j = 0; j < c.n.size(); ++j)
    csv.line(fmt::format("{},{:.12g},{:.12g}", c.n[j], c.exponents[0][j], c.exponents[1][j]));
  io::write_text_atomic(req.convergence, csv.text());
}

namespace {
// The closing line of a map or strip of exponents.
template <class Req> void maps_report(const Req& req, const lyapunov::MapResult& res, const Written& w) {
  const double steps = static_cast<double>(res.ensemble.orbits()) * static_cast<double>(req.transient + req.iterations);
  if (!w.quiet)
    std::cerr << fmt::format(
        "btob: {} orbits x {} steps = {:.3g} map iterations with the tangent cocycle in {:.3f} s "
        "({:.3g} it/s); wrote {}\n",
        res.ensemble.orbits(), req.transient + req.iterations, steps, res.iteration_seconds,
        steps / res.iteration_seconds, w.listing());
}
}  // namespace

void Spec<lyapunov::MapRequest>::warn(const lyapunov::MapRequest&, const lyapunov::MapResult& res,
                                      const core::RunControl&) {
  if (res.float_disagree > 0)
    std::cerr << fmt::format(
        "btob: warning: float and double give another sign of lambda1 on {} of the {} orbits "
        "re-run in double (first at r = {}): float rounding moves orbits off weakly contracting "
        "sinks; use --precision double\n",
        res.float_disagree, res.float_checked, res.float_disagree_r);
}

void Spec<lyapunov::MapRequest>::report(const lyapunov::MapRequest& req, const lyapunov::MapResult& res,
                                        const core::Contents&, const Written& w) {
  maps_report(req, res, w);
}

void Spec<lyapunov::StripRequest>::report(const lyapunov::StripRequest& req, const lyapunov::MapResult& res,
                                          const core::Contents&, const Written& w) {
  maps_report(req, res, w);
}

void Spec<lyapunov::HyperbolicityRequest>::print(const lyapunov::HyperbolicityRequest& req,
                                                 const lyapunov::HyperbolicityResult& res) {
  const auto& img = res.image;  // its cells' s1 may be with the MPI ranks (their rows): the counts of the parts
  std::cout << "r,cells,expanding_fraction,s1_min,s1_max\n"
            << fmt::format("{},{},{:.6f},{:.6g},{:.6g}\n", req.r, img.n1 * img.n2, img.expanding_fraction, res.s1_min,
                           res.s1_max);
}

void Spec<lyapunov::HyperbolicityRequest>::report(const lyapunov::HyperbolicityRequest&,
                                                  const lyapunov::HyperbolicityResult& res, const core::Contents&,
                                                  const Written& w) {
  if (!w.quiet)
    std::cerr << fmt::format("btob: {} cells in {:.3f} s; wrote {}\n", res.image.n1 * res.image.n2, res.seconds,
                             w.listing());
}

void Spec<lyapunov::HyperbolicityOrbitsRequest>::report(const lyapunov::HyperbolicityOrbitsRequest& req,
                                                        const lyapunov::HyperbolicityOrbitsResult& res,
                                                        const core::Contents&, const Written& w) {
  if (!w.quiet)
    std::cerr << fmt::format("btob: {} orbits x {} steps with CLVs in {:.3f} s; wrote {}\n", res.ensemble.orbits(),
                             req.transient + req.iterations + req.backward, res.clv_seconds, w.listing());
}

// ---- attractors ----
void Spec<attractors::ClassifyRequest>::print(const attractors::ClassifyRequest&,
                                              const attractors::ClassifyResult& res) {
  std::cout << res.csv();
}

void Spec<attractors::BasinsRequest>::report(const attractors::BasinsRequest& req, const attractors::BasinsResult& res,
                                             const core::Contents&, const Written& w) {
  if (w.quiet) return;
  const attractors::Basins& b = res.basins;
  const std::size_t n = res.points();
  std::cerr << fmt::format(
      "btob: basins at r = {}: {} points x {} grids in {:.2f} s ({:.3g} points/s, {} threads), "
      "{} attractors, undecided {:.4f} ({} before refinement); wrote {}\n",
      req.r, n, req.replicates + 1, b.seconds,
      static_cast<double>(n * static_cast<std::size_t>(req.replicates + 1)) / b.seconds, res.threads,
      b.attractors.size(), b.undecided.value, b.undecided_first_pass, w.listing());
  // Each attractor's fraction with its 95% interval (sampling only), of the measure the grid samples.
  std::cerr << "  fractions of the measure: " << attractors::measure_name(b.grid) << "\n";
  if (b.grid.kind == core::GridKind::strip)
    std::cerr << fmt::format(
        "  the rectangle leaves out {:.4f} of the uniform measure on the sphere of directions "
        "(sphere:NxM counts that measure)\n",
        1 - attractors::sphere_share(b.grid));
  for (std::size_t i = 0; i < b.attractors.size(); ++i)
    std::cerr << fmt::format("  {} {} {}: {:.4f} [{:.4f}, {:.4f}]\n", b.attractors[i].id,
                             attractors::type_name(b.attractors[i].type), b.attractors[i].pattern, b.fractions[i].value,
                             b.fractions[i].low, b.fractions[i].high);
  std::cerr << fmt::format("  0 undecided: {:.4f} [{:.4f}, {:.4f}]\n", b.undecided.value, b.undecided.low,
                           b.undecided.high);
  std::cerr << attractors::boundary_summary(b.boundary);
}

void Spec<attractors::BasinsRRequest>::prepare(attractors::BasinsRRequest& req) {
  req.reference_csv = io::data_text(req.reference, attractors::table_6_1_file);
}

void Spec<attractors::BasinsRRequest>::report(const attractors::BasinsRRequest& req,
                                              const attractors::BasinsRResult& res, const core::Contents&,
                                              const Written& w) {
  if (w.quiet) return;
  for (const auto& row : res.rows) {
    std::cerr << fmt::format("btob: basins-r r = {}: {} attractors\n", row.r, row.attractors.size());
    if (row.has_boundary) std::cerr << attractors::boundary_summary(row.boundary);
  }
  std::cerr << fmt::format("btob: basins-r in {:.2f} s; fractions of the measure: {}; wrote {}\n", res.seconds,
                           attractors::grid_measure(req.grid), w.listing());
}

// ---- stats ----
void Spec<stats::CorrelateRequest>::report(const stats::CorrelateRequest& req, const stats::CorrelateResult& res,
                                           const core::Contents& c, const Written& w) {
  if (w.quiet) return;
  // Everything below is read from the attributes NAME.json and NAME.h5 carry, so the terminal and the files agree.
  const auto num = [&](const char* k) {
    const auto& v = c.attrs.at(k);
    return std::holds_alternative<long>(v) ? fmt::format("{}", std::get<long>(v))
                                           : fmt::format("{:.4g}", std::get<double>(v));
  };
  const auto has = [&](const char* k) { return c.attrs.count(k) > 0; };
  std::cerr << fmt::format("btob: C_N({}, {}; 0..{}) over N = {} in {:.3g} s ({}, {}); noise floor {}",
                           stats::observable_name(res.phi), stats::observable_name(res.psi), req.n_max, res.N(),
                           res.seconds, req.method, req.precision, num("noise_floor"));
  if (res.fitted) {
    std::cerr << fmt::format("; {}: {} window(s) of {} lags above the floor",
                             std::get<std::string>(c.attrs.at("decay_verdict")), num("decay_windows"), req.window);
    if (has("envelope_first"))
      std::cerr << fmt::format(", envelope {} .. {}", num("envelope_first"), num("envelope_last"));
    std::cerr << (has("decay_floor_lag") ? fmt::format(", floor reached at lag {}", num("decay_floor_lag"))
                                         : fmt::format(", floor not reached by lag {}", req.fit_lags));
    if (has("decay_rate")) {  // the rate and its bar by core::with_error: the printed interval holds the rate
      const double v = std::get<double>(c.attrs.at("decay_rate")), e = std::get<double>(c.attrs.at("decay_rate_error"));
      const core::ValueWithError rate = std::isfinite(v) && std::isfinite(e) && e >= 0
                                            ? core::with_error(v, e)
                                            : core::ValueWithError{num("decay_rate"), num("decay_rate_error")};
      std::cerr << fmt::format(", rate {} +- {} per iteration (95%: {} .. {})", rate.value, rate.error,
                               num("decay_rate_low"), num("decay_rate_high"));
    }
    std::cerr << " (" << std::get<std::string>(c.attrs.at("decay_reason")) << ")";
  }
  if (!res.c_direct.empty())
    std::cerr << fmt::format("; fft vs direct {:.2g} relative, direct {:.3g} s", res.max_rel_diff, res.seconds_direct);
  std::cerr << "; wrote " << w.listing() << "\n";
}

void Spec<stats::MeasureRequest>::report(const stats::MeasureRequest& req, const stats::MeasureResult& res,
                                         const core::Contents&, const Written& w) {
  if (!w.quiet)
    std::cerr << fmt::format(
        "btob: {} initial conditions in {} group(s) (TV < {}); largest TV within a group {:.3g}; "
        "wrote {}\n",
        res.initial.size(), res.groups(), req.tv_same, res.tv_max_within_groups(), w.listing());
}

// ---- precision ----
void Spec<precision::TradeoffRequest>::print(const precision::TradeoffRequest&, const precision::TradeoffResult& res) {
  for (const auto& [role, text] : res.tables()) std::cout << text;
}

// ---- windows ----
void Spec<windows::PolyRequest>::print(const windows::PolyRequest&, const windows::PolyResult& res) {
  std::cout << res.text();
}

void Spec<windows::BoundsRequest>::warn(const windows::BoundsRequest&, const windows::BoundsResult& res,
                                        const core::RunControl&) {
  for (const auto& c : res.certificates)
    if (!c.valid()) std::cerr << fmt::format("btob: warning: certificate of n = {} failed\n", c.n);
}

void Spec<windows::BoundsRequest>::print(const windows::BoundsRequest&, const windows::BoundsResult& res) {
  std::cout << res.csv() << std::flush;
}

void Spec<windows::ThresholdsRequest>::print(const windows::ThresholdsRequest&, const windows::ThresholdsResult& res) {
  std::cout << res.csv();
}

void Spec<windows::StripesRequest>::print(const windows::StripesRequest&, const windows::StripesResult& res) {
  std::cout << res.csv();
}

// The closing line is the command's output (stdout, with or without quiet): the checks passed and the CSV's path.
void Spec<windows::VerifyRequest>::report(const windows::VerifyRequest&, const windows::VerifyResult& res,
                                          const core::Contents&, const Written& w) {
  std::string csv;
  for (const auto& f : w.files)
    if (f.extension() == ".csv" && csv.empty()) csv = f.string();
  std::cout << fmt::format("windows verify n = {}..{}: {} of {} checks pass ({:.1f} s); wrote {}\n", res.range.first,
                           res.range.last, res.passed, res.total, res.total_seconds, csv);
}

void Spec<windows::BoundPrecisionRequest>::print(const windows::BoundPrecisionRequest&,
                                                 const windows::BoundPrecisionResult& res) {
  std::cout << res.summary_csv();
}

// ---- patterns ----
// An empty stability set is a claim about every r: say what the scan could not see (patterns/scan_impl.hpp).
void Spec<patterns::WordRequest>::warn(const patterns::WordRequest&, const patterns::WordResult& res,
                                       const core::RunControl&) {
  if (res.mode == patterns::WordRequest::Mode::window && res.intervals.empty())
    std::cerr << "btob: no stability interval found; the scan follows every change of the dominant eigenvalue "
                 "between its grid points down to the bisection width, but an interval bounded by feasibility "
                 "changes alone and narrower than the grid step there (4.75e-5 on [0.07, 0.26)) may be missed\n";
}

void Spec<patterns::WordRequest>::print(const patterns::WordRequest&, const patterns::WordResult& res) {
  std::cout << res.text();
}

void Spec<patterns::AtlasRequest>::report(const patterns::AtlasRequest&, const patterns::AtlasResult& res,
                                          const core::Contents&, const Written& w) {
  if (w.quiet) return;
  std::cerr << "btob: " << res.summary() << "\n";
  std::cerr << "btob: wrote " << w.listing() << "\n";
}

void Spec<patterns::CurvesRequest>::report(const patterns::CurvesRequest&, const patterns::CurvesResult& res,
                                           const core::Contents&, const Written& w) {
  if (!w.quiet)
    std::cerr << fmt::format("btob: {} ({}analysed as {}) at {} r values; {} critical r; wrote {}\n", res.word,
                             res.reduced ? "J-square, " : "", res.analysed, res.r.size(), res.critical.size(),
                             w.listing());
}

// ---- strip orbits ----
void StripOrbitsRequest::validate() const {
  orbits::StripOrbitsRequest::validate();
  if (!(plot_w1 > 0 && plot_w1 <= 1e6))
    throw core::InvalidField("plot-w1", fmt::format("{}", plot_w1), "a number in (0, 1e6]");
  if (only < 0 || only > orbits)
    throw core::InvalidField("only", std::to_string(only), fmt::format("0 (all) or 1..orbits ({})", orbits));
}

void Spec<StripOrbitsRequest>::attrs(const StripOrbitsRequest& req, const orbits::StripOrbitsResult&, core::Attrs& at) {
  at["plot_w1"] = req.plot_w1;
  at["only"] = req.only;
}

void Spec<StripOrbitsRequest>::report(const StripOrbitsRequest& req, const orbits::StripOrbitsResult& res,
                                      const core::Contents&, const Written& w) {
  if (!w.quiet)
    std::cerr << fmt::format(
        "btob: r = {}: {} orbits x {} iterations, {} periodic, {} quasi-periodic, {} other ({:.2f} s); "
        "wrote {}\n",
        req.r, req.orbits, req.iterations, res.periodic, res.quasi_periodic, res.other, res.seconds, w.listing());
}

// ---- leaves ----
void Spec<leaves::Request>::report(const leaves::Request&, const leaves::Result& res, const core::Contents&,
                                   const Written& w) {
  if (w.quiet) return;
  std::cerr << fmt::format("btob: leaves at {} r values, {} points each, in {:.2f} s; wrote {}\n", res.r.size(),
                           res.grid.cells(), res.seconds, w.listing());
  for (std::size_t i = 0; i < res.r.size(); ++i)
    std::cerr << fmt::format(
        "  r = {:.10g}: theta/2pi = {:.10f}, region {:.4f}, on a P2 curve {:.4f} [{:.4f}, {:.4f}], "
        "landing t mean {:.4f} sd {:.4f}\n",
        res.r[i], res.rotation[i], res.region_share[i], res.mass[i], res.mass_low[i], res.mass_high[i],
        res.landing_mean[i], res.landing_sd[i]);
}

// ---- transfer operator ----
void Spec<transfer::TransferRequest>::report(const transfer::TransferRequest&, const transfer::TransferResult& res,
                                             const core::Contents&, const Written& w) {
  if (!w.quiet) std::cerr << res.summary() << "btob: wrote " << w.listing() << "\n";
}

void Spec<transfer::TransferRRequest>::report(const transfer::TransferRRequest&, const transfer::TransferRResult& res,
                                              const core::Contents&, const Written& w) {
  if (!w.quiet) std::cerr << res.summary() << "btob: wrote " << w.listing() << "\n";
}

// ---- particles ----
void Spec<ParticlesRequest>::print(const ParticlesRequest& req, const particles::ParticlesResult& res) {
  std::cout << res.row_csv(req.header) << std::flush;
}

void Spec<ParticlesRequest>::warn(const ParticlesRequest&, const particles::ParticlesResult& res,
                                  const core::RunControl&) {
  if (!res.failure.empty()) std::cerr << "btob: warning: " << res.failure << "\n";  // even with --quiet
}

void Spec<ParticlesRequest>::report(const ParticlesRequest&, const particles::ParticlesResult& res,
                                    const core::Contents&, const Written& w) {
  if (!w.quiet) std::cerr << res.summary() << "btob: wrote " << w.listing() << "\n";
}

}  // namespace btob::commands
