// SPDX-License-Identifier: GPL-3.0-or-later
// The spectrum of Ulam's matrix block by block (Eigen's dense solver, Spectra's Arnoldi), the invariant density of
// a closed class, and PCCA+ memberships.
#include "core/abandonable.hpp"
#include "transfer/detail.hpp"

#include <Spectra/GenEigsSolver.h>
#include <Spectra/MatOp/SparseGenMatProd.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace btob::transfer {

using detail::at;
using detail::ColMat;
using detail::LocalPair;

namespace detail {

ColMat block_transpose(const UlamMatrix& P, const std::vector<long>& boxes) {
  std::vector<int> local(at(P.n), -1);
  for (std::size_t k = 0; k < boxes.size(); ++k) local[at(boxes[k])] = static_cast<int>(k);
  const int m = static_cast<int>(boxes.size());
  std::vector<int> outer(static_cast<std::size_t>(m + 1), 0), inner;
  std::vector<double> val;
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    const std::size_t row = at(boxes[k]);
    for (int e = P.row_ptr[row]; e < P.row_ptr[row + 1]; ++e) {
      const int j = local[at(P.col[at(e)])];
      if (j < 0) continue;
      inner.push_back(j);
      val.push_back(P.val[at(e)]);
    }
    outer[k + 1] = static_cast<int>(inner.size());
  }
  const Eigen::Map<const ColMat> map(m, m, static_cast<int>(inner.size()), outer.data(), inner.data(), val.data());
  return ColMat(map);
}

}  // namespace detail

namespace {

// Spectra's product operator, polling the run's cancellation token before every product (one sparse product of
// the largest partitions takes milliseconds; the Arnoldi iteration takes up to 1000 restarts of ncv products).
struct CancellableProd : Spectra::SparseGenMatProd<double> {
  const core::CancelToken* cancel;
  CancellableProd(const ColMat& A, const core::CancelToken* c) : Spectra::SparseGenMatProd<double>(A), cancel(c) {}
  void perform_op(const double* x_in, double* y_out) const {
    core::check_cancel(cancel);
    Spectra::SparseGenMatProd<double>::perform_op(x_in, y_out);
  }
};

// Spectra's restarted Arnoldi on A (m > k + 2 boxes); empty when every attempt failed.  Spectra can fail in its
// small Schur decomposition (clustered eigenvalues on the unit circle); the attempt is repeated with a larger
// subspace, up to three times.
std::vector<LocalPair> arnoldi_eigenpairs(const ColMat& A, int k, bool vectors, Spectra::SortRule rule,
                                          const core::CancelToken* cancel) {
  const long m = A.rows();
  CancellableProd op(A, cancel);
  const int nev = static_cast<int>(std::min<long>(k, m - 3));
  std::vector<LocalPair> out;
  for (int attempt = 0; attempt < 3; ++attempt) {
    const int ncv = static_cast<int>(std::min<long>(m, std::max(2 * nev + 1, nev + 40) + 16 * attempt));
    Spectra::GenEigsSolver<CancellableProd> eigs(op, nev, ncv);
    eigs.init();
    try {
      // tol: Spectra's relative accuracy of the Ritz values; 1e-9 resolves eigenvalues 1e-6 apart (the smallest
      // distances this analysis reports are ~1e-4, the near-one and peripheral thresholds 1e-2).
      eigs.compute(rule, 1000, 1e-9);
    } catch (const core::Cancelled&) {
      throw;  // a runtime_error too: not a failed attempt
    } catch (const std::runtime_error&) {
      continue;
    }
    const Eigen::VectorXcd values = eigs.eigenvalues();
    Eigen::MatrixXcd V;
    if (vectors && values.size() > 0) V = eigs.eigenvectors();
    for (long i = 0; i < values.size(); ++i) {
      LocalPair pair;
      pair.value = values(i);
      if (vectors) pair.vector = V.col(i);
      out.push_back(std::move(pair));
    }
    break;
  }
  return out;
}

// Every eigenpair of the dense matrix D by Eigen's solver.
std::vector<LocalPair> eigen_solve(const Eigen::MatrixXd& D, bool vectors) {
  Eigen::EigenSolver<Eigen::MatrixXd> es(D, vectors);
  std::vector<LocalPair> out;
  for (long i = 0; i < D.rows(); ++i) {
    LocalPair pair;
    pair.value = es.eigenvalues()(i);
    if (vectors) pair.vector = es.eigenvectors().col(i);
    out.push_back(std::move(pair));
  }
  return out;
}

// Eigen's dense solver runs O(m^3) steps inside one call that cannot poll the token (0.03 s at 100 boxes, ~5 s at
// kDenseMaxBoxes, minutes at kDenseFallbackBoxes).  Above this size the block is solved on a thread of its own.
constexpr long kDenseInlineBoxes = 128;

// Every eigenpair of A by Eigen's dense solver.  A block above kDenseInlineBoxes is solved by core::run_abandonable
// on its own copy (the same code, so the same bits): cancelled, the solver finishes alone and frees its copy.
std::vector<LocalPair> dense_eigenpairs(const ColMat& A, bool vectors, const core::CancelToken* cancel) {
  core::check_cancel(cancel);
  if (!cancel || A.rows() <= kDenseInlineBoxes) return eigen_solve(Eigen::MatrixXd(A), vectors);
  return core::run_abandonable(cancel, [D = Eigen::MatrixXd(A), vectors] { return eigen_solve(D, vectors); });
}

}  // namespace

