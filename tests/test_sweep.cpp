// SPDX-License-Identifier: GPL-3.0-or-later
// Sweeps in parts (core/sweep.hpp), without MPI: for any partition of the items, in any order, merge(run_part...)
// equals run() bitwise, array by array; parts survive core/pack.hpp bitwise.  This is what makes `mpirun -n P`
// give the single process's files (tests/mpi_sweeps.sh checks the command line on top of it).
#include "attractors/requests.hpp"
#include "bifurcation/bifurcation.hpp"
#include "core/estimate.hpp"
#include "core/pack.hpp"
#include "core/sweep.hpp"
#include "leaves/requests.hpp"
#include "lyapunov/hyperbolicity_requests.hpp"
#include "lyapunov/requests.hpp"
#include "patterns/requests.hpp"
#include "stats/requests.hpp"
#include "windows/requests.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <set>
#include <thread>
#include <variant>

namespace {
using namespace btob;

// Two arrays of one type, bitwise.
template <class V> void expect_same_bytes(const std::vector<V>& u, const std::vector<V>& v, const std::string& what) {
  ASSERT_EQ(u.size(), v.size()) << what;
  if (!u.empty())  // memcmp must not see an empty vector's null data() (UBSan: nonnull)
    EXPECT_EQ(0, std::memcmp(u.data(), v.data(), u.size() * sizeof(V))) << what << " differs";
}

// The arrays of two results, bitwise (same names, shapes and bytes).
template <class R> void expect_same_arrays(const R& a, const R& b, const std::string& what) {
  core::Contents ca, cb;
  a.describe(ca);
  b.describe(cb);
  ASSERT_EQ(ca.arrays.size(), cb.arrays.size()) << what;
  for (std::size_t i = 0; i < ca.arrays.size(); ++i) {
    const auto& x = ca.arrays[i];
    const auto& y = cb.arrays[i];
    EXPECT_EQ(x.name, y.name) << what;
    EXPECT_EQ(x.dims, y.dims) << what << " " << x.name;
    std::visit([&](const auto* u) { expect_same_bytes(*u, *std::get<decltype(u)>(y.data), what + ": " + x.name); },
               x.data);
  }
}

// The rows named `name` of every rank (core::RowSet), placed by item: n rows of `width` values.
template <class V>
std::vector<V> place_rows(const std::vector<core::RowSet>& kept, const std::string& name, std::size_t n,
                          std::size_t width) {
  std::vector<V> placed(n * width);
  for (const core::RowSet& rs : kept)
    for (const core::RowColumn& col : rs.columns) {
      if (col.name != name) continue;
      const auto& v = std::get<std::vector<V>>(col.data);  // throws when the part's type is not the dataset's
      if (v.size() != rs.items.size() * width) throw std::logic_error(name + ": not one row per item");
      for (std::size_t j = 0; j < rs.items.size(); ++j)
        std::copy_n(v.begin() + static_cast<std::ptrdiff_t>(j * width), width,
                    placed.begin() + static_cast<std::ptrdiff_t>(rs.items[j] * width));
    }
  return placed;
}

// A merge of parts whose named rows (Part::rows) were taken out, as under mpirun when the ranks write their own
// rows (core::take_rows, core::ThinMerge): every other array bitwise the whole run's, the named ones empty with the
// whole run's shape (describe gives the datasets' shapes), their rows placed by item bitwise the whole run's, and
// the attributes (but wall times) and tables the same.  A merge or a table that read a named row would fail here.
template <class Req, class Part, class R>
void expect_thin_merge_equals_run(const Req& req, std::vector<Part> parts, const R& whole, const std::string& what) {
  const std::size_t n = req.work_items();
  std::vector<core::RowSet> kept;
  std::set<std::string> named;
  for (Part& p : parts) {
    kept.push_back(core::take_rows(p, n));
    for (const auto& c : kept.back().columns) named.insert(c.name);
  }
  const R thin = [&] {
    core::ThinMerge t;
    return merge(req, std::move(parts));
  }();
  core::Contents cw, ct;
  whole.describe(cw);
  thin.describe(ct);
  ASSERT_EQ(cw.arrays.size(), ct.arrays.size()) << what;
  std::size_t rows_checked = 0;
  for (std::size_t i = 0; i < cw.arrays.size(); ++i) {
    const auto &x = cw.arrays[i], &y = ct.arrays[i];
    EXPECT_EQ(x.name, y.name) << what;
    EXPECT_EQ(x.dims, y.dims) << what << " " << x.name;
    std::visit(
        [&](const auto* u) {
          using V = typename std::remove_cvref_t<decltype(*u)>::value_type;
          const auto* v = std::get<decltype(u)>(y.data);
          if (!named.count(x.name)) return expect_same_bytes(*u, *v, what + ", thin merge: " + x.name);
          EXPECT_TRUE(v->empty()) << what << ": the named rows of " << x.name << " were merged";
          ASSERT_EQ(x.dims.at(0), n) << what << ": " << x.name << " has not one row per item";
          expect_same_bytes(*u, place_rows<V>(kept, x.name, n, u->size() / n), what + ", rows of " + x.name);
          ++rows_checked;
        },
        x.data);
  }
  EXPECT_GT(rows_checked, 0u) << what << ": no named rows among the datasets";
  // The attributes but wall times (the whole run and the parts are timed apart).
  const auto untimed = [](core::Attrs a) {
    std::erase_if(a, [](const auto& kv) { return kv.first.find("seconds") != std::string::npos; });
    return a;
  };
  EXPECT_EQ(untimed(cw.attrs), untimed(ct.attrs)) << what << ": attributes";
  if constexpr (requires { whole.tables(); }) {
    // A table whose lines the parts name (a column of strings): the thin merge's is its header alone, and the
    // header followed by the lines placed by item is the whole run's, byte for byte.  The others the same.
    const core::Tables tw = whole.tables(), tt = thin.tables();
    ASSERT_EQ(tw.size(), tt.size()) << what << ": tables";
    for (std::size_t i = 0; i < tw.size(); ++i) {
      EXPECT_EQ(tw[i].first, tt[i].first) << what;
      std::string text = tt[i].second;
      if (named.count(tt[i].first)) {
        EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << what << ": table " << tt[i].first << " merged";
        for (const std::string& line : place_rows<std::string>(kept, tt[i].first, n, 1)) text += line + "\n";
      }
      EXPECT_EQ(tw[i].second, text) << what << ": table " << tt[i].first;
    }
  }
}

// `parts` random parts of 0..n-1 (some possibly empty), each ascending, returned in shuffled order.
std::vector<std::vector<std::size_t>> random_partition(std::size_t n, std::size_t parts, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<std::vector<std::size_t>> p(parts);
  for (std::size_t i = 0; i < n; ++i) p[rng() % parts].push_back(i);
  std::shuffle(p.begin(), p.end(), rng);
  return p;
}

// run() against merge() of the parts of several partitions, each part sent through pack/unpack; `same_text`
// compares what the arrays do not hold (decimal text, CSV tables) of the whole run and a merged one.
struct NoText {
  template <class R> void operator()(const R&, const R&, const std::string&) const {}
};
template <class Req, class Text = NoText>
void expect_any_partition_equals_run(const Req& req, const std::string& what, Text same_text = {}) {
  core::RunControl one;
  one.threads = 1;
  const auto whole = run(req, one);
  const std::size_t n = req.work_items();
  for (std::size_t parts : {std::size_t{2}, std::size_t{3}, n + 1}) {
    using Part = decltype(run_part(req, std::vector<std::size_t>{}, one));
    std::vector<Part> got;
    for (const auto& items : random_partition(n, parts, parts))
      got.push_back(core::unpack<Part>(core::pack(run_part(req, items, one))));
    if constexpr (core::HasRows<Part>) expect_thin_merge_equals_run(req, got, whole, what + ", thin");
    const auto merged = merge(req, std::move(got));
    expect_same_arrays(whole, merged, what + ", " + std::to_string(parts) + " parts");
    same_text(whole, merged, what + ", " + std::to_string(parts) + " parts");
  }
}

TEST(Sweep, CyclicItemsCoverEveryItemOnce) {
  for (std::size_t n : {0, 1, 7, 40})
    for (std::size_t p : {1, 2, 3, 64}) {
      std::vector<int> seen(n, 0);
      for (std::size_t k = 0; k < p; ++k)
        for (std::size_t i : core::cyclic_items(n, k, p)) ++seen[i];
      for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(seen[i], 1) << n << " items, " << p << " parts, item " << i;
    }
}

TEST(Sweep, MergeRefusesMissingOrRepeatedItems) {
  bifurcation::Request q;
  q.r_count = 4;
  q.iterations = 20;
  q.tail = 5;
  EXPECT_THROW(merge(q, {run_part(q, {0, 1, 2})}), std::logic_error);
  EXPECT_THROW(merge(q, {run_part(q, {0, 1, 2}), run_part(q, {2, 3})}), std::logic_error);
}

TEST(Sweep, PackRoundTripsBitwise) {
  attractors::OrbitVerdict v;
  v.type = attractors::Type::periodic;
  v.word.s = {1, 3, 2};
  v.key = "P132";
  v.lambda1 = -0.0;
  v.residual = std::numeric_limits<double>::quiet_NaN();
  v.point = core::Vec3<double>(1, -2.5, 1e-310);
  v.detail = std::string("with a\0 byte", 12);
  attractors::BasinRows p;
  p.items = {3, 5};
  p.labels = {1, 0, 2};
  attractors::BasinClass c;
  c.first = v, c.first_index = 7, c.count = {4, 5}, c.rotation_min = -0.0, c.invariant_max = 1e-310;
  p.classes = {c, c};
  p.undecided = {1, 2};
  p.iterations = 123, p.certified = 9, p.seconds = 1.5, p.threads = 2;
  const auto q = core::unpack<attractors::BasinRows>(core::pack(p));
  EXPECT_EQ(q.items, p.items);
  EXPECT_EQ(q.labels, p.labels);
  EXPECT_EQ(q.undecided, p.undecided);
  EXPECT_EQ(q.iterations, 123);
  EXPECT_EQ(q.certified, 9u);
  ASSERT_EQ(q.classes.size(), 2u);
  EXPECT_EQ(q.classes[1].first.word.s, v.word.s);
  EXPECT_EQ(q.classes[1].first.detail, v.detail);
  EXPECT_EQ(q.classes[1].first_index, 7u);
  EXPECT_EQ(q.classes[1].count, c.count);
  EXPECT_TRUE(std::signbit(q.classes[0].rotation_min));
  EXPECT_EQ(q.classes[0].invariant_max, 1e-310);
  EXPECT_TRUE(std::signbit(q.classes[0].first.lambda1));
  EXPECT_TRUE(std::isnan(q.classes[0].first.residual));
  EXPECT_EQ(q.classes[0].first.point, v.point);
  auto bytes = core::pack(p);
  bytes.pop_back();
  EXPECT_THROW(core::unpack<attractors::BasinRows>(bytes), std::runtime_error);  // short message
}

TEST(Sweep, BifurcationAnyPartitionEqualsRun) {
  bifurcation::Request q;
  q.r_min = 0.08, q.r_max = 0.4, q.r_count = 21, q.iterations = 800, q.tail = 30, q.bins = 100, q.raw = true;
  expect_any_partition_equals_run(q, "bifurcation");
  q.raw = false, q.precision = "float", q.log = true;
  expect_any_partition_equals_run(q, "bifurcation float log");
}

TEST(Sweep, LyapunovMapAnyPartitionEqualsRun) {
  // 31 r x 32 orbits: 992 orbits, not a multiple of the batch width, so parts end in partial batches that the
  // whole run has elsewhere (TangentRecorder steps partial batches through the full-width loop).
  lyapunov::MapRequest q;
  q.r_min = 0.08, q.r_max = 0.35, q.r_count = 31, q.iterations = 400, q.transient = 100, q.blocks = 4;
  expect_any_partition_equals_run(q, "lyapunov-map");
}

TEST(Sweep, LyapunovStripAnyPartitionEqualsRun) {
  lyapunov::StripRequest q;
  q.r = 0.3, q.grid = "strip:11x7", q.iterations = 300, q.transient = 50, q.blocks = 3;
  expect_any_partition_equals_run(q, "lyapunov-strip");
}

TEST(Sweep, BasinsAnyPartitionEqualsRun) {
  attractors::BasinsRequest q;
  q.r = 0.2, q.grid = "strip:13x7", q.replicates = 1;
  q.thresholds.transient = 400, q.thresholds.window = 300, q.thresholds.max_period = 200;
  q.thresholds.lyap_iterations = 400, q.thresholds.refine_factor = 2;
  // The table (first points, rotation and invariant ranges) byte for byte: the orbits decided early whose values it
  // prints are chosen in merge, the same for any partition; and the attractors' ranges bitwise.
  const auto text = [](const auto& a, const auto& b, const std::string& what) {
    EXPECT_EQ(a.tables(), b.tables()) << what;
    ASSERT_EQ(a.basins.attractors.size(), b.basins.attractors.size()) << what;
    for (std::size_t i = 0; i < a.basins.attractors.size(); ++i) {
      const auto &x = a.basins.attractors[i], &y = b.basins.attractors[i];
      EXPECT_EQ(x.point, y.point) << what << " " << x.key;
      EXPECT_EQ(x.rotation_min, y.rotation_min) << what << " " << x.key;
      EXPECT_EQ(x.rotation_max, y.rotation_max) << what << " " << x.key;
      EXPECT_EQ(x.invariant_min, y.invariant_min) << what << " " << x.key;
      EXPECT_EQ(x.invariant_max, y.invariant_max) << what << " " << x.key;
    }
    EXPECT_EQ(a.basins.certified, b.basins.certified) << what;
    EXPECT_EQ(a.basins.iterations_total, b.basins.iterations_total) << what;
  };
  expect_any_partition_equals_run(q, "basins", text);
  // The default thresholds on a 40 x 30 strip at r = 0.21 (three sinks and the P2 curves, mostly decided early).
  attractors::BasinsRequest d;
  d.r = 0.21, d.grid = "strip:40x30", d.replicates = 1;
  expect_any_partition_equals_run(d, "basins, default thresholds", text);
}

TEST(Sweep, LeavesAnyPartitionEqualsRun) {
  // Five r values across the range where the leaves exist; every per-r array (closed forms, landing law, label map,
  // followed leaves) is placed by item.
  leaves::Request q;
  q.r_min = 0.18, q.r_max = 0.6, q.r_count = 5, q.grid = "sphere:12x10", q.leaf_iterations = 300;
  q.labels = {0.5, 1.2};
  q.thresholds.transient = 400, q.thresholds.window = 300, q.thresholds.max_period = 200;
  q.thresholds.lyap_iterations = 400, q.thresholds.refine_factor = 2;
  expect_any_partition_equals_run(q, "leaves");
}

TEST(Sweep, BasinsRAnyPartitionEqualsRun) {
  attractors::BasinsRRequest q;
  q.r_values = {0.11, 0.15, 0.2, 0.3};
  q.grid = "random:40";
  q.thresholds.transient = 400, q.thresholds.window = 300, q.thresholds.max_period = 200;
  q.thresholds.lyap_iterations = 400, q.thresholds.refine_factor = 2;
  q.boundary_grid = "sphere:40x40";  // the boundary run is a basins run per r, partitioned with its r
  expect_any_partition_equals_run(q, "basins-r");
}

TEST(Sweep, HyperbolicityAnyPartitionEqualsRun) {
  lyapunov::HyperbolicityRequest q;
  q.r = 0.11, q.grid = "strip:17x9", q.w1_range = "-1.5,2.5";
  expect_any_partition_equals_run(q, "hyperbolicity");
  core::RunControl one;
  one.threads = 1;
  // The expanding fraction (an attribute) is counted over the merged cells: the same for any partition.
  const auto whole = run(q, one);
  const auto items = random_partition(q.work_items(), 3, 7);
  std::vector<lyapunov::HyperbolicityPart> parts;
  for (const auto& i : items) parts.push_back(run_part(q, i, one));
  const auto merged = merge(q, std::move(parts));
  EXPECT_EQ(merged.image.expanding_fraction, whole.image.expanding_fraction);
  EXPECT_EQ(whole.image.expanding_fraction, lyapunov::strip_singular_values(0.11, 17, 9, -1.5, 2.5).expanding_fraction);
  // s1's extremes (the printed line) folded over the parts: those of the merged cells.
  const auto [lo, hi] = std::minmax_element(whole.image.s1.begin(), whole.image.s1.end());
  EXPECT_EQ(merged.s1_min, *lo);
  EXPECT_EQ(merged.s1_max, *hi);
}

TEST(Sweep, HyperbolicityOrbitsAnyPartitionEqualsRun) {
  // Pooled quantiles and histograms per r are rows: each r pools its own orbits only.  Degenerate orbits (NaN
  // angles) occur from r = 0.2 on (invariant curves); 5 orbits are a partial batch of the tangent recorder.
  lyapunov::HyperbolicityOrbitsRequest q;
  q.r_min = 0.09, q.r_max = 0.31, q.r_count = 7, q.grid = "random:5", q.seed = 3;
  q.iterations = 200, q.transient = 100, q.backward = 100, q.bins = 12;
  expect_any_partition_equals_run(q, "hyperbolicity-orbits");
}

TEST(Sweep, HyperbolicityOrbitsPartPackRoundTrips) {
  lyapunov::HyperbolicityOrbitsRequest q;
  q.r_min = 0.11, q.r_max = 0.3, q.r_count = 3, q.grid = "1,-3,-1.1;1,0.1,-1";
  q.iterations = 100, q.transient = 50, q.backward = 50, q.bins = 5;
  core::RunControl one;
  one.threads = 1;
  const auto p = run_part(q, {0, 2}, one);
  const auto u = core::unpack<lyapunov::HyperbolicityOrbitsPart>(core::pack(p));
  EXPECT_EQ(u.items, p.items);
  EXPECT_EQ(u.angle_histogram, p.angle_histogram);
  EXPECT_EQ(u.orbit_degenerate, p.orbit_degenerate);
  EXPECT_EQ(u.orbit_lambda1, p.orbit_lambda1);
  EXPECT_EQ(u.summary.median, p.summary.median);
  EXPECT_EQ(u.summary.frac_positive, p.summary.frac_positive);
  EXPECT_EQ(u.threads, p.threads);
  EXPECT_EQ(0, std::memcmp(u.angle_median.data(), p.angle_median.data(), p.angle_median.size() * sizeof(double)));
  auto bytes = core::pack(p);
  bytes.pop_back();
  EXPECT_THROW(core::unpack<lyapunov::HyperbolicityOrbitsPart>(bytes), std::runtime_error);
}

TEST(Sweep, MeasureAnyPartitionEqualsRun) {
  // r = 0.3: the 12 random orbits fall in 4 groups (invariant curves), so heads, distances and the convergence
  // table span parts; 12 orbits are a partial batch of the kernel.
  stats::MeasureRequest q;
  q.r = 0.3, q.grid = "random:12", q.iterations = 3000, q.transient = 500, q.bins = 30;
  expect_any_partition_equals_run(q, "measure");
  q.r = 0.11, q.grid = "strip:3x4", q.coords = "angles", q.extent = {0.2, 1.2, 0.5, 2.5};  // points outside
  expect_any_partition_equals_run(q, "measure angles extent");
}

TEST(Sweep, MeasureIsEmpiricalMeasureOfTheOrbits) {
  // The measures counted from the bins of the parts are the ones empirical_measure gives from the orbits.
  const auto series = stats::orbit_series(0.3, iterate::parse_grid("random:3", 1), 200, 1000, 1);
  for (const bool zoom : {false, true}) {
    const std::vector<double> extent = zoom ? std::vector<double>{-1, 1, -0.5, 0.5} : std::vector<double>{};
    const stats::Measure frame = stats::measure_frame(stats::Chart::strip, 20, 10, extent);
    for (const auto& s : series) {
      const auto cells = stats::measure_cells(s, frame, extent.empty());
      ASSERT_EQ(cells.size(), 1000u);
      for (const long n : {1L, 16L, 1000L}) {
        const stats::Measure a = stats::measure_of_cells(frame, cells.data(), n);
        const stats::Measure b = stats::empirical_measure(s, stats::Chart::strip, 20, 10, 0, n, extent);
        EXPECT_EQ(a.mass, b.mass);
        EXPECT_EQ(a.outside, b.outside);
        EXPECT_EQ(a.points, b.points);
        EXPECT_EQ(a.u_lo, b.u_lo);
        EXPECT_EQ(a.v_hi, b.v_hi);
      }
    }
  }
}

}  // namespace

