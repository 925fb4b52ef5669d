// SPDX-License-Identifier: GPL-3.0-or-later
// Words over {1,2,3}: parsing the paper's notation, printing, rotations, J, canonical forms, enumeration.
#include "patterns/patterns.hpp"

#include "core/cancel.hpp"
#include "core/request.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <mutex>
#include <stdexcept>

namespace btob::patterns {
namespace {

// Rank in the canonical order 1 < 3 < 2.
int rank(std::uint8_t s) { return s == 1 ? 0 : (s == 3 ? 1 : 2); }

bool less_rot(const Word& w, std::size_t i, const Word& v, std::size_t j) {
  const std::size_t n = w.size();
  for (std::size_t k = 0; k < n; ++k) {
    const int a = rank(w.s[(i + k) % n]), b = rank(v.s[(j + k) % n]);
    if (a != b) return a < b;
  }
  return false;
}

// Smallest rotation of w in the canonical order: returns a start index of it, in O(n) (a word of 10^5 symbols, as
// `btob pattern` accepts, takes a millisecond; comparing every rotation with the best so far took seconds).  The
// two-pointer scan: candidate starts i != j and the length k of their rotations' common prefix.  When they differ
// at k, the start s of the larger rotation and the k starts after it cannot begin a smallest rotation (the rotation
// at s + m is beaten by the one at the other start + m), so s moves on by k + 1; when k reaches n the two rotations
// are equal (w is a power) and either is the answer.  i + j grows by k + 1 after k steps: at most 2n steps in all.
std::size_t min_rotation(const Word& w) {
  const std::size_t n = w.size();
  std::size_t i = 0, j = 1, k = 0;
  while (i < n && j < n && k < n) {
    const int a = rank(w.s[(i + k) % n]), b = rank(w.s[(j + k) % n]);
    if (a == b) {
      ++k;
      continue;
    }
    (a > b ? i : j) += k + 1;
    if (i == j) ++j;
    k = 0;
  }
  return std::min(i, j);
}

// core::InvalidField "<field>: got '<text>', <what is wrong>; expected <...>" (the request API's one error type).
[[noreturn]] void bad(const char* field, std::string_view text, const std::string& what) {
  const auto cut = what.rfind("expected ", 0) == 0 ? 0 : what.find("; expected ");
  const std::string got =
      fmt::format("'{}'", text) + (cut == 0 ? "" : ", " + what.substr(0, cut == std::string::npos ? what.size() : cut));
  std::string trimmed = got;
  while (!trimmed.empty() && (trimmed.back() == ' ' || trimmed.back() == ';')) trimmed.pop_back();
  throw core::InvalidField(
      field, trimmed, cut == std::string::npos ? "a word over 1, 2, 3" : what.substr(what.find("expected ", cut) + 9));
}

constexpr const char* kExpectedWord =
    "expected a word over 1, 2, 3 such as 132312, 132^3312^3, (ab)(cb)(acb) or abcbacb";

// The paper's notation read left to right: units (a symbol, a group in parentheses, or letters), each with an
// optional exponent; spaces and dots are skipped.  Errors are core::InvalidField naming `field`.
struct WordReader {
  std::string_view text;
  const char* field;
  std::size_t i = 0;

  char at(std::size_t j) const { return j < text.size() ? text[j] : '\0'; }

  // Greedy letter parsing at k: ab -> 1, cb -> 3, acb / cab -> 2; false when none starts there.
  bool letters_at(std::size_t& k, std::vector<std::uint8_t>& out) const {
    if (at(k) == 'a' && at(k + 1) == 'b') {
      out.push_back(1);
      k += 2;
      return true;
    }
    if (at(k) == 'c' && at(k + 1) == 'b') {
      out.push_back(3);
      k += 2;
      return true;
    }
    if ((at(k) == 'a' && at(k + 1) == 'c' && at(k + 2) == 'b') ||
        (at(k) == 'c' && at(k + 1) == 'a' && at(k + 2) == 'b')) {
      out.push_back(2);
      k += 3;
      return true;
    }
    return false;
  }

  // A group (...) of symbols and letters, i past its '('.
  std::vector<std::uint8_t> group() {
    std::vector<std::uint8_t> unit;
    while (i < text.size() && text[i] != ')') {
      if (text[i] >= '1' && text[i] <= '3') unit.push_back(static_cast<std::uint8_t>(text[i++] - '0'));
      else if (!letters_at(i, unit))
        bad(field, text, fmt::format("unexpected '{}' at position {}; {}", text[i], i + 1, kExpectedWord));
    }
    if (i >= text.size()) bad(field, text, std::string("an unclosed '('; ") + kExpectedWord);
    if (unit.empty()) bad(field, text, std::string("an empty group '()'; ") + kExpectedWord);
    ++i;
    return unit;
  }