namespace detail {

std::vector<LocalPair> block_eigenpairs(const ColMat& A, int k, bool vectors, long dense_max, Spectra::SortRule rule,
                                        const core::CancelToken* cancel) {
  const long m = A.rows();
  if (m == 0) return {};
  bool dense = m <= dense_max || m < k + 3;
  std::vector<LocalPair> out;
  if (!dense) {
    out = arnoldi_eigenpairs(A, k, vectors, rule, cancel);
    // Every attempt failed: blocks small enough go to the dense solver instead; larger ones report no eigenvalue.
    if (out.empty() && m <= kDenseFallbackBoxes) dense = true;
  }
  if (dense) out = dense_eigenpairs(A, vectors, cancel);
  std::stable_sort(out.begin(), out.end(),
                   [](const LocalPair& x, const LocalPair& y) { return std::abs(x.value) > std::abs(y.value); });
  return out;
}

}  // namespace detail

namespace {

// The boxes of each block: block 0 the transient boxes, block c the boxes of closed class c.
std::vector<std::vector<long>> boxes_of_blocks(const Decomposition& d) {
  std::vector<std::vector<long>> boxes(d.classes.size() + 1);
  for (std::size_t i = 0; i < d.class_of_box.size(); ++i) boxes[d.class_of_box[i]].push_back(static_cast<long>(i));
  return boxes;
}

// A block's local pair spread over the n boxes of the partition (zero outside the block).
Eigenpair on_all_boxes(const LocalPair& pair, int block, const std::vector<long>& boxes, long n, bool vectors) {
  Eigenpair e;
  e.value = pair.value;
  e.block = block;
  if (vectors) {
    e.vector.assign(at(n), 0);
    for (std::size_t j = 0; j < boxes.size(); ++j) e.vector[at(boxes[j])] = pair.vector(static_cast<long>(j));
  }
  return e;
}

// By decreasing modulus; ties (roots of unity, repeated eigenvalues) by argument, then block.
bool leads(const Eigenpair& x, const Eigenpair& y) {
  const double mx = std::abs(x.value), my = std::abs(y.value);
  if (std::fabs(mx - my) > 1e-12) return mx > my;
  const double ax = std::fabs(std::arg(x.value)), ay = std::fabs(std::arg(y.value));
  if (std::fabs(ax - ay) > 1e-12) return ax < ay;
  if (x.block != y.block) return x.block < y.block;
  return x.value.imag() > y.value.imag();
}

}  // namespace

std::vector<Eigenpair> leading_eigenpairs(const UlamMatrix& P, const Decomposition& d, int k, bool vectors,
                                          long dense_max, const core::CancelToken* cancel) {
  const auto blocks = boxes_of_blocks(d);
  const std::size_t wanted = static_cast<std::size_t>(k);
  std::vector<Eigenpair> all;
  for (std::size_t block = 0; block < blocks.size(); ++block) {
    if (blocks[block].empty()) continue;
    const auto pairs = detail::block_eigenpairs(detail::block_transpose(P, blocks[block]), k, vectors, dense_max,
                                                Spectra::SortRule::LargestMagn, cancel);
    for (std::size_t j = 0; j < pairs.size() && j < wanted; ++j)
      all.push_back(on_all_boxes(pairs[j], static_cast<int>(block), blocks[block], P.n, vectors));
  }
  std::stable_sort(all.begin(), all.end(), leads);
  if (all.size() > wanted) all.resize(wanted);
  return all;
}

