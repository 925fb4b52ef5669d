// SPDX-License-Identifier: GPL-3.0-or-later
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

namespace {

const char* const kBoxAxes = "first chart coordinate, second chart coordinate";

// Without --cycle: how the closed classes were named (classes.csv lists every attractor each class reaches).
void describe_class_names(const ClassNames& names, core::Contents& c) {
  const std::size_t classes = names.name.size();
  c.text("class_attractor", names.name, "closed class", "word",
         fmt::format("attractor reached from more than half of the classified box centres of each closed class "
                     "(attractors::classify with btob classify's default thresholds, at most {} boxes a class, "
                     "evenly strided): a periodic word in paper notation, 1 or 3 (collapse), P2 invariant curves, "
                     "invariant curves, chaotic; undecided when no attractor has a majority",
                     kNameSamples));
  c.text("class_verdict", names.verdict, "closed class", "verdict",
         "that attractor's verdict: stable (a stable periodic orbit), collapse, neutral (invariant curves, lambda1 = "
         "0), unstable (chaotic, lambda1 > 0), undecided");
  c.array("class_classified", names.classified, {classes}, "closed class", "count",
          "box centres of the class classified (its boxes, or kNameSamples of them evenly strided)");
  c.array("class_majority", names.majority, {classes}, "closed class", "count",
          "classified box centres that reach the class's attractor (0 when undecided)");
  c.attr("attractors_method", std::string("closed classes named by attractors::classify from their box centres"));
}

// The arrays over the boxes and the spectrum's arrays (those that need eigenvectors only with a spectrum).
void describe_arrays(const TransferResult& res, core::Contents& c) {
  const std::vector<std::size_t> box_dims{static_cast<std::size_t>(res.part.n1), static_cast<std::size_t>(res.part.n2)};
  c.text("attractors_found", res.attractors_found, "attractor", "word",
         "stable periodic attractors found in the closed classes (paper notation; without --cycle only)");
  if (res.request.cycles.empty()) describe_class_names(res.class_names, c);
  if (res.request.spectrum()) {
    c.array("density", res.density, box_dims, kBoxAxes, "mass per box",
            "sum over the components of their Lebesgue fraction times their invariant density");
    c.array("second", res.second, box_dims, kBoxAxes, "1",
            "leading real eigenvector with 0 < lambda < 1 (real part, max |.| = 1; all 0 when there is none)");
    c.array("component", res.component_of_box, box_dims, kBoxAxes, "index",
            "component of each box (1-based, as in components.csv), 0 for none");
    c.array("eig_re", res.eig_re, {res.eig_re.size()}, "eigenvalue", "1",
            "real parts of the leading eigenvalues (block route)");
    c.array("eig_im", res.eig_im, {res.eig_im.size()}, "eigenvalue", "1", "imaginary parts of the leading eigenvalues");
    c.array("eig_block", res.eig_block, {res.eig_block.size()}, "eigenvalue", "index",
            "block of each eigenvalue: 0 the transient block, c >= 1 closed class c");
    c.array("lebesgue", res.lebesgue, {res.lebesgue.size()}, "component", "1",
            "fraction of the Lebesgue measure of the chart rectangle that ends in each component");
  }
  c.coordinate_array("box_a", core::bin_centres(res.part.lo1, res.part.hi1, box_dims[0]), {"first chart coordinate"},
                     "rad", "centre of each box in the first chart coordinate a");
  c.coordinate_array("box_b", core::bin_centres(res.part.lo2, res.part.hi2, box_dims[1]), {"second chart coordinate"},
                     "1", "centre of each box in the second chart coordinate b");
  c.array("cycle_points", res.cycle_points, {res.cycle_points.size() / 2, 2}, "cycle point, (a, b)", "rad, 1",
          "chart coordinates of every point of every requested cycle, the cycles in order");
  if (res.basins.empty()) return;
  c.array("basin", res.basin_of_box, box_dims, kBoxAxes, "index",
          "attractor (1-based, as in basins.csv) with the largest absorption probability of the box, 0 for none");
  c.array("basin_probability", res.basin_probability, box_dims, kBoxAxes, "1",
          "that absorption probability (1 on the attractor's own boxes)");
  c.array("basin_fraction", res.basin_fraction, {res.basin_fraction.size()}, "attractor", "1",
          "fraction of the Lebesgue measure of the chart rectangle absorbed by each attractor's boxes");
}

// The partition, the matrix and its closed classes.
void describe_matrix(const TransferResult& res, core::Contents& c) {
  c.attr("n1", res.part.n1);
  c.attr("n2", res.part.n2);
  c.attr("lo1", res.part.lo1);
  c.attr("hi1", res.part.hi1);
  c.attr("lo2", res.part.lo2);
  c.attr("hi2", res.part.hi2);
  c.attr("nnz", res.nnz);
  c.attr("lost_samples", static_cast<long>(res.lost));
  c.attr("matrix_bytes", static_cast<long>(res.matrix_bytes));
  c.attr("closed_classes", static_cast<long>(res.closed_classes()));
  for (std::size_t k = 0; k < res.classes.size(); ++k) {
    c.attr(fmt::format("closed_class_{}_boxes", k + 1), res.classes[k].boxes);
    c.attr(fmt::format("closed_class_{}_period", k + 1), static_cast<long>(res.classes[k].period));
  }
}

// The summary numbers of the spectrum, the components and the comparison with the empirical measure.
void describe_spectrum(const TransferResult& res, core::Contents& c) {
  c.attr("near_one_count", static_cast<long>(res.near_one_count));
  c.attr("components", static_cast<long>(res.components.size()));
  c.attr("unabsorbed", res.unabsorbed);
  c.attr("second_value", res.second_value);
  c.attr("second_block", static_cast<long>(res.second_block));
  c.attr("second_positive_mass", res.second_positive_mass);
  c.attr("second_negative_mass", res.second_negative_mass);
  c.attr("second_positive_boxes", res.second_positive_boxes);
  c.attr("second_negative_boxes", res.second_negative_boxes);
  c.attr("tv_boxes", res.tv_boxes);
  c.attr("tv_coarse", res.tv_coarse);
  c.attr("measure_points", res.measure_points);
}

// The basins' and the cycles' summary attributes, and which CSV cells may be empty.
void describe_basins_and_cycles(const TransferResult& res, core::Contents& c) {
  const bool spectrum = res.request.spectrum();
  c.attr("basins", static_cast<long>(res.basins.size()));
  if (!res.basins.empty()) {
    c.attr("basin_unabsorbed", res.basin_unabsorbed);
    c.attr("basin_residual", res.basin_residual);
    c.attr("basin_iterations", res.basin_iterations);
    c.attr("seconds_basins", res.seconds_basins);
    for (std::size_t k = 0; k < res.basins.size(); ++k) c.attr(fmt::format("basin_{}", k + 1), res.basins[k].attractor);
  }
  for (std::size_t k = 0; k < res.cycles.size(); ++k) {
    c.attr(fmt::format("cycle_{}", k + 1), res.cycles[k].word);
    if (!spectrum) continue;
    c.attr(fmt::format("cycle_{}_mass_boxes", k + 1), res.cycles[k].mass_boxes);
    c.attr(fmt::format("cycle_{}_mass_neighbourhood", k + 1), res.cycles[k].mass_neighbourhood);
  }
  c.attr("csv_empty_cells",
         spectrum ? std::string("spectrum.csv: whole_re, whole_im, whole_modulus beyond the eigenvalues of the "
                                "whole-matrix cross-check (check-whole); basins.csv: exact except for the P2 region "
                                "on the strip; any empty cell: not a finite number")
                  : std::string("cycles.csv: mass_boxes, mass_neighbourhood, component_share, radius99 and "
                                "radius99_component (eigenvalues 0: no spectrum, no density; component is then the "
                                "closed class holding every box of the cycle, 0 for none); basins.csv: exact except "
                                "for the P2 region on the strip; any empty cell: "
                                "not a finite number"));
}

}  // namespace

