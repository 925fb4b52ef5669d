// SPDX-License-Identifier: GPL-3.0-or-later
// Template bodies of the scans in r (Section 7): the quantities of the paper's critical values and their roots, the
// stability set and the feasibility set of a word, with the refinement of their grid at spectral events.
#pragma once

#include "patterns/analysis_impl.hpp"

#include <algorithm>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

namespace btob::patterns {

template <class T> T quantity(const Word& w0, const T& r, Track track, Quantity q, const core::CancelToken* cancel) {
  using namespace detail;
  check_inputs(w0, r);
  const Word w = primitive_root(w0);
  const Spectrum<T> s = spectrum(w, r, is_J_square(w), cancel);
  int idx = -1;
  for (int i = 0; i < 3 && idx < 0; ++i)
    if (s.roots[i].real && (track == Track::dominant_real || s.roots[i].re < 0)) idx = i;
  if (idx < 0) return std::numeric_limits<T>::quiet_NaN();
  if (q == Quantity::dominance_gap) {
    T other = T(0);
    for (int i = 0; i < 3; ++i)
      if (i != idx) other = std::max<T>(other, s.mod[i]);
    return (s.mod[idx] - other) / s.mod[idx];
  }
  const Vec3<T> u = eigenvector<T>(s.A.m, s.roots[idx].re);
  switch (q) {
    case Quantity::x_component: return u(2) < 0 ? T(u(0)) : T(-u(0));
    case Quantity::z_component: return u(0) > 0 ? T(u(2)) : T(-u(2));
    case Quantity::alpha_y_minus_x: {
      const T val = core::alpha(r) * u(1) - u(0);
      return u(0) > 0 ? val : T(-val);
    }
    default: return T(0);
  }
}

template <class T>
T quantity_root(const Word& w, T lo, T hi, Track track, Quantity q, const T& tol, const core::CancelToken* cancel) {
  T flo = quantity(w, lo, track, q, cancel);
  const T fhi = quantity(w, hi, track, q, cancel);
  if (!((flo < 0 && fhi > 0) || (flo > 0 && fhi < 0)))
    throw std::domain_error(fmt::format("bracket: got no sign change of the quantity on [{}, {}]",
                                        static_cast<double>(lo), static_cast<double>(hi)));
  for (int it = 0; it < 100000 && hi - lo > tol; ++it) {
    const T mid = (lo + hi) / 2;
    const T fm = quantity(w, mid, track, q, cancel);
    if ((fm < 0) == (flo < 0)) {
      lo = mid;
      flo = fm;
    } else hi = mid;
  }
  return (lo + hi) / 2;
}

namespace detail {

// The spectral signature of the analysed matrix at one r: whether mu1 is real, the sign of its real part, whether mu2
// is real and whether |mu2| ties with |mu1| (tie_tol).  The eigenvalues are continuous in r (the characteristic
// polynomial's coefficients are polynomials in r), so the signature changes only at events of the spectrum: a real
// pair turning complex, two moduli crossing (the dominant eigenvalue changing sign: 1^n 3^n at the lower end of
// its window, where mu1 > 0 and mu2 < 0 trade places), a real part crossing zero.
template <class T> unsigned spectral_signature(const Spectrum<T>& s) {
  const bool tie = !(s.mod[1] < s.mod[0] * (1 - tie_tol<T>()));
  return unsigned(s.roots[0].real) | unsigned(s.roots[0].re > 0) << 1 | unsigned(s.roots[1].real) << 2 |
         unsigned(tie) << 3;
}

// One point of a scan: the scanned value at r (stable or not; a classification) and the spectral signature there.
template <class T, class V> struct ScanSample {
  T r;
  V value;
  unsigned sig = 0;
};

// The scan's samples: the grid, and the points with a non-empty value (stable; a feasible orbit) that the refinement
// below finds inside cells whose two ends have an empty value.  Why: a stable (feasible) interval begins or ends
// where the dominant eigenvalue changes (an event: spectral_signature) or where an orbit's feasibility margin crosses
// zero.  An interval narrower than the grid's step is invisible on the grid (1^n 3^n: width 1.1e-5 at n = 22,
// 1.5e-8 at n = 200, against the step 4.75e-5), but the events that bound it are visible as a signature change
// between two grid points:
//  * a cell whose ends' signatures differ is bisected at every change (both halves whenever the middle's signature
//    differs from an end's, so a tie zone, |mu1| = |mu2| within tie_tol, with its own signature, is passed on both
//    sides) down to `tol`, and from each change located so, points at distances 2 tol, 4 tol, ... on both sides are
//    probed (1^n 3^n: the dominant eigenvector enters the domain just after |mu1| = |mu2|): an interval whose
//    distance from an event is at most its width holds a probe;
//  * events may come in pairs inside one cell (1^n 3^n near 7 - 4 sqrt 3, where the rotation of P1's block makes
//    the events accumulate: 1^200 3^200 flips the dominant eigenvalue's sign twice inside the cell of its window),
//    invisible at its ends; so a cell next to a cell with an event is cut into 16 and the same rules run on its
//    sub-cells, recursively (at most 3 levels, while they are wider than 16 tol; Refiner::cells).
// Not found: an interval bounded on both sides by feasibility changes alone, in a cell with no event and no event
// next to it, narrower than the step there, or farther from every event than its own width (docs/guides/patterns.md).
// eval(r) -> ScanSample; empty(value) -> bool.
template <class T, class V, class Eval, class Empty> struct Refiner {
  const T& tol;
  Eval& eval;
  Empty& empty;
  std::vector<ScanSample<T, V>> found;

  // Bisects every signature change between a and b (both empty) and probes around each; stops at a found point.
  void events(const ScanSample<T, V>& a0, const ScanSample<T, V>& b0) {
    std::vector<T> at;  // each signature change, located to tol
    std::vector<std::pair<ScanSample<T, V>, ScanSample<T, V>>> todo{{a0, b0}};
    while (!todo.empty()) {
      auto [a, b] = std::move(todo.back());
      todo.pop_back();
      if (!(abs_<T>(T(b.r - a.r)) > tol)) {
        at.push_back(a.r);
        continue;
      }
      ScanSample<T, V> m = eval(T((a.r + b.r) / 2));
      if (!empty(m.value)) {
        found.push_back(std::move(m));
        continue;
      }
      if (a.sig != m.sig) todo.emplace_back(a, m);
      if (m.sig != b.sig) todo.emplace_back(m, b);
    }
    for (const T& e : at)
      for (int side : {1, -1})
        for (T d = 2 * tol; side > 0 ? e + d < b0.r : e - d > a0.r; d *= 2) {
          ScanSample<T, V> m = eval(T(e + side * d));
          if (!empty(m.value)) {
            found.push_back(std::move(m));
            break;
          }
        }
  }
  bool event(const ScanSample<T, V>& a, const ScanSample<T, V>& b) const {
    return empty(a.value) && empty(b.value) && a.sig != b.sig;
  }
  // The rules above on the cells of g (sorted samples), `depth` levels of cutting below the grid.  At most 3 levels
  // (16^3: the step 4.75e-5 becomes 1.2e-8), and none in a sub-grid where most cells hold an event: there the
  // signature flickers (rounding at a near-tie) and cutting further would multiply evaluations by 16 per level.
  void cells(const std::vector<ScanSample<T, V>>& g, int depth = 0) {
    std::size_t with_events = 0;
    for (std::size_t i = 0; i + 1 < g.size(); ++i) with_events += event(g[i], g[i + 1]);
    const bool cut = depth < 3 && (depth == 0 || 2 * with_events < g.size());
    for (std::size_t i = 0; i + 1 < g.size(); ++i) {
      if (!empty(g[i].value) || !empty(g[i + 1].value)) continue;
      if (event(g[i], g[i + 1])) {
        events(g[i], g[i + 1]);
        continue;
      }
      const bool near = (i > 0 && event(g[i - 1], g[i])) || (i + 2 < g.size() && event(g[i + 1], g[i + 2]));
      if (!cut || !near || !(abs_<T>(T(g[i + 1].r - g[i].r)) > 16 * tol)) continue;
      std::vector<ScanSample<T, V>> sub{g[i]};
      for (int k = 1; k < 16; ++k) {
        sub.push_back(eval(T(g[i].r + (g[i + 1].r - g[i].r) * k / 16)));
        if (!empty(sub.back().value)) {
          found.push_back(sub.back());
          break;
        }
      }
      if (!empty(sub.back().value)) continue;
      sub.push_back(g[i + 1]);
      cells(sub, depth + 1);
    }
  }
};

template <class T, class V, class Eval, class Empty>
std::vector<ScanSample<T, V>> scan_samples(const std::vector<double>& grid, const T& tol, Eval&& eval, Empty&& empty) {
  std::vector<ScanSample<T, V>> g;
  g.reserve(grid.size());
  for (double x : grid) g.push_back(eval(T(x)));
  Refiner<T, V, Eval, Empty> refine{tol, eval, empty, {}};
  refine.cells(g);
  if (refine.found.empty()) return g;
  for (auto& f : refine.found) g.push_back(std::move(f));
  std::sort(g.begin(), g.end(), [](const auto& x, const auto& y) { return x.r < y.r; });
  return g;
}

}  // namespace detail

template <class T>
std::vector<Interval<T>> stability_set(const Word& w0, const std::vector<double>& grid, const T& tol,
                                       const core::CancelToken* cancel) {
  using namespace detail;
  if (w0.s.empty()) throw core::InvalidField("word", "an empty word", "at least one symbol 1, 2 or 3");
  const Word w = primitive_root(w0);
  const bool red = is_J_square(w);
  using Sample = ScanSample<T, char>;
  const auto eval = [&](const T& r) {
    const Spectrum<T> s = spectrum(w, r, red, cancel);
    return Sample{r, char(stability_reason_of<T>(w, r, s, cancel).empty()), spectral_signature(s)};
  };
  const std::vector<Sample> st = scan_samples<T, char>(grid, tol, eval, [](char stable) { return !stable; });
  // Bisects the predicate between a (stable) and b (not stable); returns the endpoint and b's reason.
  const auto refine = [&](T a, T b) {
    for (int it = 0; it < 100000 && abs_<T>(T(b - a)) > tol; ++it) {
      const T mid = (a + b) / 2;
      if (stability_reason<T>(w, mid, red, cancel).empty()) a = mid;
      else b = mid;
    }
    return std::pair<T, std::string>{T((a + b) / 2), stability_reason<T>(w, b, red, cancel)};
  };
  std::vector<Interval<T>> out;
  for (std::size_t i = 0; i < st.size();) {
    if (!st[i].value) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j + 1 < st.size() && st[j + 1].value) ++j;
    Interval<T> iv;
    if (i == 0) {
      iv.lo = T(0);
      iv.lo_reason = "end";
    } else std::tie(iv.lo, iv.lo_reason) = refine(st[i].r, st[i - 1].r);
    if (j + 1 == st.size()) {
      iv.hi = T(1);
      iv.hi_reason = "end";
    } else std::tie(iv.hi, iv.hi_reason) = refine(st[j].r, st[j + 1].r);
    out.push_back(iv);
    i = j + 1;
  }
  return out;
}

