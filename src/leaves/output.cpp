// SPDX-License-Identifier: GPL-3.0-or-later
// The output of a leaves result: its CSV tables, and its arrays and attributes (core/result.hpp) that HDF5, the
// manifest and Python read.
#include "leaves/requests.hpp"

#include "core/csv.hpp"
#include "leaves/leaves.hpp"

#include <fmt/format.h>

namespace btob::leaves {

namespace {
std::string fmt_g(double x) { return fmt::format("{:.10g}", x); }

void per_r_arrays(const Result& res, core::Contents& c) {
  const std::size_t R = res.r.size();
  c.array("r", res.r, {R}, "r", "1", "restitution coefficient");
  c.array("cos_theta", res.cos_theta, {R}, "r", "1",
          "cos(theta) = 1 - (1 + r)^2 / (4 r): P2 / r's eigenvalues e^{+-i theta}");
  c.array("rotation", res.rotation, {R}, "r", "turns/iteration",
          "theta / (2 pi): the rotation number of every leaf with t <= 1");
  c.array("I_max", res.I_max, {R}, "r", "1",
          "(2 r - alpha^2) / r: the largest invariant I of a leaf inside P2's region (t = 1)");
  c.array(
      "region_share", res.region_share, {R}, "r", "1",
      "the region {t <= 1} filled by the leaves inside P2's region, as a fraction of the grid's measure (closed form)");
  c.array("region_mean", res.region_mean, {R}, "r", "1", "mean label t of the grid's measure restricted to the region");
  c.array("mass", res.mass, {R}, "r", "1",
          "fraction of the grid's points whose orbit lands on a P2 invariant curve (Q2)");
  c.array("mass_low", res.mass_low, {R}, "r", "1", "Clopper-Pearson 95% lower end of mass");
  c.array("mass_high", res.mass_high, {R}, "r", "1", "Clopper-Pearson 95% upper end of mass");
  c.array("outside_mass", res.outside_mass, {R}, "r", "1", "mass - region_share: landing mass from outside the region");
  c.array("landing_mean", res.landing_mean, {R}, "r", "1", "mean landing label t (labels <= 1)");
  c.array("landing_sd", res.landing_sd, {R}, "r", "1", "standard deviation of the landing label t");
  c.array("q2", res.q2, {R}, "r", "count", "orbits landing on a P2 invariant curve");
  c.array("above_one", res.above_one, {R}, "r", "count", "landing labels above 1 (none expected)");
  c.array("undecided", res.undecided, {R}, "r", "count", "orbits the classifier left undecided");
}

void landing_arrays(const Result& res, core::Contents& c) {
  const std::size_t R = res.r.size(), B = static_cast<std::size_t>(res.request.bins);
  c.coordinate_array("t", core::bin_centres(0, 1, B), {"t"}, "1", "bin centres of the label t in [0, 1]");
  c.coordinate_array("t_coarse", core::bin_centres(0, 1, B / 2), {"t_coarse"}, "1", "bin centres, bins / 2 bins");
  c.array("density", res.density, {R, B}, "r, t", "1/unit t",
          "landing label density (count / (N h)): total mass = mass");
  c.array("density_low", res.density_low, {R, B}, "r, t", "1/unit t", "Clopper-Pearson 95% lower end per bin");
  c.array("density_high", res.density_high, {R, B}, "r, t", "1/unit t", "Clopper-Pearson 95% upper end per bin");
  c.array("kde", res.kde, {R, B}, "r, t", "1/unit t",
          "Gaussian kernel density (bandwidth 1/bins, reflected at 0 and 1)");
  c.array("density_coarse", res.density_coarse, {R, B / 2}, "r, t_coarse", "1/unit t",
          "the landing density with bins / 2 bins");
  c.array("region_density", res.region_density, {R, B}, "r, t", "1/unit t",
          "the grid measure's density of labels inside the region (closed form): the points that start on a leaf");
  const core::GridAxis &a1 = res.grid.axis1, &a2 = res.grid.axis2;
  c.array(a1.name, res.axis1, {res.axis1.size()}, a1.name, a1.units, a1.meaning);
  c.array(a2.name, res.axis2, {res.axis2.size()}, a2.name, a2.units, a2.meaning);
  c.array("label_map", res.label_map, {R, static_cast<std::size_t>(a2.cells), static_cast<std::size_t>(a1.cells)},
          fmt::format("r, {}, {}", a2.name, a1.name), "1",
          "landing label t of each grid point's orbit (-1: not on a P2 curve)");
}

void leaf_arrays(const Result& res, core::Contents& c) {
  const std::size_t R = res.r.size(), L = res.request.labels.size();
  c.array("leaf_t", res.request.labels, {L}, "leaf", "1", "labels t of the leaves followed by the map");
  c.coordinate("leaf", "leaf_t");
  c.array("leaf_exact", res.leaf_exact, {R, L}, "r, leaf", "turns/iteration", "theta / (2 pi)");
  c.array("leaf_birkhoff", res.leaf_birkhoff, {R, L}, "r, leaf", "turns/iteration",
          "weighted (Das-Yorke) Birkhoff average of the eigen-angle increments along the map's orbit");
  c.array("leaf_birkhoff_half", res.leaf_birkhoff_half, {R, L}, "r, leaf", "turns/iteration",
          "the same over the first half");
  c.array("leaf_stays", res.leaf_stays, {R, L}, "r, leaf", "1", "1 when every step of the orbit used P2");
  c.array("leaf_exit", res.leaf_exit, {R, L}, "r, leaf", "iterations", "first step with symbol 1 or 3 (-1: none)");
  c.array("leaf_drift", res.leaf_drift, {R, L}, "r, leaf", "1", "max |t_k - t| before the exit (rounding)");
  c.array("ks_uniform", res.ks_uniform, {R, L}, "r, leaf", "1", "KS distance of the eigen-angles to the uniform law");
  c.array("ks_strip", res.ks_strip, {R, L}, "r, leaf", "1",
          "KS distance to normalised arc length in the strip (w1, w2)");
  c.array("ks_sphere", res.ks_sphere, {R, L}, "r, leaf", "1", "KS distance to normalised arc length on the sphere");
  c.array("law_strip", res.law_strip, {R, L}, "r, leaf", "1",
          "sup |uniform - strip arc length| (CDFs in the eigen-angle)");
  c.array("law_sphere", res.law_sphere, {R, L}, "r, leaf", "1", "sup |uniform - sphere arc length|");
  c.array("stripe_r", res.stripe_r, {res.stripe_r.size()}, "resonance", "1",
          "r(l/m) of eq. (6.3): theta / (2 pi) = l / m");
  c.array("stripe_l", res.stripe_l, {res.stripe_l.size()}, "resonance", "1", "l");
  c.array("stripe_m", res.stripe_m, {res.stripe_m.size()}, "resonance", "1", "m");
}

void attrs(const Result& res, core::Contents& c) {
  const Request& q = res.request;
  const attractors::Options& o = q.thresholds;
  if (q.r_count == 0) c.attr("r_value", q.r);
  c.attr("r_min", q.r_count == 0 ? q.r : q.r_min);
  c.attr("r_max", q.r_count == 0 ? q.r : q.r_max);
  c.attr("r_count", q.r_count);
  c.attr("grid", q.grid);
  c.attr("grid_kind", std::string(core::grid_kind_name(res.grid.kind)));
  c.attr("measure", attractors::measure_name(res.grid));
  c.attr("points", static_cast<long>(res.grid.cells()));
  c.attr("axis1", res.grid.axis1.name + " (" + res.grid.axis1.units + ")");
  c.attr("axis2", res.grid.axis2.name + " (" + res.grid.axis2.units + ")");
  c.attr("axis1_name", res.grid.axis1.name);
  c.attr("axis2_name", res.grid.axis2.name);
  c.attr("bins", static_cast<long>(q.bins));
  c.attr("leaf_iterations", q.leaf_iterations);
  c.attr("ks_critical", res.ks_critical);
  c.attr("max_m", static_cast<long>(q.max_m));
  c.attr("interval", "Clopper-Pearson 95% (sampling only)");
  c.attr("transient", o.transient);
  c.attr("window", o.window);
  c.attr("max_period", static_cast<long>(o.max_period));
  c.attr("return_tol", o.return_tol);
  c.attr("lyap_transient", o.lyap_transient);
  c.attr("lyap_iterations", o.lyap_iterations);
  c.attr("rotation_tol", o.rotation_tol);
  c.attr("refine_factor", static_cast<long>(o.refine_factor));
  c.attr("precision", "double");
  c.attr("seconds", res.seconds);
}
}  // namespace

void Result::describe(core::Contents& c) const {
  per_r_arrays(*this, c);
  landing_arrays(*this, c);
  leaf_arrays(*this, c);
  attrs(*this, c);
}

core::Tables Result::tables() const {
  const std::size_t R = r.size(), B = static_cast<std::size_t>(request.bins), L = request.labels.size();
  core::CsvTable per_r(
      "r,cos_theta,rotation,I_max,region_share,region_mean,mass,mass_low,mass_high,outside_mass,"
      "landing_mean,landing_sd,q2,above_one,undecided,points,measure");
  const std::string measure = attractors::measure_name(grid);
  for (std::size_t i = 0; i < R; ++i)
    per_r.row({fmt_g(r[i]), fmt_g(cos_theta[i]), fmt_g(rotation[i]), fmt_g(I_max[i]), fmt_g(region_share[i]),
               fmt_g(region_mean[i]), fmt_g(mass[i]), fmt_g(mass_low[i]), fmt_g(mass_high[i]), fmt_g(outside_mass[i]),
               fmt_g(landing_mean[i]), fmt_g(landing_sd[i]), fmt::format("{}", q2[i]), fmt::format("{}", above_one[i]),
               fmt::format("{}", undecided[i]), fmt::format("{}", grid.cells()), measure});
  core::CsvTable land("r,t_lo,t_hi,density,density_low,density_high,kde,density_coarse,region_density");
  for (std::size_t i = 0; i < R; ++i)
    for (std::size_t k = 0; k < B; ++k) {
      const std::size_t j = i * B + k;
      land.row({fmt_g(r[i]), fmt_g(static_cast<double>(k) / static_cast<double>(B)),
                fmt_g(static_cast<double>(k + 1) / static_cast<double>(B)), fmt_g(density[j]), fmt_g(density_low[j]),
                fmt_g(density_high[j]), fmt_g(kde[j]), fmt_g(density_coarse[i * (B / 2) + k / 2]),
                fmt_g(region_density[j])});
    }
  core::CsvTable lv(
      "r,t,exact_rotation,birkhoff_rotation,difference,birkhoff_half,stays,exit_step,label_drift,"
      "ks_uniform,ks_strip_arc,ks_sphere_arc,law_distance_strip,law_distance_sphere,ks_critical,law");
  for (std::size_t i = 0; i < R; ++i)
    for (std::size_t k = 0; k < L; ++k) {
      const std::size_t j = i * L + k;
      const bool u = ks_uniform[j] < ks_critical, a = ks_strip[j] < ks_critical, s = ks_sphere[j] < ks_critical;
      const std::string law = !leaf_stays[j]  ? "leaves the region"
                              : u && !a && !s ? "uniform eigen-angle; arc length rejected"
                              : u             ? "uniform eigen-angle; arc length not resolved at this n"
                                              : "uniform eigen-angle rejected (a resonance?)";
      lv.row({fmt_g(r[i]), fmt_g(request.labels[k]), fmt_g(leaf_exact[j]), fmt_g(leaf_birkhoff[j]),
              fmt::format("{:.3g}", leaf_birkhoff[j] - leaf_exact[j]), fmt_g(leaf_birkhoff_half[j]),
              fmt::format("{}", leaf_stays[j]), fmt::format("{}", leaf_exit[j]), fmt::format("{:.3g}", leaf_drift[j]),
              fmt_g(ks_uniform[j]), fmt_g(ks_strip[j]), fmt_g(ks_sphere[j]), fmt_g(law_strip[j]), fmt_g(law_sphere[j]),
              fmt_g(ks_critical), law});
    }
  return {{"", per_r.text()}, {"landing", land.text()}, {"leaves", lv.text()}};
}

}  // namespace btob::leaves
