// `btob pattern`: verdict of one word at r, its stability windows, or the atlas of stable patterns (Sections 6.2, 7).
#include "cli/app.hpp"
#include "cli/common.hpp"
#include "core/request.hpp"
#include "core/coords.hpp"
#include "core/scalar.hpp"
#include "io/io.hpp"
#include "patterns/atlas.hpp"
#include "patterns/exact.hpp"
#include "patterns/patterns.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <set>
#include <sstream>

namespace btob::cli {
namespace {

using namespace btob::patterns;

struct PatternArgs {
  std::string word;
  std::string r_text;
  std::string precision = "double";
  bool window = false, charpoly = false;
  int digits = 0;
  int max_length = 12;
  std::string out = "results/patterns";
  int threads = 0;
  long ics = 1000, iterations = 5000, tail = 2000;
  std::uint64_t seed = 1;
  int max_period = 500;
  bool no_check = false, no_plot = false;
  bool feasible = false;
};

template <class T> std::string str(const T& v, int digits) {
  if constexpr (std::is_same_v<T, float>) return fmt::format("{:.{}g}", v, std::min(digits, 9));
  else if constexpr (std::is_same_v<T, double>) return fmt::format("{:.{}g}", v, std::min(digits, 17));
  else if constexpr (std::is_same_v<T, long double>) return fmt::format("{:.{}g}", v, std::min(digits, 21));
  else return v.str(digits);
}

template <class T> void print_verdict(const Word& w, const T& r, int digits) {
  const Verdict<T> v = analyse<T>(w, r);
  const Word& u = v.word;
  std::cout << fmt::format("word        {} = {} ({} symbols, {} collisions); canonical {}\n", to_paper(w), to_digits(w),
                           w.size(), collisions(w), to_paper(canonical(w)));
  if (!(u == w)) std::cout << fmt::format("primitive   {} (the orbit of a power is the orbit of its root)\n", to_paper(u));
  std::cout << fmt::format("r           {}\n", str(r, digits));
  if (v.reduced) {
    Word h{std::vector<std::uint8_t>(u.s.begin(), u.s.begin() + static_cast<long>(u.size() / 2))};
    std::cout << fmt::format("matrix      J M_h with h = {}: M_w = (J M_h)^2 (Section 7.1)\n", to_digits(h));
  } else {
    std::cout << fmt::format("matrix      M_w = P_{} ... P_{} (first symbol applied first)\n", int(u.s.back()), int(u.s.front()));
  }
  for (std::size_t i = 0; i < v.spectrum.size(); ++i) {
    const auto& e = v.spectrum[i];
    std::string line = fmt::format("lambda{}     ", i + 1);
    if (e.real) {
      line += fmt::format("{} (real, |l|/|l1| = {})", str(e.re, digits), str(T(e.modulus / v.spectrum[0].modulus), 6));
      line += fmt::format(", eigenvector ({}, {}, {})", str(e.vector(0), 10), str(e.vector(1), 10), str(e.vector(2), 10));
      if (e.feasible) line += ", in the domain, all feasibility inequalities hold";
      else if (!e.in_domain) line += ", outside the domain x z < 0";
      else line += fmt::format(", in the domain, feasibility inequality {} fails (symbol {})", e.first_failure,
                               int(u.s[static_cast<std::size_t>(e.first_failure - 1)]));
    } else {
      line += fmt::format("{} {} {} i (complex, |l|/|l1| = {})", str(e.re, digits), e.im < 0 ? "-" : "+",
                          str(T(e.im < 0 ? T(-e.im) : e.im), digits), str(T(e.modulus / v.spectrum[0].modulus), 6));
    }
    std::cout << line << "\n";
  }
  std::cout << fmt::format("verdict     {}{}\n", outcome_name(v.outcome),
                           v.reason.empty() ? "" : fmt::format(" (not stable: {})", v.reason));
  std::cout << fmt::format("lyapunov    log(|l2|/|l1|)/p = {}, log(|l3|/|l1|)/p = {} (per iteration, natural log)\n",
                           str(v.lyapunov2, 10), str(v.lyapunov3, 10));
  if (v.orbit_eigen >= 0) {
    std::cout << fmt::format("letters     {} ({} collisions)\n", v.letters, collisions(u));
    std::cout << "orbit       k symbol x y z theta w1 w2\n";
    for (std::size_t k = 0; k < v.orbit.size(); ++k) {
      const auto& p = v.orbit[k];
      const auto [w1, w2] = core::strip<T>(p);
      std::cout << fmt::format("            {} {} {} {} {} {} {} {}\n", k, int(u.s[k]), str(p(0), digits), str(p(1), digits),
                               str(p(2), digits), str(core::theta<T>(p), 12), str(w1, 12), str(w2, 12));
    }
  }
}

template <class T> void print_window(const Word& w, const T& tol, int digits) {
  const auto set = stability_set<T>(w, default_grid(), tol);
  std::cout << "word,r_low,r_high,low_reason,high_reason\n";
  for (const auto& iv : set)
    std::cout << fmt::format("{},{},{},{},{}\n", to_paper(w), str(iv.lo, digits), str(iv.hi, digits), iv.lo_reason, iv.hi_reason);
}

void atlas(const PatternArgs& a, const std::string& command_line) {
  if (a.max_length < 1 || a.max_length > 16)
    throw UsageError(fmt::format("max-length: got {}, expected 1..16", a.max_length));
  if (a.threads < 0) throw UsageError(fmt::format("threads: got {}, expected at least 1", a.threads));
  const auto t0 = std::chrono::steady_clock::now();
  const io::fs::path out(a.out);
  io::ensure_dir(out);
  const double tol = 1e-15;  // bisection width in r: endpoints to ~1e-15 (double resolves r to 2.8e-17 near 0.2)
  const std::vector<double> grid = default_grid();
  const auto entries = compute_atlas(a.max_length, grid, tol, a.threads);
  const auto t1 = std::chrono::steady_clock::now();
  io::write_text_atomic(out / "atlas.csv", atlas_csv(entries));
  long stable_words = 0;
  for (const auto& e : entries) stable_words += !e.intervals.empty();
  std::cerr << fmt::format("btob: atlas of {} canonical primitive words of length <= {}: {} with a stability window ({:.1f} s)\n",
                           entries.size(), a.max_length, stable_words, std::chrono::duration<double>(t1 - t0).count());

  io::Attrs attrs = io::provenance(command_line);
  attrs["kind"] = std::string("patterns-atlas");
  attrs["max_length"] = static_cast<long>(a.max_length);
  attrs["words"] = static_cast<long>(entries.size());
  attrs["stable_words"] = stable_words;
  attrs["grid_points"] = static_cast<long>(grid.size());
  attrs["bisection_tol"] = tol;
  attrs["scalar_type"] = std::string("double");
  attrs["threads"] = static_cast<long>(a.threads > 0 ? a.threads : omp_get_max_threads());
  attrs["atlas_seconds"] = std::chrono::duration<double>(t1 - t0).count();

  if (!a.no_check) {
    // Item 6: the iterator at Table 6.1's r values, patterns detected against the atlas.
    const std::vector<double> rs = table_6_1_r();
    const DetectionRun d = detect_patterns(rs, a.ics, a.iterations, a.tail, a.seed, a.max_period, a.threads);
    const auto t2 = std::chrono::steady_clock::now();
    std::string det = "r,word,symbols,collisions,count,ics,periodic_fraction,status\n";
    std::set<std::pair<double, Word>> seen;
    long disagreements = 0, neutral = 0;
    for (const auto& f : d.found) {
      seen.insert({f.r, f.word});
      std::string status;
      if (static_cast<int>(f.word.size()) <= a.max_length) {
        bool in = false;
        for (const auto& e : entries)
          if (e.word == f.word)
            for (const auto& iv : e.intervals) in = in || (iv.lo < f.r && f.r < iv.hi);
        status = in ? "stable in atlas" : "NOT stable in atlas";
        if (!in) {
          // A symbol-periodic orbit that is not a stable periodic orbit: say what the analysis sees there.
          const Verdict<double> v = analyse<double>(f.word, f.r);
          const double ratio = v.spectrum[1].modulus / v.spectrum[0].modulus;
          // A neutral period matrix (|l2| = |l1|, e.g. the rotation P2 of the word 2): the orbit turns on an
          // invariant curve with a periodic symbol sequence; it is quasi-periodic, not a periodic sink, and
          // the atlas (sinks only) rightly does not list it.  1e-9: the moduli are computed in double.
          if (std::fabs(ratio - 1) < 1e-9) {
            status = fmt::format("quasi-periodic (neutral period matrix, |l2|/|l1| = {:.6f}: invariant curves)", ratio);
            ++neutral;
          } else {
            status += fmt::format(" ({}; {}; |l2|/|l1| = {:.6f})", outcome_name(v.outcome), v.reason, ratio);
            ++disagreements;
          }
        }
      } else {
        const Verdict<double> v = analyse<double>(f.word, f.r);
        status = v.outcome == Outcome::stable
                     ? std::string("longer than L: stable (verdict)")
                     : fmt::format("longer than L: NOT stable (verdict: {}; {}; |l2|/|l1| = {:.6f})", outcome_name(v.outcome),
                                   v.reason, v.spectrum[1].modulus / v.spectrum[0].modulus);
        disagreements += v.outcome != Outcome::stable;
      }
      const std::size_t ir = static_cast<std::size_t>(std::find(rs.begin(), rs.end(), f.r) - rs.begin());
      det += fmt::format("{},{},{},{},{},{},{:.4f},{}\n", f.r, to_paper(f.word), f.word.size(), collisions(f.word), f.count,
                         d.ics, static_cast<double>(d.periodic[ir]) / static_cast<double>(d.ics), status);
    }
    io::write_text_atomic(out / "detected.csv", det);
    // Stability sets of the found patterns longer than L (not in the atlas), same columns as atlas.csv.
    std::vector<AtlasEntry> long_entries;
    for (const auto& f : d.found)
      if (static_cast<int>(f.word.size()) > a.max_length &&
          std::none_of(long_entries.begin(), long_entries.end(), [&](const AtlasEntry& e) { return e.word == f.word; }))
        long_entries.push_back({f.word, stability_set<double>(f.word, grid, tol)});
    io::write_text_atomic(out / "long_windows.csv", atlas_csv(long_entries));
    std::string missed = "r,word,symbols,r_low,r_high\n";
    long n_missed = 0;
    for (double r : rs)
      for (const auto& e : entries)
        for (const auto& iv : e.intervals)
          if (iv.lo < r && r < iv.hi && !seen.count({r, e.word})) {
            missed += fmt::format("{},{},{},{:.17g},{:.17g}\n", r, to_paper(e.word), e.word.size(), iv.lo, iv.hi);
            ++n_missed;
          }
    io::write_text_atomic(out / "missed.csv", missed);
    attrs["check_r_values"] = static_cast<long>(rs.size());
    attrs["check_ics"] = a.ics;
    attrs["check_iterations"] = a.iterations;
    attrs["check_tail"] = a.tail;
    attrs["check_seed"] = static_cast<long>(a.seed);
    attrs["check_max_period"] = static_cast<long>(a.max_period);
    attrs["check_grid"] = std::string("random (uniform on the quarter sphere)");
    attrs["check_detected_patterns"] = static_cast<long>(d.found.size());
    attrs["check_disagreements"] = disagreements;
    attrs["check_quasi_periodic"] = neutral;
    attrs["check_missed"] = n_missed;
    attrs["check_seconds"] = std::chrono::duration<double>(t2 - t1).count();
    std::cerr << fmt::format("btob: iterator check at {} r values x {} orbits: {} (r, pattern) pairs, {} not stable in the "
                             "analysis, {} quasi-periodic (neutral period matrix), {} stable atlas entries not reached "
                             "({:.1f} s)\n",
                             rs.size(), a.ics, d.found.size(), disagreements, neutral, n_missed,
                             std::chrono::duration<double>(t2 - t1).count());
  }
  attrs["total_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  io::write_manifest(out / "atlas.json", attrs);
  if (!a.no_plot) io::run_plot("patterns_atlas.py", {out.string(), (out / "atlas.png").string()});
}

// `btob pattern atlas --feasible`: every periodic orbit, stable or unstable (issue 19, item 2).
void feasible_atlas(const PatternArgs& a, const std::string& command_line) {
  if (a.max_length < 1 || a.max_length > 16)
    throw UsageError(fmt::format("max-length: got {}, expected 1..16", a.max_length));
  if (a.threads < 0) throw UsageError(fmt::format("threads: got {}, expected at least 1", a.threads));
  const auto t0 = std::chrono::steady_clock::now();
  const io::fs::path out(a.out);
  io::ensure_dir(out);
  const double tol = 1e-13;  // bisection width in r (the transitions are reported to ~13 digits)
  const std::vector<double> grid = feasible_grid();
  long scanned = 0;
  const auto entries = compute_feasible_atlas(a.max_length, grid, tol, a.threads, &scanned);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::vector<double> rs;
  for (int i = 1; i < 1000; ++i) rs.push_back(i / 1000.0);
  io::write_text_atomic(out / "feasible.csv", feasible_csv(entries));
  io::write_text_atomic(out / "feasible_counts.csv", feasible_counts_csv(entries, rs));
  long agree = 0, checked = 0;
  io::write_text_atomic(out / "unstable_followed.csv", followed_csv(entries, 2000, a.threads, &agree, &checked));
  long stable = 0, unstable_only = 0;
  for (const auto& e : entries) {
    bool st = false;
    for (const auto& iv : e.intervals) st = st || iv.outcome == Outcome::stable;
    stable += st;
    unstable_only += !st;
  }
  std::cerr << fmt::format("btob: feasible atlas of {} canonical primitive words of length <= {}: {} feasible for some r "
                           "({} stable somewhere, {} only unstable) ({:.1f} s)\n",
                           scanned, a.max_length, entries.size(), stable, unstable_only, seconds);
  io::Attrs attrs = io::provenance(command_line);
  attrs["kind"] = std::string("patterns-feasible-atlas");
  attrs["max_length"] = static_cast<long>(a.max_length);
  attrs["words_scanned"] = scanned;
  attrs["feasible_words"] = static_cast<long>(entries.size());
  attrs["stable_words"] = stable;
  attrs["unstable_only_words"] = unstable_only;
  attrs["grid_points"] = static_cast<long>(grid.size());
  attrs["bisection_tol"] = tol;
  attrs["scalar_type"] = std::string("double");
  attrs["threads"] = static_cast<long>(a.threads > 0 ? a.threads : omp_get_max_threads());
  attrs["atlas_seconds"] = seconds;
  attrs["followed_checked"] = checked;
  attrs["followed_agree"] = agree;
  std::cerr << fmt::format("btob: unstable orbits followed by the map in double from their periodic point: {} of {} within a "
                           "factor 2 (+-2 periods) of ln(margin/eps)/ln(expansion)\n", agree, checked);
  io::write_manifest(out / "feasible.json", attrs);
  if (!a.no_plot) io::run_plot("patterns_feasible.py", {out.string(), (out / "feasible.png").string()});
}

void pattern(const PatternArgs& a, const std::string& command_line) {
  if (a.word == "atlas" && a.feasible) return feasible_atlas(a, command_line);
  if (a.feasible) throw UsageError("feasible: expected the word 'atlas' with --feasible");
  if (a.word == "atlas") return atlas(a, command_line);
  const Word w = parse_word(a.word, "word");
  if (a.charpoly) {
    // Exact characteristic polynomial of the (reduced) period matrix and its discriminant (Theorems 7.1, 7.3).
    if (a.window || !a.r_text.empty()) throw UsageError("charpoly: expected no --r and no --window with --charpoly");
    const CharPoly chi = characteristic_polynomial(w);
    const bool reduced = is_J_square(primitive_root(w));  // the same test characteristic_polynomial applies
    std::cout << fmt::format("word          {} ({} symbols); matrix {}\n", to_paper(w), w.size(),
                             reduced ? "A = J M_h, M_w = A^2 (w = h J(h))" : "A = M_w");
    std::cout << "chi(lambda) = det(lambda I - A) = lambda^3 + c2 lambda^2 + c1 lambda + c0, exact in r:\n";
    std::cout << "c2            " << chi.c2.to_string() << "\n";
    std::cout << "c1            " << chi.c1.to_string() << "\n";
    std::cout << "c0            " << chi.c0.to_string() << "\n";
    std::cout << "discriminant  " << discriminant(chi).to_string()
              << "\n              (the paper's sign: (q/2)^2 + (p/3)^3 of the depressed cubic; < 0: three real roots)\n";
    return;
  }
  if (a.window == !a.r_text.empty())
    throw UsageError("r: expected exactly one of --r R (verdict at one r) or --window (stability set)");
  const core::Precision prec = core::parse_precision(a.precision, "precision");
  if (a.window) {
    if (a.digits != 0 && (a.digits < 5 || a.digits > 1000))
      throw UsageError(fmt::format("digits: got {}, expected 5..1000", a.digits));
    if (a.digits > 15 || prec.kind == core::Precision::Kind::mpfr) {
      const int d = std::max(a.digits, prec.mpfr_digits);
      core::mpfr_float::default_precision(static_cast<unsigned>(d + 15));  // guard digits for the products
      // Bisection down to 10^-(d+3): the d printed digits are then correct up to rounding.
      print_window<core::mpfr_float>(w, core::mpfr_float(pow(core::mpfr_float(10), -(d + 3))), d);
    } else {
      print_window<double>(w, 1e-15, a.digits > 0 ? a.digits : 17);  // 1e-15: a few ulps of r near 0.2
    }
    return;
  }
  double r_check = 0;
  try {
    std::size_t pos = 0;
    r_check = std::stod(a.r_text, &pos);
    if (pos != a.r_text.size()) throw std::invalid_argument("");
  } catch (const std::exception&) {
    throw UsageError(fmt::format("r: got '{}', expected a number in the open interval (0, 1)", a.r_text));
  }
  if (!(r_check > 0 && r_check < 1))
    throw UsageError(fmt::format("r: got {}, expected a restitution coefficient in the open interval (0, 1)", a.r_text));
  switch (prec.kind) {
    case core::Precision::Kind::f32: print_verdict<float>(w, std::stof(a.r_text), 9); break;
    case core::Precision::Kind::f80: print_verdict<long double>(w, std::stold(a.r_text), 21); break;
    case core::Precision::Kind::f128: print_verdict<core::float128>(w, core::float128(a.r_text), 34); break;
    case core::Precision::Kind::mpfr: {
      core::mpfr_float::default_precision(static_cast<unsigned>(prec.mpfr_digits));
      print_verdict<core::mpfr_float>(w, core::mpfr_float(a.r_text), prec.mpfr_digits);
      break;
    }
    default: print_verdict<double>(w, r_check, 17); break;
  }
}

Register reg([](CLI::App& app) {
  auto a = std::make_shared<PatternArgs>();
  CLI::App* c = app.add_subcommand(
      "pattern", "Periodic patterns: verdict of a word at r, its stability windows, or the atlas (Sections 6.2, 7)");
  c->add_option("word", a->word, "a word over 1,2,3 (132312, 132^3312^3, (ab)(cb)(acb)), or 'atlas'")->required();
  c->add_option("--r", a->r_text, "restitution coefficient in (0,1) (verdict mode)");
  c->add_option("--precision", a->precision, "verdict mode: float, double, long-double, float128 or mpfr:D; window mode: mpfr:D")
      ->capture_default_str();
  c->add_flag("--window", a->window, "print the stability set as CSV word,r_low,r_high,low_reason,high_reason");
  c->add_flag("--charpoly", a->charpoly, "print the exact characteristic polynomial of the period matrix and its discriminant");
  c->add_option("--digits", a->digits, "window mode: digits of the endpoints (> 15 computes in MPFR)");
  c->add_option("--max-length", a->max_length, "atlas: longest word, in symbols")->capture_default_str();
  c->add_option("--out", a->out, "atlas: output directory")->capture_default_str();
  c->add_option("--threads", a->threads, "OpenMP threads, 1..1024 (default: all cores)")
      ->check(CLI::Range(1, core::RunControl::max_threads));
  c->add_option("--ics", a->ics, "atlas check: random initial points per r")->capture_default_str();
  c->add_option("--iterations", a->iterations, "atlas check: iterations per orbit")->capture_default_str();
  c->add_option("--tail", a->tail, "atlas check: symbols kept at the end of each orbit")->capture_default_str();
  c->add_option("--seed", a->seed, "atlas check: seed of the initial points")->capture_default_str();
  c->add_option("--max-period", a->max_period, "atlas check: longest period searched")->capture_default_str();
  c->add_flag("--no-check", a->no_check, "atlas: skip the iterator check");
  c->add_flag("--no-plot", a->no_plot, "atlas: write data only");
  c->add_flag("--feasible", a->feasible,
              "atlas: every feasible periodic orbit, stable or unstable (feasible.csv, feasible_counts.csv)");
  c->callback([a, c] { pattern(*a, command_line_of(c)); });
});

}  // namespace
}  // namespace btob::cli
