// SPDX-License-Identifier: GPL-3.0-or-later
// Ulam's transfer operator of P^_r: partitions, charts, the matrix of the map, and the runs (pipelines) of
// `btob transfer` (its stages in stages.hpp) and `btob transfer-r`.
#include "transfer/transfer.hpp"

#include "core/cancel.hpp"
#include "core/fields.hpp"
#include "core/grid.hpp"
#include "core/run.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "core/coords.hpp"
#include "core/map.hpp"
#include "iterate/ensemble.hpp"
#include "patterns/patterns.hpp"
#include "transfer/detail.hpp"
#include "transfer/stages.hpp"
#include "transfer/transfer_impl.hpp"
#include "windows/windows.hpp"

namespace btob::transfer {

long Partition::locate(double a, double b) const {
  if (!(a >= lo1 && a <= hi1 && b >= lo2 && b <= hi2)) return -1;  // also NaN
  const long i1 = std::min(n1 - 1, static_cast<long>((a - lo1) / (hi1 - lo1) * static_cast<double>(n1)));
  const long i2 = std::min(n2 - 1, static_cast<long>((b - lo2) / (hi2 - lo2) * static_cast<double>(n2)));
  return i1 * n2 + i2;
}

std::vector<std::pair<double, double>> sample_offsets(int samples) {
  // R2 sequence: frac(1/2 + k (1/g, 1/g^2)), g the plastic number (the root > 1 of g^3 = g + 1).
  constexpr double g = 1.32471795724474602596;
  const double a1 = 1 / g, a2 = 1 / (g * g);
  std::vector<std::pair<double, double>> o(static_cast<std::size_t>(samples));
  for (int k = 0; k < samples; ++k) {
    const double u = 0.5 + a1 * k, v = 0.5 + a2 * k;
    o[static_cast<std::size_t>(k)] = {u - std::floor(u), v - std::floor(v)};
  }
  return o;
}

// ---- The b-to-b map on a chart ------------------------------------------------------------------------------
Partition domain_partition(Domain d, long n1, long n2) {
  Partition p;
  p.n1 = n1, p.n2 = n2;
  if (d == Domain::strip) p.lo1 = -std::numbers::pi / 2, p.hi1 = std::numbers::pi / 2, p.lo2 = -1, p.hi2 = 1;
  else p.lo1 = 0, p.hi1 = std::numbers::pi / 2, p.lo2 = 0, p.hi2 = std::numbers::pi;
  return p;
}

void chart_to_vector(Domain d, double a, double b, double& x, double& y, double& z) {
  if (d == Domain::strip) {
    // from_strip(tan a, b) scaled by cos a (no overflow near |a| = pi/2).
    const double c = std::cos(a);
    x = (1 + b) / 2 * c, y = std::sin(a), z = (b - 1) / 2 * c;
  } else {
    const auto u = core::from_angles<double>(a, b);
    x = u(0), y = u(1), z = u(2);
  }
}

void vector_to_chart(Domain d, double x, double y, double z, double& a, double& b) {
  // The formulas of stats::empirical_measure (u in Q).
  if (d == Domain::strip) {
    a = std::atan2(y, x - z);
    b = (x + z) / (x - z);
  } else {
    a = std::atan2(-z, x);
    b = std::atan2(std::sqrt(x * x + z * z), -y);
  }
}

// The kernel route lives in kernel_route.cpp (compiled with the kernel flags).
void map_kernel(double r, Domain d, double* a, double* b, std::size_t n, int threads);

UlamMatrix ulam_btob(double r, Domain d, const Partition& p, int samples, const std::string& route,
                     const core::RunControl& c) {
  const int threads = core::thread_count(c.threads);
  if (route == "kernel")
    return ulam(
        p, samples, [&](double* a, double* b, std::size_t n) { map_kernel(r, d, a, b, n, threads); }, c);
  return ulam(
      p, samples,
      [&](double* a, double* b, std::size_t n) {
#pragma omp parallel for schedule(static) num_threads(threads)
        for (std::size_t k = 0; k < n; ++k) {
          core::Vec3<double> u;
          chart_to_vector(d, a[k], b[k], u(0), u(1), u(2));
          const auto s = core::step<double>(u, r);
          vector_to_chart(d, s.u(0), s.u(1), s.u(2), a[k], b[k]);
        }
      },
      c);
}

double p2_rotation_angle(double r) {
  const double c = -(1 - r) * (1 - r) / (4 * r);
  return c >= -1 ? std::acos(c) : std::numeric_limits<double>::quiet_NaN();
}
// ---- btob transfer ----------------------------------------------------------------------------------------
// The pipeline of stages.hpp: each stage's output is kept in the result as the files need it.
namespace {

// Stage 1: Ulam's matrix and its size.
UlamMatrix matrix_stage(const TransferRequest& q, Domain dom, TransferResult& res, const core::RunControl& control) {
  const auto started = std::chrono::steady_clock::now();
  UlamMatrix P = ulam_btob(q.r, dom, res.part, q.samples, q.route, control);
  res.nnz = P.nnz();
  res.lost = P.lost;
  res.matrix_bytes = P.col.size() * sizeof(int) + P.val.size() * sizeof(double) + P.row_ptr.size() * sizeof(int);
  res.seconds_matrix = core::seconds_since(started);
  core::check_cancel(control.cancel);
  return P;
}

// Stage 3's output in the result: the eigenvalues, their blocks, the near-one count, the whole-matrix check.
void record_spectrum(const Spectrum& spectrum, double near_one, TransferResult& res) {
  for (const auto& e : spectrum.pairs) {
    res.eig_re.push_back(e.value.real());
    res.eig_im.push_back(e.value.imag());
    res.eig_block.push_back(e.block);
    if (std::abs(e.value - 1.0) <= near_one) ++res.near_one_count;
  }
  for (const auto& v : spectrum.whole) {
    res.whole_re.push_back(v.real());
    res.whole_im.push_back(v.imag());
  }
}

// Stages 4-7 (with a spectrum): absorbers, projection, components, second eigenvector.  Returns the components'
// densities (for the cycle checks).
std::vector<std::vector<double>> component_stages(const UlamMatrix& P, const Decomposition& d, const Spectrum& spectrum,
                                                  const std::vector<double>& mu, const TransferRequest& q,
                                                  const core::RunControl& control, TransferResult& res) {
  const Absorbers absorbers = find_absorbers(P, d, spectrum.pairs, q.near_one, control.cancel);
  const Projection projection = project_lebesgue(P, absorbers, mu, control.cancel);
  res.unabsorbed = projection.unabsorbed;
  Components components =
      split_components(P, d, res.part, absorbers, spectrum.pairs, projection.entry, q.near_one, control.cancel);
  res.components = std::move(components.info);
  res.component_of_box = std::move(components.of_box);
  res.density = std::move(components.density);
  SecondEigenvector second = second_eigenvector(spectrum.pairs, P.n);
  res.second_value = second.value;
  res.second_block = second.block;
  res.second = std::move(second.vector);
  res.second_positive_mass = second.positive_mass, res.second_negative_mass = second.negative_mass;
  res.second_positive_boxes = second.positive_boxes, res.second_negative_boxes = second.negative_boxes;
  return std::move(components.densities);
}

// Stage 8: the named cycles, or without --cycle the stable periodic attractors found in the closed classes.
void cycle_stage(const TransferRequest& q, Domain dom, const Decomposition& d,
                 const std::vector<std::vector<double>>& densities, const core::RunControl& control,
                 TransferResult& res) {
  std::vector<std::string> words = q.cycle_words();
  if (q.cycles.empty()) {
    res.class_names = name_closed_classes(res.part, dom, d, q.r, control);
    words = res.attractors_found = res.class_names.stable_words;
  }
  const std::vector<double>* density = q.spectrum() ? &res.density : nullptr;
  for (const auto& w : words) res.cycles.push_back(check_cycle(w, q.r, dom, res.part, d, density, densities));
}

// Stage 9: basins from the Ulam graph.
void basin_stage(const UlamMatrix& P, const TransferRequest& q, Domain dom, const std::vector<double>& mu,
                 const core::RunControl& control, TransferResult& res) {
  const auto started = std::chrono::steady_clock::now();
  Basins basins = absorb(P, basin_targets(res.cycles, res.part, dom, q), mu, control.cancel);
  res.basins = std::move(basins.basins);
  for (const auto& b : res.basins) res.basin_fraction.push_back(b.fraction);
  res.basin_of_box = std::move(basins.basin_of_box);
  res.basin_probability = std::move(basins.basin_probability);
  res.basin_unabsorbed = basins.unabsorbed;
  res.basin_residual = basins.residual;
  res.basin_iterations = basins.iterations;
  res.seconds_basins = core::seconds_since(started);
  core::check_cancel(control.cancel);
}

// The arrays of the HDF5 file: "second" all 0 when there is no such eigenvalue, the Lebesgue fractions, the (a, b)
// of every cycle point.
void file_arrays(TransferResult& res) {
  if (res.second.empty() && res.request.spectrum()) res.second.assign(res.density.size(), 0);
  for (const auto& ci : res.components) res.lebesgue.push_back(ci.lebesgue);
  for (const auto& cc : res.cycles)
    for (std::size_t k = 0; k < cc.a.size(); ++k)
      res.cycle_points.push_back(cc.a[k]), res.cycle_points.push_back(cc.b[k]);
}

}  // namespace

TransferResult run(const TransferRequest& q, const core::RunControl& control) {
  q.validate();
  const auto started = std::chrono::steady_clock::now();
  TransferResult res;
  res.request = q;
  const Domain dom = parse_domain(q.domain);
  const auto [n1, n2] = parse_boxes(q.boxes);
  res.part = domain_partition(dom, n1, n2);
  const UlamMatrix P = matrix_stage(q, dom, res, control);
  const auto spectrum_started = std::chrono::steady_clock::now();
  const Decomposition d = decompose(P);
  res.classes = d.classes;
  // Without a spectrum (eigenvalues 0) there are no components, no density and no eigenvector: only the basins.
  const Spectrum spectrum = q.spectrum() ? leading_spectrum(P, d, q, control.cancel) : Spectrum{};
  record_spectrum(spectrum, q.near_one, res);
  res.seconds_spectrum = core::seconds_since(spectrum_started);
  core::check_cancel(control.cancel);
  const std::vector<double> mu = lebesgue(res.part, dom, q.w1_range);
  std::vector<std::vector<double>> densities;  // per component: its density over all boxes
  if (q.spectrum()) densities = component_stages(P, d, spectrum, mu, q, control, res);
  cycle_stage(q, dom, d, densities, control, res);
  basin_stage(P, q, dom, mu, control, res);
  if (q.measure_orbits > 0 && q.spectrum()) {  // (nothing to compare it with without the density)
    const MeasureComparison cmp = compare_with_empirical(q, dom, res.part, res.density, control);
    res.tv_boxes = cmp.tv_boxes, res.tv_coarse = cmp.tv_coarse, res.measure_points = cmp.points;
  }
  file_arrays(res);
  res.seconds_total = core::seconds_since(started);
  return res;
}

// ---- the cost of transfer and transfer-r (core/work.hpp) -------------------------------------------------------
namespace {
// The side N of an NxN probe partition near `boxes` boxes, a multiple of 8 (so tv-bins 8 divides it), at least 8.
long probe_side(double boxes) { return std::max(8L, 8 * std::lround(std::sqrt(std::max(boxes, 64.0)) / 8)); }

// Ulam's sample images in `domain` by `route`: the matrix of r = 0.15 on an NxN partition, 16 samples a box.
core::Term ulam_term(const std::string& domain, const std::string& route, double images) {
  core::Term t;
  t.route = fmt::format("transfer ulam images {} {}", domain, route);
  t.units = images;
  t.what = fmt::format("sample images of Ulam's matrix ({} route; boxes x samples)", route);
  t.probe = [domain, route](double n, const core::RunControl& c) {
    const Domain dom = parse_domain(domain);
    const long side = probe_side(n / 16);
    (void)ulam_btob(0.15, dom, domain_partition(dom, side, side), 16, route, c);
    return static_cast<double>(side * side * 16);
  };
  return t;
}

// The stages on the matrix, priced per box and eigenvalue on r = 0.15, 16 samples a box, 16 eigenvalues, at least
// 64x64 boxes (below 600 boxes the eigenvalues come from a dense solver, whose cost grows like boxes^3): transfer's
// whole pipeline without the empirical measure, or transfer-r's Arnoldi solve alone.  The Arnoldi iterations depend
// on r and on the spectrum's gaps (r = 0.3 costs about 3 times r = 0.15): the least certain of the rates.
core::Term matrix_term(const std::string& domain, double box_eigenvalues, bool transfer_r) {
  core::Term t;
  t.route = fmt::format("transfer{} matrix stages {}", transfer_r ? "-r" : "", domain);
  t.units = box_eigenvalues;
  t.what = transfer_r ? "box-eigenvalues of the Arnoldi solves (r values x boxes x eigenvalues)"
                      : "box-eigenvalues of the stages on the matrix (boxes x eigenvalues: decomposition, Arnoldi, "
                        "components, cycles, basins)";
  t.probe = [domain, transfer_r](double n, const core::RunControl& c) {
    const long side = std::max(64L, probe_side(n / 16));
    if (transfer_r) {
      TransferRRequest p;
      p.domain = domain;
      p.r_min = 0.15, p.r_max = 0.16, p.r_count = 1;
      p.boxes = fmt::format("{}x{}", side, side);
      p.eigenvalues = 16;
      (void)run(p, c);
    } else {
      TransferRequest p;
      p.domain = domain;
      p.boxes = fmt::format("{}x{}", side, side);
      p.samples = 16;
      p.eigenvalues = 16;
      p.measure_orbits = 0;
      p.tv_bins = 8;
      (void)run(p, c);
    }
    return static_cast<double>(side * side * 16);
  };
  return t;
}
}  // namespace

core::Work work(const TransferRequest& q) {
  const auto [n1, n2] = parse_boxes(q.boxes);
  const double boxes = static_cast<double>(n1) * static_cast<double>(n2), K = q.eigenvalues;
  core::Work w;
  w.terms.push_back(ulam_term(q.domain, q.route, boxes * q.samples));
  w.terms.push_back(matrix_term(q.domain, boxes * std::max(1.0, K), false));
  if (q.measure_orbits > 0 && q.spectrum()) {
    core::Term m;
    m.route = "transfer empirical measure";
    const double orbits = static_cast<double>(q.measure_orbits) * q.measure_orbits;
    m.units = orbits * static_cast<double>(q.measure_iterations + q.measure_transient);
    m.what = "map steps of the empirical measure's orbits (measure-orbits^2 x (transient + iterations))";
    m.probe = [](double n, const core::RunControl& c) {
      TransferRequest p;  // an 8x8 matrix: the measure's orbits are the run
      p.boxes = "8x8";
      p.samples = 1;
      p.eigenvalues = 1;
      p.tv_bins = 8;
      p.measure_orbits = 4;
      p.measure_transient = 0;
      p.measure_iterations = std::max(100L, static_cast<long>(n / 16));
      (void)run(p, c);
      return 16.0 * static_cast<double>(p.measure_iterations);
    };
    w.terms.push_back(std::move(m));
  }
  // Per box a few arrays (density, basins, components, the Lebesgue projection) in NAME.h5 and the tables; the
  // matrix (a 4-byte column and an 8-byte value per distinct image, at most samples a box) and the Arnoldi basis
  // (2K + 1 complex vectors of the boxes) at once.
  w.output_bytes = boxes * 8 * 6 + K * 64 + 4096;
  w.peak_bytes = boxes * std::min<double>(q.samples, 64) * 12 + boxes * (2 * K + 1) * 16 + boxes * 8 * 8;
  return w;
}

core::Work work(const TransferRRequest& q) {
  const auto [n1, n2] = parse_boxes(q.boxes);
  const double boxes = static_cast<double>(n1) * static_cast<double>(n2), R = static_cast<double>(q.r_count);
  core::Work w;
  w.terms.push_back(ulam_term(q.domain, q.route, R * boxes * q.samples));
  w.terms.push_back(matrix_term(q.domain, R * boxes * q.eigenvalues, true));
  w.output_bytes = R * (static_cast<double>(q.eigenvalues) * 2 * 20 + 100) + 4096;
  w.peak_bytes = boxes * std::min<double>(q.samples, 64) * 12 + boxes * (2.0 * q.eigenvalues + 1) * 16;
  return w;
}

// ---- btob transfer-r --------------------------------------------------------------------------------------
TransferRResult run(const TransferRRequest& q, const core::RunControl& c) {
  q.validate();
  const auto t0 = std::chrono::steady_clock::now();
  TransferRResult res;
  res.request = q;
  res.r = iterate::linspace_r(q.r_min, q.r_max, q.r_count);
  res.K = q.eigenvalues;
  const Domain dom = parse_domain(q.domain);
  const auto [n1, n2] = parse_boxes(q.boxes);
  const Partition part = domain_partition(dom, n1, n2);
  const std::size_t R = res.r.size(), K = static_cast<std::size_t>(q.eigenvalues);
  res.re.assign(R * K, std::numeric_limits<double>::quiet_NaN());
  res.im = res.re;
  core::RunControl inner = c;
  inner.progress = nullptr;
  for (std::size_t ir = 0; ir < R; ++ir) {
    core::check_cancel(c.cancel);
    const UlamMatrix P = ulam_btob(res.r[ir], dom, part, q.samples, q.route, inner);
    const Decomposition d = decompose(P);
    const auto pairs = leading_eigenpairs(P, d, q.eigenvalues, false, kDenseMaxBoxes, c.cancel);
    int per = 0;
    double min_per = 2, max_rest = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      res.re[ir * K + k] = pairs[k].value.real();
      res.im[ir * K + k] = pairs[k].value.imag();
      const double m = std::abs(pairs[k].value);
      if (1 - m < q.peripheral) ++per, min_per = std::min(min_per, m);
      else if (!(max_rest >= m)) max_rest = m;
    }
    res.peripheral_count.push_back(static_cast<std::uint32_t>(per));
    res.closed_classes.push_back(static_cast<std::uint32_t>(d.classes.size()));
    res.rest_modulus.push_back(max_rest);
    res.gap.push_back(per > 0 && std::isfinite(max_rest) ? min_per - max_rest
                                                         : std::numeric_limits<double>::quiet_NaN());
    res.p2_beta.push_back(p2_rotation_angle(res.r[ir]));
    if (c.progress) c.progress->update(ir + 1, R);
  }
  for (int n = 1; n <= 12; ++n) {
    res.window_lower.push_back(static_cast<double>(windows::window_lower_bound(n, 12)));
    res.window_upper.push_back(n >= 2 ? static_cast<double>(windows::r_crit2(n, 20))
                                      : std::numeric_limits<double>::quiet_NaN());
  }
  res.seconds = core::seconds_since(t0);
  return res;
}

}  // namespace btob::transfer
