// SPDX-License-Identifier: GPL-3.0-or-later
// Spectrum and feasibility quantities of a word's period matrix as functions of r (Figures 7.1-7.8).
#include "patterns/curves.hpp"

#include "core/cancel.hpp"
#include "core/csv.hpp"
#include "core/fields.hpp"
#include "iterate/parallel.hpp"

#include "patterns/analysis_impl.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace btob::patterns {
namespace {

// The spectrum is computed in long double: the smallest eigenvalues of these products are ~1e-13 of the
// largest at r ~ 0.005 (det = -r^11 or -r^14), and the tracked eigenvector's error grows as eps over its
// eigenvalue's distance to the others (eigenvector_error), so long double resolves it down to r = 0.0005 or so.
using L = long double;
struct Point {
  std::array<detail::Root<L>, 3> roots;  // real ascending, then complex
  int tracked = -1;
  double dominance = std::numeric_limits<double>::quiet_NaN();
  Vec3<L> u;      // tracked eigenvector, unit
  L u_error = 0;  // bound on the error of u's components (detail::eigenvector_error)
};

// Whether long double decides the tracked eigenvector: its direction to better than kResolved.  Below that the
// feasibility quantities are not computed (NaN) and a sign change of u_x or u_z is reported as undecided.
constexpr double kResolved = 1e-3;
bool resolved(const Point& p) { return p.tracked >= 0 && p.u_error < kResolved; }

// The spectrum of the analysed matrix at r (the word w is the primitive root; its half when reduced): the roots of
// the normalised matrix m's characteristic polynomial with exact coefficients (detail::char_poly); the tracked
// eigenvector and its error bound from m; the roots scaled back to the paper's unnormalised matrix.
Point at(const Word& w, bool reduced, double r_, bool negative) {
  Point p;
  const L r = r_;
  // Not polled inside (nullptr): a point is one r, and the callers poll between points (some in an OpenMP region).
  const detail::Scaled<L> A = detail::analysed_matrix<L>(w, r, reduced, nullptr);
  const std::array<L, 3> cp = detail::char_poly<L>(w, r, reduced, A, nullptr);
  p.roots = detail::cubic_roots<L>(-cp[0], cp[1], -cp[2]);
  std::sort(p.roots.begin(), p.roots.end(), [](const auto& a, const auto& b) {
    if (a.real != b.real) return a.real;
    return a.real ? a.re < b.re : a.im < b.im;
  });
  L best = -1;
  for (int i = 0; i < 3; ++i)
    if (p.roots[i].real && (!negative || p.roots[i].re < 0) && std::abs(p.roots[i].re) > best)
      best = std::abs(p.roots[i].re), p.tracked = i;
  if (p.tracked >= 0) {
    L other = 0;
    for (int i = 0; i < 3; ++i)
      if (i != p.tracked) other = std::max(other, detail::modulus(p.roots[i]));
    p.dominance = static_cast<double>((best - other) / best);
    p.u = detail::eigenvector<L>(A.m, p.roots[p.tracked].re);
    p.u_error = detail::eigenvector_error<L>(p.roots, p.tracked);  // A.m is normalised: max |A_ij| = 1
  }
  const L scale = std::exp(A.log_scale);
  for (auto& x : p.roots) x.re *= scale, x.im *= scale;
  return p;
}

}  // namespace

void CurvesRequest::validate() const {
  try {
    (void)parse_word(word, "word");
  } catch (const std::invalid_argument& e) {
    throw core::InvalidField("word", "'" + word + "'", "a word over 1,2,3 such as 132312 or 132^2312^2");
  }
  if (r_count < 2 || r_count > 1000000) throw core::InvalidField("r-count", fmt::format("{}", r_count), "2..1000000");
  core::require_r_range(r_min, r_max, r_count);
  if (track != "dominant" && track != "negative")
    throw core::InvalidField("track", "'" + track + "'", "dominant or negative");
}

