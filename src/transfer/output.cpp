// What `btob transfer` and `btob transfer-r` write, computed here so that tests reach it: the CSV tables (through
// core::CsvTable; a value that is not a finite number is an empty cell), the HDF5 arrays and attributes
// (describe), and the summary lines.
#include "transfer/transfer.hpp"

#include "core/csv.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

namespace btob::transfer {

namespace {

// The request's fields as attributes under their flag names, as the manifests of transfer runs record them:
// numbers as numbers, flags as "true"/"false", lists joined by commas.
template <class Req> void request_attrs(Req q, core::Contents& c) {  // a copy: fields() visits mutable members
  q.fields([&](const char* name, const auto& member, const char*) {
    using M = std::decay_t<decltype(member)>;
    if constexpr (std::is_same_v<M, std::string> || std::is_same_v<M, double>) c.attr(name, member);
    else if constexpr (std::is_same_v<M, bool>) c.attr(name, std::string(member ? "true" : "false"));
    else if constexpr (std::is_integral_v<M>) c.attr(name, static_cast<long>(member));
    else {
      std::string s;
      for (const auto& x : member) s += (s.empty() ? "" : ",") + fmt::format("{}", x);
      c.attr(name, s);
    }
  });
}

std::string num(double v) { return core::csv_number(v); }

}  // namespace

// ---- btob transfer ----------------------------------------------------------------------------------------

void TransferResult::describe(core::Contents& c) const {
  const std::vector<std::size_t> box_dims{static_cast<std::size_t>(part.n1), static_cast<std::size_t>(part.n2)};
  const std::string box_axes = "first chart coordinate, second chart coordinate";
  const bool spectrum = request.spectrum();  // eigenvalues 0: no spectrum, none of what needs eigenvectors
  c.text("attractors_found", attractors_found, "attractor", "word",
         "stable periodic attractors found in the closed classes (paper notation; without --cycle only)");
  if (spectrum) {
    c.array("density", density, box_dims, box_axes, "mass per box",
            "sum over the components of their Lebesgue fraction times their invariant density");
    c.array("second", second, box_dims, box_axes, "1",
            "leading real eigenvector with 0 < lambda < 1 (real part, max |.| = 1; all 0 when there is none)");
    c.array("component", component_of_box, box_dims, box_axes, "index",
            "component of each box (1-based, as in components.csv), 0 for none");
    c.array("eig_re", eig_re, {eig_re.size()}, "eigenvalue", "1", "real parts of the leading eigenvalues (block route)");
    c.array("eig_im", eig_im, {eig_im.size()}, "eigenvalue", "1", "imaginary parts of the leading eigenvalues");
    c.array("eig_block", eig_block, {eig_block.size()}, "eigenvalue", "index",
            "block of each eigenvalue: 0 the transient block, c >= 1 closed class c");
    c.array("lebesgue", lebesgue, {lebesgue.size()}, "component", "1",
            "fraction of the Lebesgue measure of the chart rectangle that ends in each component");
  }
  c.array("cycle_points", cycle_points, {cycle_points.size() / 2, 2}, "cycle point, (a, b)", "rad, 1",
          "chart coordinates of every point of every requested cycle, the cycles in order");
  if (!basins.empty()) {
    c.array("basin", basin_of_box, box_dims, box_axes, "index",
            "attractor (1-based, as in basins.csv) with the largest absorption probability of the box, 0 for none");
    c.array("basin_probability", basin_probability, box_dims, box_axes, "1",
            "that absorption probability (1 on the attractor's own boxes)");
    c.array("basin_fraction", basin_fraction, {basin_fraction.size()}, "attractor", "1",
            "fraction of the Lebesgue measure of the chart rectangle absorbed by each attractor's boxes");
  }
  request_attrs(request, c);
  c.attr("n1", part.n1);
  c.attr("n2", part.n2);
  c.attr("lo1", part.lo1);
  c.attr("hi1", part.hi1);
  c.attr("lo2", part.lo2);
  c.attr("hi2", part.hi2);
  c.attr("nnz", nnz);
  c.attr("lost_samples", static_cast<long>(lost));
  c.attr("matrix_bytes", static_cast<long>(matrix_bytes));
  c.attr("closed_classes", static_cast<long>(closed_classes()));
  for (std::size_t k = 0; k < classes.size(); ++k) {
    c.attr(fmt::format("closed_class_{}_boxes", k + 1), classes[k].boxes);
    c.attr(fmt::format("closed_class_{}_period", k + 1), static_cast<long>(classes[k].period));
  }
  if (spectrum) {
    c.attr("near_one_count", static_cast<long>(near_one_count));
    c.attr("components", static_cast<long>(components.size()));
    c.attr("unabsorbed", unabsorbed);
    c.attr("second_value", second_value);
    c.attr("second_block", static_cast<long>(second_block));
    c.attr("second_positive_mass", second_positive_mass);
    c.attr("second_negative_mass", second_negative_mass);
    c.attr("second_positive_boxes", second_positive_boxes);
    c.attr("second_negative_boxes", second_negative_boxes);
    c.attr("tv_boxes", tv_boxes);
    c.attr("tv_coarse", tv_coarse);
    c.attr("measure_points", measure_points);
  }
  // JSON has no NaN: the P2 angle is recorded only where the P2 curves exist (r >= 3 - 2 sqrt 2).
  if (const double beta = p2_rotation_angle(request.r); std::isfinite(beta)) c.attr("p2_beta", beta);
  c.attr("seconds_matrix", seconds_matrix);
  if (spectrum) c.attr("seconds_spectrum", seconds_spectrum);
  c.attr("seconds", seconds_total);
  c.attr("basins", static_cast<long>(basins.size()));
  if (!basins.empty()) {
    c.attr("basin_unabsorbed", basin_unabsorbed);
    c.attr("basin_residual", basin_residual);
    c.attr("basin_iterations", basin_iterations);
    c.attr("seconds_basins", seconds_basins);
    for (std::size_t k = 0; k < basins.size(); ++k) c.attr(fmt::format("basin_{}", k + 1), basins[k].attractor);
  }
  for (std::size_t k = 0; k < cycles.size(); ++k) {
    c.attr(fmt::format("cycle_{}", k + 1), cycles[k].word);
    if (!spectrum) continue;
    c.attr(fmt::format("cycle_{}_mass_boxes", k + 1), cycles[k].mass_boxes);
    c.attr(fmt::format("cycle_{}_mass_neighbourhood", k + 1), cycles[k].mass_neighbourhood);
  }
  c.attr("csv_empty_cells",
         spectrum ? std::string("spectrum.csv: whole_re, whole_im, whole_modulus beyond the eigenvalues of the "
                                "whole-matrix cross-check (check-whole); basins.csv: exact except for the P2 region "
                                "on the strip; any empty cell: not a finite number")
                  : std::string("cycles.csv: mass_boxes, mass_neighbourhood, component_share, radius99 and "
                                "radius99_component (eigenvalues 0: no spectrum, no density; component is then the "
                                "closed class holding every box of the cycle, 0 for none); basins.csv: exact except for the P2 region on the strip; any empty cell: "
                                "not a finite number"));
}

std::string TransferResult::spectrum_csv() const {
  core::CsvTable t("k,re,im,modulus,block,whole_re,whole_im,whole_modulus");
  for (std::size_t k = 0; k < eig_re.size(); ++k) {
    const bool w = k < whole_re.size();
    t.line(fmt::format("{},{},{},{},{},{},{},{}", k + 1, num(eig_re[k]), num(eig_im[k]), num(std::hypot(eig_re[k], eig_im[k])),
                       eig_block[k], w ? num(whole_re[k]) : "", w ? num(whole_im[k]) : "",
                       w ? num(std::hypot(whole_re[k], whole_im[k])) : ""));
  }
  return t.text();
}

std::string TransferResult::components_csv() const {
  core::CsvTable t("component,kind,boxes,period,rho,lebesgue_fraction,centre_a,centre_b,w1,w2");
  const bool strip = request.domain == "strip";
  for (std::size_t k = 0; k < components.size(); ++k) {
    const ComponentInfo& c = components[k];
    t.line(fmt::format("{},{},{},{},{},{},{},{},{},{}", k + 1, c.block > 0 ? "closed" : "almost-invariant", c.boxes,
                       c.period, num(c.rho), core::csv_number(c.lebesgue, "{:.6f}"),
                       core::csv_number(c.centre[0], "{:.6g}"), core::csv_number(c.centre[1], "{:.6g}"),
                       strip ? core::csv_number(std::tan(c.centre[0]), "{:.6g}") : "",
                       strip ? core::csv_number(c.centre[1], "{:.6g}") : ""));
  }
  return t.text();
}

std::string TransferResult::cycles_csv() const {
  if (cycles.empty()) return "";
  core::CsvTable t("word,outcome,points,boxes_found,mass_boxes,mass_neighbourhood,component,component_share,radius99,"
                   "radius99_component");
  const auto f6 = [](double v) { return core::csv_number(v, "{:.6f}"); };
  for (const CycleCheck& c : cycles) {
    long found = 0;
    for (long b : c.boxes) found += b >= 0;
    if (!request.spectrum()) {  // no density: its columns empty; component: the closed class holding the cycle
      t.line(fmt::format("{},{},{},{},,,{},,,", core::csv_text(c.word), core::csv_text(c.outcome), c.boxes.size(), found,
                         c.component));
      continue;
    }
    t.line(fmt::format("{},{},{},{},{},{},{},{},{},{}", core::csv_text(c.word), core::csv_text(c.outcome), c.boxes.size(),
                       found, f6(c.mass_boxes), f6(c.mass_neighbourhood), c.component, f6(c.component_share), c.radius99,
                       c.radius99_component));
  }
  return t.text();
}

std::string TransferResult::basins_csv() const {
  if (basins.empty()) return "";
  core::CsvTable t("attractor,kind,target_boxes,fraction,exact");
  for (const BasinInfo& b : basins)
    t.line(fmt::format("{},{},{},{},{}", core::csv_text(b.attractor), core::csv_text(b.kind), b.target_boxes,
                       core::csv_number(b.fraction, "{:.6f}"),
                       b.exact >= 0 ? core::csv_number(b.exact, "{:.6f}") : ""));
  return t.text();
}

std::string TransferResult::summary() const {
  const TransferRequest& q = request;
  std::string s;
  if (!q.spectrum()) {
    s = fmt::format("btob: transfer at r = {}: {} boxes x {} samples, nnz {} ({:.1f} MB), matrix {:.2f} s, total {:.2f} s; "
                    "{} closed classes; no spectrum (eigenvalues 0): basins only\n",
                    q.r, part.size(), q.samples, nnz, static_cast<double>(matrix_bytes) / 1e6, seconds_matrix,
                    seconds_total, closed_classes());
    for (std::size_t k = 0; k < classes.size(); ++k)
      s += fmt::format("  closed class {}: {} boxes, period {}\n", k + 1, classes[k].boxes, classes[k].period);
    for (const CycleCheck& c : cycles) {
      long found = 0;
      for (long b : c.boxes) found += b >= 0;
      s += fmt::format("  cycle {} ({}): {} of its {} points in the chart; {}\n", c.word, c.outcome, found, c.boxes.size(),
                       c.component > 0 ? fmt::format("every one in closed class {}", c.component)
                                       : std::string("not within one closed class"));
    }
  } else {
    s = fmt::format(
        "btob: transfer at r = {}: {} boxes x {} samples, nnz {} ({:.1f} MB), matrix {:.2f} s, spectrum {:.2f} s, total "
        "{:.2f} s; {} closed classes, {} eigenvalues within {} of 1; lambda_2 (real, < 1) = {:.6f}; TV to the empirical "
        "measure {:.3f} ({}x{} boxes), {:.3f} ({}x{})\n",
        q.r, part.size(), q.samples, nnz, static_cast<double>(matrix_bytes) / 1e6, seconds_matrix, seconds_spectrum,
        seconds_total, closed_classes(), near_one_count, q.near_one, second_value, tv_boxes, part.n1, part.n2, tv_coarse,
        q.tv_bins, q.tv_bins);
    for (std::size_t k = 0; k < components.size(); ++k)
      s += fmt::format("  component {}: {} boxes, period {}, rho {:.6f}, Lebesgue fraction {:.4f}\n", k + 1,
                       components[k].boxes, components[k].period, components[k].rho, components[k].lebesgue);
    for (const CycleCheck& c : cycles)
      s += fmt::format("  cycle {} ({}): mass {:.4f} on its boxes, {:.4f} on their 3x3 neighbourhoods, 99% within {} boxes; "
                       "component {} (99% of it within {} boxes)\n",
                       c.word, c.outcome, c.mass_boxes, c.mass_neighbourhood, c.radius99, c.component, c.radius99_component);
  }
  for (const BasinInfo& b : basins)
    s += fmt::format("  basin of {} ({}, {} target boxes): Lebesgue fraction {:.4f}{}\n", b.attractor, b.kind,
                     b.target_boxes, b.fraction,
                     b.exact >= 0 ? fmt::format(" (the region itself: {:.4f})", b.exact) : "");
  if (!basins.empty())
    s += fmt::format("  basins: unabsorbed {:.2e}, residual {:.1e}, {} BiCGSTAB iterations, {:.2f} s\n",
                     basin_unabsorbed, basin_residual, basin_iterations, seconds_basins);
  return s;
}

// ---- btob transfer-r --------------------------------------------------------------------------------------

void TransferRResult::describe(core::Contents& c) const {
  const std::size_t R = r.size(), K = static_cast<std::size_t>(this->K);
  c.array("r", r, {R}, "r", "1", "restitution coefficients");
  c.array("re", re, {R, K}, "r, eigenvalue", "1", "real parts of the K leading eigenvalues (NaN where fewer converged)");
  c.array("im", im, {R, K}, "r, eigenvalue", "1", "imaginary parts of the K leading eigenvalues");
  c.array("peripheral_count", peripheral_count, {R}, "r", "count", "eigenvalues with 1 - |lambda| < peripheral");
  c.array("closed_classes", closed_classes, {R}, "r", "count", "closed classes of Ulam's matrix");
  c.array("rest_modulus", rest_modulus, {R}, "r", "1", "largest |lambda| outside the peripheral set (NaN: none within K)");
  c.array("gap", gap, {R}, "r", "1", "min |peripheral| - max |rest| (NaN: no peripheral or no rest within K)");
  c.array("window_lower", window_lower, {window_lower.size()}, "n = 1, 2, ...", "1",
          "lower bound of the window of (ab)^n(cb)^n: the root of Q_n");
  c.array("window_upper", window_upper, {window_upper.size()}, "n = 1, 2, ...", "1",
          "upper end of the window of (ab)^n(cb)^n: r_crit,2(n) (NaN for n = 1, which has none)");
  request_attrs(request, c);
  c.attr("seconds", seconds);
  c.attr("csv_empty_cells",
         std::string("peripheral_r.csv: rest_modulus when every eigenvalue within K is peripheral, gap when there is no "
                     "peripheral eigenvalue or no other within K, p2_beta below r = 3 - 2 sqrt 2 (no P2 invariant curves); "
                     "windows.csv: upper for n = 1 (no r_crit,2)"));
}

std::string TransferRResult::spectrum_csv() const {
  core::CsvTable t("r,k,re,im,modulus");
  const std::size_t K = static_cast<std::size_t>(this->K);
  for (std::size_t i = 0; i < r.size(); ++i)
    for (std::size_t k = 0; k < K; ++k) {
      const double x = re[i * K + k], y = im[i * K + k];
      if (!std::isfinite(x)) continue;  // fewer than K converged at this r
      t.line(fmt::format("{},{},{},{},{}", num(r[i]), k + 1, num(x), num(y), num(std::hypot(x, y))));
    }
  return t.text();
}

std::string TransferRResult::peripheral_csv() const {
  core::CsvTable t("r,peripheral_count,closed_classes,rest_modulus,gap,p2_beta");
  for (std::size_t i = 0; i < r.size(); ++i)
    t.line(fmt::format("{},{},{},{},{},{}", num(r[i]), peripheral_count[i], closed_classes[i], num(rest_modulus[i]),
                       num(gap[i]), num(p2_rotation_angle(r[i]))));
  return t.text();
}

std::string TransferRResult::windows_csv() const {
  core::CsvTable t("n,lower,upper");
  for (std::size_t n = 0; n < window_lower.size(); ++n)
    t.line(fmt::format("{},{},{}", n + 1, num(window_lower[n]), num(window_upper[n])));
  return t.text();
}

std::string TransferRResult::summary() const {
  const TransferRRequest& q = request;
  return fmt::format("btob: transfer-r: {} r values in [{}, {}], {} boxes x {} samples, {:.1f} s\n", r.size(), q.r_min,
                     q.r_max, q.boxes, q.samples, seconds);
}

}  // namespace btob::transfer
