// SPDX-License-Identifier: GPL-3.0-or-later
// Explicit instantiations of btob::reference for float, double, long double and float128.
#include "reference/reference_impl.hpp"

#include <boost/multiprecision/eigen.hpp>  // Eigen::NumTraits for float128

namespace btob::reference {

const char* trig_status_name(TrigStatus s) {
  switch (s) {
    case TrigStatus::ok: return "ok";
    case TrigStatus::acos_domain: return "acos-domain";
    case TrigStatus::angle_lost: return "angle-lost";
    case TrigStatus::nan_state: return "nan-state";
    case TrigStatus::tie: return "tie";
    case TrigStatus::bad_sequence: return "bad-sequence";
  }
  return "?";
}

#define BTOB_REFERENCE_INSTANTIATE(T)                                                \
  template Mat3<T> collision_matrix<T>(char, const T&);                              \
  template CrossProductImage<T> cross_product_map<T>(const Vec3<T>&, const T&);      \
  template ParticleCycle<T> simulate_b_to_b<T>(const core::Particles<T>&, const T&); \
  template TrigState<T> trig_start<T>(const T&, const T&);                           \
  template TrigStatus trig_collision<T>(TrigState<T>&, const T&, T*, T*);            \
  template TrigCycle<T> trig_b_to_b<T>(TrigState<T>&, const T&);
BTOB_REFERENCE_INSTANTIATE(float)
BTOB_REFERENCE_INSTANTIATE(double)
BTOB_REFERENCE_INSTANTIATE(long double)
BTOB_REFERENCE_INSTANTIATE(core::float128)
#undef BTOB_REFERENCE_INSTANTIATE

template std::vector<std::uint64_t> trig_density<double>(const iterate::Ensemble&, long, iterate::DensityRecorder&, int,
                                                         const core::CancelToken*);
template std::vector<std::uint64_t> trig_density<long double>(const iterate::Ensemble&, long, iterate::DensityRecorder&,
                                                              int, const core::CancelToken*);

}  // namespace btob::reference
