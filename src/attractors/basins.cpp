// SPDX-License-Identifier: GPL-3.0-or-later
// Basins over grids (attractors.hpp): the grids, the sweep of rows with early exits, and the merge of its parts.
#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <stdexcept>

#include "attractors/certify.hpp"
#include "attractors/recorders.hpp"
#include "attractors/stages.hpp"
#include "core/cancel.hpp"
#include "core/coords.hpp"
#include "core/run.hpp"
#include "core/sweep.hpp"

namespace btob::attractors {

using namespace stages;

// ---- grids ----

Grid parse_grid(const std::string& spec, double w1_min, double w1_max, const char* field) {
  static const core::GridSyntax syntax{
      core::grid_kinds({core::GridKind::sphere, core::GridKind::strip, core::GridKind::angles}), false, 0,
      "sphere:NxM, strip:NxM or angles:NxM with N, M >= 1"};
  Grid g = core::parse_grid(spec, syntax, field);
  if (g.kind == core::GridKind::strip) g.set_range1(w1_min, w1_max, "w1-range");
  return g;
}

std::vector<Vec3<double>> grid_points(const Grid& g, double du, double dv) {
  const std::size_t n = iterate::checked_bytes(static_cast<std::size_t>(g.axis1.cells),
                                               static_cast<std::size_t>(g.axis2.cells), sizeof(Vec3<double>), "grid") /
                        sizeof(Vec3<double>);
  std::vector<Vec3<double>> pts(n);
  for (long j = 0; j < g.axis2.cells; ++j)
    for (long i = 0; i < g.axis1.cells; ++i)
      pts[static_cast<std::size_t>(j) * static_cast<std::size_t>(g.axis1.cells) + static_cast<std::size_t>(i)] =
          g.cell_point(i, j, du, dv);
  return pts;
}

double strip_sphere_share(double a, double b) {
  const auto F = [](double w) { return std::asin(w / std::sqrt(1 + 2 * w * w)); };
  return 2 / std::numbers::pi * (F(b) - F(a));
}

std::string strip_measure_name(double a, double b) {
  return fmt::format("Lebesgue on the strip rectangle w1 in [{}, {}] x w2 in [-1, 1] ({:.4f} of the sphere measure)", a,
                     b, strip_sphere_share(a, b));
}

double sphere_share(const Grid& g) {
  return g.kind == core::GridKind::strip ? strip_sphere_share(g.axis1.lo, g.axis1.hi) : 1.0;
}

std::string measure_name(const Grid& g) {
  switch (g.kind) {
    case core::GridKind::sphere: return "uniform on the sphere of directions of the domain (equal-area grid)";
    case core::GridKind::strip: return strip_measure_name(g.axis1.lo, g.axis1.hi);
    default: return "uniform in the angles (theta, phi), not the sphere's area";
  }
}

std::size_t basin_items(const Grid& g, int replicates) {
  return static_cast<std::size_t>(replicates + 1) * static_cast<std::size_t>(g.axis2.cells);
}

namespace stages {

// ---- one chunk of orbits: checkpoints with early exits, then the rest at full length ----

// Orbits taken through the checkpoints at once (~100 bytes an orbit: starts, states, decisions; few parallel
// regions, which cost much on a loaded machine), and through the full-length route at once (~700 bytes an orbit).
constexpr std::size_t kChunk = std::size_t{1} << 18, kFullChunk = std::size_t{1} << 16;

// A chunk's verdicts: per orbit its decision, the invariant I at the checkpoint (P2 curves), and for those decided
// at full length the index of their verdict in `full`.  `steps`: map iterations made (all orbits).
struct ChunkVerdicts {
  std::vector<Decision> decision;
  std::vector<double> I;
  std::vector<std::uint32_t> full_of;
  std::vector<OrbitVerdict> full;
  long steps = 0;
};

// Buffers kept from chunk to chunk (no fresh pages per chunk): the verdicts, the orbits still undecided and their
// states.
struct ChunkBuffers {
  ChunkVerdicts out;
  std::vector<std::size_t> active;
  iterate::Ensemble cur;
  StateRecorder st{0, 1};
};

int threads_of(const Options& opt) { return core::thread_count(opt.run.threads); }

// The decisions at checkpoint t of the active orbits, whose states st holds (threads write their orbits' only).
void decide_at_checkpoint(const Certificates& cert, const StateRecorder& st, long t, const Options& opt,
                          ChunkBuffers& buf) {
  std::vector<double> e_max(cert.cones.size());
  for (std::size_t c = 0; c < e_max.size(); ++c) e_max[c] = cone_limit(cert.cones[c], opt.transient - t, opt);
  ChunkVerdicts& out = buf.out;
  const long n_active = static_cast<long>(buf.active.size());
#pragma omp parallel for schedule(static) num_threads(threads_of(opt))
  for (long i = 0; i < n_active; ++i) {
    const Vec3<double>& u = st.state[static_cast<std::size_t>(i)];
    const std::size_t o = buf.active[static_cast<std::size_t>(i)];
    Decision d = Decision::full_length();
    for (std::size_t c = 0; c < cert.cones.size() && d.is_full_length(); ++c)
      if (e_max[c] > 0 && in_cone(cert.cones[c], u, e_max[c])) d = Decision::cone(c);
    double I = 0;
    if (d.is_full_length() && on_p2_curve(cert.trap, u, opt, I)) d = Decision::p2_curve(), out.I[o] = I;
    out.decision[o] = d;
  }
}

// Keeps the orbits still undecided at checkpoint t (their states become the next run's starts); the decided ones
// made t steps.
void drop_decided(const StateRecorder& st, long t, ChunkBuffers& buf) {
  std::size_t kept = 0;
  for (std::size_t i = 0; i < buf.active.size(); ++i) {
    const std::size_t o = buf.active[i];
    if (!buf.out.decision[o].is_full_length()) {
      buf.out.steps += t;
    } else {
      buf.active[kept] = o;
      buf.cur.initial[kept] = st.state[i];
      ++kept;
    }
  }
  buf.active.resize(kept);
  buf.cur.initial.resize(kept);
}

// Runs the active orbits through the checkpoints; returns the steps they have made.
long run_checkpoints(const Certificates& cert, const Options& opt, ChunkBuffers& buf) {
  long done = 0;
  if (cert.cones.empty() && !cert.trap.on) return done;
  for (long t : cert.checkpoints) {
    if (buf.active.empty()) break;
    StateRecorder& st = buf.st;
    st.steps = t - done;
    st.state.resize(buf.cur.initial.size());
    iterate::run<double>(buf.cur, t - done, st, opt.run);
    done = t;
    decide_at_checkpoint(cert, st, t, opt, buf);
    drop_decided(st, t, buf);
  }
  return done;
}

// The orbits no checkpoint decided, at full length, kFullChunk at a time (their recorders and verdicts take ~700
// bytes an orbit).
void classify_rest(const Options& opt, long done, ChunkBuffers& buf) {
  ChunkVerdicts& out = buf.out;
  const std::vector<std::size_t>& active = buf.active;
  for (std::size_t f0 = 0; f0 < active.size(); f0 += kFullChunk) {
    const std::size_t f1 = std::min(active.size(), f0 + kFullChunk);
    iterate::Ensemble sub;
    sub.r = buf.cur.r;
    sub.initial.assign(buf.cur.initial.begin() + static_cast<std::ptrdiff_t>(f0),
                       buf.cur.initial.begin() + static_cast<std::ptrdiff_t>(f1));
    std::vector<OrbitVerdict> v = classify_from(sub, opt, done);
    for (std::size_t i = f0; i < f1; ++i) {
      out.full_of[active[i]] = static_cast<std::uint32_t>(out.full.size());
      out.steps += v[i - f0].iterations;
      out.full.push_back(std::move(v[i - f0]));
      out.full.back().detail.shrink_to_fit();
    }
  }
}

// Classification with early exits of the orbits of `ens` (one r).
const ChunkVerdicts& classify_early(const iterate::Ensemble& ens, const Options& opt, const Certificates& cert,
                                    ChunkBuffers& buf) {
  const std::size_t N = ens.orbits();
  ChunkVerdicts& out = buf.out;
  out.decision.assign(N, Decision::full_length());
  out.I.assign(N, 0.0);
  out.full_of.assign(N, 0);
  out.full.clear();
  out.steps = 0;
  buf.active.resize(N);
  for (std::size_t o = 0; o < N; ++o) buf.active[o] = o;
  buf.cur.r = ens.r;
  buf.cur.initial.assign(ens.initial.begin(), ens.initial.end());
  const long done = run_checkpoints(cert, opt, buf);
  classify_rest(opt, done, buf);
  return out;
}

// Full-length verdicts of a few starts, in whole batches of 128 (a multiple of every kernel width): each runs
// through the recorders' full-width path, as in a whole-grid run.
std::vector<OrbitVerdict> classify_whole_batches(double r, const std::vector<Vec3<double>>& starts,
                                                 const Options& opt) {
  iterate::Ensemble e;
  e.r = {r};
  e.initial = starts;
  while (e.initial.size() % 128) e.initial.push_back(e.initial.back());
  Options o = opt;
  o.run.progress = nullptr;
  std::vector<OrbitVerdict> v = classify(e, o);
  v.resize(starts.size());
  return v;
}

void expect_verdict(const OrbitVerdict& full, Type type, const std::string& key, double r) {
  if (full.type != type || full.key != key)
    throw std::logic_error(
        fmt::format("basins: early exit said {} {} for an orbit the full-length classification "
                    "calls {} {} at r = {} (a certification bound is wrong)",
                    type_name(type), key, type_name(full.type), full.key, r));
}

void check_basins(double r, const Grid& g, int replicates, const Options& opt) {
  validate(opt);
  core::validate_r(r, "r");
  if (replicates < 0 || replicates > 100) throw core::InvalidField("replicates", std::to_string(replicates), "0..100");
  // Per point of every grid: its label in a part and in the merged images; the work runs in chunks of at most
  // kChunk orbits (see there).
  iterate::checked_bytes(static_cast<std::size_t>(g.axis1.cells), static_cast<std::size_t>(g.axis2.cells),
                         8 * static_cast<std::size_t>(replicates + 1), "grid");
}

// ---- a part of a basin run: its classes as its orbits are folded in ----

constexpr std::size_t npos = static_cast<std::size_t>(-1);

// The orbit of lowest (highest) I of a Q2 class: p replaces `kept` when kept is empty, or p's I is lower (higher),
// or equal with a lower index.
void keep_lowest_invariant(Pending& kept, const Pending& p) {
  if (p.index != npos && (kept.index == npos || p.I < kept.I || (p.I == kept.I && p.index < kept.index))) kept = p;
}
void keep_highest_invariant(Pending& kept, const Pending& p) {
  if (p.index != npos && (kept.index == npos || p.I > kept.I || (p.I == kept.I && p.index < kept.index))) kept = p;
}

// The classes of a part (linear search: a handful of attractors), their counts per grid, value ranges and the orbits
// decided early whose full-length values the merge needs.
struct ClassBook {
  BasinRows& part;
  std::size_t grids;
  // The class of v's (type, key), made on first use with empty ranges (filled from full-length verdicts only).
  std::size_t find(const OrbitVerdict& v) {
    for (std::size_t c = 0; c < part.classes.size(); ++c)
      if (part.classes[c].first.type == v.type && part.classes[c].first.key == v.key) return c;
    BasinClass bc;
    bc.first = v;
    bc.first.detail.clear();
    bc.first_index = npos;
    bc.count.assign(grids, 0);
    bc.rotation_min = bc.invariant_min = std::numeric_limits<double>::infinity();
    bc.rotation_max = bc.invariant_max = -std::numeric_limits<double>::infinity();
    part.classes.push_back(std::move(bc));
    return part.classes.size() - 1;
  }
  // An orbit classified at full length: its values (rotation, invariant) and, if the lowest index yet, its verdict.
  void add_full_length(std::size_t c, const OrbitVerdict& v, std::size_t index) {
    BasinClass& bc = part.classes[c];
    widen_curve_ranges(bc, v);
    if (index < bc.first_index) {
      bc.first = v;
      bc.first.detail.clear();
      bc.first_index = index;
      bc.first_pending = Pending{};
    }
  }
  // An orbit decided early (in a cone, or on a P2 curve with its I at the checkpoint).
  void add_certified(std::size_t c, const Vec3<double>& start, std::size_t index, bool p2_curve, double I) {
    BasinClass& bc = part.classes[c];
    if (index < bc.first_index) {
      bc.first_index = index;
      bc.first_pending = p2_curve ? Pending{start, index, I} : Pending{};
    }
    if (!p2_curve) return;
    keep_lowest_invariant(bc.lo, Pending{start, index, I});
    keep_highest_invariant(bc.hi, Pending{start, index, I});
  }
};

// The classes of certified orbits, made on first use from the verdict the full length would give.
struct CertifiedClasses {
  std::vector<std::size_t> of_cone;
  std::size_t of_p2_curve = npos;
  std::size_t of(Decision d, const Certificates& cert, ClassBook& book) {
    std::size_t& c = d.is_p2_curve() ? of_p2_curve : of_cone[d.cone_index()];
    if (c != npos) return c;
    OrbitVerdict v;
    if (d.is_p2_curve()) {
      v.type = Type::quasi_periodic, v.key = "Q2", v.p2_region = true;
    } else {
      const Cone& cone = cert.cones[d.cone_index()];
      v.type = Type::periodic, v.key = cone.key, v.word = cone.word, v.period = cone.p;
    }
    return c = book.find(v);
  }
};

// ---- the sweep of rows ----

// One progress bar for a part: a chunk runs several kernels (pass 1 with its checkpoints, the cocycle, the rotation
// run, refinement), each reporting its own 0..100%; they report into the chunk's share of the part's orbits instead,
// and the bar never moves back.
struct ShareProgress final : core::ProgressSink {
  core::ProgressSink* outer = nullptr;
  std::size_t base = 0, span = 0, total = 0, shown = 0;
  void update(std::size_t done, std::size_t of) override {
    const std::size_t v = base + (of ? span * std::min(done, of) / of : span);
    if (outer && v > shown) outer->update(shown = v, total);
  }
};

// Every grid's shift in cells, drawn for the whole request (grid 0, the main grid, is not shifted): strictly inside
// the cell, no boundary points.
std::vector<std::pair<double, double>> grid_shifts(std::uint64_t seed, std::size_t grids) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> shift(-0.45, 0.45);
  std::vector<std::pair<double, double>> out;
  for (std::size_t k = 0; k < grids; ++k) {
    const double du = k == 0 ? 0.0 : shift(rng), dv = k == 0 ? 0.0 : shift(rng);
    out.emplace_back(du, dv);
  }
  return out;
}

// A chunk of rows of one grid: rows[c0..c1) of that grid, shifted by (du, dv) cells.
struct RowChunk {
  std::size_t grid = 0;
  const std::vector<std::size_t>* rows = nullptr;
  std::size_t c0 = 0, c1 = 0;
  double du = 0, dv = 0;
};

// The chunk's starts: the grid's shifted cell points, one orbit per thread iteration.
void chunk_starts(const Grid& g, const RowChunk& ch, int threads, std::vector<Vec3<double>>& starts) {
  const std::size_t n1 = static_cast<std::size_t>(g.axis1.cells);
  starts.resize((ch.c1 - ch.c0) * n1);
  const long n_chunk = static_cast<long>(starts.size());
#pragma omp parallel for schedule(static) num_threads(threads)
  for (long q = 0; q < n_chunk; ++q) {
    const std::size_t ri = ch.c0 + static_cast<std::size_t>(q) / n1, i = static_cast<std::size_t>(q) % n1;
    starts[static_cast<std::size_t>(q)] =
        g.cell_point(static_cast<long>(i), static_cast<long>((*ch.rows)[ri]), ch.du, ch.dv);
  }
}

// A check: an orbit decided early and its decision.
struct Witness {
  Vec3<double> start;
  Decision decision;
};
// The chunk's first orbit decided early for each cone and for the P2 curves.
void note_witnesses(const ChunkVerdicts& x, const std::vector<Vec3<double>>& starts, std::vector<Witness>& witnesses) {
  std::vector<Decision> firsts;
  for (std::size_t o = 0; o < x.decision.size(); ++o)
    if (!x.decision[o].is_full_length() && std::find(firsts.begin(), firsts.end(), x.decision[o]) == firsts.end()) {
      firsts.push_back(x.decision[o]);
      witnesses.push_back({starts[o], x.decision[o]});
    }
}

// Folds a chunk's verdicts into the part: classes, counts, labels (every grid's: the merge measures the boundary
// geometry of each), undecided counts.
void fold_chunk(const ChunkVerdicts& x, const std::vector<Vec3<double>>& starts, const RowChunk& ch, const Grid& g,
                const Certificates& cert, CertifiedClasses& certified, ClassBook& book) {
  BasinRows& part = book.part;
  const std::size_t n1 = static_cast<std::size_t>(g.axis1.cells), n = g.cells(), k = ch.grid;
  for (std::size_t ri = ch.c0; ri < ch.c1; ++ri)
    for (std::size_t i = 0; i < n1; ++i) {
      const std::size_t o = (ri - ch.c0) * n1 + i, index = k * n + (*ch.rows)[ri] * n1 + i;
      const Decision d = x.decision[o];
      std::size_t c = 0;
      if (d.is_full_length()) {
        const OrbitVerdict& v = x.full[x.full_of[o]];
        if (k == 0)
          part.undecided_first_pass +=
              v.type == Type::undecided || v.detail.find("after refinement") != std::string::npos;
        if (v.type == Type::undecided) {
          ++part.undecided[k];
          part.labels.push_back(0);
          continue;
        }
        c = book.find(v);
        book.add_full_length(c, v, index);
      } else {
        ++part.certified;
        c = certified.of(d, cert, book);
        book.add_certified(c, starts[o], index, d.is_p2_curve(), x.I[o]);
      }
      ++part.classes[c].count[k];
      part.labels.push_back(static_cast<std::uint32_t>(c + 1));
    }
}

// The checks at full length: each witness's verdict must be the one its certificate gave.
void check_witnesses(double r, const std::vector<Witness>& witnesses, const Certificates& cert, const Options& opt) {
  if (witnesses.empty()) return;
  std::vector<Vec3<double>> starts;
  for (const auto& w : witnesses) starts.push_back(w.start);
  const std::vector<OrbitVerdict> wv = classify_whole_batches(r, starts, opt);
  for (std::size_t w = 0; w < witnesses.size(); ++w) {
    const Decision d = witnesses[w].decision;
    expect_verdict(wv[w], d.is_p2_curve() ? Type::quasi_periodic : Type::periodic,
                   d.is_p2_curve() ? "Q2" : cert.cones[d.cone_index()].key, r);
  }
}

// The rows of grid k among the items (item k n2 + j is row j of grid k), ascending.
std::vector<std::size_t> rows_of_grid(const std::vector<std::size_t>& items, std::size_t k, std::size_t n2) {
  std::vector<std::size_t> rows;
  for (std::size_t i : items)
    if (i / n2 == k) rows.push_back(i % n2);
  return rows;
}

}  // namespace stages

