// The request API (core/request.hpp) of the analyses moved into their modules: validation names the field,
// run(request) equals the lower-level routes it wraps bitwise, results describe their arrays, MPFR digits do not
// leak from one run to the next, field parsers read what they write.
#include "bifurcation/bifurcation.hpp"
#include "core/fields.hpp"
#include "core/scalar.hpp"
#include "iterate/kernel.hpp"
#include "iterate/recorders.hpp"
#include "lyapunov/requests.hpp"

#include <gtest/gtest.h>

#include "tolerance.hpp"

#include <cmath>
#include <limits>
#include <thread>

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
  EXPECT_THROW(core::parse_point("1,1,1"), std::domain_error);  // x*z > 0 is outside the domain
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
  s.w1_min = 1, s.w1_max = -1;
  EXPECT_EQ(failing_field([&] { s.validate(); }), "w1-range");
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
  for (const char* n : {"r", "lambda1", "err1", "lambda2", "err2", "lambda_max", "err_max", "lambda_min", "err_min", "chi1",
                        "median", "median_err", "min_err", "max_err", "frac_zero"}) {
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

// Issue 21, item 5: float near a weakly contracting sink.  At r = 0.171599 (just above 3 - 2 sqrt(2), the sink's
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
