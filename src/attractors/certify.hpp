// SPDX-License-Identifier: GPL-3.0-or-later
// The certification of early exits (basins only; see attractors.hpp): trapping cones of stable cycles and the P2
// invariant ellipses.  Internal to the attractors module; declared here so that each stage can be tested alone.
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "attractors/attractors.hpp"

namespace btob::attractors::stages {

// A stable cycle with its trapping cone.  M_s = P_s / r (the kernel's matrices), w = the key's word (length p),
// A = M_{w_p} ... M_{w_1} its monodromy, E_0 = [v1, v2, v3] with v1 the dominant eigenvector (in Q) and v2, v3 the
// other eigenvectors (real and imaginary parts for a complex pair), E_j = M_{w_j} ... M_{w_1} E_0 (the same
// coordinates carried along the word).  A state u at phase j (its next symbol w_{j+1}) has coordinates
// c = E_j^-1 u; the cone of phase j is c1 > 0, |(c2, c3)| <= delta c1.  Every ray E_j (1, +-delta, +-delta) (the
// square around the disc) satisfies the branch of w_{j+1} with a margin, so the kernel applies w_{j+1} on the cone;
// one period maps the ratio e = |(c2, c3)| / c1 to at most a + b e (D = E_0^-1 A E_0, b < 1).
struct Cone {
  std::string key;
  patterns::Word word;
  int p = 0;
  std::vector<Eigen::Matrix3d> inv;  // E_j^-1
  double delta = 0, a = 0, b = 0;    // cone radius; the ratio map e -> a + b e per period
  double noise = 0;                  // bound on the ratio added by rounding (kernel steps, this test), for ever
  double G = 0;                      // |unit(E_j (1, c)) - q_j|_inf <= G |c|
  double q_dist = 0;                 // our cycle points against the pattern tool's
  double separation = 0;             // min |q_i - q_j|_inf, i != j
};
// The cone of the cycle with key word w at r, if one can be proven (else nullopt: its orbits take the full path).
std::optional<Cone> make_cone(const std::string& key, const patterns::Word& w, double r, const Options& opt,
                              const std::vector<Vec3<double>>& exact_points);
// The largest ratio e at a checkpoint `steps_left` steps before `transient` that proves the full-length verdict
// (0: none).
double cone_limit(const Cone& c, long steps_left, const Options& opt);
// Whether u lies in the cone at some phase with ratio <= e_max.
bool in_cone(const Cone& c, const Vec3<double>& u, double e_max);

// The P2 region (Section 5.2): with s = x + z, a = x - z, the kernel applies P2 exactly when |s - 2 alpha y| <= a
// (a y - x <= 0 and a y - z >= 0), and P2 keeps I = (2 s^2 - 4 alpha s y + 4 r y^2) / a^2 = 4 (xi^2 + eta^2) / a^2
// while rotating (xi, eta) / a by beta.  On the ellipse I the largest |s - 2 alpha y| / a is
// sqrt(I r / (2r - alpha^2)), so I < I_max = (2r - alpha^2) / r keeps the orbit in the region for ever: it is a P2
// invariant curve.
struct P2Trap {
  bool on = false;
  double alpha = 0, r = 0, I_max = 0;
  double margin = 0;      // required 1 - sqrt(I / I_max): far above the drift of I by rounding over the run
  double return_k = 0;    // d_j >= return_k * sqrt(I) / V(I) for 1 <= j <= max_period (see make_trap)
  double v1 = 0, v2 = 0;  // |v|^2 <= V(I) = 1/2 + v1 I + v2 I  on the chart a = 1
};
P2Trap make_trap(double r, const Options& opt);
// I of a kernel state, as RotationRecorder computes it.
double invariant_of(const Vec3<double>& u, double r, double alpha);
// Whether u lies on a P2 invariant ellipse the trap certifies; I receives its invariant.
bool on_p2_curve(const P2Trap& t, const Vec3<double>& u, const Options& opt, double& I);

// The stable cycles at r whose cones can be proven: those the full classification finds from a fixed 16 x 16 sphere
// grid (the same for every part of a request: a part's numbers never depend on the other parts).
std::vector<Cone> probe_cones(double r, const Options& opt);

// What certifies early exits at r: the cones, the P2 trap, and the checkpoints (steps < transient) they are tried at.
struct Certificates {
  std::vector<Cone> cones;
  P2Trap trap;
  std::vector<long> checkpoints;  // ascending, < transient
};
Certificates make_certificates(double r, const Options& opt);

// How an orbit of a basin run was decided: at full length, on a P2 invariant curve (certified), or in a cone
// (certified; its index in Certificates::cones).  One int32 an orbit.
class Decision {
 public:
  Decision() = default;  // full length
  static Decision full_length() { return Decision(kFull); }
  static Decision p2_curve() { return Decision(kP2Curve); }
  static Decision cone(std::size_t index) { return Decision(static_cast<std::int32_t>(index)); }
  bool is_full_length() const { return code_ == kFull; }
  bool is_p2_curve() const { return code_ == kP2Curve; }
  std::size_t cone_index() const { return static_cast<std::size_t>(code_); }  // when neither of the above
  bool operator==(const Decision&) const = default;

 private:
  static constexpr std::int32_t kFull = -1, kP2Curve = -2;
  explicit Decision(std::int32_t code) : code_(code) {}
  std::int32_t code_ = kFull;
};

}  // namespace btob::attractors::stages