BasinRows basin_rows(double r, const Grid& g, int replicates, std::uint64_t seed, const Options& opt_in,
                     const std::vector<std::size_t>& items) {
  ShareProgress share;
  share.outer = opt_in.run.progress;
  share.total = items.size() * static_cast<std::size_t>(g.axis1.cells);
  Options opt = opt_in;
  if (share.outer) opt.run.progress = &share;
  check_basins(r, g, replicates, opt);
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t n1 = static_cast<std::size_t>(g.axis1.cells), n2 = static_cast<std::size_t>(g.axis2.cells);
  const std::size_t grids = static_cast<std::size_t>(replicates) + 1;
  BasinRows part;
  part.items = items;
  part.undecided.assign(grids, 0);
  part.labels.reserve(items.size() * n1);
  ClassBook book{part, grids};
  const Certificates cert = make_certificates(r, opt);
  CertifiedClasses certified{std::vector<std::size_t>(cert.cones.size(), npos)};
  const auto shifts = grid_shifts(seed, grids);
  const std::size_t rows_per_chunk = std::max<std::size_t>(1, kChunk / n1);
  std::vector<Witness> witnesses;
  iterate::Ensemble e;
  e.r = {r};
  ChunkBuffers buffers;
  for (std::size_t k = 0; k < grids; ++k) {
    const std::vector<std::size_t> rows = rows_of_grid(items, k, n2);
    for (std::size_t c0 = 0; c0 < rows.size(); c0 += rows_per_chunk) {
      const RowChunk ch{k, &rows, c0, std::min(rows.size(), c0 + rows_per_chunk), shifts[k].first, shifts[k].second};
      chunk_starts(g, ch, threads_of(opt), e.initial);
      share.span = e.initial.size();
      const ChunkVerdicts& x = classify_early(e, opt, cert, buffers);
      share.update(1, 1);  // the chunk is done, whatever its kernels reported
      share.base += share.span;
      part.iterations += x.steps;
      note_witnesses(x, e.initial, witnesses);  // classified again at full length after the last chunk
      fold_chunk(x, e.initial, ch, g, cert, certified, book);
      core::check_cancel(opt.run.cancel);
    }
  }
  check_witnesses(r, witnesses, cert, opt);
  part.seconds = core::seconds_since(t0);
  return part;
}

