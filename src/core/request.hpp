// SPDX-License-Identifier: GPL-3.0-or-later
// The contract every analysis follows: a plain Request struct validated once, run(request, RunControl) -> Result.
//
//   struct Request {                        // in the analysis module, e.g. btob::lyapunov::OrbitRequest
//     double r = 0.15;                      // inputs with their defaults and units, nothing else
//     ...
//     void validate() const;                // throws core::InvalidField naming the field, the value, the range
//     template <class V> void fields(V&& v) // every field once: v("name", member, "help (units, range)")
//   };
//   Result run(const Request&, const core::RunControl& = {});
//
// `fields` is the one list of a request's inputs: the command line, scene files, manifests and the Python
// binding all read and write a request through it, with the flag's long name (dashes) as the field name.
#pragma once

#include <fmt/format.h>

#include <atomic>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

namespace btob::core {

// An offending input as an error quotes it: the whole text when it has at most `max` characters, else its first
// and last (max - 20) / 2 characters around "..." with the length, "1313...2231 (100002 characters)", so that an
// error about a word of 100000 symbols stays one readable line.  A text that opens with a quoted input
// ('<input>' and then the program's own description of what is wrong with it) has the input shortened inside its
// quotes and the description kept.
inline std::string abbreviate(std::string_view text, std::size_t max = 80) {
  const auto shorten = [max](std::string_view in, std::string_view open, std::string_view close) {
    if (in.size() <= max) return fmt::format("{}{}{}", open, in, close);
    const std::size_t keep = (max - 20) / 2;
    return fmt::format("{}{}...{}{} ({} characters)", open, in.substr(0, keep), in.substr(in.size() - keep), close,
                       in.size());
  };
  const std::size_t end = text.empty() || text.front() != '\'' ? std::string_view::npos : text.find('\'', 1);
  if (end == std::string_view::npos) return shorten(text, "", "");
  return shorten(text.substr(1, end - 1), "'", "'") + std::string(text.substr(end + 1));
}

// The one error type of request validation.  what() is "<field>: got <got>, expected <expected>", <got>
// abbreviated (at most about 80 characters of the input); the command line prints it as one line and exits 2,
// Python raises ValueError with the same text.
struct InvalidField : std::invalid_argument {
  InvalidField(std::string field_, const std::string& got, const std::string& expected)
      : std::invalid_argument(field_ + ": got " + abbreviate(got) + ", expected " + expected),
        field(std::move(field_)) {}
  std::string field;
};

// Thrown by a run whose CancelToken was set; no partial result escapes.
struct Cancelled : std::runtime_error {
  Cancelled() : std::runtime_error("cancelled") {}
};

// Set from another thread (a signal handler, Python's KeyboardInterrupt) to stop a run between batches.
struct CancelToken {
  std::atomic<bool> requested{false};
  void cancel() { requested.store(true, std::memory_order_relaxed); }
  bool cancelled() const { return requested.load(std::memory_order_relaxed); }
};

// Receives progress (done out of total work units) from any thread of a run; called between batches.
struct ProgressSink {
  virtual void update(std::size_t done, std::size_t total) = 0;
  virtual ~ProgressSink() = default;
};

// How to run, never what to compute: results do not depend on any of these.
struct RunControl {
  static constexpr int max_threads = 1024;  // a stated bound; the command line refuses values outside 1..this
  int threads = 0;                          // 0: OpenMP's default (all cores); else 1..max_threads
  ProgressSink* progress = nullptr;
  const CancelToken* cancel = nullptr;  // polled by core::check_cancel / core::poll_cancel (core/cancel.hpp)
};

}  // namespace btob::core

namespace btob::core {
// A number kept as the decimal text it was given in (command line, scene, manifest, Python), with that text's double.
// r is one: double runs use `value` (strtod of the text, as a double field would be), every other precision reads
// the text itself (a float128 run at r = 0.1 uses float128's 0.1, not double's 0.1 widened).  Converts to double,
// so arithmetic and comparisons read the value; assigning a double keeps its shortest exact text.
struct Decimal {
  double value = 0;
  std::string text = "0";
  Decimal() = default;
  Decimal(double v);  // NOLINT: implicit, a double is its own decimal (the text is its shortest round-trip form)
  operator double() const { return value; }
  // The trimmed text kept as given; throws InvalidField(field, 'text', "a finite number") like a double field.
  static Decimal parse(std::string_view text, const std::string& field);
};

// Marks a field that has no sensible default: v("r", r, "help", core::required).
struct Required {};
inline constexpr Required required{};
// Marks a required field the command line takes as a positional argument (`btob pattern 132312 --r 0.2`);
// scenes, manifests and Python name it like any other field.
struct Positional {};
inline constexpr Positional positional{};
}  // namespace btob::core

// fmt prints a Decimal as its double (shortest form), exactly as the double field it replaced: messages, titles,
// file names and CSV headers are unchanged.  The text is d.text (manifests record it through core::field_text).
template <> struct fmt::formatter<btob::core::Decimal> : fmt::formatter<double> {
  auto format(const btob::core::Decimal& d, fmt::format_context& ctx) const {
    return fmt::formatter<double>::format(d.value, ctx);
  }
};
