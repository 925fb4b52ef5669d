// SPDX-License-Identifier: GPL-3.0-or-later
// The leaves request's run: per r, the closed forms, the landing of the grid's orbits and the leaves followed
// (run_part), merged in r order.
#include "leaves/requests.hpp"

#include "core/cancel.hpp"
#include "core/csv.hpp"
#include "core/fields.hpp"
#include "core/run.hpp"
#include "core/sweep.hpp"
#include "leaves/leaves.hpp"
#include "windows/windows.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <type_traits>

namespace btob::leaves {

namespace {
constexpr double pi = std::numbers::pi;

// The region {t <= x}'s share of the grid's measure and its density in t, in closed form: the sphere measure
// (geometry.hpp) for a sphere grid; for a strip grid the ellipse 2 w2^2 - 4 alpha w1 w2 + 4 r w1^2 <= x^2 I_max of
// area pi x^2 I_max / sqrt(8 r - 4 alpha^2) over the rectangle's area 2 (b - a) (validate() makes the rectangle hold
// the region: |w1| <= 1 / sqrt(2 r) on it).
double share_in(const attractors::Grid& grid, double x, const Geometry& g) {
  if (grid.kind == core::GridKind::sphere) return region_share(x, g);
  const double area = pi * x * x * g.I_max / std::sqrt(8 * g.r - 4 * g.alpha * g.alpha);
  return area / (2 * (grid.axis1.hi - grid.axis1.lo));
}
double density_in(const attractors::Grid& grid, double x, const Geometry& g) {
  if (grid.kind == core::GridKind::sphere) return region_density(x, g);
  return 2 * pi * x * g.I_max / std::sqrt(8 * g.r - 4 * g.alpha * g.alpha) / (2 * (grid.axis1.hi - grid.axis1.lo));
}

template <class T> void append(std::vector<T>& to, const std::vector<T>& from) {
  to.insert(to.end(), from.begin(), from.end());
}

// The closed forms at r: theta, the rotation number, I_max, the region's share and the law of labels it carries
// (density per bin centre; its mean by the midpoint rule on 64 x bins points).
void closed_forms(Result& res, const Geometry& g, int bins) {
  res.r.push_back(g.r), res.cos_theta.push_back(g.cos_theta), res.rotation.push_back(g.rotation);
  res.I_max.push_back(g.I_max);
  res.region_share.push_back(share_in(res.grid, 1, g));
  for (int k = 0; k < bins; ++k) res.region_density.push_back(density_in(res.grid, (k + 0.5) / bins, g));
  double m = 0;
  const int n = 64 * bins;
  for (int k = 0; k < n; ++k) {
    const double x = (k + 0.5) / n;
    m += x * density_in(res.grid, x, g) / n;
  }
  res.region_mean.push_back(m / res.region_share.back());
}

// (i): where the grid's orbits land, their law and its mass.
void landing(Result& res, const Geometry& g, const attractors::Options& opt, int bins) {
  const Landing l = land(g, res.grid, opt);
  const Density d = density(l.t, bins);
  const attractors::Fraction f = attractors::fraction(l.q2, l.t.size());
  res.mass.push_back(f.value), res.mass_low.push_back(f.low), res.mass_high.push_back(f.high);
  res.outside_mass.push_back(f.value - res.region_share.back());
  res.landing_mean.push_back(d.mean), res.landing_sd.push_back(d.sd);
  res.q2.push_back(l.q2), res.above_one.push_back(l.above_one), res.undecided.push_back(l.undecided);
  append(res.density, d.value), append(res.density_low, d.low), append(res.density_high, d.high);
  append(res.kde, d.kde);
  append(res.density_coarse, density(l.t, bins / 2).value);
  append(res.label_map, l.t);
}

// (ii) and the rotation numbers: each requested leaf followed by the map.
void follow(Result& res, const Geometry& g, const Request& q, const core::CancelToken* cancel) {
  for (double t : q.labels) {
    const LeafStudy s = study_leaf(t, g, q.leaf_iterations, cancel);
    res.leaf_exact.push_back(s.exact_rotation), res.leaf_birkhoff.push_back(s.birkhoff);
    res.leaf_birkhoff_half.push_back(s.birkhoff_half), res.leaf_exit.push_back(static_cast<double>(s.exit_step));
    res.leaf_drift.push_back(s.label_drift), res.leaf_stays.push_back(s.stays ? 1 : 0);
    res.ks_uniform.push_back(s.ks_uniform), res.ks_strip.push_back(s.ks_strip), res.ks_sphere.push_back(s.ks_sphere);
    res.law_strip.push_back(s.law_strip), res.law_sphere.push_back(s.law_sphere);
  }
}
}  // namespace

Part run_part(const Request& q, const std::vector<std::size_t>& items, const core::RunControl& control) {
  q.validate();
  const auto t0 = std::chrono::steady_clock::now();
  Part part;
  part.items = items;
  part.per_r.grid = q.parsed_grid();  // closed_forms and landing read it
  const attractors::Options opt = attractors::run_options(q.thresholds, control);
  const std::vector<double> rs = q.all_r();
  for (std::size_t k = 0; k < items.size(); ++k) {
    core::check_cancel(control.cancel);
    const Geometry g = geometry(rs.at(items[k]));
    closed_forms(part.per_r, g, q.bins);
    landing(part.per_r, g, opt, q.bins);
    follow(part.per_r, g, q, control.cancel);
    if (control.progress) control.progress->update(k + 1, items.size());
  }
  part.threads = core::thread_count(control.threads);
  part.seconds = core::seconds_since(t0);
  return part;
}

namespace {
// Array number idx of per_r_arrays(r), which has element type V.
template <class V> const std::vector<V>& nth_array(const Result& r, std::size_t idx) {
  const std::vector<V>* found = nullptr;
  std::size_t k = 0;
  per_r_arrays(r, 0, 0, 0, [&](const auto& v, std::size_t) {
    if constexpr (std::is_same_v<std::decay_t<decltype(v)>, std::vector<V>>)
      if (k == idx) found = &v;
    ++k;
  });
  if (!found) throw std::logic_error("leaves merge: no array of that type at that index");
  return *found;
}
}  // namespace

Result merge(const Request& q, std::vector<Part> parts) {
  q.validate();
  Result res;
  res.request = q;
  res.grid = q.parsed_grid();
  res.axis1 = res.grid.axis1.centres(), res.axis2 = res.grid.axis2.centres();
  const auto order = core::item_order(parts, q.work_items());
  std::size_t idx = 0;
  per_r_arrays(res, static_cast<std::size_t>(q.bins), res.grid.cells(), q.labels.size(), [&](auto& out, std::size_t w) {
    using V = typename std::decay_t<decltype(out)>::value_type;
    const std::size_t mine = idx++;
    out = core::merge_rows<Part, V>(
        parts, order, w, [&](const Part& p) -> const std::vector<V>& { return nth_array<V>(p.per_r, mine); });
  });
  for (const Part& p : parts)
    res.seconds = std::max(res.seconds, p.seconds), res.threads = std::max(res.threads, p.threads);
  for (const windows::Stripe& s : windows::thin_stripes(q.max_m, 20)) {
    if (s.value.convert_to<double>() >= 1) continue;
    res.stripe_l.push_back(static_cast<std::uint64_t>(s.l)), res.stripe_m.push_back(static_cast<std::uint64_t>(s.m));
    res.stripe_r.push_back(s.value.convert_to<double>());
  }
  res.ks_critical = ks_critical(q.leaf_iterations);
  return res;
}

Result run(const Request& q, const core::RunControl& control) {
  return merge(q, {run_part(q, core::all_items(q), control)});
}

}  // namespace btob::leaves
