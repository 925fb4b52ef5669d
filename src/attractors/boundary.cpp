// SPDX-License-Identifier: GPL-3.0-or-later
// The geometry of basin boundaries from a label image (boundary.hpp).
#include "attractors/boundary.hpp"

#include "attractors/attractors.hpp"

#include <boost/math/distributions/students_t.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>

namespace btob::attractors {

namespace {

// The two-sided 95% quantile of Student's t with `df` degrees of freedom (df >= 1).
double t975(std::size_t df) {
  return boost::math::quantile(boost::math::students_t_distribution<double>(static_cast<double>(df)), 0.975);
}

// The entropy of one box: -sum p log p over the colours of its cells (`counts` is scratch space).
double one_box_entropy(const LabelImage& img, std::size_t i0, std::size_t j0, std::size_t box,
                       std::map<std::uint32_t, std::size_t>& counts) {
  counts.clear();
  for (std::size_t j = j0; j < j0 + box; ++j)
    for (std::size_t i = i0; i < i0 + box; ++i) ++counts[img.at(i, j)];
  if (counts.size() == 1) return 0;  // exactly 0: a box of one colour is not a boundary box
  const double cells = static_cast<double>(box * box);
  double s = 0;
  for (const auto& [label, k] : counts) {
    const double p = static_cast<double>(k) / cells;
    s -= p * std::log(p);
  }
  return s;
}

}  // namespace

BoxEntropy box_entropy(const LabelImage& img, int box) {
  if (box < 1) throw std::invalid_argument(fmt::format("entropy box: got {}, expected >= 1", box));
  const std::size_t b = static_cast<std::size_t>(box), m1 = img.n1 / b, m2 = img.n2 / b;
  BoxEntropy e;
  e.box = box;
  e.boxes = m1 * m2;
  e.columns = m1;
  e.per_box.reserve(e.boxes);
  std::map<std::uint32_t, std::size_t> counts;
  double sum = 0;
  for (std::size_t bj = 0; bj < m2; ++bj)
    for (std::size_t bi = 0; bi < m1; ++bi) {
      const double s = one_box_entropy(img, bi * b, bj * b, b, counts);
      e.per_box.push_back(s);
      if (s > 0) ++e.boundary_boxes, sum += s;
    }
  e.sb = e.boxes ? sum / static_cast<double>(e.boxes) : 0.0;
  e.sbb = e.boundary_boxes ? sum / static_cast<double>(e.boundary_boxes) : 0.0;
  return e;
}

std::vector<int> uncertainty_eps(std::size_t n1, std::size_t n2) {
  const double top = std::max<double>(1, static_cast<double>(std::min(n1, n2) / 8));
  std::vector<int> eps;
  constexpr int kValues = 8;
  for (int k = 0; k < kValues; ++k) {
    const int e = static_cast<int>(std::lround(std::pow(top, k / double(kValues - 1))));
    if (eps.empty() || e > eps.back()) eps.push_back(e);
  }
  return eps;
}

std::vector<UncertainFraction> uncertain_fractions(const LabelImage& img, const std::vector<int>& eps, int margin) {
  std::vector<UncertainFraction> out;
  const std::size_t m = static_cast<std::size_t>(std::max(margin, 0));
  for (int e : eps) {
    if (e < 1 || e > margin) throw std::invalid_argument(fmt::format("uncertainty eps {} outside 1..{}", e, margin));
    UncertainFraction u;
    u.eps = e;
    const std::size_t d = static_cast<std::size_t>(e);
    for (std::size_t j = m; j + m < img.n2; ++j)
      for (std::size_t i = m; i + m < img.n1; ++i) {
        const std::uint32_t l = img.at(i, j);
        ++u.points;
        u.uncertain += img.at(i - d, j) != l || img.at(i + d, j) != l || img.at(i, j - d) != l || img.at(i, j + d) != l;
      }
    const Fraction f = fraction(u.uncertain, u.points);
    u.f = f.value, u.low = f.low, u.high = f.high;
    out.push_back(u);
  }
  return out;
}

constexpr double kSaturation = 0.5;  // the largest f(eps) fitted

UncertaintyFit fit_uncertainty(std::vector<UncertainFraction> points) {
  UncertaintyFit fit;
  fit.points = std::move(points);
  std::vector<double> x, y;
  // The power law holds while f is small; near 1 it saturates (every cell uncertain) and would flatten the slope.
  for (const auto& p : fit.points)
    if (p.uncertain > 0 && p.f <= kSaturation) x.push_back(std::log(p.eps)), y.push_back(std::log(p.f));
  const std::size_t m = x.size();
  if (m < 3 || std::exp(x.back() - x.front()) < 10 - 1e-9) {
    fit.why = m == 0 ? "no eps with 0 < f(eps) <= 1/2 (no boundary at the grid's resolution, or f saturated from "
                       "one cell: a finer grid is needed)"
                     : fmt::format(
                           "{} eps with 0 < f(eps) <= 1/2, spanning less than a decade (at least three "
                           "spanning a decade needed: a grid of at least 80 x 80 cells, f not saturated)",
                           m);
    return fit;
  }
  double mx = 0, my = 0;
  for (std::size_t k = 0; k < m; ++k) mx += x[k], my += y[k];
  mx /= static_cast<double>(m), my /= static_cast<double>(m);
  double sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < m; ++k) sxx += (x[k] - mx) * (x[k] - mx), sxy += (x[k] - mx) * (y[k] - my);
  fit.alpha = sxy / sxx;
  double ssr = 0;
  for (std::size_t k = 0; k < m; ++k) {
    const double res = y[k] - my - fit.alpha * (x[k] - mx);
    ssr += res * res;
  }
  fit.se = std::sqrt(ssr / static_cast<double>(m - 2) / sxx);
  const double half = t975(m - 2) * fit.se;
  fit.low = fit.alpha - half, fit.high = fit.alpha + half;
  fit.eps_min = static_cast<int>(std::lround(std::exp(x.front())));
  fit.eps_max = static_cast<int>(std::lround(std::exp(x.back())));
  fit.used = m;
  fit.fitted = true;
  return fit;
}

