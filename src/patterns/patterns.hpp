// SPDX-License-Identifier: GPL-3.0-or-later
// Periodic patterns of P_r (Sections 6.2 and 7): words over {1,2,3}, feasibility and stability of periodic
// orbits, stability windows in r.
#pragma once

#include "core/map.hpp"
#include "core/request.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace btob::patterns {

using core::Mat3;
using core::Vec3;

// Conventions.
//  * A word w = w_1 ... w_p over {1, 2, 3} (Section 6.2): 1 = ab (P1), 3 = cb (P3), 2 = acb or cab (P2).
//    Its matrix is M_w = P_{w_p} ... P_{w_1}: the first symbol is applied first.
//  * J (eq. 4.4) swaps the symbols 1 <-> 3 (P3 = J P1 J, P2 = J P2 J).
//  * Canonical form: the smallest rotation of w and of J(w) in the symbol order 1 < 3 < 2 (this order
//    gives the paper's spellings: 132312, 1133, 132^3312^3, 131312^3313132^3).
//  * Lengths: |w| in symbols (iterations of P_r); collisions(w) counts letters a, b, c (1, 3 -> 2, 2 -> 3),
//    as the last column of Table 6.1.
struct Word {
  std::vector<std::uint8_t> s;  // symbols 1, 2, 3
  std::size_t size() const { return s.size(); }
  template <class A> void members(A& a) { a(s); }  // core/pack.hpp
  bool operator==(const Word&) const = default;
  auto operator<=>(const Word&) const = default;
};

// Parses "132^3312^3" (a symbol or a parenthesised group followed by ^n repeats it n times),
// "(ab)(cb)(acb)", "abcbacb" (letters, greedy: ab -> 1, cb -> 3, acb / cab -> 2) or plain digits.
// Throws std::invalid_argument naming `field` on an empty word, other characters or a bad exponent.
Word parse_word(std::string_view text, const char* field = "word");
std::string to_digits(const Word& w);       // "1322231222"
std::string to_paper(const Word& w);        // "132^3312^3" (runs of 2 of length >= 2 and of 1, 3 of length >= 4)
std::string to_letters(const Word& w);      // "abcbacb...": symbol 2 written acb (Section 7.3)
int collisions(const Word& w);              // number of collisions a, b, c in one period
Word apply_J(const Word& w);                // 1 <-> 3
Word rotate(const Word& w, std::size_t k);  // w_{k+1} ... w_p w_1 ... w_k
Word primitive_root(const Word& w);         // shortest u with w = u^m
bool is_primitive(const Word& w);
Word canonical(const Word& w);  // smallest rotation of w and J(w), order 1 < 3 < 2
// w = h J(h) (Section 7.1): then M_w = (J M_h)^2 and the reduced matrix J M_h is studied instead.
bool is_J_square(const Word& w);
// Every primitive canonical word of length 1..max_length (sorted by length, then canonical order).  The odometer
// visits 3^n words of each length (3^16 = 4.3e7: seconds), so it polls `cancel` (core/cancel.hpp; throws
// core::Cancelled).
std::vector<Word> enumerate_canonical(int max_length, const core::CancelToken* cancel = nullptr);

// Outcome of the periodic-orbit analysis of a word at one r.
// stable: attracting (both exponents < 0); unstable: a saddle or a source (an exponent > 0); neutral: elliptic
// (the larger exponent zero within the eigenvalue moduli's tie tolerance, the tying eigenvalue one of a complex
// pair, whose modulus is the orbit's); undecided: the same tie with a real eigenvalue, which the precision cannot
// order (the exponent is zero within its error and the eigenvalue test cannot decide).  analyse() and the atlas's
// intervals (classify) give the same words.
enum class Outcome { none, unstable, stable, neutral, undecided };
const char* outcome_name(Outcome o);