std::vector<std::complex<double>> leading_eigenvalues_whole(const UlamMatrix& P, int k,
                                                            const core::CancelToken* cancel) {
  std::vector<long> boxes(at(P.n));
  std::iota(boxes.begin(), boxes.end(), 0L);
  const auto pairs =
      detail::block_eigenpairs(detail::block_transpose(P, boxes), k, false, 0, Spectra::SortRule::LargestMagn, cancel);
  std::vector<std::complex<double>> values;
  for (std::size_t j = 0; j < pairs.size() && j < static_cast<std::size_t>(k); ++j) values.push_back(pairs[j].value);
  return values;
}

namespace {
// The eigenvector of the eigenvalue closest to 1 in a list, as a nonnegative density of sum 1 (real part, sign
// fixed by the sum; negative round-off clipped).
std::vector<double> density_of(const std::vector<LocalPair>& pairs, std::size_t m) {
  std::size_t best = 0;
  for (std::size_t j = 1; j < pairs.size(); ++j)
    if (std::abs(pairs[j].value - 1.0) < std::abs(pairs[best].value - 1.0)) best = j;
  std::vector<double> density(m, 0);
  if (pairs.empty()) return density;
  double sum = 0;
  for (std::size_t j = 0; j < m; ++j) sum += pairs[best].vector(static_cast<long>(j)).real();
  double total = 0;
  for (std::size_t j = 0; j < m; ++j)
    total += density[j] = std::max(0.0, pairs[best].vector(static_cast<long>(j)).real() / sum);
  for (auto& x : density) x /= total;
  return density;
}
}  // namespace

std::vector<double> class_density(const UlamMatrix& P, const Decomposition& d, int c, const core::CancelToken* cancel) {
  std::vector<long> boxes;
  for (std::size_t i = 0; i < d.class_of_box.size(); ++i)
    if (d.class_of_box[i] == static_cast<std::uint32_t>(c)) boxes.push_back(static_cast<long>(i));
  const int period = d.classes[static_cast<std::size_t>(c - 1)].period;
  const auto pairs = detail::block_eigenpairs(detail::block_transpose(P, boxes), std::max(4, period + 2), true,
                                              kDenseMaxBoxes, Spectra::SortRule::LargestMagn, cancel);
  const auto local = density_of(pairs, boxes.size());
  std::vector<double> out(at(P.n), 0);
  for (std::size_t j = 0; j < boxes.size(); ++j) out[at(boxes[j])] = local[j];
  return out;
}

// PCCA+ memberships (Deuflhard and Weber 2005, inner simplex algorithm): H (m rows of boxes x p right eigenvectors
// of eigenvalues near 1, the first one constant) is mapped to memberships chi = H A^-1, A the rows of H at the p
// boxes found greedily as the vertices of the simplex the rows nearly fill.  Rows of chi sum to 1.
Eigen::MatrixXd detail::pcca(const Eigen::MatrixXd& H) {
  const long m = H.rows(), p = H.cols();
  Eigen::MatrixXd X = H;
  std::vector<long> vertex;
  long i0 = 0;
  for (long i = 1; i < m; ++i)
    if (X.row(i).norm() > X.row(i0).norm()) i0 = i;
  // The first vertex: the row farthest from the mean; then repeatedly the row farthest from the span so far.
  const Eigen::RowVectorXd mean = X.colwise().mean();
  for (long i = 0; i < m; ++i)
    if ((X.row(i) - mean).norm() > (X.row(i0) - mean).norm()) i0 = i;
  vertex.push_back(i0);
  const Eigen::RowVectorXd x0 = X.row(i0);
  X.rowwise() -= x0;
  for (long k = 1; k < p; ++k) {
    long best = 0;
    for (long i = 1; i < m; ++i)
      if (X.row(i).norm() > X.row(best).norm()) best = i;
    vertex.push_back(best);
    const Eigen::RowVectorXd e = X.row(best) / X.row(best).norm();
    const Eigen::VectorXd proj = X * e.transpose();
    X -= proj * e;
  }
  Eigen::MatrixXd A(p, p);
  for (long k = 0; k < p; ++k) A.row(k) = H.row(vertex[at(k)]);
  return H * A.inverse();
}

}  // namespace btob::transfer
