// SPDX-License-Identifier: GPL-3.0-or-later
// Stages 3-7 of `btob transfer` (stages.hpp): the leading spectrum, the absorbers, the projection of Lebesgue
// measure on them, the components with their densities, and the second eigenvector's sign structure.
#include "core/cancel.hpp"
#include "transfer/detail.hpp"
#include "transfer/stages.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace btob::transfer {

using detail::at;

Spectrum leading_spectrum(const UlamMatrix& P, const Decomposition& d, const TransferRequest& q,
                          const core::CancelToken* cancel) {
  Spectrum s;
  s.pairs = leading_eigenpairs(P, d, q.eigenvalues, true, kDenseMaxBoxes, cancel);
  if (q.check_whole) s.whole = leading_eigenvalues_whole(P, q.eigenvalues, cancel);
  return s;
}

namespace {

// The density of closed class k: its eigenvalue-1 vector among the leading pairs (real part, sign fixed by the
// sum, negative round-off clipped, sum 1), else its own solve; on the class's boxes.
std::vector<double> closed_class_density(const UlamMatrix& P, const Decomposition& d, int k,
                                         const std::vector<long>& boxes, const std::vector<Eigenpair>& pairs,
                                         const core::CancelToken* cancel) {
  const Eigenpair* best = nullptr;
  for (const auto& e : pairs)
    if (e.block == k && std::abs(e.value - 1.0) < 1e-8 &&
        (!best || std::abs(e.value - 1.0) < std::abs(best->value - 1.0)))
      best = &e;
  std::vector<double> full;
  if (best) {
    full.assign(at(P.n), 0);
    double sum = 0, total = 0;
    for (long i : boxes) sum += best->vector[at(i)].real();
    for (long i : boxes) total += full[at(i)] = std::max(0.0, best->vector[at(i)].real() / sum);
    for (auto& x : full) x /= total;
  } else {
    full = class_density(P, d, k, cancel);
  }
  std::vector<double> density;
  for (long i : boxes) density.push_back(full[at(i)]);
  return density;
}

// The transient strongly connected component that eigenvector e of the transient block lives on (its largest
// entry's), with e's moduli as its density; nullopt when that box already belongs to an absorber.
std::optional<Absorber> transient_absorber(const Eigenpair& e, const Decomposition& d, const Absorbers& absorbers) {
  std::size_t arg = 0;
  for (std::size_t i = 1; i < e.vector.size(); ++i)
    if (std::abs(e.vector[i]) > std::abs(e.vector[arg])) arg = i;
  if (absorbers.of_box[arg] != 0) return std::nullopt;  // that component is already one
  const int s = d.scc[arg];
  Absorber ab;
  ab.block = -s - 1;
  ab.rho = e.value.real();
  double total = 0;
  for (std::size_t i = 0; i < e.vector.size(); ++i)
    if (d.scc[i] == s) {
      ab.boxes.push_back(static_cast<long>(i));
      ab.density.push_back(std::abs(e.vector[i]));
      total += ab.density.back();
    }
  for (auto& x : ab.density) x /= total;
  return ab;
}

void add(Absorbers& absorbers, Absorber ab) {
  for (long i : ab.boxes) absorbers.of_box[at(i)] = static_cast<std::uint32_t>(absorbers.list.size() + 1);
  absorbers.list.push_back(std::move(ab));
}

}  // namespace

Absorbers find_absorbers(const UlamMatrix& P, const Decomposition& d, const std::vector<Eigenpair>& pairs,
                         double near_one, const core::CancelToken* cancel) {
  Absorbers absorbers;
  absorbers.of_box.assign(at(P.n), 0);
  for (int k = 1; k <= static_cast<int>(d.classes.size()); ++k) {
    Absorber ab;
    ab.block = k;
    for (std::size_t i = 0; i < d.class_of_box.size(); ++i)
      if (d.class_of_box[i] == static_cast<std::uint32_t>(k)) ab.boxes.push_back(static_cast<long>(i));
    ab.density = closed_class_density(P, d, k, ab.boxes, pairs, cancel);
    add(absorbers, std::move(ab));
  }
  for (const auto& e : pairs) {
    if (e.block != 0 || std::fabs(e.value.imag()) > 1e-12 || std::abs(e.value - 1.0) > near_one) continue;
    if (auto ab = transient_absorber(e, d, absorbers)) add(absorbers, std::move(*ab));
  }
  return absorbers;
}