// One eigenvalue of the analysed matrix (M_w, or J M_h when w = h J(h)), with its eigenvector when real.
template <class T> struct EigenInfo {
  T re{}, im{};  // eigenvalue (0 or a subnormal when it lies below T's range, inf above: see scaled_*)
  T modulus{};
  // The same eigenvalue as (scaled_re + i scaled_im) e^log_scale, scaled_modulus e^log_scale: the roots of the
  // normalised product (max entry 1) and its log-scale, finite for any word length where re, im, modulus under- or
  // overflow (a word of 10^4 symbols at r = 0.07: |mu1| ~ 1e-2300).
  T scaled_re{}, scaled_im{}, scaled_modulus{}, log_scale{};
  bool real = false;
  Vec3<T> vector;          // unit eigenvector brought into Q = {x >= 0, z <= 0} (real eigenvalues only)
  bool in_domain = false;  // x z < 0 (strictly inside the domain of P)
  bool feasible = false;   // in the domain and all p feasibility inequalities hold strictly
  int first_failure = -1;  // -1 feasible, 0 domain, k = 1..p the k-th feasibility inequality (symbol w_k)
};

template <class T> struct Verdict {
  Word word;  // the primitive root of the input word, which is what is analysed
  T r{};
  bool reduced = false;                // analysed through J M_h (Section 7.1)
  std::vector<EigenInfo<T>> spectrum;  // 3 entries, by decreasing modulus
  Outcome outcome = Outcome::none;
  int orbit_eigen = -1;        // index in spectrum of the reported periodic point (-1: none)
  std::vector<Vec3<T>> orbit;  // the p points u_0 .. u_{p-1} of the orbit (unit, in Q)
  std::string letters;         // its collision letters (acb or cab chosen by the sign of y)
  // Projective Lyapunov exponents per iteration of P_r: log(|l2|/|l1|)/p and log(|l3|/|l1|)/p of M_w
  // (natural log; from the second exterior power, accurate even when |l2/l1| underflows).
  T lyapunov2{}, lyapunov3{};
  std::string reason;  // why not stable: "complex", "dominance", "domain", "feasN"; "range" (undecided:
                       // the spectrum or the dominant eigenvector's x or z left T's range)
};

// The analysis of Section 7 for the word w at r in (0, 1).  T = double, long double, float128, mpfr_float.
// Throws std::invalid_argument (field "word") on an empty word, core::InvalidField (field "r") outside (0, 1).
// Every function of the analysis below that takes `cancel` polls it along the word's symbols (every symbol in MPFR,
// every core::cancel_stride symbols otherwise) and throws core::Cancelled once it is set; nullptr: never (a caller
// inside an OpenMP region, which polls between words instead).
template <class T> Verdict<T> analyse(const Word& w, const T& r, const core::CancelToken* cancel = nullptr);
// True when analyse(w, r).outcome == stable, without building the orbit (the atlas's inner loop).
template <class T> bool is_stable(const Word& w, const T& r, const core::CancelToken* cancel = nullptr);

// One interval of r in (0, 1) on which a stable periodic orbit with word w exists, with the condition
// failing just outside each endpoint: "complex" (dominant eigenvalue becomes complex), "dominance"
// (another eigenvalue takes over), "domain" (eigenvector leaves x z < 0), "feasK" (the K-th feasibility
// inequality, K = 1..p), "end" (r = 0 or 1).
template <class T> struct Interval {
  T lo{}, hi{};
  std::string lo_reason, hi_reason;
  template <class A> void members(A& a) { a(lo, hi, lo_reason, hi_reason); }  // core/pack.hpp
};
// The scan grid in double; transitions are then bisected in T down to `tol` (absolute, in r).
std::vector<double> default_grid();  // 7500 points, denser on [0.07, 0.26) where windows are thin
template <class T>
std::vector<Interval<T>> stability_set(const Word& w, const std::vector<double>& grid, const T& tol,
                                       const core::CancelToken* cancel = nullptr);

