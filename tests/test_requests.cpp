// SPDX-License-Identifier: GPL-3.0-or-later
// The request API (core/request.hpp) of the analyses moved into their modules: validation names the field,
// run(request) equals the lower-level routes it wraps bitwise, results describe their arrays, MPFR digits do not
// leak from one run to the next, field parsers read what they write.
#include "attractors/requests.hpp"
#include "bifurcation/bifurcation.hpp"
#include "core/fields.hpp"
#include "core/map.hpp"
#include "core/run.hpp"
#include "core/scalar.hpp"
#include "iterate/kernel.hpp"
#include "iterate/recorders.hpp"
#include "leaves/requests.hpp"
#include "lyapunov/hyperbolicity.hpp"
#include "lyapunov/hyperbolicity_requests.hpp"
#include "lyapunov/lyapunov.hpp"
#include "lyapunov/requests.hpp"
#include "orbits/orbits.hpp"
#include "particles/particles.hpp"
#include "patterns/curves.hpp"
#include "patterns/patterns.hpp"
#include "patterns/requests.hpp"
#include "precision/tradeoff.hpp"
#include "stats/requests.hpp"
#include "stats/stats.hpp"
#include "transfer/transfer.hpp"
#include "windows/windows.hpp"

#include <boost/lexical_cast.hpp>
#include <climits>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <omp.h>

#include "tolerance.hpp"

#include <cmath>
#include <limits>
#include <thread>
#include <typeinfo>

using btob::test::bound;
using btob::test::statistical;
using btob::test::ulps;