namespace {

TEST(Sweep, WindowsPolyAnyPartitionEqualsRun) {
  windows::PolyRequest q;
  q.n = "2..9";
  expect_any_partition_equals_run(q, "windows poly", [](const auto& a, const auto& b, const std::string& what) {
    EXPECT_EQ(a.text(), b.text()) << what;
  });
}

TEST(Sweep, WindowsBoundsAnyPartitionEqualsRun) {
  // The certificates' brackets travel as exact rationals: the merged CSV prints the same a, b and root counts.
  windows::BoundsRequest q;
  q.n = "1..14", q.digits = 15, q.certify = true;
  const auto text = [](const auto& a, const auto& b, const std::string& what) {
    EXPECT_EQ(a.csv(), b.csv()) << what;
    ASSERT_EQ(a.certificates.size(), b.certificates.size()) << what;
    for (std::size_t i = 0; i < a.certificates.size(); ++i) {
      EXPECT_EQ(a.certificates[i].a, b.certificates[i].a) << what << ", n = " << a.n[i];
      EXPECT_EQ(a.certificates[i].b, b.certificates[i].b) << what << ", n = " << a.n[i];
      EXPECT_EQ(a.certificates[i].decimals, b.certificates[i].decimals) << what << ", n = " << a.n[i];
      EXPECT_TRUE(b.certificates[i].valid()) << what << ", n = " << a.n[i];
    }
  };
  expect_any_partition_equals_run(q, "windows bounds --certify", text);
  q.n = "5..11", q.certify = false;
  expect_any_partition_equals_run(q, "windows bounds", text);
}

TEST(Sweep, WindowsVerifyAnyPartitionEqualsRun) {
  windows::VerifyRequest q;
  q.n = "2..7", q.iterations = 2000, q.per_n = 10, q.tail = 1000;
  expect_any_partition_equals_run(q, "windows verify", [](const auto& a, const auto& b, const std::string& what) {
    EXPECT_EQ(a.csv(), b.csv()) << what;
    EXPECT_EQ(a.passed, b.passed) << what;
    EXPECT_EQ(a.total, b.total) << what;
  });
}

TEST(Sweep, WindowsPrecisionAnyPartitionEqualsRun) {
  // The seconds column times each bound: compared without it.  The summary's largest n are derived in merge.
  windows::BoundPrecisionRequest q;
  q.n = "1..9", q.mpfr_digits = 20;
  core::RunControl one;
  one.threads = 1;
  const auto whole = run(q, one);
  std::vector<windows::BoundPrecisionPart> parts;
  for (const auto& items : random_partition(q.work_items(), 3, 11))
    parts.push_back(core::unpack<windows::BoundPrecisionPart>(core::pack(run_part(q, items, one))));
  const auto merged = merge(q, std::move(parts));
  ASSERT_EQ(whole.rows.size(), merged.rows.size());
  for (std::size_t i = 0; i < whole.rows.size(); ++i) {
    const auto &a = whole.rows[i], &b = merged.rows[i];
    EXPECT_EQ(a.precision + a.route, b.precision + b.route) << i;
    EXPECT_EQ(a.n, b.n) << i;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(a.value), std::bit_cast<std::uint64_t>(b.value))
        << a.precision << " n = " << a.n;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(a.abs_error), std::bit_cast<std::uint64_t>(b.abs_error))
        << a.precision << " n = " << a.n;
    EXPECT_EQ(a.correct_12, b.correct_12) << a.precision << " n = " << a.n;
  }
  ASSERT_EQ(whole.summary.size(), 10u);
  ASSERT_EQ(merged.summary.size(), 10u);
  for (std::size_t k = 0; k < 10; ++k) {
    EXPECT_EQ(whole.summary[k].largest_all, merged.summary[k].largest_all) << whole.summary[k].precision;
    EXPECT_EQ(whole.summary[k].largest_any, merged.summary[k].largest_any) << whole.summary[k].precision;
  }
  EXPECT_EQ(whole.correct_12, merged.correct_12);
}

