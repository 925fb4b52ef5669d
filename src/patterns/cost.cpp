// SPDX-License-Identifier: GPL-3.0-or-later
// The cost of a word's analysis (`btob pattern`) before it runs (core/work.hpp): its verdict priced from instances
// of it in proportion to the counted work (core/size_model.hpp, core::Term::work_of), its window and characteristic
// polynomial by running the request itself (core::self_term).  Kept apart from requests.cpp, which holds the analysis.
#include "patterns/requests.hpp"

#include "core/work.hpp"
#include "patterns/walk_steps.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <limits>
#include <map>
#include <memory>
#include <string>

namespace btob::patterns {

namespace {
// A word of about `length` symbols that is its own primitive root, for the verdict's cost model: the prefix of u
// (a primitive word) of that length, its last symbol changed when the prefix is a power (1313 = (13)^2), whose
// verdict would analyse its short root instead.
Word primitive_prefix(const Word& u, std::size_t length) {
  Word p;
  p.s.assign(u.s.begin(), u.s.begin() + static_cast<std::ptrdiff_t>(std::min(length, u.size())));
  for (int k = 0; k < 3 && primitive_root(p).size() < p.size(); ++k)
    p.s.back() = static_cast<std::uint8_t>(p.s.back() % 3 + 1);
  return p;
}
// The work of a verdict of the primitive word u at r, in matrix-vector steps, counted on the analysis in double or
// long double (microseconds a symbol: 0.1 to 0.3 s for the longest word parse_word accepts): per_symbol_steps for
// each symbol (the
// passes whose number is fixed: the normalised product and its cofactors, twice, the feasibility walks, the orbit
// and its decimals) plus the steps the orbit walks took (orbit_walk_steps), whose number of whole periods (1 to 64
// per walk) follows the word's eigenvalue ratios.  Why not the length: the prefixes of (132312)^500 1 took 0.1 to
// 2.5 ms a symbol in mpfr:60 as their walks converged in few or many periods, and a power law through two of them
// predicted 1.1e4 s for a run of 4 s.  The walks' periods in T follow those counted where they converge in one or
// two periods or hit the cap (most words); between, they grow with T's digits, which the instances timed in T
// carry into the rate.  0 when r is no double (the power law in the length prices it then).
constexpr double per_symbol_steps = 16;
double verdict_work(const Word& u, const std::string& r_text, bool wide) {
  const std::uint64_t before = orbit_walk_steps();
  try {
    const double r = std::stod(r_text);
    if (!(r > 0 && r < 1)) return 0;
    if (wide) (void)analyse<long double>(u, static_cast<long double>(r));
    else (void)analyse<double>(u, r);
  } catch (const std::exception&) {  // r out of double's range: the request's own checks say so when it runs
    return 0;
  }
  return per_symbol_steps * static_cast<double>(u.size()) + static_cast<double>(orbit_walk_steps() - before);
}

// The instances the verdict's cost model times, each with its counted work.  In the precisions wider than double
// the instance of size l is the prefix (primitive_prefix) among lengths l 2^(k/4), k = -4..3, whose work per symbol
// is nearest the whole word's (the word itself once l reaches its length): the prefixes' own work per symbol varies
// tenfold, and instances of proportionate work let the fit's doubling (core::fit_sizes, which stops when its power
// law predicts the next instance over budget) go on to instances of a few tenths of a second.  The choice runs
// inside the instance's timing: eight analyses in long double, a quarter of a long-double instance at most (whose
// check runs in float128), less in float128 and MPFR; in float and
// double, where it would be most of it, the instance is the prefix of length l (the fit reaches long prefixes
// anyway).  The whole word's count runs first, from work_of, outside the timing (io::fitted_rate).
struct Instances {
  struct Instance {
    Word word;
    double work = 0;
  };
  Word u;
  std::string r;
  bool wide = false;       // counted in long double (else double)
  double per_symbol = -1;  // the whole word's work per symbol (0: not counted), at the first instance: work(req)
                           // runs before every request, which must not pay for the count
  std::map<std::size_t, Instance> done;
  Instances(Word w, std::string r_text, bool wide_) : u(std::move(w)), r(std::move(r_text)), wide(wide_) {}
  Instance& at(std::size_t length) {
    auto it = done.find(length);
    if (it != done.end()) return it->second;
    if (per_symbol < 0) per_symbol = verdict_work(u, r, wide) / static_cast<double>(u.size());
    Instance best{u, per_symbol * static_cast<double>(u.size())};
    if (length < u.size() && !wide) best = {primitive_prefix(u, length), 0};  // counted as it runs
    if (length < u.size() && wide) {
      double distance = std::numeric_limits<double>::infinity();
      for (int k = -4; k <= 3; ++k) {
        const auto m = static_cast<std::size_t>(std::llround(static_cast<double>(length) * std::exp2(k / 4.0)));
        if (m < 2 || m >= u.size()) continue;
        Instance c{primitive_prefix(u, m), 0};
        c.work = verdict_work(c.word, r, wide);
        const double d = std::abs(std::log(c.work / (per_symbol * static_cast<double>(length))));
        if (c.work > 0 && per_symbol > 0 && d < distance) distance = d, best = std::move(c);
      }
      if (!(per_symbol > 0)) best = {primitive_prefix(u, length), 0};
    }
    return done.emplace(length, std::move(best)).first->second;
  }
};
}  // namespace

core::Work work(const WordRequest& req) {
  const char* mode = req.mode() == WordRequest::Mode::verdict  ? "verdict"
                     : req.mode() == WordRequest::Mode::window ? "window"
                                                               : "charpoly";
  const std::string word = core::abbreviate(req.word);  // a route name and a line, not the whole of a long word
  core::Work w;
  if (req.mode() == WordRequest::Mode::verdict) {
    // Its cost grows with the length of the word's primitive root (the word analysed) times the periods its orbit
    // walks take: priced by the verdicts of the root's prefixes of about 16, 32, 64, ... symbols (Instances) at the
    // same r and precision, in proportion to the counted work, never by running the request.
    const Word u = primitive_root(parse_word(req.word, "word"));
    core::Term t;
    t.route = fmt::format("pattern verdict {} r={} {}", word, req.r, req.precision);
    t.units = 1;
    t.what = fmt::format(
        "verdict of the word {} ({} symbols in its primitive root; one indivisible computation, "
        "priced from shorter instances by the counted work of its orbit walks)",
        word, u.size());
    t.size_parameter = "word length";
    t.size = static_cast<double>(u.size());
    t.smallest = 16;
    // Counted in long double for the precisions wider than double (long double's verdict, and the others' checks,
    // separate eigenvalues that double ties: the whole (132312)^2000 1 counts 18 steps a symbol in double, 37 in long
    // double; priced from the double count, its long-double dry run predicted a quarter of the run), else in double.
    const core::Precision::Kind kind = core::parse_precision(req.precision, "precision").kind;
    const auto instances =
        std::make_shared<Instances>(u, req.r, kind != core::Precision::Kind::f32 && kind != core::Precision::Kind::f64);
    // Each instance's work as it ran in the request's precision (its orbit walks may need more periods than in
    // double: a short prefix's eigenvalue ratio per period is moderate, and MPFR converges to its own epsilon), per
    // analysis: a fixed-size precision's verdict runs its check in the next wider type too (patterns/accuracy.hpp).
    const double analyses = kind == core::Precision::Kind::mpfr ? 1 : 2;
    t.sized_run = [req, instances, analyses](double length, const core::RunControl& c) {
      Instances::Instance& one_instance = instances->at(static_cast<std::size_t>(length));
      WordRequest one = req;
      one.word = to_digits(one_instance.word);
      const std::uint64_t before = orbit_walk_steps();
      (void)run(one, c);
      one_instance.work = per_symbol_steps * static_cast<double>(one_instance.word.size()) +
                          static_cast<double>(orbit_walk_steps() - before) / analyses;
    };
    t.work_of = [instances](double length) { return instances->at(static_cast<std::size_t>(length)).work; };
    w.terms.push_back(std::move(t));
  } else {
    w.terms.push_back(core::self_term(
        req, fmt::format("pattern {} {} r={} {} digits={}", mode, word, req.r, req.precision, req.digits),
        fmt::format("{} of the word {} (one indivisible computation: its probe is this request)", mode, word)));
  }
  const double L = static_cast<double>(parse_word(req.word, "word").size());
  w.output_bytes = 400 + 4 * L;  // one printed row with the word
  w.peak_bytes = 65536 + 64 * L * (req.digits > 15 ? static_cast<double>(req.digits) : 1.0);
  return w;
}

}  // namespace btob::patterns