void TransferResult::describe(core::Contents& c) const {
  describe_arrays(*this, c);
  request_attrs(request, c);
  describe_matrix(*this, c);
  if (request.spectrum()) describe_spectrum(*this, c);
  // JSON has no NaN: the P2 angle is recorded only where the P2 curves exist (r >= 3 - 2 sqrt 2).
  if (const double beta = p2_rotation_angle(request.r); std::isfinite(beta)) c.attr("p2_beta", beta);
  c.attr("seconds_matrix", seconds_matrix);
  if (request.spectrum()) c.attr("seconds_spectrum", seconds_spectrum);
  c.attr("seconds", seconds_total);
  describe_basins_and_cycles(*this, c);
}

std::string TransferResult::spectrum_csv() const {
  core::CsvTable t("k,re,im,modulus,block,whole_re,whole_im,whole_modulus");
  for (std::size_t k = 0; k < eig_re.size(); ++k) {
    const bool w = k < whole_re.size();
    t.line(fmt::format("{},{},{},{},{},{},{},{}", k + 1, num(eig_re[k]), num(eig_im[k]),
                       num(std::hypot(eig_re[k], eig_im[k])), eig_block[k], w ? num(whole_re[k]) : "",
                       w ? num(whole_im[k]) : "", w ? num(std::hypot(whole_re[k], whole_im[k])) : ""));
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
  core::CsvTable t(
      "word,outcome,points,boxes_found,mass_boxes,mass_neighbourhood,component,component_share,radius99,"
      "radius99_component");
  const auto f6 = [](double v) { return core::csv_number(v, "{:.6f}"); };
  for (const CycleCheck& c : cycles) {
    long found = 0;
    for (long b : c.boxes) found += b >= 0;
    if (!request.spectrum()) {  // no density: its columns empty; component: the closed class holding the cycle
      t.line(fmt::format("{},{},{},{},,,{},,,", core::csv_text(c.word), core::csv_text(c.outcome), c.boxes.size(),
                         found, c.component));
      continue;
    }
    t.line(fmt::format("{},{},{},{},{},{},{},{},{},{}", core::csv_text(c.word), core::csv_text(c.outcome),
                       c.boxes.size(), found, f6(c.mass_boxes), f6(c.mass_neighbourhood), c.component,
                       f6(c.component_share), c.radius99, c.radius99_component));
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

std::string TransferResult::classes_csv() const {
  if (!request.cycles.empty()) return "";
  core::CsvTable t("closed_class,attractor,type,verdict,starts");
  for (const ClassAttractor& a : class_names.reached)
    t.line(fmt::format("{},{},{},{},{}", a.closed_class, core::csv_text(a.attractor), core::csv_text(a.type),
                       core::csv_text(a.verdict), a.starts));
  return t.text();
}

namespace {
// Without --cycle: one line per closed class, its name and what its starts reached.
std::string class_lines(const ClassNames& names) {
  std::string s;
  for (std::size_t k = 0; k < names.name.size(); ++k) {
    std::string reached;
    for (const ClassAttractor& a : names.reached)
      if (a.closed_class == static_cast<int>(k + 1))
        reached += fmt::format("{}{} {}", reached.empty() ? "" : ", ", a.attractor, a.starts);
    const std::string verdict = names.name[k] == names.verdict[k] ? "" : " (" + names.verdict[k] + ")";
    s += fmt::format("  closed class {}: {}{}; of {} box centres classified: {}\n", k + 1, names.name[k], verdict,
                     names.classified[k], reached);
  }
  return s;
}
}  // namespace

std::string TransferResult::summary() const {
  const TransferRequest& q = request;
  std::string s;
  if (!q.spectrum()) {
    s = fmt::format(
        "btob: transfer at r = {}: {} boxes x {} samples, nnz {} ({:.1f} MB), matrix {:.2f} s, total {:.2f} s; "
        "{} closed classes; no spectrum (eigenvalues 0): basins only\n",
        q.r, part.size(), q.samples, nnz, static_cast<double>(matrix_bytes) / 1e6, seconds_matrix, seconds_total,
        closed_classes());
    for (std::size_t k = 0; k < classes.size(); ++k)
      s += fmt::format("  closed class {}: {} boxes, period {}\n", k + 1, classes[k].boxes, classes[k].period);
    for (const CycleCheck& c : cycles) {
      long found = 0;
      for (long b : c.boxes) found += b >= 0;
      s += fmt::format("  cycle {} ({}): {} of its {} points in the chart; {}\n", c.word, c.outcome, found,
                       c.boxes.size(),
                       c.component > 0 ? fmt::format("every one in closed class {}", c.component)
                                       : std::string("not within one closed class"));
    }
  } else {
    s = fmt::format(
        "btob: transfer at r = {}: {} boxes x {} samples, nnz {} ({:.1f} MB), matrix {:.2f} s, spectrum {:.2f} s, "
        "total "
        "{:.2f} s; {} closed classes, {} eigenvalues within {} of 1; lambda_2 (real, < 1) = {:.6f}; TV to the "
        "empirical "
        "measure {:.3f} ({}x{} boxes), {:.3f} ({}x{})\n",
        q.r, part.size(), q.samples, nnz, static_cast<double>(matrix_bytes) / 1e6, seconds_matrix, seconds_spectrum,
        seconds_total, closed_classes(), near_one_count, q.near_one, second_value, tv_boxes, part.n1, part.n2,
        tv_coarse, q.tv_bins, q.tv_bins);
    for (std::size_t k = 0; k < components.size(); ++k)
      s += fmt::format("  component {}: {} boxes, period {}, rho {:.6f}, Lebesgue fraction {:.4f}\n", k + 1,
                       components[k].boxes, components[k].period, components[k].rho, components[k].lebesgue);
    for (const CycleCheck& c : cycles)
      s += fmt::format(
          "  cycle {} ({}): mass {:.4f} on its boxes, {:.4f} on their 3x3 neighbourhoods, 99% within {} boxes; "
          "component {} (99% of it within {} boxes)\n",
          c.word, c.outcome, c.mass_boxes, c.mass_neighbourhood, c.radius99, c.component, c.radius99_component);
  }
  if (q.cycles.empty()) s += class_lines(class_names);
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
  c.array("re", re, {R, K}, "r, eigenvalue", "1",
          "real parts of the K leading eigenvalues (NaN where fewer converged)");
  c.array("im", im, {R, K}, "r, eigenvalue", "1", "imaginary parts of the K leading eigenvalues");
  c.array("peripheral_count", peripheral_count, {R}, "r", "count", "eigenvalues with 1 - |lambda| < peripheral");
  c.array("closed_classes", closed_classes, {R}, "r", "count", "closed classes of Ulam's matrix");
  c.array("rest_modulus", rest_modulus, {R}, "r", "1",
          "largest |lambda| outside the peripheral set (NaN: none within K)");
  c.array("gap", gap, {R}, "r", "1", "min |peripheral| - max |rest| (NaN: no peripheral or no rest within K)");
  c.array("p2_beta", p2_beta, {R}, "r", "rad",
          "rotation angle beta of P2's invariant curves, cos beta = -(1 - r)^2 / (4 r) (NaN below r = 3 - 2 sqrt 2)");
  c.array("window_lower", window_lower, {window_lower.size()}, "n = 1, 2, ...", "1",
          "lower bound of the window of (ab)^n(cb)^n: the root of Q_n");
  c.array("window_upper", window_upper, {window_upper.size()}, "n = 1, 2, ...", "1",
          "upper end of the window of (ab)^n(cb)^n: r_crit,2(n) (NaN for n = 1, which has none)");
  request_attrs(request, c);
  c.attr("seconds", seconds);
  c.attr("csv_empty_cells",
         std::string(
             "peripheral_r.csv: rest_modulus when every eigenvalue within K is peripheral, gap when there is no "
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
                       num(gap[i]), num(p2_beta[i])));
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
