// SPDX-License-Identifier: GPL-3.0-or-later
// Every command of btob, declared once (commands/spec.hpp says what a declaration holds).  The command line's
// subcommands and their flags, `btob run`'s scenes and manifests, and the Python module's functions and keywords are
// all generated from this list by for_each_command; none of them names a command anywhere else.
//
// A new analysis: its request and result in its module (fields, validate, run, describe, tables), one Spec here
// and its type in for_each_command.  The terminal words of a command (warn, print, report) are in
// commands/reports.cpp.
#pragma once

#include "attractors/requests.hpp"
#include "bifurcation/bifurcation.hpp"
#include "commands/spec.hpp"
#include "core/fields.hpp"
#include "leaves/requests.hpp"
#include "lyapunov/hyperbolicity_requests.hpp"
#include "lyapunov/requests.hpp"
#include "orbits/orbits.hpp"
#include "particles/particles.hpp"
#include "patterns/curves.hpp"
#include "patterns/requests.hpp"
#include "precision/tradeoff.hpp"
#include "stats/requests.hpp"
#include "transfer/transfer.hpp"
#include "windows/requests.hpp"

#include <fmt/format.h>

#include <string>
#include <vector>

namespace btob::commands {

// strip-orbits: the request and how its figure is drawn (presentation only: no number depends on these two fields,
// which the figure's script reads from the attributes).
struct StripOrbitsRequest : orbits::StripOrbitsRequest {
  double plot_w1 = 2;  // the plot shows -plot_w1 <= w1 <= plot_w1 (the paper: 2, and 30 for Figure 6.10)
  long only = 0;       // the plot shows only this orbit (1-based), 0 = all
  void validate() const;
  template <class V> void fields(V&& v) {
    orbits::StripOrbitsRequest::fields(v);
    v("plot-w1", plot_w1, "plot: -plot-w1 <= w1 <= plot-w1");
    v("only", only, "plot: only this orbit (1-based), 0 = all");
  }
};

// particles: the request and whether the printed row has its header line (presentation only).
struct ParticlesRequest : particles::ParticlesRequest {
  bool header = false;
  template <class V> void fields(V&& v) {
    particles::ParticlesRequest::fields(v);
    v("header", header, "print the CSV header line before the row (the command line's row on stdout)");
  }
};

}  // namespace btob::commands

