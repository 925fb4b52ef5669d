// SPDX-License-Identifier: GPL-3.0-or-later
// The stages of `btob transfer` (transfer::run), each a function of typed inputs to a typed output, so that each
// can be run and tested alone:
//   1. matrix       ulam_btob                   Ulam's matrix of P_r on the partition (transfer.hpp)
//   2. classes      decompose                   strongly connected components, closed classes, periods
//   3. spectrum     leading_spectrum            the K leading eigenpairs, block by block (+ the whole-matrix check)
//   4. absorbers    find_absorbers              closed classes and almost-invariant transient components
//   5. projection   project_lebesgue            where the Lebesgue measure of the request enters the absorbers
//   6. components   split_components            PCCA+ parts of absorbers, their densities and Lebesgue fractions
//   7. second       second_eigenvector          sign structure of the leading real eigenvector below 1
//   8. cycles       name_closed_classes         without --cycle: the attractors of the closed classes (classify)
//                   check_cycle                 the named (or found) cycles' boxes and the density's mass there
//   9. basins       ulam_basins                 absorption probabilities into the attractors' boxes
//  10. comparison   compare_with_empirical      total variation to the empirical measure of orbits
#pragma once

#include "transfer/transfer.hpp"

#include <complex>
#include <cstdint>
#include <string>
#include <vector>

namespace btob::transfer {

// 3. The leading eigenpairs (with eigenvectors) and, with check_whole, Spectra's eigenvalues of the whole matrix.
struct Spectrum {
  std::vector<Eigenpair> pairs;
  std::vector<std::complex<double>> whole;
};
Spectrum leading_spectrum(const UlamMatrix& P, const Decomposition& d, const TransferRequest& q,
                          const core::CancelToken* cancel);

// 4. The sets made absorbing for the projection: the closed classes, then the almost-invariant transient
// components (a real eigenvalue of the transient block within near_one of 1: its eigenvector's largest entry names
// the strongly connected component).
struct Absorber {
  int block = 0;   // class c >= 1, or -s - 1 (transient strongly connected component s)
  double rho = 1;  // mass kept per step: 1 for a class, the eigenvalue for a transient component
  std::vector<long> boxes;
  std::vector<double> density;  // on `boxes`, sum 1
};
struct Absorbers {
  std::vector<Absorber> list;
  std::vector<std::uint32_t> of_box;  // 0: none, a: list[a - 1]
};
Absorbers find_absorbers(const UlamMatrix& P, const Decomposition& d, const std::vector<Eigenpair>& pairs,
                         double near_one, const core::CancelToken* cancel);

// 5. Lebesgue measure (box masses `mu`) pushed through the chain with the absorbers absorbing: mass starting in an
// absorber stays there; the rest flows until less than 1e-13 is left (or 10^5 steps).
struct Projection {
  std::vector<double> entry;  // per box: the mass that starts in or enters an absorber at that box
  double unabsorbed = 0;      // the mass still flowing at the end
};
Projection project_lebesgue(const UlamMatrix& P, const Absorbers& absorbers, const std::vector<double>& mu,
                            const core::CancelToken* cancel);

// 6. The components: each absorber, or, for a closed class with several real eigenvalues in (1 - near_one, 1],
// its PCCA+ parts (the resolution merged attractors that the map keeps apart, through boxes straddling their
// basins' boundaries): a part receives the mass entering the class weighted by its membership chi, and its density
// is the class's density weighted by chi.
struct Components {
  std::vector<ComponentInfo> info;
  std::vector<std::uint32_t> of_box;           // 0: none, k: info[k - 1]
  std::vector<double> density;                 // sum_k lebesgue_k * (density of k), mass per box
  std::vector<std::vector<double>> densities;  // per component, over all boxes, sum 1
};
Components split_components(const UlamMatrix& P, const Decomposition& d, const Partition& partition,
                            const Absorbers& absorbers, const std::vector<Eigenpair>& pairs,
                            const std::vector<double>& entry, double near_one, const core::CancelToken* cancel);

// 7. The leading real eigenvalue in (0, 1 - 1e-9) and the sign structure of its eigenvector (almost-invariant
// sets); values all 0 when there is none.
struct SecondEigenvector {
  double value = 0;
  int block = 0;
  std::vector<double> vector;  // real part, max |.| = 1; empty when there is none
  double positive_mass = 0, negative_mass = 0;
  long positive_boxes = 0, negative_boxes = 0;
};
SecondEigenvector second_eigenvector(const std::vector<Eigenpair>& pairs, long n);

// 8. A periodic word's exact cycle at r located in the boxes, with the density's mass around it (or, without a
// density, the closed class holding it).  `densities` are the components' (empty without a spectrum).
CycleCheck check_cycle(const std::string& word, double r, Domain dom, const Partition& part, const Decomposition& d,
                       const std::vector<double>* density, const std::vector<std::vector<double>>& densities);
// Without --cycle: the closed classes named by the attractors their boxes' orbits reach (ClassNames in
// transfer.hpp); its stable_words are the cycles to check.
ClassNames name_closed_classes(const Partition& part, Domain dom, const Decomposition& d, double r,
                               const core::RunControl& control);

// 9. Basins from the Ulam graph (BasinInfo in transfer.hpp): the targets, then the absorption probabilities.
struct BasinTargets {
  std::vector<BasinInfo> basins;
  std::vector<std::uint32_t> of_box;  // 0: none, k: basins[k - 1]
};
BasinTargets basin_targets(const std::vector<CycleCheck>& cycles, const Partition& part, Domain dom,
                           const TransferRequest& q);
struct Basins {
  std::vector<BasinInfo> basins;            // with their fractions
  std::vector<std::uint32_t> basin_of_box;  // n boxes; empty when there is no target
  std::vector<double> basin_probability;
  double unabsorbed = 0, residual = 0;
  long iterations = 0;
};
Basins absorb(const UlamMatrix& P, BasinTargets targets, const std::vector<double>& mu,
              const core::CancelToken* cancel = nullptr);

// The request's Lebesgue measure as box masses (sum 1): on the strip the rectangle w1 in [a, b] x w2 in [-1, 1],
// uniform on the angles.
std::vector<double> lebesgue(const Partition& p, Domain d, const std::vector<double>& w1_range);

// 10. Total variation between the transfer density and the empirical measure of an NxN grid of orbits.
struct MeasureComparison {
  double tv_boxes = -1, tv_coarse = -1;
  long points = 0;
};
MeasureComparison compare_with_empirical(const TransferRequest& q, Domain dom, const Partition& part,
                                         const std::vector<double>& density, const core::RunControl& control);

}  // namespace btob::transfer