Projection project_lebesgue(const UlamMatrix& P, const Absorbers& absorbers, const std::vector<double>& mu,
                            const core::CancelToken* cancel) {
  const std::size_t n = at(P.n);
  Projection out;
  out.entry.assign(n, 0);
  std::vector<double> mass(n, 0), next(n, 0);  // the mass still flowing, before and after a step
  for (std::size_t i = 0; i < n; ++i) {
    if (absorbers.of_box[i]) out.entry[i] += mu[i];
    else mass[i] = mu[i];
  }
  double left = 0;
  for (int step = 0; step < 100000; ++step) {
    left = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double xi = mass[i];
      if (xi == 0) continue;
      for (int e = P.row_ptr[i]; e < P.row_ptr[i + 1]; ++e) {
        const std::size_t j = at(P.col[at(e)]);
        const double moved = xi * P.val[at(e)];
        if (absorbers.of_box[j]) out.entry[j] += moved;
        else next[j] += moved;
      }
    }
    std::swap(mass, next);
    std::fill(next.begin(), next.end(), 0.0);
    for (double v : mass) left += v;
    if (left < 1e-13) break;
    if (step % 64 == 0) core::check_cancel(cancel);
  }
  out.unabsorbed = left;
  return out;
}

namespace {

// The memberships of an absorber's boxes in its parts (one column per part): PCCA+ on the right eigenvectors
// (P h = lambda h) of a closed class with several real eigenvalues in (1 - near_one, 1]; one part (all 1) otherwise.
Eigen::MatrixXd memberships(const UlamMatrix& P, const Absorber& ab, const std::vector<Eigenpair>& pairs,
                            double near_one, const core::CancelToken* cancel) {
  std::vector<double> values;  // the near-one real eigenvalues of this absorber (classes only)
  if (ab.block > 0)
    for (const auto& e : pairs)
      if (e.block == ab.block && std::fabs(e.value.imag()) < 1e-12 && e.value.real() > 1 - near_one)
        values.push_back(e.value.real());
  const long m = static_cast<long>(ab.boxes.size());
  Eigen::MatrixXd chi = Eigen::MatrixXd::Ones(m, 1);
  if (values.size() < 2) return chi;
  const detail::ColMat A = detail::block_transpose(P, ab.boxes);
  const detail::ColMat Q = A.transpose();
  const int p = static_cast<int>(values.size());
  auto right = detail::block_eigenpairs(Q, p + 2, true, kDenseMaxBoxes, Spectra::SortRule::LargestReal, cancel);
  std::stable_sort(right.begin(), right.end(), [](const detail::LocalPair& x, const detail::LocalPair& y) {
    return x.value.real() > y.value.real();
  });
  Eigen::MatrixXd H(m, p);
  int got = 0;
  for (const auto& pair : right)
    if (got < p && std::fabs(pair.value.imag()) < 1e-12) H.col(got++) = pair.vector.real();
  if (got == p) chi = detail::pcca(H);
  return chi;
}

// A part's membership of box j of its absorber, clamped: PCCA+ rows may overshoot [0, 1] slightly.
double membership(const Eigen::MatrixXd& chi, std::size_t j, long part) {
  return std::clamp(chi(static_cast<long>(j), part), 0.0, 1.0);
}

// Metastability of a part: the chance of staying in it for one step, averaged over its density w (unnormalised,
// total `total`): sum_i w_i sum_j P_ij chi_j / sum_i w_i, chi extended by 0 outside the class.
double metastability(const UlamMatrix& P, const Absorber& ab, const Eigen::MatrixXd& chi, long part,
                     const std::vector<double>& w, double total) {
  std::vector<double> chi_full(at(P.n), 0);
  for (std::size_t j = 0; j < ab.boxes.size(); ++j) chi_full[at(ab.boxes[j])] = membership(chi, j, part);
  double stay = 0;
  for (std::size_t j = 0; j < ab.boxes.size(); ++j) {
    const std::size_t i = at(ab.boxes[j]);
    double kept = 0;
    for (int e = P.row_ptr[i]; e < P.row_ptr[i + 1]; ++e) kept += P.val[at(e)] * chi_full[at(P.col[at(e)])];
    stay += w[j] * kept;
  }
  return total > 0 ? stay / total : 0;
}

// The part of largest membership of box j.
long strongest_part(const Eigen::MatrixXd& chi, std::size_t j) {
  long arg = 0;
  for (long k = 1; k < chi.cols(); ++k)
    if (chi(static_cast<long>(j), k) > chi(static_cast<long>(j), arg)) arg = k;
  return arg;
}

// Adds part `part` of absorber ab to the components: its Lebesgue fraction, density, centre and boxes.
void add_part(const UlamMatrix& P, const Decomposition& d, const Partition& partition, const Absorber& ab,
              const Eigen::MatrixXd& chi, long part, const std::vector<double>& entry, Components& out) {
  ComponentInfo ci;
  ci.block = ab.block;
  ci.rho = ab.rho;
  ci.period = ab.block > 0 && chi.cols() == 1 ? d.classes[at(ab.block - 1)].period : 1;
  double fraction = 0, total = 0;
  std::vector<double> w(ab.boxes.size());
  for (std::size_t j = 0; j < ab.boxes.size(); ++j) {
    const double x = membership(chi, j, part);
    fraction += entry[at(ab.boxes[j])] * x;
    total += w[j] = ab.density[j] * x;
  }
  ci.lebesgue = fraction;
  if (chi.cols() > 1) ci.rho = metastability(P, ab, chi, part, w, total);
  const double h1 = (partition.hi1 - partition.lo1) / static_cast<double>(partition.n1);
  const double h2 = (partition.hi2 - partition.lo2) / static_cast<double>(partition.n2);
  double ca = 0, cb = 0;
  std::vector<double> full(at(P.n), 0);
  for (std::size_t j = 0; j < ab.boxes.size(); ++j) {
    const long i = ab.boxes[j];
    const double wn = total > 0 ? w[j] / total : 0;
    full[at(i)] = wn;
    out.density[at(i)] += fraction * wn;
    ca += wn * (partition.lo1 + (static_cast<double>(i / partition.n2) + 0.5) * h1);
    cb += wn * (partition.lo2 + (static_cast<double>(i % partition.n2) + 0.5) * h2);
    if (strongest_part(chi, j) != part) continue;
    ++ci.boxes;
    out.of_box[at(i)] = static_cast<std::uint32_t>(out.info.size() + 1);
  }
  ci.centre = {ca, cb};
  out.info.push_back(ci);
  out.densities.push_back(std::move(full));
}

}  // namespace

