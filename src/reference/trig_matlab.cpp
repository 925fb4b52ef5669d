// SPDX-License-Identifier: GPL-3.0-or-later
// Appendix A.1 with MATLAB's complex semantics: the paper's trigonometric code as it actually runs once acos
// leaves [-1, 1] (Figure 4.7 shows what it draws).
#include "core/cancel.hpp"
#include "iterate/parallel.hpp"
#include "reference/reference.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>

namespace btob::reference {
namespace {

using C = std::complex<double>;
using CVec = Eigen::Matrix<C, 3, 1>;
const C I(0, 1);

// MATLAB's acos: real for a real argument in [-1, 1] (MATLAB and Octave keep real arrays real there), otherwise the
// principal branch -i log(z + i sqrt(1 - z^2)).  Evaluating that formula on a real argument in [-1, 1] would give it
// an imaginary part of rounding size (about 6e-18 at z = 0.3) that the printed code never sees, and count an orbit
// that stayed in acos's domain as complex.
C acos_matlab(const C& z) {
  if (z.imag() == 0 && std::abs(z.real()) <= 1) return C(std::acos(z.real()), 0.0);
  return -I * std::log(z + I * std::sqrt(C(1) - z * z));
}
double norm_matlab(const CVec& v) { return std::sqrt(std::norm(v(0)) + std::norm(v(1)) + std::norm(v(2))); }
C dot_matlab(const CVec& a, const CVec& b) {  // dot(a, b) = sum conj(a_i) b_i
  return std::conj(a(0)) * b(0) + std::conj(a(1)) * b(1) + std::conj(a(2)) * b(2);
}
bool finite(const CVec& v) {
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(v(i).real()) || !std::isfinite(v(i).imag())) return false;
  return true;
}

struct State {
  CVec X, V;
  int contact = 2;
  bool complex = false;  // some acos argument left [-1, 1] (or was already complex)
};

// One pass of the MATLAB while-loop; theta, phi are those read before the collision (as the code records).
void collision(State& s, double r, C& theta, C& phi) {
  const int c = s.contact;
  const int ix = c == 1 ? 1 : (c == 2 ? 2 : 0), iv = c == 1 ? 2 : (c == 2 ? 0 : 1);
  const C xa = s.X(ix);
  if (xa.imag() != 0 || std::abs(xa.real()) > 1) s.complex = true;
  theta = acos_matlab(xa);
  const C cphi = s.V(iv) / std::cos(theta);
  if (cphi.imag() != 0 || std::abs(cphi.real()) > 1) s.complex = true;
  phi = acos_matlab(cphi);
  const double half_pi = std::acos(0.0);
  if (phi.real() == half_pi) return;  // neither branch of the MATLAB code: nothing changes
  const bool low = phi.real() < half_pi;
  const C st = std::sin(theta), ct = std::cos(theta), sp = std::sin(phi), cp = std::cos(phi);
  CVec X;
  char letter;
  switch (c) {
    case 1:
      if (low) {
        X << ct * sp, 0.0, cp;
        letter = 'b';
      } else {
        X << st * sp, -cp, 0.0;
        letter = 'c';
      }
      break;
    case 2:
      if (low) {
        X << cp, ct * sp, 0.0;
        letter = 'c';
      } else {
        X << 0.0, st * sp, -cp;
        letter = 'a';
      }
      break;
    default:
      if (low) {
        X << 0.0, cp, ct * sp;
        letter = 'a';
      } else {
        X << -cp, 0.0, st * sp;
        letter = 'b';
      }
      break;
  }
  X /= norm_matlab(X);
  CVec V = collision_matrix<double>(letter, r).cast<C>() * s.V;
  V = V - dot_matlab(V, X) * X;
  V /= norm_matlab(V);
  s.X = X;
  s.V = V;
  s.contact = letter - 'a' + 1;
}

// An orbit as the MATLAB code steps it: in real arithmetic (trig_collision) while the state is real and every acos
// argument lies in (-1, 1), where MATLAB's arithmetic is the real one; in complex arithmetic from the first pass
// that leaves that domain on.
struct MatlabOrbit {
  TrigState<double> real;
  bool is_real = true;
  State s;
};

// Leaves real arithmetic: the complex state starts from the real one.
void go_complex(MatlabOrbit& o) {
  o.is_real = false;
  o.s.X = o.real.X.cast<C>();
  o.s.V = o.real.V.cast<C>();
  o.s.contact = o.real.contact;
}

// One pass of the MATLAB while-loop: the real collision while it reports ok, the complex one otherwise.
void matlab_pass(MatlabOrbit& o, double r) {
  C theta, phi;
  if (o.is_real) {
    TrigState<double> next = o.real;
    if (trig_collision<double>(next, r) == TrigStatus::ok) {
      o.real = next;
      o.s.contact = o.real.contact;
      return;
    }
    go_complex(o);
  }
  collision(o.s, r, theta, phi);
}

// At a b-collision of a real orbit: the angle the next pass reads (theta, or phi when want_phi) when both acos
// arguments lie in (-1, 1); false (and no angle) otherwise.
bool real_angle(const MatlabOrbit& o, bool want_phi, double& angle) {
  const double x3 = o.real.X(2);
  if (!(x3 > -1 && x3 < 1)) return false;
  const double th = std::acos(x3), cp = o.real.V(0) / std::cos(th);
  if (!(cp > -1 && cp < 1)) return false;
  angle = want_phi ? std::acos(cp) : th;
  return true;
}

// The bins of one r's column: a value outside [lo, hi] or not finite is counted apart.
struct MatlabColumn {
  std::uint32_t* col;
  std::uint64_t &nan_points, &outside;
  int bins;
  double lo, hi, scale;
  void operator()(double v) const {
    if (!std::isfinite(v)) {
      ++nan_points;
      return;
    }
    if (v < lo || v > hi) {
      ++outside;
      return;
    }
    ++col[std::min(bins - 1, static_cast<int>((v - lo) * scale))];
  }
};

// One orbit from u: up to 4 x iterations collisions (a b-to-b step takes 2 or 3; the cap ends orbits stuck on a
// tie), its b-collisions k >= first counted by angle.  Returns the b-collisions reached; `complex` says whether
// the orbit left real arithmetic.
long matlab_orbit(Vec3<double> u, double r, long iterations, long first, bool want_phi, const MatlabColumn& count,
                  const core::CancelToken* cancel, bool& complex) {
  u = core::to_quadrant<double>(u / u.norm());
  MatlabOrbit o;
  o.real = trig_start<double>(core::theta<double>(u), core::phi<double>(u));
  long k = 0;
  for (long pass = 0; pass < 4 * iterations && k < iterations && !core::cancel_due(cancel, pass); ++pass) {
    matlab_pass(o, r);
    if (o.s.contact != 2) continue;
    if (o.is_real) {
      double angle = 0;
      if (real_angle(o, want_phi, angle)) {
        ++k;
        if (k >= first) count(angle);
        continue;
      }
      go_complex(o);  // the next pass will leave the domain: continue in complex arithmetic from here
    }
    ++k;
    // The angles the next pass reads (contact 2), as MATLAB computes them.
    const C th = acos_matlab(o.s.X(2));
    const C ph = acos_matlab(o.s.V(0) / std::cos(th));
    if (th.imag() != 0 || ph.imag() != 0) o.s.complex = true;
    if (k >= first) count(want_phi ? ph.real() : th.real());
  }
  complex = o.s.complex;
  return k;
}

}  // namespace

