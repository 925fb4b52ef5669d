// `btob transfer` (Ulam's transfer operator at one r: spectrum, invariant densities, Lebesgue projection, TV to the
// empirical measure) and `btob transfer-r` (peripheral spectrum and gap across r): Section 8's programme.
#include "cli/app.hpp"
#include "cli/common.hpp"
#include "core/csv.hpp"
#include "io/io.hpp"
#include "transfer/transfer.hpp"
#include "windows/windows.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

namespace btob::cli {
namespace {

// Adapts io::Progress to the request contract's progress sink.
struct Progress : core::ProgressSink {
  io::Progress bar;
  explicit Progress(std::string label) : bar(std::move(label)) {}
  void update(std::size_t done, std::size_t total) override { bar.update(done, total); }
};

// Binds every field of a request to a flag of the same long name.
template <class Request> void bind(CLI::App* c, Request& q) {
  q.fields([c](const char* name, auto& member, const char* help) {
    using M = std::decay_t<decltype(member)>;
    if constexpr (std::is_same_v<M, bool>) {
      c->add_flag(std::string("--") + name, member, help);
      return;
    }
    auto* o = c->add_option(std::string("--") + name, member, help);
    if constexpr (std::is_same_v<M, std::vector<double>>) o->delimiter(',')->expected(2);
    else if constexpr (std::is_same_v<M, std::vector<std::string>>) o->delimiter(',');
    else o->capture_default_str();
  });
}

struct Common {
  std::string out, name;
  int threads = 0;
  bool no_plot = false, quiet = false;
};

void check_threads(int t) {
  if (t < 0 || t > core::RunControl::max_threads)
    throw core::InvalidField("threads", std::to_string(t), fmt::format("0..{} (0: all cores)", core::RunControl::max_threads));
}

std::string csv_value(double v) { return std::isfinite(v) ? fmt::format("{:.17g}", v) : std::string("nan"); }

// ---- btob transfer ----
void transfer_cmd(const transfer::TransferRequest& q, const Common& a) {
  q.validate();
  check_threads(a.threads);
  const io::fs::path out(a.out);
  io::ensure_dir(out);
  const auto since = start_time();  // for the list of files written
  Progress progress("transfer");
  core::RunControl control;
  control.threads = a.threads;
  control.progress = &progress;
  const transfer::TransferResult res = transfer::run(q, control);
  const auto& p = res.part;
  const int threads = a.threads > 0 ? a.threads : omp_get_max_threads();

  core::CsvTable spec("k,re,im,modulus,block,whole_re,whole_im,whole_modulus");
  for (std::size_t k = 0; k < res.eig_re.size(); ++k) {
    const bool w = k < res.whole_re.size();
    spec.line(fmt::format("{},{},{},{},{},{},{},{}", k + 1, csv_value(res.eig_re[k]), csv_value(res.eig_im[k]),
                        csv_value(std::hypot(res.eig_re[k], res.eig_im[k])), res.eig_block[k],
                        w ? csv_value(res.whole_re[k]) : "", w ? csv_value(res.whole_im[k]) : "",
                        w ? csv_value(std::hypot(res.whole_re[k], res.whole_im[k])) : ""));
  }
  io::write_text_atomic(out / "spectrum.csv", spec.text());

  core::CsvTable comp("component,kind,boxes,period,rho,lebesgue_fraction,centre_a,centre_b,w1,w2");
  for (std::size_t k = 0; k < res.components.size(); ++k) {
    const auto& c = res.components[k];
    const bool strip = q.domain == "strip";
    comp.line(fmt::format("{},{},{},{},{},{:.6f},{:.6g},{:.6g},{},{}", k + 1, c.block > 0 ? "closed" : "almost-invariant",
                        c.boxes, c.period, csv_value(c.rho), c.lebesgue, c.centre[0], c.centre[1],
                        strip ? fmt::format("{:.6g}", std::tan(c.centre[0])) : "", strip ? fmt::format("{:.6g}", c.centre[1]) : ""));
  }
  io::write_text_atomic(out / "components.csv", comp.text());

  core::CsvTable cyc("word,outcome,points,boxes_found,mass_boxes,mass_neighbourhood,component,component_share,radius99,"
                     "radius99_component");
  for (const auto& c : res.cycles) {
    long found = 0;
    for (long b : c.boxes) found += b >= 0;
    cyc.line(fmt::format("{},{},{},{},{:.6f},{:.6f},{},{:.6f},{},{}", core::csv_text(c.word), core::csv_text(c.outcome), c.boxes.size(), found, c.mass_boxes,
                       c.mass_neighbourhood, c.component, c.component_share, c.radius99, c.radius99_component));
  }
  if (!res.cycles.empty()) io::write_text_atomic(out / "cycles.csv", cyc.text());

  io::Attrs at = io::provenance(command_line_of(nullptr));
  at["kind"] = std::string("transfer");
  auto fields = q;  // fields() visits mutable members
  fields.fields([&](const char* name, const auto& member, const char*) {
    using M = std::decay_t<decltype(member)>;
    if constexpr (std::is_same_v<M, std::string>) at[name] = member;
    else if constexpr (std::is_same_v<M, double>) at[name] = member;
    else if constexpr (std::is_same_v<M, bool>) at[name] = std::string(member ? "true" : "false");
    else if constexpr (std::is_integral_v<M>) at[name] = static_cast<long>(member);
    else {
      std::string s;
      for (const auto& x : member) s += (s.empty() ? "" : ",") + fmt::format("{}", x);
      at[name] = s;
    }
  });
  at["n1"] = p.n1;
  at["n2"] = p.n2;
  at["lo1"] = p.lo1;
  at["hi1"] = p.hi1;
  at["lo2"] = p.lo2;
  at["hi2"] = p.hi2;
  at["nnz"] = res.nnz;
  at["lost_samples"] = static_cast<long>(res.lost);
  at["matrix_bytes"] = static_cast<long>(res.matrix_bytes);
  at["closed_classes"] = static_cast<long>(res.closed_classes);
  at["near_one_count"] = static_cast<long>(res.near_one_count);
  at["components"] = static_cast<long>(res.components.size());
  at["unabsorbed"] = res.unabsorbed;
  at["second_value"] = res.second_value;
  at["second_block"] = static_cast<long>(res.second_block);
  at["second_positive_mass"] = res.second_positive_mass;
  at["second_negative_mass"] = res.second_negative_mass;
  at["second_positive_boxes"] = res.second_positive_boxes;
  at["second_negative_boxes"] = res.second_negative_boxes;
  at["tv_boxes"] = res.tv_boxes;
  at["tv_coarse"] = res.tv_coarse;
  at["measure_points"] = res.measure_points;
  // JSON has no NaN: the P2 angle is recorded only where the P2 curves exist (r >= 3 - 2 sqrt 2).
  if (std::isfinite(transfer::p2_rotation_angle(q.r))) at["p2_beta"] = transfer::p2_rotation_angle(q.r);
  at["seconds_matrix"] = res.seconds_matrix;
  at["seconds_spectrum"] = res.seconds_spectrum;
  at["seconds"] = res.seconds_total;
  at["threads"] = static_cast<long>(threads);
  at["scalar_type"] = std::string("double");
  for (std::size_t k = 0; k < res.cycles.size(); ++k) {
    at[fmt::format("cycle_{}", k + 1)] = res.cycles[k].word;
    at[fmt::format("cycle_{}_mass_boxes", k + 1)] = res.cycles[k].mass_boxes;
    at[fmt::format("cycle_{}_mass_neighbourhood", k + 1)] = res.cycles[k].mass_neighbourhood;
  }
  const io::fs::path h5 = out / (a.name + ".h5");
  {
    io::H5Writer w(h5);
    w.attrs(at);
    const std::vector<std::size_t> dims{static_cast<std::size_t>(p.n1), static_cast<std::size_t>(p.n2)};
    w.dataset("density", res.density, dims);
    w.dataset("second", res.second.empty() ? std::vector<double>(res.density.size(), 0) : res.second, dims);
    w.dataset("component", res.component_of_box, dims);
    w.dataset("eig_re", res.eig_re, {res.eig_re.size()});
    w.dataset("eig_im", res.eig_im, {res.eig_im.size()});
    std::vector<double> leb;
    for (const auto& c : res.components) leb.push_back(c.lebesgue);
    w.dataset("lebesgue", leb, {leb.size()});
    std::vector<double> pts;  // (a, b) of every cycle point, all cycles in order
    for (const auto& c : res.cycles)
      for (std::size_t k = 0; k < c.a.size(); ++k) pts.push_back(c.a[k]), pts.push_back(c.b[k]);
    w.dataset("cycle_points", pts, {pts.size() / 2, 2});
    w.commit();
  }
  io::write_manifest(out / (a.name + ".json"), at);
  if (!a.quiet) {
    std::cerr << fmt::format(
        "btob: transfer at r = {}: {} boxes x {} samples, nnz {} ({:.1f} MB), matrix {:.2f} s, spectrum {:.2f} s, total "
        "{:.2f} s; {} closed classes, {} eigenvalues within {} of 1; lambda_2 (real, < 1) = {:.6f}; TV to the empirical "
        "measure {:.3f} ({}x{} boxes), {:.3f} ({}x{})\n",
        q.r, p.size(), q.samples, res.nnz, res.matrix_bytes / 1e6, res.seconds_matrix, res.seconds_spectrum,
        res.seconds_total, res.closed_classes, res.near_one_count, q.near_one, res.second_value, res.tv_boxes, p.n1, p.n2,
        res.tv_coarse, q.tv_bins, q.tv_bins);
    for (std::size_t k = 0; k < res.components.size(); ++k)
      std::cerr << fmt::format("  component {}: {} boxes, period {}, rho {:.6f}, Lebesgue fraction {:.4f}\n", k + 1,
                               res.components[k].boxes, res.components[k].period, res.components[k].rho,
                               res.components[k].lebesgue);
    for (const auto& c : res.cycles)
      std::cerr << fmt::format("  cycle {} ({}): mass {:.4f} on its boxes, {:.4f} on their 3x3 neighbourhoods, 99% within "
                               "{} boxes; component {} (99% of it within {} boxes)\n",
                               c.word, c.outcome, c.mass_boxes, c.mass_neighbourhood, c.radius99, c.component,
                               c.radius99_component);
  }
  if (!a.no_plot) io::run_plot("transfer.py", {h5.string(), (out / "spectrum.csv").string(), (out / (a.name + ".png")).string()});
  if (!a.quiet)
    print_written({out / "spectrum.csv", out / "components.csv", out / "cycles.csv", h5, out / (a.name + ".json"),
                   out / (a.name + ".png")},
                  since);
}

// ---- btob transfer-r ----
void transfer_r_cmd(const transfer::TransferRRequest& q, const Common& a) {
  q.validate();
  check_threads(a.threads);
  const io::fs::path out(a.out);
  io::ensure_dir(out);
  const auto since = start_time();  // for the list of files written
  Progress progress("transfer-r");
  core::RunControl control;
  control.threads = a.threads;
  control.progress = &progress;
  const transfer::TransferRResult res = transfer::run(q, control);
  const std::size_t K = static_cast<std::size_t>(res.K);

  core::CsvTable eig("r,k,re,im,modulus");
  core::CsvTable sum("r,peripheral_count,closed_classes,rest_modulus,gap,p2_beta");
  for (std::size_t i = 0; i < res.r.size(); ++i) {
    for (std::size_t k = 0; k < K; ++k) {
      const double re = res.re[i * K + k], im = res.im[i * K + k];
      if (!std::isfinite(re)) continue;
      eig.line(fmt::format("{},{},{},{},{}", csv_value(res.r[i]), k + 1, csv_value(re), csv_value(im),
                           csv_value(std::hypot(re, im))));
    }
    sum.line(fmt::format("{},{},{},{},{},{}", csv_value(res.r[i]), res.peripheral_count[i], res.closed_classes[i],
                         csv_value(res.rest_modulus[i]), csv_value(res.gap[i]),
                         csv_value(transfer::p2_rotation_angle(res.r[i]))));
  }
  io::write_text_atomic(out / "spectrum_r.csv", eig.text());
  io::write_text_atomic(out / "peripheral_r.csv", sum.text());
  // The windows of (ab)^n(cb)^n inside the range: [lower bound of Q_n, r_crit,2(n)] (src/windows), n = 1..12
  // (narrower windows are below the resolution of any r grid we draw).
  core::CsvTable win("n,lower,upper");
  for (int n = 1; n <= 12; ++n) {
    const double lo = static_cast<double>(windows::window_lower_bound(n, 12));
    const double hi = n >= 2 ? static_cast<double>(windows::r_crit2(n, 20)) : std::numeric_limits<double>::quiet_NaN();
    win.line(fmt::format("{},{},{}", n, csv_value(lo), csv_value(hi)));
  }
  io::write_text_atomic(out / "windows.csv", win.text());

  io::Attrs at = io::provenance(command_line_of(nullptr));
  at["kind"] = std::string("transfer-r");
  auto fields = q;  // fields() visits mutable members
  fields.fields([&](const char* name, const auto& member, const char*) {
    using M = std::decay_t<decltype(member)>;
    if constexpr (std::is_same_v<M, std::string>) at[name] = member;
    else if constexpr (std::is_same_v<M, double>) at[name] = member;
    else at[name] = static_cast<long>(member);
  });
  at["seconds"] = res.seconds;
  at["threads"] = static_cast<long>(a.threads > 0 ? a.threads : omp_get_max_threads());
  at["scalar_type"] = std::string("double");
  io::write_manifest(out / (a.name + ".json"), at);
  if (!a.quiet)
    std::cerr << fmt::format("btob: transfer-r: {} r values in [{}, {}], {} boxes x {} samples, {:.1f} s\n",
                             res.r.size(), q.r_min, q.r_max, q.boxes, q.samples, res.seconds);
  if (!a.no_plot)
    io::run_plot("transfer_r.py", {(out / "spectrum_r.csv").string(), (out / "peripheral_r.csv").string(),
                                   (out / "windows.csv").string(), (out / (a.name + ".png")).string(), q.boxes,
                                   std::to_string(q.samples), fmt::format("{}", q.peripheral)});
  if (!a.quiet)
    print_written({out / "spectrum_r.csv", out / "peripheral_r.csv", out / "windows.csv", out / (a.name + ".json"),
                   out / (a.name + ".png")},
                  since);
}

void add_common(CLI::App* c, Common& a) {
  c->add_option("--out", a.out, "output directory")->capture_default_str();
  c->add_option("--name", a.name, "file stem of the HDF5 file, manifest and image")->capture_default_str();
  c->add_option("--threads", a.threads, "OpenMP threads (0: all cores); results do not depend on it")->capture_default_str();
  c->add_flag("--no-plot", a.no_plot, "write data only");
  c->add_flag("--quiet", a.quiet, "no summary on stderr");
}

Register reg([](CLI::App& app) {
  {
    auto q = std::make_shared<transfer::TransferRequest>();
    auto a = std::make_shared<Common>(Common{"results/transfer/r0.15", "transfer"});
    CLI::App* c = app.add_subcommand(
        "transfer", "Ulam's transfer operator of P^_r on a box partition (Section 8): leading spectrum (Spectra), closed "
                    "classes and invariant densities, projection of Lebesgue measure (basin fractions), almost-invariant "
                    "sets, TV distance to the empirical measure; writes spectrum.csv, components.csv, NAME.h5/.json/.png");
    bind(c, *q);
    add_common(c, *a);
    c->callback([q, a] { transfer_cmd(*q, *a); });
  }
  {
    auto q = std::make_shared<transfer::TransferRRequest>();
    auto a = std::make_shared<Common>(Common{"results/transfer/r_scan", "transfer_r"});
    CLI::App* c = app.add_subcommand(
        "transfer-r", "Peripheral spectrum of Ulam's operator across r (eigenvalues within --peripheral of the unit "
                      "circle) and its gap to the rest; writes spectrum_r.csv, peripheral_r.csv, windows.csv, NAME.png");
    bind(c, *q);
    add_common(c, *a);
    c->callback([q, a] { transfer_r_cmd(*q, *a); });
  }
});

}  // namespace
}  // namespace btob::cli