Components split_components(const UlamMatrix& P, const Decomposition& d, const Partition& partition,
                            const Absorbers& absorbers, const std::vector<Eigenpair>& pairs,
                            const std::vector<double>& entry, double near_one, const core::CancelToken* cancel) {
  Components out;
  out.of_box.assign(at(P.n), 0);
  out.density.assign(at(P.n), 0);
  for (const auto& ab : absorbers.list) {
    const Eigen::MatrixXd chi = memberships(P, ab, pairs, near_one, cancel);
    for (long part = 0; part < chi.cols(); ++part) add_part(P, d, partition, ab, chi, part, entry, out);
  }
  return out;
}

SecondEigenvector second_eigenvector(const std::vector<Eigenpair>& pairs, long n) {
  SecondEigenvector s;
  for (const auto& e : pairs) {
    if (std::fabs(e.value.imag()) > 1e-12 || !(e.value.real() > 0 && e.value.real() < 1 - 1e-9)) continue;
    s.value = e.value.real();
    s.block = e.block;
    s.vector.assign(at(n), 0);
    double largest = 0, pos = 0, neg = 0;
    for (const auto& x : e.vector) largest = std::max(largest, std::fabs(x.real()));
    for (std::size_t i = 0; i < s.vector.size(); ++i) {
      const double v = largest > 0 ? e.vector[i].real() / largest : 0;
      s.vector[i] = v;
      // Entries below 1e-9 of the maximum are round-off of the eigensolver: no sign.
      if (v > 1e-9) pos += v, ++s.positive_boxes;
      else if (v < -1e-9) neg -= v, ++s.negative_boxes;
    }
    if (pos + neg > 0) s.positive_mass = pos / (pos + neg), s.negative_mass = neg / (pos + neg);
    break;
  }
  return s;
}

}  // namespace btob::transfer