// ---- the merge of parts ----
namespace stages {

using ClassKey = std::pair<int, std::string>;  // (type, key): collect's order, ids by sorted key
using JoinedClasses = std::map<ClassKey, BasinClass>;

// Class c of a part joined into j (the same attractor): lowest-index first orbit, counts, ranges, lowest and
// highest I.
void join_class(BasinClass& j, const BasinClass& c, std::size_t grids) {
  if (c.first_index < j.first_index)
    j.first = c.first, j.first_index = c.first_index, j.first_pending = c.first_pending;
  for (std::size_t k = 0; k < grids; ++k) j.count[k] += c.count[k];
  widen_curve_ranges(j, c.rotation_min, c.rotation_max, c.invariant_min, c.invariant_max);
  keep_lowest_invariant(j.lo, c.lo);
  keep_highest_invariant(j.hi, c.hi);
}

// The classes of all parts joined by (type, key); the parts' totals summed into b, undecided counts per grid.
JoinedClasses join_parts(const std::vector<BasinRows>& parts, std::size_t grids, Basins& b,
                         std::vector<std::size_t>& undecided, double& part_seconds) {
  JoinedClasses joined;
  undecided.assign(grids, 0);
  for (const auto& p : parts) {
    part_seconds = std::max(part_seconds, p.seconds);
    b.iterations_total += p.iterations;
    b.undecided_first_pass += p.undecided_first_pass;
    b.certified += p.certified;
    if (p.undecided.size() != grids) throw std::logic_error("basin rows: undecided counts of another request");
    for (std::size_t k = 0; k < grids; ++k) undecided[k] += p.undecided[k];
    for (const auto& c : p.classes) {
      auto [it, fresh] = joined.try_emplace({static_cast<int>(c.first.type), c.first.key}, c);
      if (!fresh) join_class(it->second, c, grids);
    }
  }
  return joined;
}

// The orbits decided early whose full-length values the table prints (the same ones for any partition): the first
// orbit of a non-periodic attractor, and the Q2 orbits of smallest and largest I; classified at full length.
void settle_pending(JoinedClasses& joined, double r, const Options& opt) {
  enum class Role { first, lowest, highest };
  std::vector<Vec3<double>> starts;
  std::vector<std::pair<BasinClass*, Role>> what;
  for (auto& [k, c] : joined) {
    if (c.first.type == Type::periodic) continue;
    if (c.first_pending.index != npos && c.first_pending.index == c.first_index)
      starts.push_back(c.first_pending.start), what.push_back({&c, Role::first});
    if (c.lo.index != npos) starts.push_back(c.lo.start), what.push_back({&c, Role::lowest});
    if (c.hi.index != npos) starts.push_back(c.hi.start), what.push_back({&c, Role::highest});
  }
  if (!starts.empty()) {
    const std::vector<OrbitVerdict> full = classify_whole_batches(r, starts, opt);
    for (std::size_t w = 0; w < full.size(); ++w) {
      BasinClass& c = *what[w].first;
      expect_verdict(full[w], c.first.type, c.first.key, r);
      if (what[w].second == Role::first) c.first = full[w], c.first.detail.clear();
      widen_curve_ranges(c, full[w]);
    }
  }
  for (auto& [k, c] : joined)
    if (c.rotation_min > c.rotation_max) {  // only orbits decided early, none pending: a periodic key's values
      if (c.first.type != Type::periodic) throw std::logic_error("basins: an attractor without full-length values");
      c.rotation_min = c.rotation_max = c.invariant_min = c.invariant_max = 0;
    }
}

// The attractors of the joined classes (ids by sorted key), their main-grid fractions and replicate fractions.
std::map<ClassKey, std::uint32_t> name_attractors(const JoinedClasses& joined,
                                                  const std::vector<std::size_t>& undecided, double r, std::size_t n,
                                                  Basins& b) {
  std::map<ClassKey, std::uint32_t> id_of;
  const std::size_t grids = undecided.size();
  for (const auto& [k, c] : joined) {
    Attractor a = attractor_of(c.first, r);
    a.id = static_cast<int>(b.attractors.size()) + 1;
    a.count = c.count[0];
    a.rotation_min = c.rotation_min, a.rotation_max = c.rotation_max;
    a.invariant_min = c.invariant_min, a.invariant_max = c.invariant_max;
    id_of[k] = static_cast<std::uint32_t>(a.id);
    b.attractors.push_back(std::move(a));
    std::vector<double> per_grid(grids);
    for (std::size_t kk = 0; kk < grids; ++kk) per_grid[kk] = static_cast<double>(c.count[kk]) / static_cast<double>(n);
    b.replicate_fractions.push_back(std::move(per_grid));
    b.fractions.push_back(fraction(c.count[0], n));
  }
  std::vector<double> per_grid(grids);
  for (std::size_t kk = 0; kk < grids; ++kk) per_grid[kk] = static_cast<double>(undecided[kk]) / static_cast<double>(n);
  b.replicate_fractions.push_back(std::move(per_grid));
  b.undecided = fraction(undecided[0], n);
  return id_of;
}

// The labels of grid k (0: the main grid): rows placed by item (item k n2 + j is row j of grid k; a part's labels
// hold n1 per item in its ascending item order), each part's class numbers mapped to the attractors' ids.
std::vector<std::uint32_t> grid_labels(const std::vector<BasinRows>& parts, const std::vector<core::ItemRef>& order,
                                       const Grid& g, const std::map<ClassKey, std::uint32_t>& id_of, std::size_t k) {
  const std::size_t n1 = static_cast<std::size_t>(g.axis1.cells), n2 = static_cast<std::size_t>(g.axis2.cells);
  std::vector<std::uint32_t> labels(n1 * n2, 0);
  std::vector<std::vector<std::uint32_t>> ids(parts.size());
  for (std::size_t p = 0; p < parts.size(); ++p)
    for (const auto& c : parts[p].classes) ids[p].push_back(id_of.at({static_cast<int>(c.first.type), c.first.key}));
  for (std::size_t j = 0; j < n2; ++j) {
    const auto& at = order[k * n2 + j];
    const auto& src = parts[at.part].labels;
    if (src.size() < (at.index + 1) * n1) throw std::logic_error("basin rows: a row is missing");
    for (std::size_t q = 0; q < n1; ++q) {
      const std::uint32_t l = src[at.index * n1 + q];
      labels[j * n1 + q] = l == 0 ? 0 : ids[at.part].at(l - 1);
    }
  }
  return labels;
}

}  // namespace stages