  // The unit at i (empty at a space or a dot, which is skipped).
  std::vector<std::uint8_t> unit() {
    std::vector<std::uint8_t> unit;
    const char c = text[i];
    if (c >= '1' && c <= '3') {
      unit.push_back(static_cast<std::uint8_t>(c - '0'));
      ++i;
    } else if (c == '(') {
      ++i;
      unit = group();
    } else if (c == ' ' || c == '.') {
      ++i;
    } else if (c == 'a' || c == 'c') {
      if (!letters_at(i, unit))
        bad(field, text, fmt::format("letters at position {} that are not ab, cb, acb or cab", i + 1));
    } else {
      bad(field, text, fmt::format("unexpected '{}' at position {}; {}", c, i + 1, kExpectedWord));
    }
    return unit;
  }

  // The digits of an exponent written without braces, i at its first digit.  The paper writes 132^3312^3 for
  // 132^{3}312^{3}: a digit run followed by another '^' also holds the next symbols.  The exponent is then the
  // string's last exponent if the run starts with it (the paper's families 132^n312^n, 131312^n313132^n), else the
  // run minus its last digit.
  std::size_t bare_exponent_length() const {
    std::size_t end = i;
    while (end < text.size() && text[end] >= '0' && text[end] <= '9') ++end;
    std::size_t len = end - i;
    if (end < text.size() && text[end] == '^' && len >= 2) {
      const std::size_t last = text.rfind('^');
      std::string_view tail = text.substr(last + 1);
      if (!tail.empty() && tail.front() == '{')
        tail = tail.substr(1, tail.find('}') == std::string_view::npos ? 0 : tail.find('}') - 1);
      const std::string_view run = text.substr(i, len);
      len = (!tail.empty() && tail.size() < len && run.substr(0, tail.size()) == tail) ? tail.size() : len - 1;
    }
    return len;
  }

