// `btob classify` (one orbit), `btob basins` (one r over a grid: basin image and fractions), `btob basins-r`
// (basin fractions across r, compared to Table 6.1): the attractors of Section 8.1 (1), flags ->
// attractors::*Request -> run -> files.
#include "attractors/requests.hpp"
#include "cli/command.hpp"
#include "cli/common.hpp"
#include "cli/sweep.hpp"
#include "core/coords.hpp"
#include "io/io.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>

namespace btob::cli {
namespace {

std::string csv_quote(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// ---- btob classify ----
void classify(const attractors::ClassifyRequest& req, const Output&, const Context& ctx) {
  const attractors::ClassifyResult res = attractors::run(req, ctx.control);
  const attractors::OrbitVerdict& v = res.verdict;
  std::cout << "type,pattern,period,lambda1,err,detail\n";
  std::cout << fmt::format("{},{},{},{:.6g},{:.2g},{}\n", attractors::type_name(v.type), csv_quote(res.pattern),
                           v.period, v.lambda1, v.err1, csv_quote(res.detail));
}

// ---- btob basins ----
// fractions.csv: the requested columns first, then counts, replicate spread and evidence.
std::string fractions_csv(const attractors::BasinsResult& res) {
  const attractors::Basins& b = res.basins;
  std::string csv =
      "attractor,type,pattern,fraction,ci_low,ci_high,count,replicate_mean,replicate_sd,canonical,period,collisions,"
      "stability,lyapunov2,rotation_min,rotation_max,invariant_min,invariant_max,w1,w2,letters\n";
  for (std::size_t i = 0; i < b.attractors.size(); ++i) {
    const auto& at = b.attractors[i];
    const auto w = core::strip<double>(at.point);
    csv += fmt::format("{},{},{},{:.6f},{:.6f},{:.6f},{},{:.6f},{:.6f},{},{},{},{},{:.6g},{:.10g},{:.10g},{:.8g},{:.8g},{:.12g},{:.12g},{}\n",
                       at.id, attractors::type_name(at.type), csv_quote(at.pattern), b.fractions[i].value,
                       b.fractions[i].low, b.fractions[i].high, at.count, res.replicate_mean[i], res.replicate_sd[i],
                       csv_quote(at.canonical), at.period, at.collisions, csv_quote(at.stability), at.lyapunov2,
                       at.rotation_min, at.rotation_max, at.invariant_min, at.invariant_max, w.first, w.second,
                       csv_quote(at.letters));
  }
  const std::size_t u = b.attractors.size();
  csv += fmt::format("0,unresolved,,{:.6f},{:.6f},{:.6f},{},{:.6f},{:.6f},,,,,,,,,,,\n", b.unresolved.value,
                     b.unresolved.low, b.unresolved.high, res.unresolved_count, res.replicate_mean[u],
                     res.replicate_sd[u]);
  return csv;
}

void basins(const attractors::BasinsRequest& req, const Output& o, const Context& ctx) {
  const auto got = sweep(req, ctx);  // every MPI rank computes its share of the rows; rank 0 writes
  if (!got) return;
  const attractors::BasinsResult& res = *got;
  core::Contents c;
  res.describe(c);
  const io::Attrs at = ctx.attrs(o, c, "basins", "double");
  io::ResultFiles files(o.out, o.name);
  files.text("fractions.csv", fractions_csv(res));
  files.h5(c, at);
  ctx.manifest(files, at);
  if (!o.no_plot) files.plot_inputs("attractors_basins.py", {o.name + ".h5", "fractions.csv"});
  const auto written = files.commit();
  const attractors::Basins& b = res.basins;
  const std::size_t n = res.points();
  if (!o.quiet)
    std::cerr << fmt::format("btob: basins at r = {}: {} points x {} grids in {:.2f} s ({:.3g} points/s, {} threads), "
                             "{} attractors, unresolved {:.4f} ({} before refinement); wrote {}\n",
                             req.r, n, req.replicates + 1, b.seconds,
                             static_cast<double>(n * static_cast<std::size_t>(req.replicates + 1)) / b.seconds,
                             res.threads, b.attractors.size(), b.unresolved.value, b.unresolved_first_pass,
                             listing(written));
}

// ---- btob basins-r ----
std::string fractions_r_csv(const attractors::BasinsRResult& res) {
  std::string csv = "r,attractor_key,type,pattern,fraction,ci_low,ci_high,count,stability\n";
  for (const auto& row : res.rows) {
    for (std::size_t i = 0; i < row.attractors.size(); ++i)
      csv += fmt::format("{},{},{},{},{:.6f},{:.6f},{:.6f},{},{}\n", row.r, row.attractors[i].key,
                         attractors::type_name(row.attractors[i].type), csv_quote(row.attractors[i].pattern),
                         row.fractions[i].value, row.fractions[i].low, row.fractions[i].high, row.attractors[i].count,
                         csv_quote(row.attractors[i].stability));
    csv += fmt::format("{},,unresolved,,{:.6f},{:.6f},{:.6f},{},\n", row.r, row.unresolved.value, row.unresolved.low,
                       row.unresolved.high,
                       static_cast<std::size_t>(std::llround(row.unresolved.value * static_cast<double>(res.points))));
  }
  return csv;
}

// table_6_1_comparison.csv: periodic fraction (paper: % of 10 orbits) and the patterns found, per r.
std::string comparison_csv(const attractors::BasinsRResult& res) {
  std::string cmp =
      "r,paper_percent_periodic,paper_ci_low,paper_ci_high,consistent,paper_patterns,periodic_fraction,ci_low,ci_high,"
      "patterns_found,paper_patterns_found,extra_patterns,other_types\n";
  for (const auto& c : res.comparison) {
    std::string pci_lo, pci_hi, consistent;
    if (c.has_percent) {
      pci_lo = fmt::format("{:.4f}", c.paper.low), pci_hi = fmt::format("{:.4f}", c.paper.high);
      consistent = c.consistent ? "yes" : "no";
    }
    const std::string paper_found = c.in_table ? fmt::format("{}/{}", c.paper_found, c.paper_total) : "";
    cmp += fmt::format("{},{},{},{},{},{},{:.4f},{:.4f},{:.4f},{},{},{},{}\n", c.r, c.paper_percent, pci_lo, pci_hi,
                       consistent, csv_quote(c.paper_patterns), c.periodic.value, c.periodic.low, c.periodic.high,
                       csv_quote(c.found), paper_found, csv_quote(c.extra), csv_quote(c.other));
  }
  return cmp;
}

void basins_r(const attractors::BasinsRRequest& given, const Output& o, const Context& ctx) {
  // Table 6.1 is data of the lab (io::data_file) unless --reference names another CSV.
  attractors::BasinsRRequest req = given;
  const io::fs::path ref =
      req.reference.empty() ? io::data_file("reference/patterns_paper_table_6_1.csv") : io::fs::path(req.reference);
  std::ifstream in(ref);
  if (in) {
    std::stringstream ss;
    ss << in.rdbuf();
    req.reference_csv = ss.str();
  }
  const auto got = sweep(req, ctx);  // every MPI rank computes its share of the r values; rank 0 writes
  if (!got) return;
  const attractors::BasinsRResult& res = *got;
  if (!o.quiet)
    for (const auto& row : res.rows)
      std::cerr << fmt::format("btob: basins-r r = {}: {} attractors\n", row.r, row.attractors.size());
  core::Contents c;
  res.describe(c);
  const io::Attrs at = ctx.attrs(o, c, "basins-r", "double");
  io::ResultFiles files(o.out, o.name);
  files.text(o.name + ".csv", fractions_r_csv(res));
  files.text("table_6_1_comparison.csv", comparison_csv(res));
  files.h5(c, at);
  ctx.manifest(files, at);
  if (!o.no_plot) files.plot("attractors_fractions_r.py");
  const auto written = files.commit();
  if (!o.quiet) std::cerr << fmt::format("btob: basins-r in {:.2f} s; wrote {}\n", res.seconds, listing(written));
}

struct Registration {
  Registration() {
    command<attractors::ClassifyRequest>(
        "classify", "Classify one orbit: periodic, collapse, quasi-periodic, chaotic or unresolved", Output::to_stdout(),
        classify);
    command<attractors::BasinsRequest>(
        "basins",
        "Basins of the attractors at one r over a grid: image and fractions; writes fractions.csv, NAME.h5, NAME.json, "
        "NAME.png",
        Output{"results/attractors/basins", "basins", "", 0, false, false}, basins);
    command<attractors::BasinsRRequest>(
        "basins-r",
        "Basin fractions across r (Table 6.1 with many orbits), stacked areas; writes NAME.csv, "
        "table_6_1_comparison.csv, NAME.h5, NAME.json, NAME.png",
        Output{"results/attractors/basins_r", "fractions_r", "", 0, false, false}, basins_r);
  }
} registration;

}  // namespace
}  // namespace btob::cli
