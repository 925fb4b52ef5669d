// SPDX-License-Identifier: GPL-3.0-or-later
// Section 7 as functions of r (Figures 7.1-7.8): the spectrum of the period matrix of a word (J M_h when
// w = h J(h), else M_w), and the feasibility quantities of the tracked eigenvector along the word, on a grid
// of r; with the critical r where the eigenvector's x component or the tracked eigenvalue's dominance changes.
#pragma once

#include "core/request.hpp"
#include "core/result.hpp"
#include "core/work.hpp"
#include "patterns/patterns.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace btob::patterns {

// Conventions (the paper's, Section 7.1).
//  * The analysed matrix A is not normalised: its eigenvalues are those the paper plots (Figures 7.1, 7.6).
//  * The tracked eigenvector u is normalised by u_x = 1 (it blows up where u_x = 0: r_crit,132J,1 and
//    r_crit,1322J,3).  v_0 = u and v_k = P_{h_k} v_{k-1} for the symbols h_1 .. h_n of the analysed word
//    (h when w = h J(h), else w).  For each step k the three branch quantities of v_{k-1} are kept:
//    y, alpha y - x and alpha y - z (symbol 1 needs alpha y - x > 0; 3 needs alpha y - z < 0; 2 needs
//    alpha y - x < 0 < alpha y - z), and the domain quantity u_z (< 0 in the domain).  For 132312 the paper's
//    six inequalities are u_z, (alpha y - x)(v_0), y(v_1), (alpha y - z)(v_1), (alpha y - x)(v_2), (alpha y - z)(v_2).
struct CurvesRequest {
  std::string word = "132312";     // a word over 1,2,3 (132312, 13223122, 132^3312^3, letters)
  double r_min = 0.0005;           // smallest r, in (0, 1)
  double r_max = 0.9995;           // largest r, in (r_min, 1)
  long r_count = 2000;             // evenly spaced r values, 2 .. 1e6
  std::string track = "dominant";  // "dominant": the real eigenvalue of largest modulus; "negative": the
                                   // negative real eigenvalue of largest modulus (lambda^real of 13223122)

  void validate() const;
  template <class V> void fields(V&& v) {
    v("word", word, "a word over 1,2,3, e.g. 132312 or 132^2312^2");
    v("r-min", r_min, "smallest r, in (0,1)");
    v("r-max", r_max, "largest r, in (r-min,1)");
    v("r-count", r_count, "number of evenly spaced r values, 2..1e6");
    v("track", track, "eigenvalue followed: dominant or negative");
  }
};

struct CurvesResult {
  CurvesRequest request;                        // the request, as run (validated)
  std::string word;                             // paper notation of the primitive root
  bool reduced = false;                         // analysed through J M_h
  std::string analysed;                         // the analysed word (h or w), digits
  std::vector<double> r;                        // [n]
  std::vector<double> eig_re, eig_im, modulus;  // [n x 3] row-major; real roots ascending, then the complex pair
  std::vector<double> tracked;                  // [n] the tracked eigenvalue (NaN where none is real / negative)
  std::vector<double> dominance;                // [n] (|tracked| - max |other|) / |tracked|: > 0 where it dominates
  std::vector<double> feas;                     // [n x (1 + 3 p)] row-major: u_z, then y, ay-x, ay-z of v_0 .. v_{p-1}
  std::vector<std::string> feas_names;          // [1 + 3 p]: "u_z", "y(v0)", "ay-x(v0)", "ay-z(v0)", ...
  std::vector<double> u_error;         // [n] bound on the error of the tracked unit eigenvector (NaN: none tracked)
  std::vector<std::uint8_t> resolved;  // [n] 1 where u_error < 1e-3: the feasibility quantities are computed
  struct Critical {
    std::string what;  // "u_x = 0", "u_z = 0" (u leaves the domain), "dominance" (the tracked eigenvalue
                       // stops or starts dominating) or "undecided in long double" (a sign change of u_x u_z
                       // where the eigenvector is below long double's resolution)
    double r = 0;
  };
  std::vector<Critical> critical;          // bisected to 1e-15 from the grid's sign changes
  std::vector<double> critical_r;          // [critical]: their r
  std::vector<std::string> critical_what;  // [critical]: what changes there (Critical::what)

  std::string critical_csv() const;                                       // what,r (16 decimals)
  core::Tables tables() const { return {{"critical", critical_csv()}}; }  // NAME_critical.csv
  void describe(core::Contents& c) const;
};

// Throws core::InvalidField naming the field (word, r-min, r-max, r-count, track).
CurvesResult run(const CurvesRequest& request, const core::RunControl& control = {});
// Its cost (core/work.hpp): r-count x the analysed word's symbols (a period matrix, its eigenvalues and the branch
// quantities per r), probed on 132312 over r in (0, 1).
core::Work work(const CurvesRequest& request);

}  // namespace btob::patterns