// Per r (in parallel, each r its own column): every orbit of the grid through matlab_orbit.
MatlabTrigImage trig_density_matlab(const iterate::Ensemble& ens, long iterations, long tail, bool want_phi, int bins,
                                    double lo, double hi, int threads, const core::CancelToken* cancel) {
  const std::size_t n_r = ens.r.size(), n_ic = ens.initial.size();
  MatlabTrigImage img;
  img.counts.assign(n_r * static_cast<std::size_t>(bins), 0);
  img.complex_orbits.assign(n_r, 0);
  img.nan_points.assign(n_r, 0);
  img.outside.assign(n_r, 0);
  img.stalled.assign(n_r, 0);
  const long first = std::max<long>(iterations - tail + 1, 1);
  const double scale = bins / (hi - lo);
  iterate::parallel_for(n_r, threads, [&](std::size_t ir) {
    if (cancel && cancel->cancelled()) return;  // no exception may leave an OpenMP region
    const MatlabColumn count{
        &img.counts[ir * static_cast<std::size_t>(bins)], img.nan_points[ir], img.outside[ir], bins, lo, hi, scale};
    for (std::size_t ic = 0; ic < n_ic; ++ic) {
      bool complex = false;
      const long k = matlab_orbit(ens.initial[ic], ens.r[ir], iterations, first, want_phi, count, cancel, complex);
      img.complex_orbits[ir] += complex ? 1 : 0;
      // Orbits that stop producing b-collisions (a tie, or a complex state cycling among a and c) within the
      // 4 x iterations collisions: the tail states they never reached.
      img.stalled[ir] += static_cast<std::uint64_t>(tail - std::clamp<long>(k - first + 1, 0, tail));
    }
  });
  core::check_cancel(cancel);
  return img;
}

}  // namespace btob::reference