UncertaintyFit uncertainty_exponent(const LabelImage& img) {
  const std::vector<int> eps = uncertainty_eps(img.n1, img.n2);
  // The margin keeps the four neighbours of every counted cell inside the image, for every eps: the same cells.
  const int margin = eps.back();
  if (2 * static_cast<std::size_t>(margin) >= std::min(img.n1, img.n2)) return fit_uncertainty({});
  return fit_uncertainty(uncertain_fractions(img, eps, margin));
}

namespace {

constexpr int kFar = std::numeric_limits<int>::max() / 2;

// Chessboard distance from every cell to the nearest cell of `in` (kFar when there is none): the two-pass
// transform over the 8 neighbours, exact for the max norm (each pass carries the distance along the half of the
// neighbours already visited; a shortest king path splits into such steps).
std::vector<int> chessboard_distance(const std::vector<char>& in, std::size_t n1, std::size_t n2) {
  std::vector<int> d(in.size());
  for (std::size_t c = 0; c < in.size(); ++c) d[c] = in[c] ? 0 : kFar;
  const auto relax = [&](std::size_t c, long i, long j) {
    if (i < 0 || j < 0 || i >= static_cast<long>(n1) || j >= static_cast<long>(n2)) return;
    d[c] = std::min(d[c], d[static_cast<std::size_t>(j) * n1 + static_cast<std::size_t>(i)] + 1);
  };
  for (long j = 0; j < static_cast<long>(n2); ++j)
    for (long i = 0; i < static_cast<long>(n1); ++i) {
      const std::size_t c = static_cast<std::size_t>(j) * n1 + static_cast<std::size_t>(i);
      relax(c, i - 1, j), relax(c, i - 1, j - 1), relax(c, i, j - 1), relax(c, i + 1, j - 1);
    }
  for (long j = static_cast<long>(n2) - 1; j >= 0; --j)
    for (long i = static_cast<long>(n1) - 1; i >= 0; --i) {
      const std::size_t c = static_cast<std::size_t>(j) * n1 + static_cast<std::size_t>(i);
      relax(c, i + 1, j), relax(c, i + 1, j + 1), relax(c, i, j + 1), relax(c, i - 1, j + 1);
    }
  return d;
}

// The labels of the 4-neighbours of cell (i, j) that differ from its own (empty: not a boundary cell).
std::vector<std::uint32_t> other_neighbours(const LabelImage& img, std::size_t i, std::size_t j) {
  std::vector<std::uint32_t> out;
  const std::uint32_t l = img.at(i, j);
  const auto see = [&](std::uint32_t m) {
    if (m != l && std::find(out.begin(), out.end(), m) == out.end()) out.push_back(m);
  };
  if (i > 0) see(img.at(i - 1, j));
  if (i + 1 < img.n1) see(img.at(i + 1, j));
  if (j > 0) see(img.at(i, j - 1));
  if (j + 1 < img.n2) see(img.at(i, j + 1));
  return out;
}

// Per cell, the basins whose boundary B_i (i against the rest) it lies on: its own label and its differing
// 4-neighbours' labels, basins (>= 1) only, when it has a differing neighbour.
std::vector<std::vector<std::uint32_t>> boundary_memberships(const LabelImage& img) {
  std::vector<std::vector<std::uint32_t>> on(img.n1 * img.n2);
  for (std::size_t j = 0; j < img.n2; ++j)
    for (std::size_t i = 0; i < img.n1; ++i) {
      std::vector<std::uint32_t> other = other_neighbours(img, i, j);
      if (other.empty()) continue;
      other.push_back(img.at(i, j));
      std::erase(other, 0u);
      on[j * img.n1 + i] = std::move(other);
    }
  return on;
}

}  // namespace