namespace {

// The word analysed: its primitive root w (returned), and h = the half of w when w = h J(h) (reduced), else w; the
// names of the result and of the feasibility columns.
Word analysed_word(const CurvesRequest& q, CurvesResult& res) {
  const Word w = primitive_root(parse_word(q.word, "word"));
  res.word = to_paper(w);
  res.reduced = is_J_square(w);
  Word h;
  h.s.assign(w.s.begin(), w.s.begin() + static_cast<long>(res.reduced ? w.size() / 2 : w.size()));
  res.analysed = to_digits(h);
  res.feas_names.push_back("u_z");
  for (std::size_t k = 0; k < h.size(); ++k)
    for (const char* s : {"y", "ay-x", "ay-z"}) res.feas_names.push_back(fmt::format("{}(v{})", s, k));
  return w;
}

// The arrays of n r values, NaN where a value may stay undefined.
void allocate_curves(std::size_t n, std::size_t nf, CurvesResult& res) {
  res.r.resize(n);
  res.eig_re.assign(3 * n, 0);
  res.eig_im.assign(3 * n, 0);
  res.modulus.assign(3 * n, 0);
  res.tracked.assign(n, std::numeric_limits<double>::quiet_NaN());
  res.dominance.assign(n, std::numeric_limits<double>::quiet_NaN());
  res.feas.assign(n * nf, std::numeric_limits<double>::quiet_NaN());
  res.u_error.assign(n, std::numeric_limits<double>::quiet_NaN());
  res.resolved.assign(n, 0);
}

// Row i of the curves at r: the spectrum, the tracked eigenvalue and its dominance, and the feasibility quantities
// along the orbit of its eigenvector over the analysed word h (the paper's normalisation u_x = 1).
void curve_row(const Word& w, bool negative, std::size_t i, double r, CurvesResult& res) {
  const std::size_t p = res.reduced ? w.size() / 2 : w.size(), nf = 1 + 3 * p;
  res.r[i] = r;
  const Point pt = at(w, res.reduced, r, negative);
  for (int j = 0; j < 3; ++j) {
    res.eig_re[3 * i + j] = static_cast<double>(pt.roots[j].re);
    res.eig_im[3 * i + j] = pt.roots[j].real ? 0.0 : static_cast<double>(pt.roots[j].im);
    res.modulus[3 * i + j] = static_cast<double>(detail::modulus(pt.roots[j]));
  }
  if (pt.tracked < 0) return;
  res.tracked[i] = static_cast<double>(pt.roots[pt.tracked].re);
  res.dominance[i] = pt.dominance;
  res.u_error[i] = static_cast<double>(pt.u_error);
  res.resolved[i] = resolved(pt);
  if (pt.u(0) == 0 || !res.resolved[i]) return;
  Vec3<L> v = pt.u / pt.u(0);
  const L rl = r, a = core::alpha(rl);
  const std::array<Mat3<L>, 3> P = {core::P1(rl), core::P2(rl), core::P3(rl)};
  double* f = &res.feas[i * nf];
  f[0] = static_cast<double>(v(2));
  for (std::size_t k = 0; k < p; ++k) {
    f[1 + 3 * k] = static_cast<double>(v(1));
    f[2 + 3 * k] = static_cast<double>(a * v(1) - v(0));
    f[3 + 3 * k] = static_cast<double>(a * v(1) - v(2));
    v = P[w.s[k] - 1] * v;
  }
}

// The roots of f between consecutive r of the grid where its sign changes (both ends finite), bisected on f down
// to 1e-15 (a few ulps of r).  The token is polled every core::cancel_stride grid intervals.
template <class F>
std::vector<double> sign_changes(const std::vector<double>& grid, F f, const core::CancelToken* cancel) {
  std::vector<double> roots;
  for (std::size_t i = 0; i + 1 < grid.size(); ++i) {
    core::poll_cancel(cancel, static_cast<long>(i));
    double a = grid[i], b = grid[i + 1], fa = f(a), fb = f(b);
    if (!(std::isfinite(fa) && std::isfinite(fb)) || (fa > 0) == (fb > 0)) continue;
    while (b - a > 1e-15) {
      const double m = 0.5 * (a + b), fm = f(m);
      if (!std::isfinite(fm)) break;
      if ((fm > 0) == (fa > 0)) a = m, fa = fm;
      else b = m;
    }
    roots.push_back(0.5 * (a + b));
  }
  return roots;
}

// Critical r: sign changes of -u_x u_z (sign-free: u_x = 0 or u_z = 0, where u leaves the domain; named by the
// component that vanishes), then of the dominance margin.  A sign change is decided when, at both grid values
// around it, the eigenvector is resolved and |u_x u_z| exceeds its error bound (the signs are then those of the
// exact eigenvector, and it crosses in between); otherwise it is "undecided in long double" (at r near 0, where
// the tracked eigenvalue falls to ~1e-17 of the largest, its eigenvector is rounding).
void critical_points(const Word& w, bool negative, CurvesResult& res, const core::CancelToken* cancel) {
  const auto domain = [&](double r) {
    const Point pt = at(w, res.reduced, r, negative);
    return pt.tracked < 0 ? std::numeric_limits<double>::quiet_NaN() : static_cast<double>(pt.u(0) * -pt.u(2));
  };
  const auto certain = [&](double r) {
    const Point pt = at(w, res.reduced, r, negative);
    return resolved(pt) && std::abs(pt.u(0) * pt.u(2)) > pt.u_error;
  };
  for (double rc : sign_changes(res.r, domain, cancel)) {
    const Point pt = at(w, res.reduced, rc, negative);
    const auto i = static_cast<std::size_t>(std::upper_bound(res.r.begin(), res.r.end(), rc) - res.r.begin());
    const bool decided = i > 0 && i < res.r.size() && certain(res.r[i - 1]) && certain(res.r[i]);
    res.critical.push_back({!decided                                ? "undecided in long double"
                            : std::abs(pt.u(0)) < std::abs(pt.u(2)) ? "u_x = 0"
                                                                    : "u_z = 0",
                            rc});
  }
  for (double rc : sign_changes(
           res.r, [&](double r) { return at(w, res.reduced, r, negative).dominance; }, cancel))
    res.critical.push_back({"dominance", rc});
  for (const auto& c : res.critical) {
    res.critical_r.push_back(c.r);
    res.critical_what.push_back(c.what);
  }
}

}  // namespace

