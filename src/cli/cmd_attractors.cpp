// `btob classify` (one orbit), `btob basins` (one r over a grid: basin image and fractions), `btob basins-r`
// (basin fractions across r, compared to Table 6.1): the attractors of Section 8.1 (1).
#include "attractors/attractors.hpp"
#include "patterns/patterns.hpp"
#include "cli/app.hpp"
#include "cli/common.hpp"
#include "core/coords.hpp"
#include "core/fields.hpp"
#include "io/io.hpp"
#include "iterate/ensemble.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

namespace btob::cli {
namespace {

std::string csv_quote(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// The classification thresholds shared by the three commands.
void add_options(CLI::App* c, attractors::Options& o) {
  c->add_option("--transient", o.transient, "steps before the window (>= 1)")->capture_default_str();
  c->add_option("--iterations", o.window, "window of the period / collapse test (>= max-period)")->capture_default_str();
  c->add_option("--max-period", o.max_period, "longest period searched, 1..1024")->capture_default_str();
  c->add_option("--return-tol", o.return_tol, "return distance counted as a period, (0, 1e-3]")->capture_default_str();
  c->add_option("--point-tol", o.point_tol, "distance to the exact cycle, (0, 1e-2]")->capture_default_str();
  c->add_option("--collapse-theta", o.collapse_theta, "theta (pi/2 - theta) of a collapse, (0, 0.1]")
      ->capture_default_str();
  c->add_option("--lyap-transient", o.lyap_transient, "tangent alignment steps of pass 2")->capture_default_str();
  c->add_option("--lyap-iterations", o.lyap_iterations, "averaged steps of pass 2")->capture_default_str();
  c->add_option("--lyap-blocks", o.lyap_blocks, "batch-means blocks, 2..1000")->capture_default_str();
  c->add_option("--rotation-tol", o.rotation_tol, "convergence of the weighted rotation number (turns), (0, 0.1]")
      ->capture_default_str();
  c->add_option("--refine-factor", o.refine_factor, "transient factor of the refinement pass (0 = off)")
      ->capture_default_str();
  c->add_option("--threads", o.run.threads, "OpenMP threads, 1..1024 (default: all cores; results do not depend on it)")
      ->check(CLI::Range(1, core::RunControl::max_threads));
}

std::string pattern_of(const attractors::OrbitVerdict& v, double r) {
  if (v.type == attractors::Type::unresolved) return "";
  // The attractor's own spelling (mirror-aware) from a one-verdict collection.
  const auto a = attractors::collect({v}, r, nullptr);
  return a.empty() ? "" : a[0].pattern;
}

// ---- btob classify ----
struct ClassifyArgs {
  double r = 0;
  std::string point;
  attractors::Options opt;
};

void classify_cmd(const ClassifyArgs& a) {
  core::require_r(a.r, "r");
  const core::Vec3<double> u = core::parse_point(a.point, "point");
  attractors::validate(a.opt);
  const attractors::OrbitVerdict v = attractors::classify_point(u, a.r, a.opt);
  std::string detail = v.detail + fmt::format("; {} iterations", v.iterations);
  if (v.type == attractors::Type::periodic && !v.word.s.empty()) {
    // The pattern tool's verdict at this r: stability and the collision letters (acb / cab resolved).
    const patterns::Verdict<double> pv = patterns::analyse<double>(v.word, a.r);
    detail += fmt::format("; pattern tool: {}; letters {}", patterns::outcome_name(pv.outcome), pv.letters);
  }
  std::cout << "type,pattern,period,lambda1,err,detail\n";
  std::cout << fmt::format("{},{},{},{:.6g},{:.2g},{}\n", attractors::type_name(v.type), csv_quote(pattern_of(v, a.r)),
                           v.period, v.lambda1, v.err1, csv_quote(detail));
}

// ---- btob basins ----
struct BasinsArgs {
  double r = 0;
  std::string grid = "strip:200x200";
  std::vector<double> w1_range{-2, 2};
  int replicates = 2;
  std::uint64_t seed = 1;
  std::string out = "results/attractors/basins";
  std::string name = "basins";
  bool no_plot = false, quiet = false;
  attractors::Options opt;
};

void basins_cmd(const BasinsArgs& a, const std::string& command_line) {
  core::require_r(a.r, "r");
  if (a.w1_range.size() != 2) throw UsageError("w1-range: expected two numbers a,b");
  attractors::validate(a.opt);
  const attractors::Grid g = attractors::parse_grid(a.grid, a.w1_range[0], a.w1_range[1], "grid");
  const std::size_t n = static_cast<std::size_t>(g.n1) * static_cast<std::size_t>(g.n2);
  iterate::checked_bytes(n, 800, "grid");  // refused up front, with the size it needs
  const io::fs::path out(a.out);
  io::ensure_dir(out);
  const attractors::Basins b = attractors::basins(a.r, g, a.replicates, a.seed, a.opt);
  const int threads = a.opt.run.threads > 0 ? a.opt.run.threads : omp_get_max_threads();

  // fractions.csv: the requested columns first, then counts, replicate spread and evidence.
  std::string csv =
      "attractor,type,pattern,fraction,ci_low,ci_high,count,replicate_mean,replicate_sd,canonical,period,collisions,"
      "stability,lyapunov2,rotation_min,rotation_max,invariant_min,invariant_max,w1,w2,letters\n";
  const auto spread = [&](std::size_t i) {
    const auto& v = b.replicate_fractions[i];
    double m = 0, s = 0;
    for (double x : v) m += x;
    m /= static_cast<double>(v.size());
    for (double x : v) s += (x - m) * (x - m);
    return std::pair<double, double>(m, v.size() > 1 ? std::sqrt(s / static_cast<double>(v.size() - 1)) : 0.0);
  };
  for (std::size_t i = 0; i < b.attractors.size(); ++i) {
    const auto& at = b.attractors[i];
    const auto [m, sd] = spread(i);
    const auto w = core::strip<double>(at.point);
    csv += fmt::format("{},{},{},{:.6f},{:.6f},{:.6f},{},{:.6f},{:.6f},{},{},{},{},{:.6g},{:.10g},{:.10g},{:.8g},{:.8g},{:.12g},{:.12g},{}\n",
                       at.id, attractors::type_name(at.type), csv_quote(at.pattern), b.fractions[i].value,
                       b.fractions[i].low, b.fractions[i].high, at.count, m, sd, csv_quote(at.canonical), at.period,
                       at.collisions, csv_quote(at.stability), at.lyapunov2, at.rotation_min, at.rotation_max,
                       at.invariant_min, at.invariant_max, w.first, w.second, csv_quote(at.letters));
  }
  {
    const auto [m, sd] = spread(b.attractors.size());
    std::size_t cnt = 0;
    for (auto l : b.labels) cnt += l == 0;
    csv += fmt::format("0,unresolved,,{:.6f},{:.6f},{:.6f},{},{:.6f},{:.6f},,,,,,,,,,,\n", b.unresolved.value,
                       b.unresolved.low, b.unresolved.high, cnt, m, sd);
  }
  io::write_text_atomic(out / "fractions.csv", csv);

  io::Attrs at = io::provenance(command_line);
  at["kind"] = std::string("basins");
  at["r"] = a.r;
  at["grid"] = a.grid;
  at["n1"] = g.n1;
  at["n2"] = g.n2;
  at["axis1_lo"] = g.lo1;
  at["axis1_hi"] = g.hi1;
  at["axis2_lo"] = g.lo2;
  at["axis2_hi"] = g.hi2;
  at["grid_kind"] = g.kind;
  at["replicates"] = static_cast<long>(a.replicates);
  at["seed"] = static_cast<long>(a.seed);
  at["transient"] = a.opt.transient;
  at["window"] = a.opt.window;
  at["max_period"] = static_cast<long>(a.opt.max_period);
  at["return_tol"] = a.opt.return_tol;
  at["point_tol"] = a.opt.point_tol;
  at["collapse_theta"] = a.opt.collapse_theta;
  at["lyap_transient"] = a.opt.lyap_transient;
  at["lyap_iterations"] = a.opt.lyap_iterations;
  at["lyap_blocks"] = static_cast<long>(a.opt.lyap_blocks);
  at["rotation_tol"] = a.opt.rotation_tol;
  at["refine_factor"] = static_cast<long>(a.opt.refine_factor);
  at["threads"] = static_cast<long>(threads);
  at["scalar_type"] = std::string("double");
  at["attractors"] = static_cast<long>(b.attractors.size());
  at["unresolved_fraction"] = b.unresolved.value;
  at["unresolved_first_pass"] = static_cast<long>(b.unresolved_first_pass);
  at["map_iterations"] = b.iterations_total;
  at["seconds"] = b.seconds;
  at["points_per_second"] = static_cast<double>(n * (a.replicates + 1)) / b.seconds;
  for (const auto& x : b.attractors)
    at[fmt::format("legend_{}", x.id)] = fmt::format("{} ({})", x.pattern, attractors::type_name(x.type));
  const io::fs::path h5 = out / (a.name + ".h5");
  {
    io::H5Writer w(h5);
    w.attrs(at);
    w.dataset("labels", b.labels, {static_cast<std::size_t>(g.n2), static_cast<std::size_t>(g.n1)});
    std::vector<double> fr, lo, hi;
    for (const auto& f : b.fractions) fr.push_back(f.value), lo.push_back(f.low), hi.push_back(f.high);
    w.dataset("fraction", fr, {fr.size()});
    w.dataset("ci_low", lo, {lo.size()});
    w.dataset("ci_high", hi, {hi.size()});
    w.commit();
  }
  io::write_manifest(out / (a.name + ".json"), at);
  if (!a.quiet)
    std::cerr << fmt::format("btob: basins at r = {}: {} points x {} grids in {:.2f} s ({:.3g} points/s, {} threads), "
                             "{} attractors, unresolved {:.4f} ({} before refinement); wrote {}\n",
                             a.r, n, a.replicates + 1, b.seconds,
                             static_cast<double>(n * (a.replicates + 1)) / b.seconds, threads, b.attractors.size(),
                             b.unresolved.value, b.unresolved_first_pass, (out / "fractions.csv").string());
  if (!a.no_plot)
    io::run_plot("attractors_basins.py", {h5.string(), (out / "fractions.csv").string(), (out / (a.name + ".png")).string()});
}

// ---- btob basins-r ----
struct BasinsRArgs {
  std::vector<double> r_values;
  bool table = false;
  std::string grid = "random:2000";
  std::uint64_t seed = 1;
  std::string out = "results/attractors/basins_r";
  std::string reference = io::data_file("reference/patterns_paper_table_6_1.csv").string();
  bool no_plot = false, quiet = false;
  attractors::Options opt;
};

// Table 6.1's r values, percentages and patterns (read from the reference CSV when given).
struct TableRow {
  double r;
  std::string percent, patterns;
};
std::vector<TableRow> read_table(const std::string& path) {
  std::vector<TableRow> rows;
  std::ifstream in(path);
  if (!in) return rows;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string item;
    while (std::getline(ss, item, ',')) f.push_back(item);
    if (f.size() < 2) continue;
    rows.push_back({std::stod(f[0]), f[1], f.size() > 2 ? f[2] : ""});
  }
  return rows;
}

void basins_r_cmd(const BasinsRArgs& a, const std::string& command_line) {
  attractors::validate(a.opt);
  const std::vector<TableRow> table = read_table(a.reference);
  std::vector<double> rs = a.r_values;
  if (a.table) {
    if (table.empty()) throw UsageError(fmt::format("reference: could not read '{}'", a.reference));
    for (const auto& t : table)
      if (t.r >= 0.1 - 1e-12 && t.r <= 0.6 + 1e-12) rs.push_back(t.r);
  }
  if (rs.empty()) throw UsageError("r-values: got none, expected a list of r in (0, 1) or --table");
  for (double r : rs) core::require_r(r, "r-values");
  const std::vector<core::Vec3<double>> pts = iterate::parse_grid(a.grid, a.seed, "grid");
  if (pts.empty()) throw UsageError(fmt::format("grid: got '{}' with no points, expected at least one", a.grid));
  iterate::checked_bytes(pts.size(), 800, "grid");
  const io::fs::path out(a.out);
  io::ensure_dir(out);
  const auto t0 = std::chrono::steady_clock::now();

  // Per r: the attractors (matched across r by key), fractions and intervals.
  struct Row {
    double r;
    std::vector<attractors::Attractor> at;
    std::vector<attractors::Fraction> fr;
    attractors::Fraction unresolved;
  };
  std::vector<Row> rows;
  for (double r : rs) {
    iterate::Ensemble e;
    e.r = {r};
    e.initial = pts;
    const auto v = attractors::classify(e, a.opt);
    Row row{r, attractors::collect(v, r, nullptr), {}, {}};
    std::size_t unres = 0;
    for (const auto& x : v) unres += x.type == attractors::Type::unresolved;
    for (const auto& x : row.at) row.fr.push_back(attractors::fraction(x.count, v.size()));
    row.unresolved = attractors::fraction(unres, v.size());
    rows.push_back(std::move(row));
    if (!a.quiet) std::cerr << fmt::format("btob: basins-r r = {}: {} attractors\n", r, rows.back().at.size());
  }
  // Keys across r, sorted (type, key): the columns of the stacked areas.
  std::map<std::pair<int, std::string>, std::string> keys;
  for (const auto& row : rows)
    for (const auto& x : row.at) keys[{static_cast<int>(x.type), x.key}] = x.pattern;
  std::string csv = "r,attractor_key,type,pattern,fraction,ci_low,ci_high,count,stability\n";
  for (const auto& row : rows) {
    for (std::size_t i = 0; i < row.at.size(); ++i)
      csv += fmt::format("{},{},{},{},{:.6f},{:.6f},{:.6f},{},{}\n", row.r, row.at[i].key,
                         attractors::type_name(row.at[i].type), csv_quote(row.at[i].pattern), row.fr[i].value,
                         row.fr[i].low, row.fr[i].high, row.at[i].count, csv_quote(row.at[i].stability));
    csv += fmt::format("{},,unresolved,,{:.6f},{:.6f},{:.6f},{},\n", row.r, row.unresolved.value, row.unresolved.low,
                       row.unresolved.high, static_cast<std::size_t>(std::llround(row.unresolved.value * pts.size())));
  }
  io::write_text_atomic(out / "fractions_r.csv", csv);

  // Comparison with Table 6.1: periodic fraction (paper: % of 10 orbits) and the patterns found.
  std::string cmp =
      "r,paper_percent_periodic,paper_ci_low,paper_ci_high,consistent,paper_patterns,periodic_fraction,ci_low,ci_high,"
      "patterns_found,paper_patterns_found,extra_patterns,other_types\n";
  for (const auto& row : rows) {
    const TableRow* t = nullptr;
    for (const auto& x : table)
      if (std::fabs(x.r - row.r) < 1e-9) t = &x;
    std::size_t periodic = 0;
    std::set<std::string> found;
    std::string found_s, other;
    for (std::size_t i = 0; i < row.at.size(); ++i) {
      const auto& x = row.at[i];
      if (x.type == attractors::Type::periodic) {
        periodic += x.count;
        found.insert(x.pattern);
        found_s += fmt::format("{}{} ({:.3f})", found_s.empty() ? "" : "; ", x.pattern, row.fr[i].value);
      } else {
        const std::string type = attractors::type_name(x.type);
        const std::string label = x.pattern.empty() || x.pattern == type ? type : type + " " + x.pattern;
        other += fmt::format("{}{} ({:.3f})", other.empty() ? "" : "; ", label, row.fr[i].value);
      }
    }
    other += fmt::format("{}unresolved ({:.3f})", other.empty() ? "" : "; ", row.unresolved.value);
    std::string paper_found, extra;
    std::set<std::string> paper;
    if (t) {
      std::stringstream ss(t->patterns);
      std::string p;
      while (std::getline(ss, p, ';'))
        if (!p.empty()) paper.insert(p);
    }
    int hit = 0;
    for (const auto& p : paper) hit += found.count(p) ? 1 : 0;
    paper_found = t ? fmt::format("{}/{}", hit, paper.size()) : "";
    for (const auto& p : found)
      if (!paper.count(p)) extra += (extra.empty() ? "" : "; ") + p;
    const auto f = attractors::fraction(periodic, pts.size());
    // The paper's percentage is k of 10 orbits: its own 95% interval, and whether our fraction lies inside.
    std::string pci_lo, pci_hi, consistent;
    if (t && !t->percent.empty()) {
      const auto k = static_cast<std::size_t>(std::llround(std::stod(t->percent) / 10));
      const auto pf = attractors::fraction(k, 10);
      pci_lo = fmt::format("{:.4f}", pf.low), pci_hi = fmt::format("{:.4f}", pf.high);
      consistent = f.value >= pf.low && f.value <= pf.high ? "yes" : "no";
    }
    cmp += fmt::format("{},{},{},{},{},{},{:.4f},{:.4f},{:.4f},{},{},{},{}\n", row.r, t ? t->percent : "", pci_lo, pci_hi,
                       consistent, csv_quote(t ? t->patterns : ""), f.value, f.low, f.high, csv_quote(found_s),
                       paper_found, csv_quote(extra), csv_quote(other));
  }
  io::write_text_atomic(out / "table_6_1_comparison.csv", cmp);

  // HDF5: fraction matrix [r x key] for the stacked areas.
  std::vector<double> frac(rows.size() * (keys.size() + 1), 0.0), rv;
  std::size_t col = 0;
  io::Attrs at = io::provenance(command_line);
  for (const auto& [k, pat] : keys) {
    for (std::size_t i = 0; i < rows.size(); ++i)
      for (std::size_t j = 0; j < rows[i].at.size(); ++j)
        if (rows[i].at[j].key == k.second) frac[i * (keys.size() + 1) + col] = rows[i].fr[j].value;
    const std::string type = attractors::type_name(static_cast<attractors::Type>(k.first));
    at[fmt::format("column_{}", col)] = pat.empty() || pat == type ? type : fmt::format("{} ({})", pat, type);
    ++col;
  }
  for (std::size_t i = 0; i < rows.size(); ++i) {
    frac[i * (keys.size() + 1) + col] = rows[i].unresolved.value;
    rv.push_back(rows[i].r);
  }
  at[fmt::format("column_{}", col)] = std::string("unresolved");
  at["kind"] = std::string("basins-r");
  at["grid"] = a.grid;
  at["seed"] = static_cast<long>(a.seed);
  at["points"] = static_cast<long>(pts.size());
  at["columns"] = static_cast<long>(keys.size() + 1);
  at["transient"] = a.opt.transient;
  at["window"] = a.opt.window;
  at["max_period"] = static_cast<long>(a.opt.max_period);
  at["lyap_iterations"] = a.opt.lyap_iterations;
  at["refine_factor"] = static_cast<long>(a.opt.refine_factor);
  at["threads"] = static_cast<long>(a.opt.run.threads > 0 ? a.opt.run.threads : omp_get_max_threads());
  at["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const io::fs::path h5 = out / "fractions_r.h5";
  {
    io::H5Writer w(h5);
    w.attrs(at);
    w.dataset("r", rv, {rv.size()});
    w.dataset("fraction", frac, {rows.size(), keys.size() + 1});
    w.commit();
  }
  io::write_manifest(out / "fractions_r.json", at);
  if (!a.no_plot) io::run_plot("attractors_fractions_r.py", {h5.string(), (out / "fractions_r.png").string()});
}

Register reg([](CLI::App& app) {
  {
    auto a = std::make_shared<ClassifyArgs>();
    CLI::App* c = app.add_subcommand("classify", "Classify one orbit: periodic, collapse, quasi-periodic, chaotic or unresolved");
    c->add_option("--r", a->r, "restitution coefficient in (0, 1)")->required();
    c->add_option("--point", a->point, "initial direction x,y,z with x z <= 0")->required();
    add_options(c, a->opt);
    c->callback([a] { classify_cmd(*a); });
  }
  {
    auto a = std::make_shared<BasinsArgs>();
    CLI::App* c = app.add_subcommand("basins", "Basins of the attractors at one r over a grid: image and fractions");
    c->add_option("--r", a->r, "restitution coefficient in (0, 1)")->required();
    c->add_option("--grid", a->grid, "strip:NxM (w1 x w2) or angles:NxM (theta x phi)")->capture_default_str();
    c->add_option("--w1-range", a->w1_range, "w1 range a,b of a strip grid")->delimiter(',')->expected(2);
    c->add_option("--replicates", a->replicates, "randomly shifted replicate grids, 0..100")->capture_default_str();
    c->add_option("--seed", a->seed, "seed of the replicate shifts")->capture_default_str();
    c->add_option("--out", a->out, "output directory")->capture_default_str();
    c->add_option("--name", a->name, "file stem of the HDF5 file and image")->capture_default_str();
    c->add_flag("--no-plot", a->no_plot, "write data only");
    c->add_flag("--quiet", a->quiet, "no summary on stderr");
    add_options(c, a->opt);
    c->callback([a, c] { basins_cmd(*a, command_line_of(c)); });
  }
  {
    auto a = std::make_shared<BasinsRArgs>();
    CLI::App* c = app.add_subcommand("basins-r", "Basin fractions across r (Table 6.1 with many orbits), stacked areas");
    c->add_option("--r-values", a->r_values, "r values r1,r2,... in (0, 1)")->delimiter(',');
    c->add_flag("--table", a->table, "add the r values of Table 6.1 in [0.1, 0.6]");
    c->add_option("--grid", a->grid, "initial conditions: random:N, paper, strip:NxM or x,y,z;...")->capture_default_str();
    c->add_option("--seed", a->seed, "seed of random grids")->capture_default_str();
    c->add_option("--reference", a->reference, "Table 6.1 as CSV")->capture_default_str();
    c->add_option("--out", a->out, "output directory")->capture_default_str();
    c->add_flag("--no-plot", a->no_plot, "write data only");
    c->add_flag("--quiet", a->quiet, "no progress on stderr");
    add_options(c, a->opt);
    c->callback([a, c] { basins_r_cmd(*a, command_line_of(c)); });
  }
});

}  // namespace
}  // namespace btob::cli
