// SPDX-License-Identifier: GPL-3.0-or-later
// The cost of a word's analysis (`btob pattern`) before it runs (core/work.hpp): its verdict priced by a cost model
// in the length of the word's primitive root (core/size_model.hpp), its window and characteristic polynomial by
// running the request itself (core::self_term).  Kept apart from requests.cpp, which holds the analysis.
#include "patterns/requests.hpp"

#include "core/work.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
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
}  // namespace

core::Work work(const WordRequest& req) {
  const char* mode = req.mode() == WordRequest::Mode::verdict ? "verdict" : req.mode() == WordRequest::Mode::window ? "window" : "charpoly";
  const std::string word = core::abbreviate(req.word);  // a route name and a line, not the whole of a long word
  core::Work w;
  if (req.mode() == WordRequest::Mode::verdict) {
    // Its cost grows with the length of the word's primitive root (the word analysed): priced by the verdicts of
    // the root's prefixes of 16, 32, 64, ... symbols at the same r and precision, never by running the request.
    const Word u = primitive_root(parse_word(req.word, "word"));
    core::Term t;
    t.route = fmt::format("pattern verdict {} r={} {}", word, req.r, req.precision);
    t.units = 1;
    t.what = fmt::format("verdict of the word {} ({} symbols in its primitive root; one indivisible computation, "
                         "priced by a cost model in the root's length)", word, u.size());
    t.size_parameter = "word length";
    t.size = static_cast<double>(u.size());
    t.smallest = 16;
    t.sized_run = [req, u](double length, const core::RunControl& c) {
      WordRequest one = req;
      one.word = to_digits(primitive_prefix(u, static_cast<std::size_t>(length)));
      (void)run(one, c);
    };
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
