// SPDX-License-Identifier: GPL-3.0-or-later
// The compiled module btob._btob: every request-based analysis bound by the one template of bind.hpp; the table
// below only names each one (Python function, kind and file stem as the command line records them, plot script).
#include "attractors/requests.hpp"
#include "bifurcation/bifurcation.hpp"
#include "bind.hpp"
#include "io/citation.hpp"
#include "leaves/requests.hpp"
#include "lyapunov/hyperbolicity_requests.hpp"
#include "lyapunov/requests.hpp"
#include "orbits/orbits.hpp"
#include "patterns/curves.hpp"
#include "patterns/requests.hpp"
#include "precision/tradeoff.hpp"
#include "stats/requests.hpp"
#include "windows/requests.hpp"

#include <btob/build_info.hpp>
#include <fmt/format.h>

namespace btob::python {

void bind_result(py::module_& m);
void bind_blocks(py::module_& m);

#define BTOB_ROUTE(REQ, FUNCTION, COMMAND, KIND, STEM, PLOT, HELP) \
  template <> struct Route<REQ> : RouteBase<REQ, Route<REQ>> {     \
    static constexpr const char* function = FUNCTION;              \
    static constexpr const char* command = COMMAND;                \
    static constexpr const char* kind = KIND;                      \
    static constexpr const char* stem = STEM;                      \
    static constexpr const char* plot = PLOT;                      \
    static constexpr const char* help = HELP;                      \
    BTOB_ROUTE_BODY                                                \
  };

// Routes whose scalar_type attribute is "double" (the default) and need nothing before the run.
#define BTOB_ROUTE_BODY
BTOB_ROUTE(
    attractors::BasinsRequest, "basins", "basins", "basins", "basins", "attractors_basins.py",
    "Basins of the attractors at one r over a grid: labels image and fractions with Clopper-Pearson 95% intervals")
BTOB_ROUTE(lyapunov::HyperbolicityOrbitsRequest, "hyperbolicity_orbits", "hyperbolicity-orbits", "hyperbolicity-orbits",
           "hyperbolicity_orbits", "hyperbolicity_orbits.py",
           "Per r: fraction of expanding steps and CLV angles along orbits, beside lambda1")
BTOB_ROUTE(attractors::ClassifyRequest, "classify", "classify", "classify", "classify", "",
           "Classify one orbit: periodic, collapse, quasi-periodic, chaotic or undecided")
BTOB_ROUTE(stats::MeasureRequest, "measure", "measure", "measure", "measure", "stats_measure.py",
           "Empirical measures of many initial conditions at one r, their distances and convergence (Section 8.1 (2))")
BTOB_ROUTE(windows::PolyRequest, "windows_poly", "windows poly", "windows_poly", "poly", "",
           "Q_n = r^2n P_n(r) P_n(1/r) - r^2n exactly, developed and factorised (Table B.2)")
BTOB_ROUTE(windows::BoundsRequest, "windows_bounds", "windows bounds", "windows_bounds", "bounds", "",
           "Window lower bounds and r_crit,2(n) (Table B.1) as exact decimals; certify=True adds exact certificates")
BTOB_ROUTE(windows::ThresholdsRequest, "windows_thresholds", "windows thresholds", "windows_thresholds", "thresholds",
           "", "7-4sqrt3, 3-2sqrt2, 5-2sqrt6, 2^(2/3)-1 in high precision")
BTOB_ROUTE(windows::StripesRequest, "windows_stripes", "windows stripes", "windows_stripes", "stripes", "",
           "Thin stripes r(l/m), eq. (6.3), 1/4 < l/m <= 1/2, m <= max_m")
BTOB_ROUTE(leaves::Request, "leaves", "leaves", "leaves", "leaves", "leaves.py",
           "P2's invariant curves: labels, region, rotation numbers, where orbits land and the measure on a leaf")
#undef BTOB_ROUTE_BODY

// Routes whose scalar_type is the request's precision.
#define BTOB_ROUTE_BODY \
  template <class Res> static std::string scalar(const auto& req, const Res&) { return req.precision; }
BTOB_ROUTE(lyapunov::MapRequest, "lyapunov_map", "lyapunov-map", "lyapunov-map", "lyapunov_map", "lyapunov_map.py",
           "Lyapunov exponents of every orbit over r values x a grid, summarised per r")
BTOB_ROUTE(lyapunov::StripRequest, "lyapunov_strip", "lyapunov-strip", "lyapunov-strip", "lyapunov_strip",
           "lyapunov_strip.py", "Lyapunov exponent at one r over a strip grid (w1, w2), as an image")
BTOB_ROUTE(stats::CorrelateRequest, "correlate", "correlate", "correlate", "correlation", "stats_correlation.py",
           "C_N(phi, psi; n) along one orbit, its envelope, decay rate and power spectrum (Section 8.1 (2))")
#undef BTOB_ROUTE_BODY

// The rest, one by one.
#define BTOB_ROUTE_BODY                                                                                 \
  template <class Res> static std::string scalar(const auto& req, const Res&) { return req.precision; } \
  static std::string name_of(const auto& req) { return req.default_name(); }
BTOB_ROUTE(windows::VerifyRequest, "windows_verify", "windows verify", "windows_verify", "verify", "",
           "Iterate the Section 4 grid inside and below each window: is the pattern (ab)^n(cb)^n reached?")
#undef BTOB_ROUTE_BODY
// The strip orbits' figure: the script reads the saved NAME.h5 (verdicts included), as the command line runs it.
#define BTOB_ROUTE_BODY \
  static std::vector<std::string> plot_inputs() { return {".h5"}; }
BTOB_ROUTE(orbits::StripOrbitsRequest, "strip_orbits", "strip-orbits", "strip-orbits", "strip_orbits",
           "strip_orbits.py", "Tails of orbits at one r in the strip (w1, w2), each classified (Figures 6.9-6.11)")
#undef BTOB_ROUTE_BODY
// convergence: the command line writes the table to a CSV file; Python has it as arrays of every result, so a
// path is refused (accepting and ignoring it would lie).
#define BTOB_ROUTE_BODY                                                                                    \
  template <class Res> static std::string scalar(const auto& req, const Res&) { return req.precision; }    \
  static void prepare(lyapunov::OrbitRequest& req) {                                                       \
    if (!req.convergence.empty())                                                                          \
      throw core::InvalidField("convergence", "'" + req.convergence + "'",                                 \
                               "no value (a CSV file of the command line; in Python every result holds "   \
                               "the table: res.convergence_n, convergence_lambda1, convergence_lambda2)"); \
  }
BTOB_ROUTE(lyapunov::OrbitRequest, "lyapunov", "lyapunov", "lyapunov", "lyapunov", "",
           "Both Lyapunov exponents of one orbit (projective derivative cocycle, QR) with batch-means error bars")
#undef BTOB_ROUTE_BODY
#define BTOB_ROUTE_BODY \
  template <class Res> static std::string scalar(const auto&, const Res& res) { return res.scalar_type; }
BTOB_ROUTE(bifurcation::Request, "bifurcation", "bifurcation", "bifurcation", "bifurcation", "bifurcation.py",
           "Tails of theta or phi against r, as a density image (Figures 4.x, 6.x)")
#undef BTOB_ROUTE_BODY
#define BTOB_ROUTE_BODY \
  template <class Res> static std::string scalar(const auto&, const Res& res) { return res.scalar_type; }
BTOB_ROUTE(patterns::WordRequest, "pattern", "pattern", "pattern", "pattern", "",
           "Periodic pattern WORD: verdict at r (spectrum, stability, orbit), window=True its stability set, "
           "charpoly=True its exact characteristic polynomial; numbers in the precision's digits come back as text")
#undef BTOB_ROUTE_BODY
#define BTOB_ROUTE_BODY                                                                                               \
  static std::string name_of(const auto& req) { return req.default_name(); }                                          \
  static std::string kind_of(const auto& req) { return req.feasible ? "patterns-feasible-atlas" : "patterns-atlas"; } \
  static std::string plot_of(const auto& req) { return req.feasible ? "patterns_feasible.py" : "patterns_atlas.py"; } \
  static std::vector<std::string> plot_inputs() { return {".h5"}; }
BTOB_ROUTE(patterns::AtlasRequest, "pattern_atlas", "pattern atlas", "patterns-atlas", "", "",
           "Every canonical primitive word up to a length: stability sets, checked against the iterator")
#undef BTOB_ROUTE_BODY
#define BTOB_ROUTE_BODY                                                     \
  template <class Res> static std::string scalar(const auto&, const Res&) { \
    return "double (spectrum in long double)";                              \
  }                                                                         \
  static std::vector<std::string> plot_inputs() { return {".h5"}; }         \
  static constexpr bool plot_many = true;
BTOB_ROUTE(patterns::CurvesRequest, "pattern_curves", "pattern-curves", "pattern-curves", "curves", "pattern_curves.py",
           "Spectrum and feasibility quantities of a word's period matrix against r (Figures 7.1-7.8)")
#undef BTOB_ROUTE_BODY
#define BTOB_ROUTE_BODY \
  static std::string name_of(const auto& req) { return req.default_name(); }
BTOB_ROUTE(lyapunov::HyperbolicityRequest, "hyperbolicity", "hyperbolicity", "hyperbolicity-strip", "",
           "hyperbolicity_strip.py",
           "Singular values of the one-step derivative of the projective map over a strip grid")
#undef BTOB_ROUTE_BODY
#define BTOB_ROUTE_BODY                                                           \
  static void prepare(attractors::BasinsRRequest& req) {                          \
    req.reference_csv = io::data_text(req.reference, attractors::table_6_1_file); \
  }
BTOB_ROUTE(attractors::BasinsRRequest, "basins_r", "basins-r", "basins-r", "fractions_r", "attractors_fractions_r.py",
           "Basin fractions across r (Table 6.1 with many orbits)")
#undef BTOB_ROUTE_BODY
#define BTOB_ROUTE_BODY                                                     \
  template <class Res> static std::string scalar(const auto&, const Res&) { \
    return "float,double,long-double,float128,mpfr:50,mpfr:100,mpfr:256";   \
  }
BTOB_ROUTE(precision::TradeoffRequest, "precision_study", "precision", "precision_tradeoff", "tradeoff",
           "precision_tradeoff.py", "Speed against accuracy of each precision and algorithm (vs 256-digit MPFR)")
#undef BTOB_ROUTE_BODY
#define BTOB_ROUTE_BODY                                                               \
  template <class Res> static std::string scalar(const auto& req, const Res&) {       \
    return fmt::format("float,double,long-double,float128,mpfr:{}", req.mpfr_digits); \
  }                                                                                   \
  static std::vector<std::string> plot_inputs() { return {".h5"}; }
BTOB_ROUTE(windows::BoundPrecisionRequest, "windows_precision", "windows precision", "windows_precision", "precision",
           "windows_precision.py", "Largest n with a 12-decimal window bound per precision and route")
#undef BTOB_ROUTE_BODY
#undef BTOB_ROUTE

}  // namespace btob::python