// analyse(w, r).outcome without the orbit and the exponents (the inner loop of the feasible atlas): stable
// when the dominant eigenvector is feasible and strictly dominant, unstable when another real eigenvector
// (or a non-dominant one) is feasible, none otherwise.  No input checks (callers validate).
//
// `collapse`: whether four particles can follow that periodic orbit for ever.  Velocities change only at
// collisions, so after n periods they are K_w^n q (K_w the product of the collision matrices of eq. 2.5 over one
// period; K_w does not depend on acb / cab since AC = CA).  The plane normal to the orbit's u is invariant
// under K_w, and cof(K_w) = r^n2 M_w (n2 = number of symbols 2).  A collapse repeating w needs K_w to have on
// that plane two real eigenvalues mu_v, mu_l with mu_v > |mu_l| (q2 > 0 after every b-collision: a complex pair
// would turn q through every direction).  From M_w's eigenvalues l_o (the orbit's), l_a, l_b (|l_a| >= |l_b|):
// mu_v mu_l = r^n2 l_o, and mu_v / mu_l = l_a / l_b, so the condition is: l_a and l_b real, |l_a| > |l_b|, and
// mu_v = r^n2 l_a / mu_j > 0 with mu_j = (-r)^collisions / (r^n2 l_o) (det K_w = (-r)^collisions).
struct Classification {
  Outcome outcome = Outcome::none;
  bool collapse = false;  // meaningful when outcome != none
  bool operator==(const Classification&) const = default;
};
std::string classification_name(const Classification& c);  // "none", "stable", "unstable", "stable (no collapse)", ...
template <class T> Classification classify(const Word& w, const T& r, const core::CancelToken* cancel = nullptr);
// One interval of r on which w has a feasible periodic point with a constant classification; lo_reason /
// hi_reason name the classification just beyond the endpoint (classification_name) or "end".
template <class T> struct FeasibleInterval {
  T lo{}, hi{};
  Outcome outcome = Outcome::none;
  bool collapse = false;
  std::string lo_reason, hi_reason;
  template <class A> void members(A& a) { a(lo, hi, outcome, collapse, lo_reason, hi_reason); }  // core/pack.hpp
};
// classify on `grid`, each change bisected in T down to `tol`.  Intervals narrower than the grid step can be
// missed; the grid is the caller's resolution.
template <class T>
std::vector<FeasibleInterval<T>> feasibility_set(const Word& w, const std::vector<double>& grid, const T& tol,
                                                 const core::CancelToken* cancel = nullptr);

// Quantities of Section 7 as functions of r, for the real eigenvalue picked by Track of the analysed matrix
// (J M_h if w = h J(h), else M_w).  Signs are those of the paper's normalisation x = 1 (z = 1 for x_component).
enum class Track { dominant_real, negative_real };
enum class Quantity {
  x_component,      // x of the eigenvector normalised so that z < 0     (r_crit,132J,1, r_crit,1322J,3)
  z_component,      // z of the eigenvector normalised so that x > 0     (r_crit,1322J,4)
  alpha_y_minus_x,  // alpha y - x with x > 0: first feasibility inequality (r_crit,132J, r_crit,1322J,5)
  dominance_gap     // (|l_tracked| - max |l_other|) / |l_tracked|        (r_crit,1322J,1 and 2)
};
template <class T>
T quantity(const Word& w, const T& r, Track track, Quantity q, const core::CancelToken* cancel = nullptr);
// A root of quantity(w, ., track, q) in [lo, hi] (sign change required) by bisection down to tol.
template <class T>
T quantity_root(const Word& w, T lo, T hi, Track track, Quantity q, const T& tol,
                const core::CancelToken* cancel = nullptr);

}  // namespace btob::patterns

#include "core/scalar.hpp"

namespace btob::patterns {
#define BTOB_PATTERNS_EXTERN(T)                                                                                \
  extern template Verdict<T> analyse<T>(const Word&, const T&, const core::CancelToken*);                      \
  extern template bool is_stable<T>(const Word&, const T&, const core::CancelToken*);                          \
  extern template std::vector<Interval<T>> stability_set<T>(const Word&, const std::vector<double>&, const T&, \
                                                            const core::CancelToken*);                         \
  extern template T quantity<T>(const Word&, const T&, Track, Quantity, const core::CancelToken*);             \
  extern template Classification classify<T>(const Word&, const T&, const core::CancelToken*);                 \
  extern template std::vector<FeasibleInterval<T>> feasibility_set<T>(const Word&, const std::vector<double>&, \
                                                                      const T&, const core::CancelToken*);     \
  extern template T quantity_root<T>(const Word&, T, T, Track, Quantity, const T&, const core::CancelToken*);
BTOB_PATTERNS_EXTERN(float)
BTOB_PATTERNS_EXTERN(double)
BTOB_PATTERNS_EXTERN(long double)
BTOB_PATTERNS_EXTERN(core::float128)
BTOB_PATTERNS_EXTERN(core::mpfr_float)
#undef BTOB_PATTERNS_EXTERN
}  // namespace btob::patterns
