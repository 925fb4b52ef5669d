// SPDX-License-Identifier: GPL-3.0-or-later
// What the transfer module's files share and no caller needs: box indices as vector positions, the sparse block
// of a set of boxes, the dense/Arnoldi eigensolver of one block, PCCA+ memberships, the P2 region's level.
#pragma once

#include "transfer/transfer.hpp"

#include <Spectra/Util/SelectionRule.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <chrono>
#include <complex>
#include <cstddef>
#include <vector>

namespace btob::transfer::detail {

// A box index (long, the partition's type) as a position in a std::vector.
constexpr std::size_t at(long box) { return static_cast<std::size_t>(box); }

// A block on which every Arnoldi attempt failed still gets a dense solve up to this size (8 m^2 bytes: 128 MB).
constexpr long kDenseFallbackBoxes = 4000;

using ColMat = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// The block of P on the boxes (sorted), transposed: A = (P restricted to boxes x boxes)^T, column-major (the
// row-major arrays of the block read as column-major are its transpose).
ColMat block_transpose(const UlamMatrix& P, const std::vector<long>& boxes);

struct LocalPair {
  std::complex<double> value;
  Eigen::VectorXcd vector;  // on the block's boxes
};

// The eigenpairs of one block A (k wanted; all of them from the dense solver), by decreasing modulus.
std::vector<LocalPair> block_eigenpairs(const ColMat& A, int k, bool vectors, long dense_max,
                                        Spectra::SortRule rule = Spectra::SortRule::LargestMagn,
                                        const core::CancelToken* cancel = nullptr);

// PCCA+ memberships of the m boxes from p right eigenvectors (columns of H, the first constant); rows sum to 1.
Eigen::MatrixXd pcca(const Eigen::MatrixXd& H);

// The level c = 2 - alpha^2 / r of the P2 region R = {I < c} (I the conserved quantity of P2): R exists iff c > 0
// (r > 3 - 2 sqrt 2).
double p2_level(double r);

}  // namespace btob::transfer::detail