int wada_cells(std::size_t n1, std::size_t n2) { return std::max(3, static_cast<int>(std::min(n1, n2) / 50)); }

WadaTest wada_merging(const LabelImage& img, int cells) {
  WadaTest w;
  w.cells = cells;
  std::set<std::uint32_t> present(img.labels->begin(), img.labels->end());
  present.erase(0);
  w.basins = static_cast<int>(present.size());
  w.applies = w.basins >= 3;
  if (!w.applies) return w;
  const auto on = boundary_memberships(img);
  std::size_t boundary_cells = 0, seeing_all = 0;
  std::vector<char> sees_all(on.size(), 1);
  for (std::uint32_t b : present) {
    std::vector<char> in_boundary(on.size()), in_basin(on.size());
    for (std::size_t c = 0; c < on.size(); ++c) {
      in_boundary[c] = std::find(on[c].begin(), on[c].end(), b) != on[c].end();
      in_basin[c] = (*img.labels)[c] == b;
    }
    const std::vector<int> to_boundary = chessboard_distance(in_boundary, img.n1, img.n2);
    for (std::size_t c = 0; c < on.size(); ++c)
      for (std::uint32_t other : on[c])
        if (other != b) w.hausdorff = std::max(w.hausdorff, to_boundary[c]);
    const std::vector<int> to_basin = chessboard_distance(in_basin, img.n1, img.n2);
    for (std::size_t c = 0; c < on.size(); ++c) sees_all[c] = sees_all[c] && to_basin[c] <= cells;
  }
  for (std::size_t c = 0; c < on.size(); ++c)
    if (!other_neighbours(img, c % img.n1, c / img.n1).empty()) ++boundary_cells, seeing_all += sees_all[c];
  w.all_basins_share = boundary_cells ? static_cast<double>(seeing_all) / static_cast<double>(boundary_cells) : 0.0;
  w.wada = w.hausdorff <= cells;
  return w;
}

std::string WadaTest::verdict() const {
  if (!applies) return fmt::format("not applicable ({} basins; the Wada property needs three)", basins);
  return wada ? fmt::format("Wada at this resolution (the {} basin boundaries lie within {} cells of each other)",
                            basins, hausdorff)
              : fmt::format("not Wada at this resolution (boundaries {} cells apart, more than {})", hausdorff, cells);
}

Spread spread(const std::vector<double>& v) {
  Spread s;
  if (v.empty()) return s;
  s.value = v[0];
  for (double x : v) s.mean += x;
  s.mean /= static_cast<double>(v.size());
  for (double x : v) s.sd += (x - s.mean) * (x - s.mean);
  s.sd = v.size() > 1 ? std::sqrt(s.sd / static_cast<double>(v.size() - 1)) : 0.0;
  const double half = v.size() > 1 ? t975(v.size() - 1) * s.sd / std::sqrt(static_cast<double>(v.size())) : 0.0;
  s.low = (v.size() > 1 ? s.mean : s.value) - half;
  s.high = (v.size() > 1 ? s.mean : s.value) + half;
  return s;
}

BoundaryGeometry boundary_geometry(const std::vector<std::vector<std::uint32_t>>& grids, std::size_t n1, std::size_t n2,
                                   int box) {
  if (grids.empty()) throw std::logic_error("boundary geometry: no grid");
  BoundaryGeometry g;
  std::vector<double> sb, sbb, share;
  for (const auto& labels : grids) {
    const BoxEntropy e = box_entropy(LabelImage{&labels, n1, n2}, box);
    sb.push_back(e.sb), sbb.push_back(e.sbb), share.push_back(e.boundary_share());
    if (sb.size() == 1) g.entropy = e;
  }
  g.sb = spread(sb), g.sbb = spread(sbb), g.boundary_share = spread(share);
  const LabelImage main{&grids[0], n1, n2};
  g.uncertainty = uncertainty_exponent(main);
  g.wada = wada_merging(main);
  return g;
}

}  // namespace btob::attractors