namespace btob::commands {

// ---- the iterated map: bifurcation diagrams ----
template <> struct Spec<bifurcation::Request> : SpecBase<bifurcation::Request, Spec<bifurcation::Request>> {
  static constexpr const char* command = "bifurcation";
  static constexpr const char* function = "bifurcation";
  static constexpr const char* summary = "Tails of theta or phi against r, as a density image (Figures 4.x, 6.x)";
  static constexpr const char* folder = "results/bifurcation";
  static constexpr const char* stem = "bifurcation";
  static constexpr const char* kind = "bifurcation";
  static constexpr const char* plot = "bifurcation.py";
  static constexpr bool timed = true;
  static void warn(const bifurcation::Request&, const bifurcation::Result&, const core::RunControl&);
  static void report(const bifurcation::Request&, const bifurcation::Result&, const core::Contents&, const Written&);
};

// ---- Lyapunov exponents ----
template <> struct Spec<lyapunov::OrbitRequest> : SpecBase<lyapunov::OrbitRequest, Spec<lyapunov::OrbitRequest>> {
  static constexpr const char* command = "lyapunov";
  static constexpr const char* function = "lyapunov";
  static constexpr const char* summary =
      "Both Lyapunov exponents of one orbit (the projective derivative cocycle along the kernel's orbit: one tangent "
      "vector, Gram-Schmidt every few steps, lambda2 from the area growth) with batch-means error bars and weighted "
      "Birkhoff averages. Only the tangent cocycle is used: two nearby orbits straddle the branch boundaries of this "
      "piecewise-linear map and give wrong exponents";
  static constexpr const char* kind = "lyapunov";
  static void warn(const lyapunov::OrbitRequest&, const lyapunov::ProjectiveResult&, const core::RunControl&);
  static void print(const lyapunov::OrbitRequest&, const lyapunov::ProjectiveResult&);
  // convergence = FILE: the convergence table (n, lambda1, lambda2) also written to FILE as CSV.
  static void also_write(const lyapunov::OrbitRequest&, const lyapunov::ProjectiveResult&);
};

template <> struct Spec<lyapunov::MapRequest> : SpecBase<lyapunov::MapRequest, Spec<lyapunov::MapRequest>> {
  static constexpr const char* command = "lyapunov-map";
  static constexpr const char* function = "lyapunov_map";
  static constexpr const char* summary = "Lyapunov exponents of every orbit over r values x a grid, summarised per r";
  static constexpr const char* folder = "results/lyapunov";
  static constexpr const char* stem = "lyapunov_map";
  static constexpr const char* kind = "lyapunov-map";
  static constexpr const char* plot = "lyapunov_map.py";
  static void warn(const lyapunov::MapRequest&, const lyapunov::MapResult&, const core::RunControl&);
  static void report(const lyapunov::MapRequest&, const lyapunov::MapResult&, const core::Contents&, const Written&);
};

template <> struct Spec<lyapunov::StripRequest> : SpecBase<lyapunov::StripRequest, Spec<lyapunov::StripRequest>> {
  static constexpr const char* command = "lyapunov-strip";
  static constexpr const char* function = "lyapunov_strip";
  static constexpr const char* summary = "Lyapunov exponent at one r over a strip grid (w1, w2), as an image";
  static constexpr const char* folder = "results/lyapunov";
  static constexpr const char* stem = "lyapunov_strip";
  static constexpr const char* kind = "lyapunov-strip";
  static constexpr const char* plot = "lyapunov_strip.py";
  static void report(const lyapunov::StripRequest&, const lyapunov::MapResult&, const core::Contents&, const Written&);
};

template <>
struct Spec<lyapunov::HyperbolicityRequest>
    : SpecBase<lyapunov::HyperbolicityRequest, Spec<lyapunov::HyperbolicityRequest>> {
  static constexpr const char* command = "hyperbolicity";
  static constexpr const char* function = "hyperbolicity";
  static constexpr const char* summary =
      "Singular values of the one-step derivative of the projective map over a strip grid";
  static constexpr const char* folder = "results/hyperbolicity";
  static constexpr const char* kind = "hyperbolicity-strip";
  static constexpr const char* plot = "hyperbolicity_strip.py";
  static void print(const lyapunov::HyperbolicityRequest&, const lyapunov::HyperbolicityResult&);
  static void report(const lyapunov::HyperbolicityRequest&, const lyapunov::HyperbolicityResult&, const core::Contents&,
                     const Written&);
};

template <>
struct Spec<lyapunov::HyperbolicityOrbitsRequest>
    : SpecBase<lyapunov::HyperbolicityOrbitsRequest, Spec<lyapunov::HyperbolicityOrbitsRequest>> {
  static constexpr const char* command = "hyperbolicity-orbits";
  static constexpr const char* function = "hyperbolicity_orbits";
  static constexpr const char* summary =
      "Per r: fraction of expanding steps and CLV angles (Ginelli) along orbits, beside lambda1";
  static constexpr const char* folder = "results/hyperbolicity";
  static constexpr const char* stem = "hyperbolicity_orbits";
  static constexpr const char* kind = "hyperbolicity-orbits";
  static constexpr const char* plot = "hyperbolicity_orbits.py";
  static void report(const lyapunov::HyperbolicityOrbitsRequest&, const lyapunov::HyperbolicityOrbitsResult&,
                     const core::Contents&, const Written&);
};

// ---- attractors ----
template <>
struct Spec<attractors::ClassifyRequest> : SpecBase<attractors::ClassifyRequest, Spec<attractors::ClassifyRequest>> {
  static constexpr const char* command = "classify";
  static constexpr const char* function = "classify";
  static constexpr const char* summary = "Classify one orbit: periodic, collapse, quasi-periodic, chaotic or undecided";
  static constexpr const char* kind = "classify";
  static constexpr bool served = true;  // the explorer's orbit panel
  static void print(const attractors::ClassifyRequest&, const attractors::ClassifyResult&);
};

template <>
struct Spec<attractors::BasinsRequest> : SpecBase<attractors::BasinsRequest, Spec<attractors::BasinsRequest>> {
  static constexpr const char* command = "basins";
  static constexpr const char* function = "basins";
  static constexpr const char* summary =
      "Basins of the attractors at one r over a grid: image, fractions with Clopper-Pearson 95% intervals, basin "
      "entropies, uncertainty exponent, Wada test; writes NAME_fractions.csv, NAME_boundary.csv, NAME.h5, NAME.json, "
      "NAME.png";
  static constexpr const char* folder = "results/attractors/basins";
  static constexpr const char* stem = "basins";
  static constexpr const char* kind = "basins";
  static constexpr const char* plot = "attractors_basins.py";
  static constexpr bool served = true;  // the explorer's basins panel
  static void report(const attractors::BasinsRequest&, const attractors::BasinsResult&, const core::Contents&,
                     const Written&);
};

template <>
struct Spec<attractors::BasinsRRequest> : SpecBase<attractors::BasinsRRequest, Spec<attractors::BasinsRRequest>> {
  static constexpr const char* command = "basins-r";
  static constexpr const char* function = "basins_r";
  static constexpr const char* summary =
      "Basin fractions across r (Table 6.1 with many orbits), stacked areas, and basin entropies and uncertainty "
      "exponent per r; writes NAME.csv, table_6_1_comparison.csv, NAME_boundary.csv, NAME.h5, NAME.json, NAME.png";
  static constexpr const char* folder = "results/attractors/basins_r";
  static constexpr const char* stem = "fractions_r";
  static constexpr const char* kind = "basins-r";
  static constexpr const char* plot = "attractors_fractions_r.py";
  // table: Table 6.1 is data of the lab (io::data_file) unless reference names another CSV; read before the request
  // is validated, so that a dry run samples its r values too.
  static void prepare(attractors::BasinsRRequest& req);
  static void report(const attractors::BasinsRRequest&, const attractors::BasinsRResult&, const core::Contents&,
                     const Written&);
};

// ---- statistics (Section 8.1 (2)) ----
template <> struct Spec<stats::CorrelateRequest> : SpecBase<stats::CorrelateRequest, Spec<stats::CorrelateRequest>> {
  static constexpr const char* command = "correlate";
  static constexpr const char* function = "correlate";
  static constexpr const char* summary =
      "C_N(phi, psi; n) = (1/N) sum_{k<N} phi(x_k) psi(x_{k+n}) - mean(phi) mean(psi), n = 0..n-max, along one orbit, "
      "its envelope, decay rate and power spectrum (Section 8.1 (2)); writes NAME.csv (lag,C_N), NAME.h5, NAME.json, "
      "NAME.png";
  static constexpr const char* folder = "results/stats";
  static constexpr const char* stem = "correlation";
  static constexpr const char* kind = "correlate";
  static constexpr const char* plot = "stats_correlation.py";
  static void report(const stats::CorrelateRequest&, const stats::CorrelateResult&, const core::Contents&,
                     const Written&);
};

template <> struct Spec<stats::MeasureRequest> : SpecBase<stats::MeasureRequest, Spec<stats::MeasureRequest>> {
  static constexpr const char* command = "measure";
  static constexpr const char* function = "measure";
  static constexpr const char* summary =
      "Empirical measures mu_{N,x} = (1/N) sum_{k<N} delta_{x_k} of many initial conditions at one r (Section 8.1 "
      "(2)): 2-D histograms, marginals, total variation and 1-D Wasserstein distances, groups of coinciding "
      "measures, convergence against N; writes NAME.h5, NAME_report.csv, NAME.json, NAME.png";
  static constexpr const char* folder = "results/stats";
  static constexpr const char* stem = "measure";
  static constexpr const char* kind = "measure";
  static constexpr const char* plot = "stats_measure.py";
  static void report(const stats::MeasureRequest&, const stats::MeasureResult&, const core::Contents&, const Written&);
};

// ---- precision ----
template <>
struct Spec<precision::TradeoffRequest> : SpecBase<precision::TradeoffRequest, Spec<precision::TradeoffRequest>> {
  static constexpr const char* command = "precision";
  static constexpr const char* function = "precision_study";
  static constexpr const char* summary =
      "Speed against accuracy of each precision and algorithm (vs 256-digit MPFR). Most of its time is fixed parts "
      "(each method's window tests up to the largest window-n, its Lyapunov errors on the sinks and its throughput), "
      "about a minute whatever the orbits, which no short probe prices: the dry run of a request not yet run on this "
      "machine runs it once (writing nothing); a completed run keeps its time for the dry runs after it";
  static constexpr const char* folder = "results/precision";
  static constexpr const char* stem = "tradeoff";
  static constexpr const char* kind = "precision_tradeoff";
  static constexpr const char* plot = "precision_tradeoff.py";
  template <class Res> static std::string scalar(const precision::TradeoffRequest&, const Res&) {
    return "float,double,long-double,float128,mpfr:50,mpfr:100,mpfr:256";
  }
  static void print(const precision::TradeoffRequest&, const precision::TradeoffResult&);
};

// ---- windows of stability (Section 4, Appendix B) ----
template <> struct Spec<windows::PolyRequest> : SpecBase<windows::PolyRequest, Spec<windows::PolyRequest>> {
  static constexpr const char* command = "windows poly";
  static constexpr const char* function = "windows_poly";
  static constexpr const char* summary =
      "Q_n = r^2n P_n(r) P_n(1/r) - r^2n exactly, developed and factorised (Table B.2)";
  static constexpr const char* kind = "windows_poly";
  static void print(const windows::PolyRequest&, const windows::PolyResult&);
};

template <> struct Spec<windows::BoundsRequest> : SpecBase<windows::BoundsRequest, Spec<windows::BoundsRequest>> {
  static constexpr const char* command = "windows bounds";
  static constexpr const char* function = "windows_bounds";
  static constexpr const char* summary =
      "Window lower bounds and r_crit,2(n) (Table B.1) as exact decimals, CSV n,lower_bound,upper_bound; certify adds "
      "exact certificates";
  static constexpr const char* kind = "windows_bounds";
  static void warn(const windows::BoundsRequest&, const windows::BoundsResult&, const core::RunControl&);
  static void print(const windows::BoundsRequest&, const windows::BoundsResult&);
};

template <>
struct Spec<windows::ThresholdsRequest> : SpecBase<windows::ThresholdsRequest, Spec<windows::ThresholdsRequest>> {
  static constexpr const char* command = "windows thresholds";
  static constexpr const char* function = "windows_thresholds";
  static constexpr const char* summary = "7-4sqrt3, 3-2sqrt2, 5-2sqrt6, 2^(2/3)-1 in high precision";
  static constexpr const char* kind = "windows_thresholds";
  static void print(const windows::ThresholdsRequest&, const windows::ThresholdsResult&);
};

template <> struct Spec<windows::StripesRequest> : SpecBase<windows::StripesRequest, Spec<windows::StripesRequest>> {
  static constexpr const char* command = "windows stripes";
  static constexpr const char* function = "windows_stripes";
  static constexpr const char* summary = "Thin stripes r(l/m), eq. (6.3), 1/4 < l/m <= 1/2, m <= max-m";
  static constexpr const char* kind = "windows_stripes";
  static void print(const windows::StripesRequest&, const windows::StripesResult&);
};

template <> struct Spec<windows::VerifyRequest> : SpecBase<windows::VerifyRequest, Spec<windows::VerifyRequest>> {
  static constexpr const char* command = "windows verify";
  static constexpr const char* function = "windows_verify";
  static constexpr const char* summary =
      "Iterate the Section 4 grid inside and below each window: is the pattern (ab)^n(cb)^n reached? CSV + manifest "
      "(file stem verify for n = 2..125, else verify_A-B, unless a name is given)";
  static constexpr const char* folder = "results/windows";
  static constexpr const char* kind = "windows_verify";
  static void report(const windows::VerifyRequest&, const windows::VerifyResult&, const core::Contents&,
                     const Written&);
};

template <>
struct Spec<windows::BoundPrecisionRequest>
    : SpecBase<windows::BoundPrecisionRequest, Spec<windows::BoundPrecisionRequest>> {
  static constexpr const char* command = "windows precision";
  static constexpr const char* function = "windows_precision";
  static constexpr const char* summary = "Largest n with a 12-decimal window bound per precision and route; CSV + PNG";
  static constexpr const char* folder = "results/windows";
  static constexpr const char* stem = "precision";
  static constexpr const char* kind = "windows_precision";
  static constexpr const char* plot = "windows_precision.py";
  static std::vector<std::string> plot_inputs() { return {".h5"}; }
  template <class Res> static std::string scalar(const windows::BoundPrecisionRequest& req, const Res&) {
    return fmt::format("float,double,long-double,float128,mpfr:{}", req.mpfr_digits);
  }
  static void print(const windows::BoundPrecisionRequest&, const windows::BoundPrecisionResult&);
};

// ---- periodic patterns (Sections 6.2, 7) ----
template <> struct Spec<patterns::WordRequest> : SpecBase<patterns::WordRequest, Spec<patterns::WordRequest>> {
  static constexpr const char* command = "pattern";
  static constexpr const char* function = "pattern";
  static constexpr const char* summary =
      "Periodic pattern WORD: verdict at r (spectrum, stability, orbit), window its stability set, charpoly its exact "
      "characteristic polynomial; the atlas of every word up to a length (pattern atlas)";
  static constexpr const char* kind = "pattern";
  static void warn(const patterns::WordRequest&, const patterns::WordResult&, const core::RunControl&);
  static void print(const patterns::WordRequest&, const patterns::WordResult&);
};

template <> struct Spec<patterns::AtlasRequest> : SpecBase<patterns::AtlasRequest, Spec<patterns::AtlasRequest>> {
  static constexpr const char* command = "pattern atlas";
  static constexpr const char* function = "pattern_atlas";
  static constexpr const char* summary =
      "Every canonical primitive word up to a length: stability sets, checked against the iterator";
  static constexpr const char* folder = "results/patterns";
  static constexpr const char* kind = "patterns-atlas";
  static constexpr bool timed = true;
  static std::string kind_of(const patterns::AtlasRequest& req) {
    return req.feasible ? "patterns-feasible-atlas" : "patterns-atlas";
  }
  static std::string plot_of(const patterns::AtlasRequest& req) {
    return req.feasible ? "patterns_feasible.py" : "patterns_atlas.py";
  }
  static std::vector<std::string> plot_inputs() { return {".h5"}; }
  static void report(const patterns::AtlasRequest&, const patterns::AtlasResult&, const core::Contents&,
                     const Written&);
};

template <> struct Spec<patterns::CurvesRequest> : SpecBase<patterns::CurvesRequest, Spec<patterns::CurvesRequest>> {
  static constexpr const char* command = "pattern-curves";
  static constexpr const char* function = "pattern_curves";
  static constexpr const char* summary =
      "Spectrum and feasibility quantities of a word's period matrix against r (Figures 7.1-7.8)";
  static constexpr const char* folder = "results/pattern_curves";
  static constexpr const char* stem = "curves";
  static constexpr const char* kind = "pattern-curves";
  static constexpr const char* plot = "pattern_curves.py";
  static constexpr bool timed = true;
  static std::vector<std::string> plot_inputs() { return {".h5"}; }
  static constexpr bool plot_many = true;
  template <class Res> static std::string scalar(const patterns::CurvesRequest&, const Res&) {
    return "double (spectrum in long double)";
  }
  static void report(const patterns::CurvesRequest&, const patterns::CurvesResult&, const core::Contents&,
                     const Written&);
};

// ---- orbits, leaves, transfer operator, particles ----
template <> struct Spec<StripOrbitsRequest> : SpecBase<StripOrbitsRequest, Spec<StripOrbitsRequest>> {
  static constexpr const char* command = "strip-orbits";
  static constexpr const char* function = "strip_orbits";
  static constexpr const char* summary =
      "Tails of orbits at one r in the strip (w1, w2), each titled by the classifier's verdict (Figures 6.9-6.11)";
  static constexpr const char* folder = "results/strip_orbits";
  static constexpr const char* stem = "strip_orbits";
  static constexpr const char* kind = "strip-orbits";
  static constexpr const char* plot = "strip_orbits.py";
  static constexpr bool served = true;  // orbits at the picked r, for a page that draws them
  static std::vector<std::string> plot_inputs() { return {".h5"}; }
  static void attrs(const StripOrbitsRequest& req, const orbits::StripOrbitsResult&, core::Attrs& at);
  static void report(const StripOrbitsRequest&, const orbits::StripOrbitsResult&, const core::Contents&,
                     const Written&);
};

template <> struct Spec<leaves::Request> : SpecBase<leaves::Request, Spec<leaves::Request>> {
  static constexpr const char* command = "leaves";
  static constexpr const char* function = "leaves";
  static constexpr const char* summary =
      "P2's invariant curves: labels, region, rotation numbers, where orbits land and the measure on a leaf, at one "
      "r or across r; writes NAME.csv, NAME_landing.csv, NAME_leaves.csv, NAME.h5, NAME.json, NAME.png";
  static constexpr const char* folder = "results/leaves";
  static constexpr const char* stem = "leaves";
  static constexpr const char* kind = "leaves";
  static constexpr const char* plot = "leaves.py";
  static void report(const leaves::Request&, const leaves::Result&, const core::Contents&, const Written&);
};

template <>
struct Spec<transfer::TransferRequest> : SpecBase<transfer::TransferRequest, Spec<transfer::TransferRequest>> {
  static constexpr const char* command = "transfer";
  static constexpr const char* function = "transfer";
  static constexpr const char* summary =
      "Ulam's transfer operator of P^_r on a box partition (Section 8): leading spectrum (Spectra), closed classes "
      "and invariant densities, projection of Lebesgue measure, almost-invariant sets, TV distance to the empirical "
      "measure, basins from the Ulam graph (absorption into the named attractors; without cycle, into those found by "
      "classifying the closed classes' boxes); writes spectrum.csv, components.csv, cycles.csv, basins.csv, "
      "classes.csv, NAME.h5/.json/.png";
  static constexpr const char* folder = "results/transfer/r0.15";
  static constexpr const char* stem = "transfer";
  static constexpr const char* kind = "transfer";
  static constexpr const char* plot = "transfer.py";
  static void report(const transfer::TransferRequest&, const transfer::TransferResult&, const core::Contents&,
                     const Written&);
};

template <>
struct Spec<transfer::TransferRRequest> : SpecBase<transfer::TransferRRequest, Spec<transfer::TransferRRequest>> {
  static constexpr const char* command = "transfer-r";
  static constexpr const char* function = "transfer_r";
  static constexpr const char* summary =
      "Peripheral spectrum of Ulam's operator across r (eigenvalues within peripheral of the unit circle) and its gap "
      "to the rest; writes spectrum_r.csv, peripheral_r.csv, windows.csv, NAME.h5/.json/.png";
  static constexpr const char* folder = "results/transfer/r_scan";
  static constexpr const char* stem = "transfer_r";
  static constexpr const char* kind = "transfer-r";
  static constexpr const char* plot = "transfer_r.py";
  static void report(const transfer::TransferRRequest&, const transfer::TransferRResult&, const core::Contents&,
                     const Written&);
};

template <> struct Spec<ParticlesRequest> : SpecBase<ParticlesRequest, Spec<ParticlesRequest>> {
  static constexpr const char* command = "particles";
  static constexpr const char* function = "particles";
  static constexpr const char* summary =
      "Four particles realise the periodic pattern WORD: event-driven collapse, letters and contraction per period "
      "against the period matrix; prints word,r,periods,letters,sequence_ok,contraction,predicted,time_to_collapse";
  static constexpr const char* folder = "";  // no default: the output folder must be given
  static constexpr const char* stem = "particles";
  static constexpr const char* kind = "particles";
  static constexpr const char* plot = "particles.py";
  static std::vector<std::string> plot_inputs() { return {".h5"}; }
  static constexpr bool plot_many = true;
  static void warn(const ParticlesRequest&, const particles::ParticlesResult&, const core::RunControl&);
  static void print(const ParticlesRequest&, const particles::ParticlesResult&);
  static void report(const ParticlesRequest&, const particles::ParticlesResult&, const core::Contents&, const Written&);
};

// Calls f.template operator()<Req>() for every declared request, in the order of `btob --help` and of the Python
// module's functions.
template <class F> void for_each_command(F&& f) {
  f.template operator()<bifurcation::Request>();
  f.template operator()<lyapunov::OrbitRequest>();
  f.template operator()<lyapunov::MapRequest>();
  f.template operator()<lyapunov::StripRequest>();
  f.template operator()<lyapunov::HyperbolicityRequest>();
  f.template operator()<lyapunov::HyperbolicityOrbitsRequest>();
  f.template operator()<attractors::ClassifyRequest>();
  f.template operator()<attractors::BasinsRequest>();
  f.template operator()<attractors::BasinsRRequest>();
  f.template operator()<stats::CorrelateRequest>();
  f.template operator()<stats::MeasureRequest>();
  f.template operator()<precision::TradeoffRequest>();
  f.template operator()<windows::PolyRequest>();
  f.template operator()<windows::BoundsRequest>();
  f.template operator()<windows::ThresholdsRequest>();
  f.template operator()<windows::StripesRequest>();
  f.template operator()<windows::VerifyRequest>();
  f.template operator()<windows::BoundPrecisionRequest>();
  f.template operator()<patterns::WordRequest>();
  f.template operator()<patterns::AtlasRequest>();
  f.template operator()<patterns::CurvesRequest>();
  f.template operator()<StripOrbitsRequest>();
  f.template operator()<leaves::Request>();
  f.template operator()<transfer::TransferRequest>();
  f.template operator()<transfer::TransferRRequest>();
  f.template operator()<ParticlesRequest>();
}

}  // namespace btob::commands