// A sweep whose items each take `item_seconds` (asleep): the dry run's sample (core/estimate.hpp) on items of known
// cost.  run_part is found by argument-dependent lookup, as a module's is.
struct SleepySweep {
  std::size_t n = 1000;
  double item_seconds = 0.002;
  std::size_t work_items() const { return n; }
};
std::vector<double> run_part(const SleepySweep& q, const std::vector<std::size_t>& items, const core::RunControl&) {
  std::this_thread::sleep_for(std::chrono::duration<double>(q.item_seconds * static_cast<double>(items.size())));
  return std::vector<double>(items.size(), 1.0);
}

// The sample holds at least `min_items` items even once it took `target` seconds: 2 ms items reach the target
// (20 ms) at 16 items, and the sample goes on to 32 (a sample of a few items of a basin image missed its mean by
// 2-4 times).  Sleeping longer than asked (a loaded machine) only reaches the target sooner, never the 1 s cap.
TEST(Sweep, EstimateSamplesAtLeastMinItems) {
  core::RunControl one;
  one.threads = 1;
  const SleepySweep q;
  const auto e = core::estimate_sweep(q, one, 1, 1, 0.02, 32, 1.0);
  EXPECT_EQ(e.sampled, 32u);
  EXPECT_EQ(e.items, q.n);
  // Each item slept at least its 2 ms, so the prediction is at least n x 2 ms.
  EXPECT_GE(e.predicted_seconds, static_cast<double>(q.n) * q.item_seconds);
  EXPECT_GT(e.bytes, 0.0);
}