Basins merge_basins(double r, const Grid& g, int replicates, const Options& opt, std::vector<BasinRows> parts,
                    int entropy_box) {
  check_basins(r, g, replicates, opt);
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t grids = static_cast<std::size_t>(replicates) + 1;
  const auto order = core::item_order(parts, basin_items(g, replicates));
  Basins b;
  b.r = r;
  b.grid = g;
  std::vector<std::size_t> undecided;
  double part_seconds = 0;
  JoinedClasses joined = join_parts(parts, grids, b, undecided, part_seconds);
  settle_pending(joined, r, opt);
  const auto id_of = name_attractors(joined, undecided, r, g.cells(), b);
  // The boundary geometry from every grid's whole image (the sweep rule: computed here, from the merged rows).
  std::vector<std::vector<std::uint32_t>> images;
  for (std::size_t k = 0; k < grids; ++k) images.push_back(grid_labels(parts, order, g, id_of, k));
  b.boundary = boundary_geometry(images, static_cast<std::size_t>(g.axis1.cells),
                                 static_cast<std::size_t>(g.axis2.cells), entropy_box);
  b.labels = std::move(images[0]);
  b.seconds = part_seconds + core::seconds_since(t0);
  return b;
}

Basins basins(double r, const Grid& g, int replicates, std::uint64_t seed, const Options& opt, int entropy_box) {
  check_basins(r, g, replicates, opt);
  return merge_basins(r, g, replicates, opt,
                      {basin_rows(r, g, replicates, seed, opt, core::all_items(basin_items(g, replicates)))},
                      entropy_box);
}

}  // namespace btob::attractors