  // The exponent after a unit: 1 without '^', else an integer in 1..10000 (^n, or LaTeX's unambiguous ^{n}).
  long exponent() {
    if (!(i < text.size() && text[i] == '^')) return 1;
    ++i;
    std::string_view e;
    if (i < text.size() && text[i] == '{') {
      const std::size_t close = text.find('}', i);
      if (close == std::string_view::npos) bad(field, text, "an unclosed '^{'");
      e = text.substr(i + 1, close - i - 1);
      i = close + 1;
    } else {
      const std::size_t len = bare_exponent_length();
      e = text.substr(i, len);
      i += len;
    }
    long times = 0;
    for (char d : e) {
      if (d < '0' || d > '9' || times > 100000) {
        times = -1;
        break;
      }
      times = times * 10 + (d - '0');
    }
    if (e.empty() || times < 1 || times > 10000) bad(field, text, "an exponent that is not an integer in 1..10000");
    return times;
  }
};

}  // namespace

Word parse_word(std::string_view text, const char* field) {
  if (text.empty()) bad(field, text, std::string("an empty word; ") + kExpectedWord);
  Word w;
  WordReader in{text, field};
  while (in.i < text.size()) {
    const char c = text[in.i];
    const std::vector<std::uint8_t> unit = in.unit();
    if (c == ' ' || c == '.') continue;
    const long times = in.exponent();
    for (long t = 0; t < times; ++t) w.s.insert(w.s.end(), unit.begin(), unit.end());
    if (w.size() > 100000) bad(field, text, "a word longer than 100000 symbols");
  }
  if (w.s.empty())
    bad(field, text, std::string("no symbol (only spaces or dots); ") + kExpectedWord);  // " " gave an empty word
  return w;
}

std::string to_digits(const Word& w) {
  std::string out;
  for (auto c : w.s) out.push_back(static_cast<char>('0' + c));
  return out;
}

std::string to_paper(const Word& w) {
  // Plain form first (132^3312^3, as the paper prints it); braces for inner exponents when the plain form
  // would not parse back to w (e.g. 12^{10}3).
  const auto render = [&](bool braces) {
    std::string out;
    for (std::size_t i = 0; i < w.size();) {
      std::size_t j = i;
      while (j < w.size() && w.s[j] == w.s[i]) ++j;
      const std::size_t run = j - i;
      const char c = static_cast<char>('0' + w.s[i]);
      const bool power = (w.s[i] == 2 && run >= 2) || run >= 4;
      if (power) out += braces ? fmt::format("{}^{{{}}}", c, run) : fmt::format("{}^{}", c, run);
      else out.append(run, c);
      i = j;
    }
    return out;
  };
  std::string plain = render(false);
  if (w.s.empty()) return plain;
  // Each form is returned only if it reads back as w (the fuzz harness found exponent sequences where the plain
  // form does not); the digits themselves always do.
  for (const std::string& form : {plain, render(true)}) {
    try {
      if (parse_word(form) == w) return form;
    } catch (const std::invalid_argument&) {
    }
  }
  return to_digits(w);
}

std::string to_letters(const Word& w) {
  std::string out;
  for (auto c : w.s) out += c == 1 ? "ab" : (c == 3 ? "cb" : "acb");
  return out;
}

int collisions(const Word& w) {
  int n = 0;
  for (auto c : w.s) n += c == 2 ? 3 : 2;
  return n;
}

Word apply_J(const Word& w) {
  Word v = w;
  for (auto& c : v.s) c = static_cast<std::uint8_t>(4 - c);
  return v;
}

Word rotate(const Word& w, std::size_t k) {
  Word v = w;
  if (!w.s.empty()) std::rotate(v.s.begin(), v.s.begin() + static_cast<long>(k % w.size()), v.s.end());
  return v;
}

Word primitive_root(const Word& w) {
  const std::size_t n = w.size();
  for (std::size_t d = 1; d < n; ++d) {
    if (n % d) continue;
    bool ok = true;
    for (std::size_t i = d; i < n && ok; ++i) ok = w.s[i] == w.s[i - d];
    if (ok) return Word{std::vector<std::uint8_t>(w.s.begin(), w.s.begin() + static_cast<long>(d))};
  }
  return w;
}

bool is_primitive(const Word& w) { return primitive_root(w).size() == w.size(); }

Word canonical(const Word& w) {
  if (w.s.empty()) return w;
  const Word j = apply_J(w);
  const std::size_t a = min_rotation(w), b = min_rotation(j);
  return less_rot(j, b, w, a) ? rotate(j, b) : rotate(w, a);
}

bool is_J_square(const Word& w) {
  const std::size_t n = w.size();
  if (n == 0 || n % 2) return false;
  for (std::size_t i = 0; i < n / 2; ++i)
    if (w.s[i + n / 2] != 4 - w.s[i]) return false;
  return true;
}

namespace {
// The words of every length enumerated so far: a sweep asks for them several times (its item count, each part, the
// merge; each round of a resumed run), and the odometer over 3^16 words takes seconds.  Only whole lists are kept.
std::mutex canonical_mutex;
std::map<int, std::vector<Word>>& canonical_lists() {
  static std::map<int, std::vector<Word>> m;
  return m;
}
std::vector<Word> enumerate_canonical_uncached(int max_length, const core::CancelToken* cancel);
}  // namespace

std::vector<Word> enumerate_canonical(int max_length, const core::CancelToken* cancel) {
  if (max_length < 1 || max_length > 18) throw core::InvalidField("max-length", fmt::format("{}", max_length), "1..18");
  {
    const std::lock_guard<std::mutex> lock(canonical_mutex);
    if (const auto it = canonical_lists().find(max_length); it != canonical_lists().end()) return it->second;
  }
  std::vector<Word> out = enumerate_canonical_uncached(max_length, cancel);
  const std::lock_guard<std::mutex> lock(canonical_mutex);
  canonical_lists().emplace(max_length, out);
  return out;
}

namespace {
std::vector<Word> enumerate_canonical_uncached(int max_length, const core::CancelToken* cancel) {
  std::vector<Word> out;
  for (int n = 1; n <= max_length; ++n) {
    // Odometer over {1,2,3}^n; keep canonical primitive words.  A canonical word starts with its
    // smallest symbol in the order 1 < 3 < 2, so starting with 1 suffices unless the word has no 1 and no 3.
    Word w{std::vector<std::uint8_t>(static_cast<std::size_t>(n), 1)};
    std::vector<Word> level;
    for (long step = 1;; ++step) {
      core::poll_cancel(cancel, step);
      if (w.s[0] == 1 || n == 1) {
        if (is_primitive(w) && canonical(w) == w) level.push_back(w);
      }
      int k = n - 1;
      while (k >= 0 && w.s[static_cast<std::size_t>(k)] == 3) w.s[static_cast<std::size_t>(k--)] = 1;
      if (k < 0) break;
      ++w.s[static_cast<std::size_t>(k)];
    }
    if (n == 1) level = {Word{{1}}, Word{{2}}};  // 3 = J(1)
    std::sort(level.begin(), level.end(), [](const Word& a, const Word& b) {
      for (std::size_t i = 0; i < a.size(); ++i)
        if (a.s[i] != b.s[i]) return rank(a.s[i]) < rank(b.s[i]);
      return false;
    });
    out.insert(out.end(), level.begin(), level.end());
  }
  return out;
}
}  // namespace

const char* outcome_name(Outcome o) {
  switch (o) {
    case Outcome::none: return "no periodic orbit";
    case Outcome::unstable: return "unstable orbit";
    case Outcome::stable: return "stable orbit";
    case Outcome::neutral: return "neutral orbit";
    case Outcome::undecided: return "undecided orbit";
  }
  return "?";
}

}  // namespace btob::patterns
