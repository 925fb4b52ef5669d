// SPDX-License-Identifier: GPL-3.0-or-later
// Four inelastic particles realising a periodic pattern: an event-driven simulation of the collapse.
#pragma once

#include "core/map.hpp"
#include "core/request.hpp"
#include "core/result.hpp"
#include "core/work.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace btob::particles {

// Conventions (Section 2 of the paper).
//  * n = G + 1 unit-mass point particles on a line; gaps p_i = x_{i+1} - x_i >= 0 and relative velocities
//    q_i = v_{i+1} - v_i, i = 1..G.  Pairs are 0-based here: a = 0 (particles 1-2), b = 1, c = 2.
//  * Free flight p += t q (eq. 2.2); a collision of pair j multiplies q by the collision matrix of eq. (2.5):
//    q_j -> -r q_j, q_{j-1} += alpha q_j, q_{j+1} += alpha q_j, alpha = (1 + r)/2 (momentum conserved, relative
//    velocity reflected and contracted by r, eq. 2.1).
//  * The normal n = p x q of the plane Span[p, q] is unchanged by free flight and multiplied by cof(K) at a
//    collision, so over one period of a word w with collision product K_w: n -> cof(K_w) n exactly, and
//    cof(K_w) = r^{n2(w)} M_w (P1 = cof(BA), P3 = cof(BC), P2 = cof(BCA)/r; n2 = number of symbols 2).
//  * Self-similar collapse: q -> K_w q over a period, so velocities contract by the larger eigenvalue mu_v of
//    K_w on the invariant plane, lengths by the smaller mu_l, times by mu_l/mu_v.  In terms of the moduli of
//    M_w's eigenvalues, l_o (the orbit's) and l_a >= l_b (the other two):
//        lengths  rho   = sqrt(r^n2 l_o l_b / l_a),  velocities  sigma = sqrt(r^n2 l_o l_a / l_b),
//        times    rho / sigma = l_b / l_a.

template <class T, int G> using Vec = Eigen::Matrix<T, G, 1>;
template <class T, int G> struct Gaps {
  Vec<T, G> p;  // gaps, >= 0
  Vec<T, G> q;  // relative velocities
};

// q -> K_j q for the collision of pair j (eq. 2.5).
template <class T, int G> void collide(Vec<T, G>& q, int j, const T& r);
// The pair that collides next (the approaching pair q_j < 0 whose gap closes first) and the flight time t to
// it; -1 when no pair approaches (the particles separate for ever).
template <class T, int G> int next_collision(const Gaps<T, G>& s, T& t);
// Free flight for t, then the collision of pair j (its gap set to exactly 0, the others kept >= 0).
template <class T, int G> void advance(Gaps<T, G>& s, const T& t, int j, const T& r);
// Positions (or velocities, from q) of the n particles in the centre-of-mass frame (sum = 0).
template <class T, int G> Eigen::Matrix<T, G + 1, 1> absolute(const Vec<T, G>& gaps);
// Kinetic energy (1/2) sum v_i^2 in the centre-of-mass frame (unit masses).
template <class T, int G> T kinetic_energy(const Vec<T, G>& q);

// One run of the four particles through `periods` periods of the collision letters `letters` (one period,
// ending with b, e.g. "abcbcabcbabacb"), from `start` right after a b-collision.  With `rescale`, p and q are
// multiplied by exact powers of two after every period (a space and a time scaling: the letters and the
// ratios are unchanged, and the run equals the unrescaled one bit for bit until the latter underflows).
template <class T> struct PatternRun {
  long periods_ok = 0;  // periods whose letters all matched
  long collisions = 0;  // collisions that matched
  std::string failure;  // "" or why the run stopped (wrong letter, separation, non-finite state)
  std::vector<double> length_ratio, velocity_ratio;  // per period: |p| and |q| after / before (size periods_ok)
  std::vector<double> duration;    // per period, in units |p0| / |q0| (double: may underflow to 0 late)
  std::vector<double> time_ratio;  // per period: duration / previous duration (NaN for the first), from T
  T total_time{};                  // sum of the durations, in T
  // Events of the first record_periods periods: period, time since the period's start, x1..x4 (centre-of-mass
  // frame, units |p0|), letter (0 start, 1 a, 2 b, 3 c); row-major, 7 values per event.
  std::vector<double> events;
};
template <class T>
PatternRun<T> simulate_pattern(const Gaps<T, 3>& start, const std::string& letters, const T& r, long periods,
                               bool rescale, long record_periods = 0, const core::CancelToken* cancel = nullptr);

// The self-similar start from the periodic point u (in Q) of a word with one period of letters `letters`:
// p = (-z, 0, x) / |.| (u x e_y) and q the unit eigenvector, with q2 > 0, of K_w (the product of the collision
// matrices of the letters) on the plane normal to u, for its eigenvalue of largest modulus.  Returns false
// (and q normal to p) when K_w's eigenvalues on that plane are not real with a positive dominant one.
template <class T>
bool self_similar_start(const core::Vec3<T>& u, const std::string& letters, const T& r, Gaps<T, 3>& out);

// ---- the request/result contract (src/core/request.hpp) ----