// word -> arrays -> a row per r (in parallel) -> critical r.
CurvesResult run(const CurvesRequest& q, const core::RunControl& control) {
  q.validate();
  core::check_cancel(control.cancel);
  CurvesResult res;
  res.request = q;
  const Word w = analysed_word(q, res);
  const bool negative = q.track == "negative";
  const std::size_t n = static_cast<std::size_t>(q.r_count);
  allocate_curves(n, res.feas_names.size(), res);
  iterate::parallel_for(n, control.threads, [&](std::size_t i) {
    if (control.cancel && control.cancel->cancelled()) return;  // no exception may leave an OpenMP region
    const double r = q.r_min + (q.r_max - q.r_min) * static_cast<double>(i) / static_cast<double>(n - 1);
    curve_row(w, negative, i, r, res);
  });
  core::check_cancel(control.cancel);
  critical_points(w, negative, res, control.cancel);
  if (control.progress) control.progress->update(1, 1);
  return res;
}

// What a critical r is: a sign change on the grid bisected in long double to 1e-15, then rounded to double (which
// holds every digit the bisection vouches for: no decimal); not proved.
namespace {
core::Status critical_status() {
  return core::estimated("sign change on the r grid bisected in long double to 1e-15 (absolute), rounded to double",
                         "error bar 1e-15 plus the rounding to double, a numerical bound without proof");
}
}  // namespace

