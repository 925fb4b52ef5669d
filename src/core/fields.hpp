// SPDX-License-Identifier: GPL-3.0-or-later
// Text <-> value for the fields of a request (core/request.hpp): one parser per field type, shared by the command
// line, scene files, manifests and the Python binding, each failure a core::InvalidField naming the field.
#pragma once

#include "core/map.hpp"
#include "core/request.hpp"

#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace btob::core {

// The field types a request may have.
template <class T>
inline constexpr bool is_field_type_v =
    std::is_same_v<T, bool> || std::is_same_v<T, int> || std::is_same_v<T, long> || std::is_same_v<T, std::uint64_t> ||
    std::is_same_v<T, double> || std::is_same_v<T, std::string> || std::is_same_v<T, std::vector<double>> ||
    std::is_same_v<T, std::vector<std::string>> || std::is_same_v<T, Decimal> ||
    std::is_same_v<T, std::vector<Decimal>>;

// Parses one scalar: the whole text must be consumed.  Doubles accept subnormals and must be finite.
bool parse_bool(std::string_view text, const std::string& field);
long parse_long(std::string_view text, const std::string& field);
std::uint64_t parse_u64(std::string_view text, const std::string& field);
double parse_double(std::string_view text, const std::string& field);

// Sets `value` from its text form(s): one item for scalars, one or more for vectors (a single item holding
// commas or spaces is split too, so "0.1,0.2" and "0.1 0.2" both give two numbers).
template <class T> void set_field(T& value, const std::vector<std::string>& items, const std::string& field);

// The text form of a value, exact for doubles (shortest representation that reads back bitwise); a Decimal's text
// as it was given.
template <class T> std::vector<std::string> field_text(const T& value);

// An initial direction "x,y,z": three finite numbers (subnormals and 1e308 included), non-zero, not x = z = 0,
// in the domain x*z <= 0.  Returned scaled by an exact power of two so that its largest component lies in
// [1, 2): the same direction to the last bit, safe to normalise in any precision.
Vec3<double> parse_point(std::string_view text, const std::string& field = "point");
// "A..B" or "A" (the whole text, decimal integers) with lo <= A <= B <= hi, as {A, B}; anything else throws
// InvalidField(field, "'text'", "A..B or A with lo <= A <= B <= hi").  Ranges of n, of lengths, of ranks.
std::pair<long, long> parse_int_range(std::string_view text, long lo, long hi, const std::string& field);

struct Precision;

// ---- the quantities every request shares: one check and one wording each, every failure a core::InvalidField ----
// (A starting point is checked by parse_point above and core::validate_point, core/map.hpp.)

// r in the open interval (0, 1): else "FIELD: got R, expected a value in the open interval (0, 1)".
void require_r(double r, const std::string& field);
// An r range of r-count values: r-min and r-max in (0, 1) (require_r), r-min <= r-max (equal only for one value:
// "r-max: got B, expected a value in [r-min = A, 1)", or "(r-min = A, 1)" for r-count >= 2), and r-count distinct
// doubles in it (require_distinct).  The fields are named r-min, r-max and r-count; r-count's own bounds are the
// caller's (each sweep has its own).
void require_r_range(double r_min, double r_max, long r_count);
// A list of r, named `field`: at least one value ("FIELD: got no value, expected one or more r values in (0, 1)"),
// each in (0, 1) (require_r).
void require_r_values(const std::vector<double>& r, const std::string& field);
// A thread count: 0 (all cores) or 1..RunControl::max_threads, else "threads: got T, expected 0 (all cores) or
// 1..1024" (threads_expected() is that "expected" text, for a front end that must append a fact of its own).
void require_threads(long threads, const std::string& field = "threads");
std::string threads_expected();
// A count of at least `least`: else "FIELD: got N, expected at least LEAST".
void require_at_least(long value, long least, const std::string& field);
// A precision name among `accepted`, spelled exactly as listed (a run that dispatches on the name sees only
// these); the entry "mpfr" accepts any mpfr:D that parse_precision accepts.  Else "precision: got 'NAME', expected
// float, double or long-double" (the accepted names, "mpfr" as mpfr:D with 10 <= D <= 10000).
Precision require_precision(const std::string& text, const std::vector<std::string>& accepted,
                            const std::string& field = "precision");
// The smallest r whose Lyapunov exponents precision p resolves (sqrt(1e3 eps): 4.7e-7 in double), and r in
// [that, 1) else InvalidField naming `field`, the precision and, as advice, the narrowest precision that resolves
// r among `accepted`: the precisions the command's own --precision takes ("float", "double", "long-double",
// "float128", "mpfr" for mpfr:D with D <= 10000), so that the advice is a command line the same command accepts.
// A command without a precision choice (classify, basins) passes {} and gets no advice.  Every tool that reports
// an exponent (lyapunov, classify, basins) accepts this one domain.
double smallest_r_exponents(const Precision& p);
void require_r_exponents(double r, const Precision& p, const std::string& field,
                         const std::vector<std::string>& accepted = {"float", "double", "long-double", "float128",
                                                                     "mpfr"});

// The doubles x with lo <= x <= hi (finite, lo <= hi), counted by their ordered bit patterns (+0 and -0 once):
// 2 in [0.2, 0.2 + 1e-16], 2^52 + 1 in [1, 2].
double distinct_doubles(double lo, double hi);
// A sweep of `count` evenly spaced values over [lo, hi] (count >= 2) computes at least that many distinct doubles,
// else its values repeat and the sweep would claim a resolution it has not: refused with InvalidField naming
// `count_field`, the range's fields `range` ("r-min..r-max") and how many distinct doubles the range holds.
void require_distinct(double lo, double hi, long count, const std::string& count_field, const std::string& range);

// The Decimals' values (a list of r for code that computes in double).
std::vector<double> values(const std::vector<Decimal>& v);

// ---- one vocabulary of fields for every front end (command line, scenes, manifests, the explorer, Python) ----

// A request's fields as (name, text values), in declaration order: what a manifest records, a scene holds and a
// Python result keeps as its request.
using Args = std::vector<std::pair<std::string, std::vector<std::string>>>;

// A field visitor (Request::fields) that lists the fields as Args: req.fields(core::ArgsWriter{&args}).
struct ArgsWriter {
  Args* out;
  template <class T, class... Tag> void operator()(const std::string& name, T& member, const std::string&, Tag...) {
    out->emplace_back(name, field_text(member));
  }
};

// The documentation of one field: its name (the flag), default as text, help, and whether it must be given
// (core::required, or core::positional: an argument on the command line, a required key everywhere else).
struct FieldDoc {
  std::string name;
  std::vector<std::string> defaults;
  std::string help;
  bool required = false, positional = false;
};
// A field visitor that lists the fields' documentation: req.fields(core::DocLister{&docs}).
struct DocLister {
  std::vector<FieldDoc>* out;
  template <class T, class... Tag>
  void operator()(const std::string& name, T& member, const std::string& help, Tag...) {
    constexpr bool positional = (std::is_same_v<Tag, Positional> || ...);
    constexpr bool required = positional || (std::is_same_v<Tag, Required> || ...);
    out->push_back(FieldDoc{name, field_text(member), help, required, positional});
  }
};

}  // namespace btob::core