template <class T>
std::vector<FeasibleInterval<T>> feasibility_set(const Word& w0, const std::vector<double>& grid, const T& tol,
                                                 const core::CancelToken* cancel) {
  using namespace detail;
  if (w0.s.empty()) throw core::InvalidField("word", "an empty word", "at least one symbol 1, 2 or 3");
  const Word w = primitive_root(w0);
  const bool red = is_J_square(w);
  using Sample = ScanSample<T, Classification>;
  const auto eval = [&](const T& r) {
    const Spectrum<T> s = spectrum(w, r, red, cancel);
    return Sample{r, classify_of<T>(w, r, s, red, cancel), spectral_signature(s)};
  };
  const std::vector<Sample> o = scan_samples<T, Classification>(
      grid, tol, eval, [](const Classification& c) { return c.outcome == Outcome::none; });
  // Bisects between a (classification ca) and b (another one); returns the endpoint and b's name.
  const auto refine = [&](T a, T b, const Classification& ca) {
    for (int it = 0; it < 100000 && abs_<T>(T(b - a)) > tol; ++it) {
      const T mid = (a + b) / 2;
      if (classify<T>(w, mid, cancel) == ca) a = mid;
      else b = mid;
    }
    return std::pair<T, std::string>{T((a + b) / 2), classification_name(classify<T>(w, b, cancel))};
  };
  std::vector<FeasibleInterval<T>> out;
  for (std::size_t i = 0; i < o.size();) {
    if (o[i].value.outcome == Outcome::none) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j + 1 < o.size() && o[j + 1].value == o[i].value) ++j;
    FeasibleInterval<T> iv;
    iv.outcome = o[i].value.outcome;
    iv.collapse = o[i].value.collapse;
    if (i == 0) {
      iv.lo = T(0);
      iv.lo_reason = "end";
    } else std::tie(iv.lo, iv.lo_reason) = refine(o[i].r, o[i - 1].r, o[i].value);
    if (j + 1 == o.size()) {
      iv.hi = T(1);
      iv.hi_reason = "end";
    } else std::tie(iv.hi, iv.hi_reason) = refine(o[j].r, o[j + 1].r, o[i].value);
    out.push_back(iv);
    i = j + 1;
  }
  return out;
}

}  // namespace btob::patterns