struct ParticlesRequest {
  std::string word = "132312";         // a word over 1, 2, 3 (patterns::parse_word: 132312, 132^3312^3, (ab)(cb))
  core::Decimal r = 0.5;               // restitution coefficient, (0, 1), kept as given (read in the precision)
  long periods = 10000;                // periods simulated with rescaling, 1..100000000
  std::string precision = "double";    // double, long-double, float128 or mpfr:D (10 <= D <= 10000)
  std::string start = "self-similar";  // self-similar (velocity eigenvector of K_w) or normal (q normal to p,
                                       // shifted by -lambda p until the first periods match)
  long diagram_periods = 6;            // periods recorded event by event (space-time diagram), 1..50

  void validate() const;  // throws core::InvalidField; a word with no feasible periodic point at r is refused
  template <class V> void fields(V&& v) {
    v("word", word, "periodic word over 1,2,3 (132312, 132^3312^3, (ab)(cb)(acb))", core::positional);
    v("r", r, "restitution coefficient in (0, 1)");
    v("periods", periods, "periods simulated (rescaled every period), 1..1e8");
    v("precision", precision, "double, long-double, float128 or mpfr:D (D digits, 10..10000)");
    v("start", start, "self-similar (exact collapse) or normal (q normal to p, converges to it)");
    v("diagram-periods", diagram_periods, "periods recorded event by event for the space-time diagram, 1..50");
  }
};

struct ParticlesResult {
  std::string word, digits;  // the primitive root, paper notation and digits
  std::string letters;       // collision letters of one period from the periodic point
  std::string outcome;       // "stable" or "unstable": the periodic point used (patterns::analyse)
  bool collapse = false;     // patterns::Classification::collapse: K_w has real eigenvalues on the orbit's plane
  double r = 0;              // restitution coefficient, in (0, 1)
  long periods = 0;          // periods of the pattern the particles were run for (the request's)
  std::string precision;     // the arithmetic of the event-driven run (the request's)
  std::string start;         // the request's start
  bool sequence_ok = false;  // every period's letters matched
  long periods_ok = 0;       // periods whose collision letters matched the pattern's
  std::string failure;       // why the run stopped matching the pattern (empty when every period matched)
  // Last period's contraction against the prediction from M_w's eigenvalues (see the conventions).
  double length_contraction = 0, length_predicted = 0;
  double velocity_contraction = 0, velocity_predicted = 0;
  double time_contraction = 0, time_predicted = 0;
  double length_spread = 0;     // max over the last half of the periods of |rho_n / rho_last - 1| (convergence)
  double time_to_collapse = 0;  // units |p0| / |q0|: simulated periods plus the geometric tail
  double energy_ratio = 0;      // kinetic energy after / before one period (= sigma^2 asymptotically)
  std::vector<double> moduli;   // |eigenvalues| of M_w, decreasing (3)
  int orbit_eigen = 0;          // index in moduli of the periodic point's eigenvalue
  // Without rescaling: collisions reproduced before the run fails (underflow), and the prediction
  // diagram: periods until the gaps fall below the smallest normal number, times letters per period.
  long collisions_unrescaled = 0;
  std::string unrescaled_end;
  double collisions_limit_predicted = 0;
  // Per period (size periods_ok): |p|, |q| and duration ratios.
  std::vector<double> length_ratio, velocity_ratio, time_ratio;
  // Events of the first diagram periods, 8 values each: period, time since the start, time to collapse (NaN
  // without a collapse), x1..x4, letter (0 start, 1 a, 2 b, 3 c); times in units |p0|/|q0|, positions in units
  // |p0| (centre-of-mass frame, collapse point 0).
  std::vector<double> events;
  // The same events as columns (split_events), the datasets of NAME.h5 and the columns of events.csv: positions
  // [event, particle] row-major, letters "start", "a", "b", "c".
  std::vector<std::uint32_t> event_period;
  std::vector<double> event_time, event_time_to_collapse, event_x;
  std::vector<std::string> event_letter;
  double seconds = 0;

  void split_events();  // fills the event_* columns from `events`

  // What `btob particles` writes (output.cpp); every value that is not a finite number is an empty cell.
  static const char* row_header();         // word,r,periods,letters,sequence_ok,contraction,predicted,time_to_collapse
  std::string row() const;                 // those columns, one line without its end
  std::string row_csv(bool header) const;  // the printed row, with its header line first if asked
  std::string csv() const;                 // particles.csv: the row's columns, then digits, outcome, ..., failure
  std::string convergence_csv() const;     // period,length_ratio,velocity_ratio,time_ratio at convergence_rows()
  std::string events_csv() const;          // period,time,time_to_collapse,x1,x2,x3,x4,letter
  core::Tables tables() const {            // NAME.csv, convergence.csv, events.csv
    return {{"", csv()}, {"convergence.csv", convergence_csv()}, {"events.csv", events_csv()}};
  }
  // Arrays length_ratio, velocity_ratio, time_ratio, the event_* columns, moduli; the summary as attributes (JSON has
  // no NaN: a value that is not finite is the string "nan", "inf" or "-inf").
  void describe(core::Contents& c) const;
  std::string summary() const;  // the line printed on stderr
};

// The periods (0-based) convergence.csv lists out of `periods`: every one up to 100, then about 20 per decade
// (the next at ceil(k 10^(1/20)) after period k), and the last.
std::vector<std::size_t> convergence_rows(std::size_t periods);

ParticlesResult run(const ParticlesRequest& request, const core::RunControl& control = {});
// Its cost (core/work.hpp): collisions of the event loop, letters per period x (the rescaled run's periods, the
// diagram's periods again, the unrescaled run's periods), probed on 132312 at r = 0.5 in the request's precision.
core::Work work(const ParticlesRequest& request);

}  // namespace btob::particles