std::string CurvesResult::critical_csv() const {
  core::CsvTable csv("what,r,status");  // status: docs/reference/numbers.md (critical_status)
  const std::string st = critical_status().kind;
  for (const auto& c : critical) csv.row({c.what, fmt::format("{:.16f}", c.r), st});
  return csv.text();
}

void CurvesResult::describe(core::Contents& c) const {
  const std::size_t n = r.size();
  c.array("r", r, {n}, "r", "1", "restitution coefficients, evenly spaced");
  c.array("eig_re", eig_re, {n, 3}, "r, eigenvalue (real roots ascending, then the complex pair)", "1",
          "real parts of the eigenvalues of the analysed matrix (not normalised)");
  c.array("eig_im", eig_im, {n, 3}, "r, eigenvalue", "1", "imaginary parts of the eigenvalues");
  c.array("modulus", modulus, {n, 3}, "r, eigenvalue", "1", "moduli of the eigenvalues");
  c.array("tracked", tracked, {n}, "r", "1", "the tracked eigenvalue (NaN where it is not real or not negative)");
  c.array("dominance", dominance, {n}, "r", "1", "(|tracked| - max |other|) / |tracked|: > 0 where it dominates");
  c.text("quantity", feas_names, "quantity", "name",
         "name of each column of feas: u_z, then y, ay-x, ay-z of each point v_k of the orbit (as feas_names)");
  c.array("feas", feas, {n, feas_names.size()}, "r, quantity", "1",
          "u_z, then y, alpha y - x, alpha y - z of v_0 .. v_{p-1} (eigenvector normalised by u_x = 1; NaN where "
          "not resolved)");
  c.array("u_error", u_error, {n}, "r", "1",
          "bound on the error of the tracked unit eigenvector's components in long double: 64 eps max|A_ij| / "
          "distance to the nearest other eigenvalue");
  c.array("resolved", resolved, {n}, "r", "1 (boolean)",
          "1 where u_error < 1e-3: the eigenvector, hence the feasibility quantities, decided in long double");
  c.array("critical_r", critical_r, {critical_r.size()}, "critical value", "1",
          "r where u_x = 0, u_z = 0 or dominance changes (bisected to 1e-15)");
  c.status_of("critical_r", critical_status());
  c.text("critical_what", critical_what, "critical value", "name",
         "what changes at each critical_r: u_x = 0, u_z = 0 (u leaves the domain), dominance, or undecided in "
         "long double (a sign change of u_x u_z where the eigenvector is not resolved)");
  std::string names;
  for (const auto& f : feas_names) names += (names.empty() ? "" : ",") + f;
  c.attr("feas_names", names);
  c.attr("word", word);
  c.attr("analysed", analysed);
  c.attr("reduced", static_cast<long>(reduced));
  c.attr("track", request.track);
  c.attr("r_min", request.r_min);
  c.attr("r_max", request.r_max);
  c.attr("r_count", request.r_count);
}

core::Work work(const CurvesRequest& req) {
  const double L = static_cast<double>(parse_word(req.word, "word").size()), R = static_cast<double>(req.r_count);
  core::Work w;
  core::Term t;
  t.route = "pattern-curves " + req.track;
  t.units = R * L;
  t.what = "r values x symbols of the word (a period matrix and its eigenvalues per r)";
  t.probe = [track = req.track](double n, const core::RunControl& c) {
    CurvesRequest p;  // 132312 over the default r range
    p.track = track;
    p.r_count = std::clamp(static_cast<long>(n / 6), 2L, 1000000L);
    (void)run(p, c);
    return 6.0 * static_cast<double>(p.r_count);
  };
  w.terms.push_back(std::move(t));
  // Per r: 3 eigenvalues (re, im, modulus), the tracked one and its dominance, and 1 + 3 L branch quantities, in
  // NAME.h5 (8 bytes) and NAME.csv (~20 bytes a number).
  w.output_bytes = R * (12 + 3 * L) * 28;
  w.peak_bytes = R * (12 + 3 * L) * 8 * 2 + 65536;
  return w;
}

}  // namespace btob::patterns