// Slow items stop the sample at the cap with fewer items: 30 ms items and a 0.1 s cap give 4 items (fewer when the
// sleeps overran), never the 32 a cheap sweep samples; the prediction scales by n / sampled.
TEST(Sweep, EstimateSampleStopsAtTheCap) {
  core::RunControl one;
  one.threads = 1;
  SleepySweep q;
  q.item_seconds = 0.03;
  const auto e = core::estimate_sweep(q, one, 2, 1, 0.02, 32, 0.1);
  EXPECT_LE(e.sampled, 4u);
  EXPECT_GE(e.sample_seconds, 0.1);
  EXPECT_NEAR(e.predicted_seconds, e.sample_seconds / static_cast<double>(e.sampled) * static_cast<double>(q.n) / 2,
              1e-12 * e.predicted_seconds);  // two ranks share the items
}

// The atlas's tables are where its words and the check's patterns are: they must agree byte for byte.
void expect_same_tables(const patterns::AtlasResult& a, const patterns::AtlasResult& b, const std::string& what) {
  EXPECT_EQ(a.tables(), b.tables()) << what;
  EXPECT_EQ(a.words_scanned, b.words_scanned) << what;
  EXPECT_EQ(a.stable_words, b.stable_words) << what;
  EXPECT_EQ(a.detected, b.detected) << what;
  EXPECT_EQ(a.disagreements, b.disagreements) << what;
  EXPECT_EQ(a.missed, b.missed) << what;
  EXPECT_EQ(a.followed_agree, b.followed_agree) << what;
  EXPECT_EQ(a.followed_checked, b.followed_checked) << what;
}

TEST(Sweep, PatternAtlasAnyPartitionEqualsRun) {
  // Items: the words of length <= 6, then Table 6.1's 33 r values of the check (patterns longer than 6 found).
  patterns::AtlasRequest q;
  q.max_length = 6, q.ics = 20, q.iterations = 1500, q.tail = 400, q.max_period = 150;
  const auto text = [](const auto& a, const auto& b, const std::string& what) { expect_same_tables(a, b, what); };
  expect_any_partition_equals_run(q, "pattern atlas", text);
  core::RunControl one;
  one.threads = 1;
  const auto whole = run(q, one);
  EXPECT_GT(whole.detected, 0);
  EXPECT_EQ(q.work_items(), static_cast<std::size_t>(whole.words_scanned) + patterns::table_6_1_r().size());
  q.feasible = true, q.max_length = 5;  // unstable orbits followed per word, in its part
  expect_any_partition_equals_run(q, "pattern atlas --feasible", text);
  EXPECT_GT(run(q, one).followed_checked, 0);
}

}  // namespace