namespace {
using namespace btob;

// The field of an InvalidField thrown by f, or "" when none is thrown.
template <class F> std::string failing_field(F&& f) {
  try {
    f();
  } catch (const core::InvalidField& e) {
    return e.field;
  }
  return "";
}

// ------------------------------------------------------------------------------------------------ fields
// Every check of user input below the requests throws core::InvalidField naming its field (a bare
// std::invalid_argument would lose the field), with the message the command line prints.
TEST(Fields, ValidationBelowTheRequestsNamesTheField) {
  lyapunov::Options o;
  o.blocks = 1;
  EXPECT_EQ(failing_field([&] { lyapunov::validate(o); }), "blocks");
  lyapunov::ClvOptions c;
  c.window = 0;
  EXPECT_EQ(failing_field([&] { lyapunov::validate(c); }), "window");
  EXPECT_EQ(failing_field([] { iterate::linspace_r(0.1, 0.2, 0); }), "r-count");
  EXPECT_EQ(failing_field([] { iterate::strip_grid(0, 3); }), "grid");
  EXPECT_EQ(failing_field([] { iterate::parse_grid("strip:axb", 1, "grid"); }), "grid");
  EXPECT_EQ(failing_field([] { stats::parse_chart("polar", "coords"); }), "coords");
  EXPECT_EQ(failing_field([] { stats::measure_frame(stats::Chart::strip, 0, 10); }), "bins");
  EXPECT_EQ(failing_field([] { windows::validate_digits(5); }), "digits");
  EXPECT_EQ(failing_field([] { patterns::analyse<double>(patterns::Word{}, 0.3); }), "word");
  try {
    lyapunov::validate(o);
  } catch (const std::exception& e) {
    EXPECT_STREQ(e.what(), "blocks: got 1, expected at least 2");
  }
  try {
    iterate::parse_grid("strip:axb", 1, "grid");
  } catch (const std::exception& e) {
    EXPECT_STREQ(e.what(),
                 "grid: got 'strip:axb', expected strip:NxM[:w1min:w1max] with N, M >= 1 and finite w1min < "
                 "w1max");
  }
}

// One vocabulary of fields: ArgsWriter lists every field as text in declaration order, DocLister the same names
// with their help and whether they must be given (a positional field is required everywhere but the command line).
// ------------------------------------------------------------------------------------------------ shared checks
// The message of the InvalidField thrown by f, "" when none is thrown (another exception type fails the test).
template <class F> std::string failing_message(F&& f) {
  try {
    f();
  } catch (const core::InvalidField& e) {
    return e.what();
  }
  return "";
}

// r = 0, 1, NaN and -0.1 set by `set` on a valid request `valid` are refused by its validate() with core's one
// wording for r, naming `field` (before, each module had its own: "a number in the open interval", "a restitution
// coefficient in ...", "a number in (0, 1)", std::domain_error from core::validate_r).
template <class Req, class Set> void expect_one_r_wording(Req valid, const std::string& field, Set set) {
  SCOPED_TRACE(field + " of " + typeid(Req).name());
  ASSERT_EQ(failing_message([&] { valid.validate(); }), "");
  for (double bad : {0.0, 1.0, std::nan(""), -0.1}) {
    Req req = valid;
    set(req, bad);
    EXPECT_EQ(failing_message([&] { req.validate(); }),
              fmt::format("{}: got {}, expected a value in the open interval (0, 1)", field, bad));
  }
}

TEST(SharedChecks, EveryRequestRefusesROutsideTheOpenIntervalWithOneWording) {
  const auto r = [](auto& q, double v) { q.r = v; };
  const auto r_min = [](auto& q, double v) { q.r_min = v; };
  const auto r_max = [](auto& q, double v) { q.r_max = v; };
  attractors::ClassifyRequest classify;
  classify.r = 0.3, classify.point = "1,0.1,-1";
  expect_one_r_wording(classify, "r", r);
  attractors::BasinsRequest basins;
  basins.r = 0.3;
  expect_one_r_wording(basins, "r", r);
  attractors::BasinsRRequest basins_r;
  basins_r.r_count = 3;
  expect_one_r_wording(basins_r, "r-min", r_min);
  expect_one_r_wording(basins_r, "r-max", r_max);
  basins_r.r_count = 0, basins_r.r_values = {0.3};
  expect_one_r_wording(basins_r, "r-values", [](auto& q, double v) { q.r_values = {0.3, v}; });
  bifurcation::Request bif;
  expect_one_r_wording(bif, "r-min", r_min);
  expect_one_r_wording(bif, "r-max", r_max);
  leaves::Request leaf;
  expect_one_r_wording(leaf, "r", r);
  leaf.r_count = 3, leaf.r_min = 0.2, leaf.r_max = 0.3;
  expect_one_r_wording(leaf, "r-min", r_min);
  expect_one_r_wording(leaf, "r-max", r_max);
  lyapunov::OrbitRequest orbit;
  orbit.r = 0.3, orbit.point = "1,0.1,-1";
  expect_one_r_wording(orbit, "r", r);
  lyapunov::MapRequest map;
  expect_one_r_wording(map, "r-min", r_min);
  expect_one_r_wording(map, "r-max", r_max);
  expect_one_r_wording(lyapunov::StripRequest{}, "r", r);
  lyapunov::HyperbolicityRequest hyperbolicity;
  hyperbolicity.r = 0.3;
  expect_one_r_wording(hyperbolicity, "r", r);
  lyapunov::HyperbolicityOrbitsRequest hyperbolicity_orbits;
  expect_one_r_wording(hyperbolicity_orbits, "r-min", r_min);
  expect_one_r_wording(hyperbolicity_orbits, "r-max", r_max);
  expect_one_r_wording(orbits::StripOrbitsRequest{}, "r", r);
  expect_one_r_wording(particles::ParticlesRequest{}, "r", r);
  patterns::WordRequest word;
  word.word = "132312", word.r = "0.3";
  expect_one_r_wording(word, "r", [](auto& q, double v) { q.r = fmt::format("{}", v); });
  patterns::CurvesRequest curves;
  expect_one_r_wording(curves, "r-min", r_min);
  expect_one_r_wording(curves, "r-max", r_max);
  expect_one_r_wording(precision::TradeoffRequest{}, "r-values", [](auto& q, double v) { q.r = {0.3, v}; });
  expect_one_r_wording(stats::CorrelateRequest{}, "r", r);
  expect_one_r_wording(stats::MeasureRequest{}, "r", r);
  expect_one_r_wording(transfer::TransferRequest{}, "r", r);
  transfer::TransferRRequest transfer_r;
  expect_one_r_wording(transfer_r, "r-min", r_min);
  expect_one_r_wording(transfer_r, "r-max", r_max);
}

// The other shared quantities: an r range's order, a list of r, threads, precision names, counts, a point.
TEST(SharedChecks, OtherSharedQuantitiesHaveOneWordingEach) {
  EXPECT_EQ(failing_message([] { core::require_r_range(0.3, 0.2, 5); }),
            "r-max: got 0.2, expected a value in (r-min = 0.3, 1)");
  EXPECT_EQ(failing_message([] { core::require_r_range(0.3, 0.3, 5); }),
            "r-max: got 0.3, expected a value in (r-min = 0.3, 1)");
  EXPECT_EQ(failing_message([] { core::require_r_range(0.3, 0.3, 1); }), "");  // one value: r-min = r-max
  EXPECT_EQ(failing_message([] { core::require_r_range(0.3, 0.2, 1); }),
            "r-max: got 0.2, expected a value in [r-min = 0.3, 1)");
  EXPECT_EQ(failing_message([] { core::require_r_values({}, "r-values"); }),
            "r-values: got no value, expected one or more r values in (0, 1)");
  EXPECT_EQ(failing_message([] { core::require_threads(-1); }), "threads: got -1, expected 0 (all cores) or 1..1024");
  EXPECT_EQ(failing_message([] { core::require_threads(1025); }),
            "threads: got 1025, expected 0 (all cores) or 1..1024");
  EXPECT_EQ(failing_message([] { core::require_threads(0); }), "");
  EXPECT_EQ(failing_message([] { core::require_threads(1024); }), "");
  EXPECT_EQ(failing_message([] { core::require_at_least(0, 1, "iterations"); }),
            "iterations: got 0, expected at least 1");
  EXPECT_EQ(failing_message([] {
              (void)core::require_precision("long double", {"float", "double", "long-double"});
            }),
            "precision: got 'long double', expected float, double or long-double");
  EXPECT_EQ(failing_message([] {
              (void)core::require_precision("float", {"double", "mpfr"});
            }),
            "precision: got 'float', expected double or mpfr:D with 10 <= D <= 10000");
  EXPECT_EQ(core::require_precision("mpfr:30", {"double", "mpfr"}).mpfr_digits, 30);
  EXPECT_EQ(failing_message([] { core::validate_point(1, 0, 1, "point"); }),
            "point: got (1, 0, 1) with x*z > 0, expected a point of the domain x*z <= 0 (eq. 3.4)");
  EXPECT_EQ(failing_message([] { core::validate_r(1.5L); }),
            "r: got 1.5, expected a value in the open interval (0, 1)");
  // The machine's helpers: 0 threads means OpenMP's default.
  EXPECT_EQ(core::thread_count(0), omp_get_max_threads());
  EXPECT_EQ(core::thread_count(3), 3);
}

TEST(Fields, ArgsWriterAndDocListerListTheSameFields) {
  lyapunov::OrbitRequest req;
  core::Args args;
  req.fields(core::ArgsWriter{&args});
  std::vector<core::FieldDoc> docs;
  req.fields(core::DocLister{&docs});
  ASSERT_EQ(args.size(), docs.size());
  for (std::size_t i = 0; i < args.size(); ++i) {
    EXPECT_EQ(args[i].first, docs[i].name);
    EXPECT_EQ(args[i].second, docs[i].defaults);
    EXPECT_FALSE(docs[i].help.empty()) << docs[i].name;
  }
  const auto r = std::find_if(docs.begin(), docs.end(), [](const auto& d) { return d.name == "r"; });
  ASSERT_NE(r, docs.end());
  EXPECT_TRUE(r->required);
  EXPECT_FALSE(r->positional);
  const auto it = std::find_if(docs.begin(), docs.end(), [](const auto& d) { return d.name == "iterations"; });
  ASSERT_NE(it, docs.end());
  EXPECT_FALSE(it->required);
}

TEST(Fields, PointsAcceptSubnormalsAndHugeValuesAndScaleExactly) {
  // 1e-320 is subnormal: strtod flags ERANGE but returns the number; the direction is kept to the last bit.
  const auto p = core::parse_point("1e-320,-3e-320,-1e-320");
  EXPECT_GE(std::abs(p(1)), 1.0);
  EXPECT_LT(std::abs(p(1)), 2.0);
  EXPECT_EQ(p(0) / p(1), 1e-320 / -3e-320);  // exact scaling by a power of two leaves every ratio bitwise
  const auto q = core::parse_point("1e308,-1e308,-1e308");
  EXPECT_TRUE(q.allFinite());
  EXPECT_EQ(q(0), -q(1));
  const auto u = core::parse_point("1,-3,-1.1");
  EXPECT_EQ(u(0) * 4, 1.0 * 2);  // largest component 3 -> 1.5: scaled by 2^-1
  EXPECT_EQ(failing_field([] { core::parse_point("1,2"); }), "point");
  EXPECT_EQ(failing_field([] { core::parse_point("1,inf,-1"); }), "point");
  EXPECT_EQ(failing_field([] { core::parse_point("1e400,-1,-1"); }), "point");
  EXPECT_THROW(core::parse_point("1,1,1"), core::InvalidField);  // x*z > 0 is outside the domain
}

TEST(Fields, TextRoundTripsBitwise) {
  for (double v : {0.1, 0.1717, 7 - 4 * std::sqrt(3.0), 1e-300, 4.9e-324, 0.17169999999999999}) {
    double back = 0;
    core::set_field(back, core::field_text(v), "x");
    EXPECT_EQ(back, v);
  }
  std::vector<double> range;
  core::set_field(range, {"-16 0.25"}, "range");
  EXPECT_EQ(range, (std::vector<double>{-16, 0.25}));
  core::set_field(range, {"1", "2"}, "range");
  EXPECT_EQ(range, (std::vector<double>{1, 2}));
  long n = 0;
  EXPECT_EQ(failing_field([&] { core::set_field(n, {"12x"}, "r-count"); }), "r-count");
  bool b = false;
  core::set_field(b, {}, "log");
  EXPECT_TRUE(b);
  core::set_field(b, {"false"}, "log");
  EXPECT_FALSE(b);
}

TEST(Fields, IntegersAcceptExactScientificNotationOnly) {
  const auto as_long = [](const std::string& t) {
    long v = 0;
    core::set_field(v, {t}, "iterations");
    return v;
  };
  EXPECT_EQ(as_long("1e6"), 1000000);
  EXPECT_EQ(as_long("2.5e3"), 2500);
  EXPECT_EQ(as_long("-3E2"), -300);
  EXPECT_EQ(as_long("1.000e3"), 1000);
  EXPECT_EQ(as_long("12000e-3"), 12);  // a negative exponent is fine where the value stays whole
  EXPECT_EQ(as_long("9223372036854775807"), LONG_MAX);
  EXPECT_EQ(as_long("-9223372036854775808"), LONG_MIN);
  std::uint64_t seed = 0;
  core::set_field(seed, {"1.8446744073709551615e19"}, "seed");  // 2^64 - 1, exactly: no rounding through double
  EXPECT_EQ(seed, UINT64_MAX);
  int small = 0;
  core::set_field(small, {"2e9"}, "tail");
  EXPECT_EQ(small, 2000000000);
  for (const char* bad : {"1.5e0", "1e-3", "2.55e1", "1e", "e3", "1.", "1e19", "9223372036854775808", "0x10", "1e6x"})
    EXPECT_EQ(failing_field([&] { as_long(bad); }), "iterations") << bad;
  EXPECT_EQ(failing_field([&] { core::set_field(seed, {"1.8446744073709551616e19"}, "seed"); }), "seed");
  EXPECT_EQ(failing_field([&] { core::set_field(seed, {"-1"}, "seed"); }), "seed");
  EXPECT_EQ(failing_field([&] { core::set_field(small, {"3e9"}, "tail"); }), "tail");
  try {
    as_long("1.5e0");
  } catch (const core::InvalidField& e) {
    EXPECT_STREQ(e.what(),
                 "iterations: got '1.5e0', expected an integer (1000000, or exactly in scientific notation: "
                 "1e6, 2.5e3)");
  }
}

// ------------------------------------------------------------------------------------------------ r in the precision
// r is carried in the run's precision from the request to the lanes.  A request keeps the decimal
// text it was given (core::Decimal), the ensemble keeps it (a list, or a range's ends and count), and every
// precision reads r from it (Ensemble::r_at<T>), so a float128 run at r = 0.1 uses float128's 0.1.

TEST(Fields, DecimalKeepsItsTextAndReadsLikeADouble) {
  core::Decimal d;
  core::set_field(d, {" 0.10 "}, "r");
  EXPECT_EQ(d.text, "0.10");                                         // trimmed, otherwise as given
  EXPECT_EQ(d.value, 0.1);                                           // strtod of the text, as a double field reads it
  EXPECT_EQ(core::field_text(d), std::vector<std::string>{"0.10"});  // manifests record the text
  EXPECT_EQ(fmt::format("{}", d), "0.1");                            // messages and titles print the double, as before
  core::Decimal many;
  core::set_field(many, {"0.1000000000000000000000001"}, "r");  // more digits than a double holds: kept
  EXPECT_EQ(many.value, 0.1);
  EXPECT_EQ(many.text, "0.1000000000000000000000001");
  EXPECT_EQ(core::Decimal(0.0717).text, "0.0717");  // a double's shortest exact form
  EXPECT_EQ(failing_field([] {
              core::Decimal x;
              core::set_field(x, {"0.1x"}, "r-min");
            }),
            "r-min");
  EXPECT_EQ(failing_field([] {
              core::Decimal x;
              core::set_field(x, {"1e999"}, "r");
            }),
            "r");
  std::vector<core::Decimal> list;
  core::set_field(list, {"0.11,0.2", "0.30"}, "r");
  ASSERT_EQ(list.size(), 3u);
  EXPECT_EQ(list[2].text, "0.30");
  EXPECT_EQ(core::values(list), (std::vector<double>{0.11, 0.2, 0.3}));
}

// T's nearest value to `text`, checked independently of core::from_decimal: the exact decimal as a ratio of
// integers in MPFR at 400 bits (mpfr_set_str of the integer digits, then one division, error 2^-400), and |x - exact|
// no larger than the distance of either neighbour of x.
template <class T> bool is_nearest(const T& x, const std::string& digits, const std::string& ten_power) {
  core::MpfrDigits wide(130);  // 430 bits
  const core::mpfr_float exact = core::mpfr_float(digits) / core::mpfr_float(ten_power);
  using boost::multiprecision::nextafter;
  using std::nextafter;
  const T up = nextafter(x, T(1)), down = nextafter(x, T(0));
  const core::mpfr_float d = abs(core::mpfr_float(x) - exact);
  return d <= abs(core::mpfr_float(up) - exact) && d <= abs(core::mpfr_float(down) - exact);
}

TEST(RInPrecision, ListedRIsTheNearestValueOfEachPrecision) {
  iterate::Ensemble e;
  e.set_r_list({core::Decimal::parse("0.1", "r"), core::Decimal::parse("0.171599", "r")});
  EXPECT_EQ(e.r, (std::vector<double>{0.1, 0.171599}));  // double: the values as before
  EXPECT_TRUE(is_nearest(e.r_at<long double>(0), "1", "10"));
  EXPECT_TRUE(is_nearest(e.r_at<core::float128>(0), "1", "10"));
  EXPECT_TRUE(is_nearest(e.r_at<float>(0), "1", "10"));
  EXPECT_TRUE(is_nearest(e.r_at<core::float128>(1), "171599", "1000000"));
  EXPECT_TRUE(is_nearest(e.r_at<long double>(1), "171599", "1000000"));
  // And not double's value widened: 0.1 in double is 0.1 + 5.55e-18, 1.6e16 ulps of float128 away.
  EXPECT_NE(e.r_at<core::float128>(0), core::float128(0.1));
  EXPECT_NE(e.r_at<long double>(0), static_cast<long double>(0.1));
  EXPECT_EQ(e.r_at<core::float128>(0), boost::lexical_cast<core::float128>("0.1"));
  EXPECT_EQ(e.r_at<long double>(0), boost::lexical_cast<long double>("0.1"));
  {
    core::MpfrDigits fifty(50);
    EXPECT_EQ(e.r_at<core::mpfr_float>(0), core::mpfr_float(1) / 10);  // the rational 1/10 rounded once, to 50 digits
    EXPECT_NE(e.r_at<core::mpfr_float>(0), core::mpfr_float(0.1));
  }
  // Values computed in double (no decimal source) are widened exactly.
  iterate::Ensemble c;
  c.r = {0.1};
  EXPECT_EQ(c.r_at<core::float128>(0), core::float128(0.1));
  // A source that no longer matches r is refused rather than read out of step.
  iterate::Ensemble bad = e;
  bad.r.push_back(0.5);
  EXPECT_THROW((void)bad.r_at<core::float128>(0), std::logic_error);
}

TEST(RInPrecision, RangeIsEvaluatedInThePrecisionAndIsBitwiseInDouble) {
  // r_i = lo + (hi - lo) i / (n - 1), in T from T's lo and hi: double gets linspace_r bit for bit, float128 the
  // exact r_i to a few float128 roundings (four operations), never the double's error (up to ~1e-17).
  const long n = 37;
  iterate::Ensemble e;
  e.set_r_range(core::Decimal::parse("0.0717", "r-min"), core::Decimal::parse("0.1717", "r-max"), n);
  EXPECT_EQ(e.r, iterate::linspace_r(0.0717, 0.1717, n));
  core::MpfrDigits wide(60);
  double worst_double = 0, worst_quad = 0;
  for (long i = 0; i < n; ++i) {
    const std::size_t j = static_cast<std::size_t>(i);
    // The exact r_i = (717 (n - 1) + 1000 i) / (10000 (n - 1)).
    const core::mpfr_float exact = core::mpfr_float(717 * (n - 1) + 1000 * i) / core::mpfr_float(10000 * (n - 1));
    const core::float128 q = e.r_at<core::float128>(j);
    const core::float128 lo = boost::lexical_cast<core::float128>("0.0717"),
                         hi = boost::lexical_cast<core::float128>("0.1717");
    EXPECT_EQ(q, i == 0 ? lo : i == n - 1 ? hi : core::float128(lo + (hi - lo) * i / (n - 1))) << i;
    worst_quad = std::max(worst_quad, static_cast<double>(abs(core::mpfr_float(q) - exact) / exact));
    worst_double = std::max(worst_double, static_cast<double>(abs(core::mpfr_float(e.r[j]) - exact) / exact));
    EXPECT_EQ(e.r_at<float>(j), static_cast<float>(e.r[j])) << i;  // float: the committed float runs' r (see README)
  }
  EXPECT_SMALL(worst_quad,
               ulps<core::float128>(4, "four float128 roundings: lo, hi, the difference, the product, the quotient"));
  EXPECT_GT(worst_double, 1e3 * static_cast<double>(std::numeric_limits<core::float128>::epsilon()));  // what it fixes
  // A part of a sweep keeps the whole range and its items' indices.
  iterate::Ensemble part;
  const std::vector<std::size_t> items = {3, 17, 36};
  part.set_r_range(core::Decimal::parse("0.0717", "r-min"), core::Decimal::parse("0.1717", "r-max"), n, &items);
  for (std::size_t k = 0; k < items.size(); ++k) {
    EXPECT_EQ(part.r[k], e.r[items[k]]);
    EXPECT_EQ(part.r_at<core::float128>(k), e.r_at<core::float128>(items[k]));
  }
  const iterate::Ensemble sub = e.with_r(items);
  EXPECT_EQ(sub.r_at<core::float128>(1), e.r_at<core::float128>(17));
  // r_in<T> (what the kernel reads, the range's ends parsed once) is r_at<T> for every value.
  for (const iterate::Ensemble* x : std::vector<const iterate::Ensemble*>{&e, &part, &sub}) {
    const auto q = x->r_in<core::float128>();
    const auto l = x->r_in<long double>();
    const auto f = x->r_in<float>();
    for (std::size_t j = 0; j < x->r.size(); ++j) {
      EXPECT_EQ(q[j], x->r_at<core::float128>(j));
      EXPECT_EQ(l[j], x->r_at<long double>(j));
      EXPECT_EQ(f[j], x->r_at<float>(j));
    }
  }
}

TEST(RInPrecision, Float128AndMpfrRunsUseTheirOwnR) {
  // At r = 0.11 the map is chaotic (README: symbols are lost after ~ digits x ln(10) / 0.66 steps): the 6e-18
  // relative difference between float128's 0.11 and double's 0.11 widened grows until the symbol sequences part
  // within ~60 steps (MPFR at 40 digits likewise).  Before the change both ensembles gave the same
  // lanes (double's r widened), so the symbols were equal.
  iterate::Ensemble text, widened;
  text.set_r_list({core::Decimal::parse("0.11", "r")});
  widened.r = {0.11};
  text.initial = widened.initial = iterate::random_points(8, 3);
  const long steps = 3000;
  iterate::SymbolRecorder a(text.orbits(), 1, steps), b(text.orbits(), 1, steps);
  iterate::run<core::float128>(text, steps, a);
  iterate::run<core::float128>(widened, steps, b);
  EXPECT_NE(a.out, b.out);
  iterate::SymbolRecorder sa(text.orbits(), 1, steps), sb(text.orbits(), 1, steps);
  iterate::run_scalar<core::float128>(text, steps, sa);
  iterate::run_scalar<core::float128>(widened, steps, sb);
  EXPECT_NE(sa.out, sb.out);
  {
    core::MpfrDigits forty(40);
    iterate::SymbolRecorder ma(text.orbits(), 1, 600), mb(text.orbits(), 1, 600);
    iterate::run<core::mpfr_float>(text, 600, ma);
    iterate::run<core::mpfr_float>(widened, 600, mb);
    EXPECT_NE(ma.out, mb.out);
  }
  // Double: the decimal source changes nothing.
  iterate::SymbolRecorder da(text.orbits(), 1, steps), db(text.orbits(), 1, steps);
  iterate::run<double>(text, steps, da);
  iterate::run<double>(widened, steps, db);
  EXPECT_EQ(da.out, db.out);
}

TEST(RInPrecision, BifurcationInDoubleIsUnchangedAndFloat128ReadsTheDecimal) {
  bifurcation::Request r;
  core::set_field(r.r_min, {"0.105"}, "r-min");  // chaotic (README: r = 0.11): the tails differ with r's last bits
  core::set_field(r.r_max, {"0.11"}, "r-max");
  r.r_count = 3, r.iterations = 2000, r.tail = 200, r.bins = 256;
  // Double: the kernel over linspace_r's doubles, as before the change, bitwise.
  const bifurcation::Result d = bifurcation::run(r);
  iterate::Ensemble e;
  e.r = iterate::linspace_r(0.105, 0.11, 3);
  e.initial = iterate::paper_grid();
  iterate::DensityRecorder dens(iterate::Coord::theta, e, r.iterations, r.tail, 256, 0, std::acos(-1.0) / 2,
                                static_cast<std::size_t>(omp_get_max_threads()));
  iterate::run<double>(e, r.iterations, dens);
  EXPECT_EQ(d.density, dens.merge());
  // float128: the same r values from the decimals, not the doubles widened.
  r.precision = "float128";
  const bifurcation::Result q = bifurcation::run(r);
  iterate::DensityRecorder wid(iterate::Coord::theta, e, r.iterations, r.tail, 256, 0, std::acos(-1.0) / 2,
                               static_cast<std::size_t>(omp_get_max_threads()));
  iterate::run<core::float128>(e, r.iterations, wid);
  EXPECT_NE(q.density, wid.merge());
}

TEST(RInPrecision, OrbitRequestReadsRInItsPrecision) {
  // The Lyapunov orbit request passes T's r: equal to projective_exponents<T> at T's parse of the decimal, and (the
  // orbit at r = 0.11 being chaotic) not to the run at double's r widened.
  lyapunov::OrbitRequest req;
  core::set_field(req.r, {"0.11"}, "r");
  req.point = "1,-0.5,-1";
  req.iterations = 20000;
  req.transient = 100;
  req.precision = "float128";
  req.weighted = true;  // the weighted averages too, which the library's Options compute by default
  const lyapunov::ProjectiveResult a = lyapunov::run(req);
  lyapunov::Options o;
  o.iterations = req.iterations;
  o.transient = req.transient;
  o.reorthonormalise = req.reorthonormalise;
  o.blocks = req.blocks;
  const core::Vec3<double> u = core::parse_point(req.point, "point");
  const core::Vec3<core::float128> uq(u(0), u(1), u(2));
  const lyapunov::ProjectiveResult t =
      lyapunov::projective_exponents<core::float128>(uq, boost::lexical_cast<core::float128>("0.11"), o);
  const lyapunov::ProjectiveResult w = lyapunov::projective_exponents<core::float128>(uq, core::float128(0.11), o);
  EXPECT_EQ(a.weighted, t.weighted);
  EXPECT_TRUE(a.final_point == t.final_point);
  EXPECT_TRUE(a.final_point != w.final_point);
}

// ------------------------------------------------------------------------------------------------ lyapunov
TEST(LyapunovRequest, ValidationNamesTheField) {
  lyapunov::OrbitRequest o;
  o.point = "1,-3,-1.1";
  EXPECT_EQ(failing_field([&] { o.validate(); }), "r");  // r has no default
  o.r = 0.15;
  EXPECT_EQ(failing_field([&] { o.validate(); }), "");
  o.blocks = 1;
  EXPECT_EQ(failing_field([&] { o.validate(); }), "blocks");
  o.blocks = 20;
  o.precision = "quad";
  EXPECT_EQ(failing_field([&] { o.validate(); }), "precision");
  o.precision = "double";
  o.r = 1e-300;  // below what double resolves (r^2 < 1e3 eps): refused, naming r and a precision that works
  try {
    o.validate();
    FAIL() << "r = 1e-300 accepted in double";
  } catch (const core::InvalidField& e) {
    EXPECT_EQ(e.field, "r");
    EXPECT_NE(std::string(e.what()).find("mpfr:"), std::string::npos) << e.what();
  }
  lyapunov::MapRequest m;
  m.r_count = 0;
  EXPECT_EQ(failing_field([&] { m.validate(); }), "r-count");
  lyapunov::StripRequest s;
  s.grid = "strip:4x4:1:-1";
  EXPECT_EQ(failing_field([&] { s.validate(); }), "grid");
  s.grid = "strip:0x4";
  EXPECT_EQ(failing_field([&] { s.validate(); }), "grid");
}

TEST(LyapunovRequest, OrbitEqualsTheQrRouteBitwise) {
  lyapunov::OrbitRequest o;
  o.r = 0.15;
  o.point = "1,-3,-1.1";
  o.iterations = 5000;
  const lyapunov::ProjectiveResult a = lyapunov::run(o);
  lyapunov::Options opt;
  opt.iterations = 5000;
  const auto b = lyapunov::projective_exponents<double>(core::Vec3<double>(1, -3, -1.1), 0.15, opt);
  EXPECT_EQ(a.lambda[0].value, b.lambda[0].value);
  EXPECT_EQ(a.lambda[1].value, b.lambda[1].value);
}

TEST(LyapunovRequest, SmallestResolvedRAgreesWithAWiderPrecision) {
  // Just above double's bound sqrt(1e3 eps) = 4.7e-7 the exponents agree with long double's to about eps/r^2
  // relative per step; 1e-3 absolute is the criterion the bound states.
  lyapunov::OrbitRequest o;
  o.r = 5e-7;
  o.point = "1,-3,-1.1";
  o.iterations = 2000;
  o.transient = 100;
  const auto d = lyapunov::run(o);
  o.precision = "long-double";
  const auto l = lyapunov::run(o);
  const auto criterion = bound(1e-3, "the criterion double's bound on r states (eps / r^2 relative per step)");
  EXPECT_CLOSE(d.lambda[0].value, l.lambda[0].value, criterion);
  EXPECT_CLOSE(d.lambda[1].value, l.lambda[1].value, criterion);
}

TEST(LyapunovRequest, MpfrDigitsDoNotLeakBetweenRuns) {
  const unsigned before = core::mpfr_float::default_precision();
  lyapunov::OrbitRequest o;
  o.r = 0.3;
  o.point = "1,-3,-1.1";
  o.iterations = 400;
  o.transient = 10;
  o.precision = "mpfr:30";
  const auto a = lyapunov::run(o);
  EXPECT_EQ(core::mpfr_float::default_precision(), before);
  o.precision = "mpfr:60";
  (void)lyapunov::run(o);
  o.precision = "mpfr:30";
  const auto b = lyapunov::run(o);
  EXPECT_EQ(a.lambda[0].value, b.lambda[0].value);  // the 60-digit run in between changed nothing
  EXPECT_EQ(core::mpfr_float::default_precision(), before);
}

TEST(LyapunovRequest, MapDescribesEveryArrayWithItsShape) {
  lyapunov::MapRequest m;
  m.r_min = 0.1, m.r_max = 0.2, m.r_count = 3, m.iterations = 200, m.transient = 20;
  const auto res = lyapunov::run(m);
  core::Contents c;
  res.describe(c);
  for (const char* n : {"r", "lambda1", "err1", "lambda2", "err2", "lambda_max", "err_max", "lambda_min", "err_min",
                        "chi1", "median", "median_err", "min_err", "max_err", "frac_zero"}) {
    const core::ArrayView* a = c.find(n);
    ASSERT_NE(a, nullptr) << n;
    std::size_t total = 1;
    for (auto d : a->dims) total *= d;
    EXPECT_EQ(total, a->size()) << n;
    EXPECT_FALSE(a->units.empty()) << n;
    EXPECT_FALSE(a->description.empty()) << n;
  }
  EXPECT_EQ(c.find("lambda1")->dims, (std::vector<std::size_t>{3, 32}));
  for (std::size_t i = 0; i < c.arrays.size(); ++i)  // one HDF5 dataset per name (a repeated name fails to write)
    for (std::size_t j = 0; j < i; ++j) EXPECT_NE(c.arrays[i].name, c.arrays[j].name);
}

TEST(LyapunovRequest, CancelledRunThrows) {
  lyapunov::MapRequest m;
  m.r_count = 50, m.iterations = 2000, m.transient = 20;
  core::CancelToken t;
  t.cancel();
  core::RunControl c;
  c.cancel = &t;
  EXPECT_THROW(lyapunov::run(m, c), core::Cancelled);
}

// ------------------------------------------------------------------------------------------------ bifurcation
TEST(BifurcationRequest, ValidationNamesTheField) {
  bifurcation::Request r;
  EXPECT_EQ(failing_field([&] { r.validate(); }), "");
  r.tail = 0;
  EXPECT_EQ(failing_field([&] { r.validate(); }), "tail");
  r = {};
  r.range = {1, 0};
  EXPECT_EQ(failing_field([&] { r.validate(); }), "range");
  r = {};
  r.log = true;
  r.coord = "phi";
  EXPECT_EQ(failing_field([&] { r.validate(); }), "log");
  r = {};
  r.algorithm = "trig";
  r.precision = "float";
  EXPECT_EQ(failing_field([&] { r.validate(); }), "algorithm");
  r = {};
  r.r_max = 1;
  EXPECT_EQ(failing_field([&] { r.validate(); }), "r-max");
}

TEST(BifurcationRequest, DensityEqualsTheKernelWithItsRecorderBitwise) {
  bifurcation::Request r;
  r.r_count = 40, r.iterations = 600, r.tail = 50, r.bins = 64;
  core::RunControl one;
  one.threads = 1;
  const bifurcation::Result a = bifurcation::run(r, one);
  // The same run through the kernel directly.
  iterate::Ensemble e;
  e.r = iterate::linspace_r(r.r_min, r.r_max, r.r_count);
  e.initial = iterate::paper_grid();
  iterate::DensityRecorder d(iterate::Coord::theta, e, r.iterations, r.tail, 64, 0, std::acos(-1.0) / 2, 2);
  iterate::RunOptions opt;
  opt.threads = 2;
  iterate::run<double>(e, r.iterations, d, opt);
  EXPECT_EQ(a.density, d.merge());  // and 1 thread equals 2 threads
  std::uint64_t points = 0;
  for (auto v : a.density) points += v;
  EXPECT_EQ(points + a.points_below() + a.points_above(), 40u * 32u * 50u);
  core::Contents c;
  a.describe(c);
  EXPECT_EQ(c.find("density")->dims, (std::vector<std::size_t>{40, 64}));
}

}  // namespace