PYBIND11_MODULE(_btob, m) {
  using namespace btob;
  using namespace btob::python;
  m.doc() = "btob: the b-to-b map of four inelastic hard spheres (compiled core; import btob instead)";
  m.attr("__version__") = build::version;
  m.attr("git_commit") = build::git_commit;
  m.def(
      "cite", [](const std::string& format) { return io::citation(format); }, pybind11::arg("format") = "bibtex",
      "How to cite btob (the software at this build's version and commit, and the paper): format 'bibtex', 'cff' "
      "or 'text', as `btob cite --format F` prints it");
  bind_result(m);
  bind<bifurcation::Request>(m);
  bind<lyapunov::OrbitRequest>(m);
  bind<lyapunov::MapRequest>(m);
  bind<lyapunov::StripRequest>(m);
  bind<lyapunov::HyperbolicityRequest>(m);
  bind<lyapunov::HyperbolicityOrbitsRequest>(m);
  bind<attractors::ClassifyRequest>(m);
  bind<attractors::BasinsRequest>(m);
  bind<attractors::BasinsRRequest>(m);
  bind<stats::CorrelateRequest>(m);
  bind<stats::MeasureRequest>(m);
  bind<precision::TradeoffRequest>(m);
  bind<windows::PolyRequest>(m);
  bind<windows::BoundsRequest>(m);
  bind<windows::ThresholdsRequest>(m);
  bind<windows::StripesRequest>(m);
  bind<windows::VerifyRequest>(m);
  bind<windows::BoundPrecisionRequest>(m);
  bind<patterns::WordRequest>(m);
  bind<patterns::AtlasRequest>(m);
  bind<patterns::CurvesRequest>(m);
  bind<orbits::StripOrbitsRequest>(m);
  bind<leaves::Request>(m);
  bind_blocks(m);
}
