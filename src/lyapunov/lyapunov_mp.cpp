// SPDX-License-Identifier: GPL-3.0-or-later
// Explicit instantiations of the Lyapunov cocycles for float, float128 and MPFR (every precision),
// in their own unit so that the double build of lyapunov.cpp stays fast.  Sums of log R_ii are accumulated in
// long double and results are reported in double (see lyapunov.hpp): for float128 and MPFR the exponent is
// therefore known to ~1e-16 relative at best, which the precision study states.
#include "core/scalar.hpp"
#include "lyapunov/lyapunov_impl.hpp"
#include "lyapunov/orbit.hpp"

namespace btob::lyapunov::detail {
// Defined in orbit_mpfr.cpp (the mpfr_* C API): declared wherever the MPFR frame is stepped.
template <>
void advance<core::mpfr_float>(OrbitFrame<core::mpfr_float>& f, long n, long first, std::uint8_t* ring,
                               Trace<long double> tr);
}  // namespace btob::lyapunov::detail

namespace btob::lyapunov {

using core::float128;
using core::mpfr_float;

template ProjectiveResult projective_exponents<float>(const Vec3<float>&, const float&, const Options&);
template LinearResult linear_exponents<float>(const Vec3<float>&, const float&, const Options&);
template ProjectiveResult projective_exponents<float128>(const Vec3<float128>&, const float128&, const Options&);
template LinearResult linear_exponents<float128>(const Vec3<float128>&, const float128&, const Options&);
template ProjectiveResult projective_exponents<mpfr_float>(const Vec3<mpfr_float>&, const mpfr_float&, const Options&);
template ProjectiveResult projective_exponents_qr<float>(const Vec3<float>&, const float&, const Options&);
template ProjectiveResult projective_exponents_qr<float128>(const Vec3<float128>&, const float128&, const Options&);
template ProjectiveResult projective_exponents_qr<mpfr_float>(const Vec3<mpfr_float>&, const mpfr_float&,
                                                              const Options&);
template LinearResult linear_exponents<mpfr_float>(const Vec3<mpfr_float>&, const mpfr_float&, const Options&);

}  // namespace btob::lyapunov