// Float near a weakly contracting sink.  At r = 0.171599 (just above 3 - 2 sqrt(2), the sink's
// exponent -0.0116 per step) float rounding moves orbits of the Section 4 grid off the sink (lyapunov-map called 37.5%
// of them "zero", double none): the float run re-runs its orbits in double and counts the disagreements, which
// the command line prints as a warning.  On the strongly contracting sink 1133 (r = 0.15) they agree.
TEST(LyapunovRequest, FloatIsCheckedAgainstDoubleNearTheNeutralSink) {
  lyapunov::MapRequest m;
  m.r_min = m.r_max = 0.171599, m.r_count = 1, m.precision = "float";
  const auto near = lyapunov::run(m);
  EXPECT_EQ(near.float_checked, 32);
  EXPECT_GT(near.float_disagree, 0);
  EXPECT_EQ(near.float_disagree_r, 0.171599);
  m.r_min = m.r_max = 0.15;
  const auto far = lyapunov::run(m);
  EXPECT_EQ(far.float_checked, 32);
  EXPECT_EQ(far.float_disagree, 0);
  m.r_min = 0.1, m.r_max = 0.2, m.r_count = 200, m.iterations = 200, m.transient = 20;  // every 4th r value: 50 x 32
  EXPECT_EQ(lyapunov::run(m).float_checked, 50 * 32);
  m.precision = "double";
  EXPECT_EQ(lyapunov::run(m).float_checked, 0);  // double is not checked against itself
}
