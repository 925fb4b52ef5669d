// SPDX-License-Identifier: GPL-3.0-or-later
// Fuzz harness: patterns::parse_word (user words such as "132^3312^3", "(ab)(cb)", "abcbacb").
// A parse either throws std::invalid_argument or returns a word of symbols 1..3 that survives the round trips
// through the paper's notation and digits (anything else aborts: a crash for libFuzzer).
#include "patterns/patterns.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace btob::patterns;
  if (size > 4096) return 0;  // a word of the command line, not a file
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  Word w;
  try {
    w = parse_word(text, "word");
  } catch (const std::invalid_argument&) {
    return 0;
  }
  if (w.s.empty()) std::abort();
  for (auto s : w.s)
    if (s < 1 || s > 3) std::abort();
  if (w.s.size() > (1u << 16)) return 0;  // a legal huge exponent: the round trips below would only be slow
  if (parse_word(to_digits(w)) != w) std::abort();
  if (parse_word(to_paper(w)) != w) std::abort();
  if (parse_word(to_letters(w)) != w) std::abort();
  return 0;
}
