// Ulam's transfer operator of P^_r: partitions, ergodic decomposition, spectra (Eigen, Spectra), projections.
#include "transfer/transfer.hpp"
#include "core/cancel.hpp"

#include <Spectra/GenEigsSolver.h>
#include <Spectra/MatOp/SparseGenMatProd.h>
#include <fmt/format.h>
#include <omp.h>

#include <Eigen/Dense>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <numeric>
#include <stdexcept>

#include "core/coords.hpp"
#include "core/map.hpp"
#include "iterate/ensemble.hpp"
#include "patterns/atlas.hpp"
#include "patterns/patterns.hpp"
#include "stats/stats.hpp"
#include "transfer/transfer_impl.hpp"
#include "windows/windows.hpp"

namespace btob::transfer {

long Partition::locate(double a, double b) const {
  if (!(a >= lo1 && a <= hi1 && b >= lo2 && b <= hi2)) return -1;  // also NaN
  const long i1 = std::min(n1 - 1, static_cast<long>((a - lo1) / (hi1 - lo1) * static_cast<double>(n1)));
  const long i2 = std::min(n2 - 1, static_cast<long>((b - lo2) / (hi2 - lo2) * static_cast<double>(n2)));
  return i1 * n2 + i2;
}

std::vector<std::pair<double, double>> sample_offsets(int samples) {
  // R2 sequence: frac(1/2 + k (1/g, 1/g^2)), g the plastic number (the root > 1 of g^3 = g + 1).
  constexpr double g = 1.32471795724474602596;
  const double a1 = 1 / g, a2 = 1 / (g * g);
  std::vector<std::pair<double, double>> o(static_cast<std::size_t>(samples));
  for (int k = 0; k < samples; ++k) {
    const double u = 0.5 + a1 * k, v = 0.5 + a2 * k;
    o[static_cast<std::size_t>(k)] = {u - std::floor(u), v - std::floor(v)};
  }
  return o;
}

// ---- Ergodic decomposition --------------------------------------------------------------------------------
Decomposition decompose(const UlamMatrix& P) {
  const long n = P.n;
  Decomposition d;
  d.scc.assign(static_cast<std::size_t>(n), -1);
  // Tarjan's algorithm, iterative (the graph has up to ~10^6 vertices: no recursion).
  std::vector<long> index(static_cast<std::size_t>(n), -1), low(static_cast<std::size_t>(n), 0);
  std::vector<char> on(static_cast<std::size_t>(n), 0);
  std::vector<long> stack;
  std::vector<std::pair<long, int>> call;  // (vertex, next edge position)
  long counter = 0;
  int comps = 0;
  for (long s = 0; s < n; ++s) {
    if (index[static_cast<std::size_t>(s)] >= 0) continue;
    call.push_back({s, P.row_ptr[static_cast<std::size_t>(s)]});
    index[static_cast<std::size_t>(s)] = low[static_cast<std::size_t>(s)] = counter++;
    stack.push_back(s);
    on[static_cast<std::size_t>(s)] = 1;
    while (!call.empty()) {
      auto& [v, e] = call.back();
      if (e < P.row_ptr[static_cast<std::size_t>(v + 1)]) {
        const long w = P.col[static_cast<std::size_t>(e++)];
        if (index[static_cast<std::size_t>(w)] < 0) {
          index[static_cast<std::size_t>(w)] = low[static_cast<std::size_t>(w)] = counter++;
          stack.push_back(w);
          on[static_cast<std::size_t>(w)] = 1;
          call.push_back({w, P.row_ptr[static_cast<std::size_t>(w)]});
        } else if (on[static_cast<std::size_t>(w)]) {
          low[static_cast<std::size_t>(v)] = std::min(low[static_cast<std::size_t>(v)], index[static_cast<std::size_t>(w)]);
        }
        continue;
      }
      const long vv = v;
      if (low[static_cast<std::size_t>(vv)] == index[static_cast<std::size_t>(vv)]) {
        long w;
        do {
          w = stack.back();
          stack.pop_back();
          on[static_cast<std::size_t>(w)] = 0;
          d.scc[static_cast<std::size_t>(w)] = comps;
        } while (w != vv);
        ++comps;
      }
      call.pop_back();
      if (!call.empty()) {
        const long u = call.back().first;
        low[static_cast<std::size_t>(u)] = std::min(low[static_cast<std::size_t>(u)], low[static_cast<std::size_t>(vv)]);
      }
    }
  }
  d.components = comps;
  // Closed components: no transition leaves them (an empty row, whose samples all left the chart, is not closed).
  std::vector<char> closed(static_cast<std::size_t>(comps), 1);
  std::vector<long> first_box(static_cast<std::size_t>(comps), -1), size(static_cast<std::size_t>(comps), 0);
  for (long i = 0; i < n; ++i) {
    const int c = d.scc[static_cast<std::size_t>(i)];
    if (first_box[static_cast<std::size_t>(c)] < 0) first_box[static_cast<std::size_t>(c)] = i;
    ++size[static_cast<std::size_t>(c)];
    if (P.row_ptr[static_cast<std::size_t>(i)] == P.row_ptr[static_cast<std::size_t>(i + 1)]) closed[static_cast<std::size_t>(c)] = 0;
    for (int e = P.row_ptr[static_cast<std::size_t>(i)]; e < P.row_ptr[static_cast<std::size_t>(i + 1)]; ++e)
      if (d.scc[static_cast<std::size_t>(P.col[static_cast<std::size_t>(e)])] != c) closed[static_cast<std::size_t>(c)] = 0;
  }
  // Classes numbered by their first box (deterministic, independent of the traversal).
  std::vector<int> order;
  for (int c = 0; c < comps; ++c)
    if (closed[static_cast<std::size_t>(c)]) order.push_back(c);
  std::sort(order.begin(), order.end(), [&](int x, int y) { return first_box[static_cast<std::size_t>(x)] < first_box[static_cast<std::size_t>(y)]; });
  std::vector<int> class_id(static_cast<std::size_t>(comps), 0);
  for (std::size_t k = 0; k < order.size(); ++k) class_id[static_cast<std::size_t>(order[k])] = static_cast<int>(k + 1);
  d.class_of_box.assign(static_cast<std::size_t>(n), 0);
  for (long i = 0; i < n; ++i) d.class_of_box[static_cast<std::size_t>(i)] = static_cast<std::uint32_t>(class_id[static_cast<std::size_t>(d.scc[static_cast<std::size_t>(i)])]);
  // Period of each class: gcd of level(u) + 1 - level(v) over its edges, levels from a BFS of the class.
  d.classes.resize(order.size());
  std::vector<long> level(static_cast<std::size_t>(n), -1);
  for (std::size_t k = 0; k < order.size(); ++k) {
    const int c = order[k];
    d.classes[k].boxes = size[static_cast<std::size_t>(c)];
    std::vector<long> queue{first_box[static_cast<std::size_t>(c)]};
    level[static_cast<std::size_t>(queue[0])] = 0;
    long g = 0;
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const long u = queue[q];
      for (int e = P.row_ptr[static_cast<std::size_t>(u)]; e < P.row_ptr[static_cast<std::size_t>(u + 1)]; ++e) {
        const long v = P.col[static_cast<std::size_t>(e)];
        if (level[static_cast<std::size_t>(v)] < 0) {
          level[static_cast<std::size_t>(v)] = level[static_cast<std::size_t>(u)] + 1;
          queue.push_back(v);
        } else {
          g = std::gcd(g, std::labs(level[static_cast<std::size_t>(u)] + 1 - level[static_cast<std::size_t>(v)]));
        }
      }
    }
    d.classes[k].period = g == 0 ? 1 : static_cast<int>(g);
  }
  return d;
}

// ---- Spectra of blocks ------------------------------------------------------------------------------------
namespace {

using ColMat = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// The block of P on the boxes idx (sorted), transposed: A = (P restricted to idx x idx)^T, column-major
// (the row-major arrays of the block read as column-major are its transpose).
ColMat block_transpose(const UlamMatrix& P, const std::vector<long>& idx) {
  std::vector<int> loc(static_cast<std::size_t>(P.n), -1);
  for (std::size_t k = 0; k < idx.size(); ++k) loc[static_cast<std::size_t>(idx[k])] = static_cast<int>(k);
  const int m = static_cast<int>(idx.size());
  std::vector<int> outer(static_cast<std::size_t>(m + 1), 0), inner;
  std::vector<double> val;
  for (int k = 0; k < m; ++k) {
    const long i = idx[static_cast<std::size_t>(k)];
    for (int e = P.row_ptr[static_cast<std::size_t>(i)]; e < P.row_ptr[static_cast<std::size_t>(i + 1)]; ++e) {
      const int j = loc[static_cast<std::size_t>(P.col[static_cast<std::size_t>(e)])];
      if (j < 0) continue;
      inner.push_back(j);
      val.push_back(P.val[static_cast<std::size_t>(e)]);
    }
    outer[static_cast<std::size_t>(k + 1)] = static_cast<int>(inner.size());
  }
  const Eigen::Map<const ColMat> map(m, m, static_cast<int>(inner.size()), outer.data(), inner.data(), val.data());
  return ColMat(map);
}

struct LocalPair {
  std::complex<double> value;
  Eigen::VectorXcd vector;  // on the block's boxes
};

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

std::vector<LocalPair> block_eigenpairs(const ColMat& A, int k, bool vectors, long dense_max,
                                       Spectra::SortRule rule = Spectra::SortRule::LargestMagn,
                                       const core::CancelToken* cancel = nullptr) {
  const long m = A.rows();
  std::vector<LocalPair> out;
  if (m == 0) return out;
  bool dense = m <= dense_max || m < k + 3;
  if (!dense) {
    CancellableProd op(A, cancel);
    const int nev = static_cast<int>(std::min<long>(k, m - 3));
    // Spectra's restarted Arnoldi can fail in its small Schur decomposition (clustered eigenvalues on the unit
    // circle); the attempt is repeated with a larger subspace, up to three times.
    for (int attempt = 0; attempt < 3; ++attempt) {
      const int ncv = static_cast<int>(std::min<long>(m, std::max(2 * nev + 1, nev + 40) + 16 * attempt));
      Spectra::GenEigsSolver<CancellableProd> eigs(op, nev, ncv);
      eigs.init();
      const auto tt = std::chrono::steady_clock::now();
      try {
        // tol: Spectra's relative accuracy of the Ritz values; 1e-9 resolves eigenvalues 1e-6 apart (the smallest
        // distances this analysis reports are ~1e-4, the near-one and peripheral thresholds 1e-2).
        eigs.compute(rule, 1000, 1e-9);
      } catch (const core::Cancelled&) {
        throw;  // a runtime_error too: not a failed attempt
      } catch (const std::runtime_error& e) {
        if (std::getenv("BTOB_TRANSFER_DEBUG")) fmt::print(stderr, "spectra: m {} ncv {}: {}\n", m, ncv, e.what());
        continue;
      }
      if (std::getenv("BTOB_TRANSFER_DEBUG"))
        fmt::print(stderr, "spectra: m {} nev {} ncv {} iterations {} matvecs {} nconv {} {:.2f} s\n", m, nev, ncv,
                   eigs.num_iterations(), eigs.num_operations(), eigs.eigenvalues().size(),
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - tt).count());
      const Eigen::VectorXcd v = eigs.eigenvalues();
      Eigen::MatrixXcd V;
      if (vectors && v.size() > 0) V = eigs.eigenvectors();
      for (long i = 0; i < v.size(); ++i) {
        LocalPair p;
        p.value = v(i);
        if (vectors) p.vector = V.col(i);
        out.push_back(std::move(p));
      }
      break;
    }
    // Every attempt failed: blocks small enough for a dense solve (4000 boxes: 128 MB) go to Eigen instead;
    // larger ones report no eigenvalue.
    if (out.empty() && m <= 4000) dense = true;
  }
  if (dense) {
    core::check_cancel(cancel);
    const Eigen::MatrixXd D(A);
    Eigen::EigenSolver<Eigen::MatrixXd> es(D, vectors);
    for (long i = 0; i < m; ++i) {
      LocalPair p;
      p.value = es.eigenvalues()(i);
      if (vectors) p.vector = es.eigenvectors().col(i);
      out.push_back(std::move(p));
    }
  }
  std::stable_sort(out.begin(), out.end(), [](const LocalPair& x, const LocalPair& y) {
    return std::abs(x.value) > std::abs(y.value);
  });
  return out;
}

std::vector<std::vector<long>> block_indices(const Decomposition& d) {
  std::vector<std::vector<long>> idx(d.classes.size() + 1);
  for (std::size_t i = 0; i < d.class_of_box.size(); ++i) idx[d.class_of_box[i]].push_back(static_cast<long>(i));
  return idx;
}

}  // namespace

std::vector<Eigenpair> leading_eigenpairs(const UlamMatrix& P, const Decomposition& d, int k, bool vectors,
                                          long dense_max, const core::CancelToken* cancel) {
  const auto idx = block_indices(d);
  std::vector<Eigenpair> all;
  for (std::size_t b = 0; b < idx.size(); ++b) {
    if (idx[b].empty()) continue;
    const auto pairs = block_eigenpairs(block_transpose(P, idx[b]), k, vectors, dense_max,
                                        Spectra::SortRule::LargestMagn, cancel);
    for (std::size_t q = 0; q < pairs.size() && static_cast<int>(q) < k; ++q) {
      Eigenpair e;
      e.value = pairs[q].value;
      e.block = static_cast<int>(b);
      if (vectors) {
        e.vector.assign(static_cast<std::size_t>(P.n), 0);
        for (std::size_t j = 0; j < idx[b].size(); ++j)
          e.vector[static_cast<std::size_t>(idx[b][j])] = pairs[q].vector(static_cast<long>(j));
      }
      all.push_back(std::move(e));
    }
  }
  // By decreasing modulus; ties (roots of unity, repeated eigenvalues) by argument, then block.
  std::stable_sort(all.begin(), all.end(), [](const Eigenpair& x, const Eigenpair& y) {
    const double mx = std::abs(x.value), my = std::abs(y.value);
    if (std::fabs(mx - my) > 1e-12) return mx > my;
    const double ax = std::fabs(std::arg(x.value)), ay = std::fabs(std::arg(y.value));
    if (std::fabs(ax - ay) > 1e-12) return ax < ay;
    if (x.block != y.block) return x.block < y.block;
    return x.value.imag() > y.value.imag();
  });
  if (static_cast<int>(all.size()) > k) all.resize(static_cast<std::size_t>(k));
  return all;
}

std::vector<std::complex<double>> leading_eigenvalues_whole(const UlamMatrix& P, int k, const core::CancelToken* cancel) {
  std::vector<long> idx(static_cast<std::size_t>(P.n));
  std::iota(idx.begin(), idx.end(), 0L);
  const auto pairs = block_eigenpairs(block_transpose(P, idx), k, false, 0, Spectra::SortRule::LargestMagn, cancel);
  std::vector<std::complex<double>> v;
  for (std::size_t q = 0; q < pairs.size() && static_cast<int>(q) < k; ++q) v.push_back(pairs[q].value);
  return v;
}

namespace {
// The eigenvector of the eigenvalue closest to 1 in a list, as a nonnegative density of sum 1 (real part, sign
// fixed by the sum; negative round-off clipped).
std::vector<double> density_of(const std::vector<LocalPair>& pairs, std::size_t m) {
  std::size_t best = 0;
  for (std::size_t q = 1; q < pairs.size(); ++q)
    if (std::abs(pairs[q].value - 1.0) < std::abs(pairs[best].value - 1.0)) best = q;
  std::vector<double> v(m, 0);
  if (pairs.empty()) return v;
  double s = 0;
  for (std::size_t j = 0; j < m; ++j) s += pairs[best].vector(static_cast<long>(j)).real();
  double t = 0;
  for (std::size_t j = 0; j < m; ++j) t += v[j] = std::max(0.0, pairs[best].vector(static_cast<long>(j)).real() / s);
  for (auto& x : v) x /= t;
  return v;
}

// PCCA+ memberships (Deuflhard and Weber 2005, inner simplex algorithm): H (m rows of boxes x p right eigenvectors
// of eigenvalues near 1, the first one constant) is mapped to memberships chi = H A^-1, A the rows of H at the p
// boxes found greedily as the vertices of the simplex the rows nearly fill.  Rows of chi sum to 1.
Eigen::MatrixXd pcca(const Eigen::MatrixXd& H) {
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
  for (long k = 0; k < p; ++k) A.row(k) = H.row(vertex[static_cast<std::size_t>(k)]);
  return H * A.inverse();
}
}  // namespace

std::vector<double> class_density(const UlamMatrix& P, const Decomposition& d, int c, const core::CancelToken* cancel) {
  std::vector<long> idx;
  for (std::size_t i = 0; i < d.class_of_box.size(); ++i)
    if (d.class_of_box[i] == static_cast<std::uint32_t>(c)) idx.push_back(static_cast<long>(i));
  const int period = d.classes[static_cast<std::size_t>(c - 1)].period;
  const auto pairs = block_eigenpairs(block_transpose(P, idx), std::max(4, period + 2), true, 600,
                                      Spectra::SortRule::LargestMagn, cancel);
  const auto local = density_of(pairs, idx.size());
  std::vector<double> out(static_cast<std::size_t>(P.n), 0);
  for (std::size_t j = 0; j < idx.size(); ++j) out[static_cast<std::size_t>(idx[j])] = local[j];
  return out;
}

// ---- The b-to-b map on a chart ------------------------------------------------------------------------------
Partition domain_partition(Domain d, long n1, long n2) {
  Partition p;
  p.n1 = n1, p.n2 = n2;
  if (d == Domain::strip) p.lo1 = -std::numbers::pi / 2, p.hi1 = std::numbers::pi / 2, p.lo2 = -1, p.hi2 = 1;
  else p.lo1 = 0, p.hi1 = std::numbers::pi / 2, p.lo2 = 0, p.hi2 = std::numbers::pi;
  return p;
}

void chart_to_vector(Domain d, double a, double b, double& x, double& y, double& z) {
  if (d == Domain::strip) {
    // from_strip(tan a, b) scaled by cos a (no overflow near |a| = pi/2).
    const double c = std::cos(a);
    x = (1 + b) / 2 * c, y = std::sin(a), z = (b - 1) / 2 * c;
  } else {
    const auto u = core::from_angles<double>(a, b);
    x = u(0), y = u(1), z = u(2);
  }
}

void vector_to_chart(Domain d, double x, double y, double z, double& a, double& b) {
  // The formulas of stats::empirical_measure (u in Q).
  if (d == Domain::strip) {
    a = std::atan2(y, x - z);
    b = (x + z) / (x - z);
  } else {
    a = std::atan2(-z, x);
    b = std::atan2(std::sqrt(x * x + z * z), -y);
  }
}

// The kernel route lives in kernel_route.cpp (compiled with the kernel flags).
void map_kernel(double r, Domain d, double* a, double* b, std::size_t n, int threads);

UlamMatrix ulam_btob(double r, Domain d, const Partition& p, int samples, const std::string& route,
                     const core::RunControl& c) {
  const int threads = c.threads > 0 ? c.threads : omp_get_max_threads();
  if (route == "kernel")
    return ulam(p, samples, [&](double* a, double* b, std::size_t n) { map_kernel(r, d, a, b, n, threads); }, c);
  return ulam(
      p, samples,
      [&](double* a, double* b, std::size_t n) {
#pragma omp parallel for schedule(static) num_threads(threads)
        for (std::size_t k = 0; k < n; ++k) {
          core::Vec3<double> u;
          chart_to_vector(d, a[k], b[k], u(0), u(1), u(2));
          const auto s = core::step<double>(u, r);
          vector_to_chart(d, s.u(0), s.u(1), s.u(2), a[k], b[k]);
        }
      },
      c);
}

double p2_rotation_angle(double r) {
  const double c = -(1 - r) * (1 - r) / (4 * r);
  return c >= -1 ? std::acos(c) : std::numeric_limits<double>::quiet_NaN();
}

// The level c = 2 - alpha^2 / r of the P2 region R = {I < c} (I the conserved quantity of P2): R exists iff c > 0
// (r > 3 - 2 sqrt 2).
namespace {
double p2_level(double r) {
  const double al = core::alpha(r);
  return 2 - al * al / r;
}
}  // namespace

// ---- Requests ---------------------------------------------------------------------------------------------
namespace {
std::string str(double v) { return fmt::format("{}", v); }
constexpr long kMaxSide = 1L << 15;  // a stated bound on N and M (2^30 boxes is far beyond memory anyway)
constexpr long kMaxSamples = 65536;

void check_size(long n, long samples) {
  // int indices of the sparse matrix: every sample's transition must be addressable.
  if (static_cast<double>(n) * static_cast<double>(samples) >= 2147483647.0)
    throw core::InvalidField("boxes", fmt::format("{} boxes x {} samples", n, samples),
                             "fewer than 2^31 samples in all (int indices of the sparse matrix)");
  // Memory: per box its row (<= samples entries of 12 bytes, counted at most 32 per box: rows of a map
  // concentrate), the chunk buffers, the decomposition and K eigenvectors (~ 400 bytes); refused up front.
  try {
    iterate::checked_bytes(static_cast<std::size_t>(n), 12 * static_cast<std::size_t>(std::min<long>(samples, 32)) + 400,
                           "boxes");
  } catch (const std::length_error& e) {
    throw core::InvalidField("boxes", fmt::format("{} boxes", n), "a partition that fits in memory (" + std::string(e.what()) + ")");
  }
}
}  // namespace

std::pair<long, long> parse_boxes(const std::string& s, const char* field) {
  const auto x = s.find('x');
  const std::string expected = fmt::format("NxM with 1 <= N, M <= {}", kMaxSide);
  if (x == std::string::npos) throw core::InvalidField(field, "'" + s + "'", expected);
  try {
    std::size_t p1 = 0, p2 = 0;
    const long n1 = std::stol(s.substr(0, x), &p1), n2 = std::stol(s.substr(x + 1), &p2);
    if (p1 != x || p2 != s.size() - x - 1 || n1 < 1 || n2 < 1 || n1 > kMaxSide || n2 > kMaxSide)
      throw core::InvalidField(field, "'" + s + "'", expected);
    return {n1, n2};
  } catch (const std::logic_error&) {
    throw core::InvalidField(field, "'" + s + "'", expected);
  }
}

Domain parse_domain(const std::string& s, const char* field) {
  if (s == "strip") return Domain::strip;
  if (s == "angles") return Domain::angles;
  throw core::InvalidField(field, "'" + s + "'", "strip or angles");
}

namespace {
// eigenvalues_min: 1 for transfer-r (its output is the spectrum), 0 for transfer (0: no spectrum, only the basins).
void check_common(double r, const std::string& boxes, const std::string& domain, int samples, int eigenvalues,
                  const std::string& route, const char* r_field, int eigenvalues_min = 1) {
  if (!(r > 0 && r < 1)) throw core::InvalidField(r_field, str(r), "a restitution coefficient in the open interval (0, 1)");
  const auto [n1, n2] = parse_boxes(boxes);
  parse_domain(domain);
  if (samples < 1 || samples > kMaxSamples)
    throw core::InvalidField("samples", std::to_string(samples), fmt::format("1..{}", kMaxSamples));
  check_size(n1 * n2, samples);
  if (eigenvalues < eigenvalues_min || eigenvalues > n1 * n2)
    throw core::InvalidField("eigenvalues", std::to_string(eigenvalues),
                             fmt::format("{}..{} (the number of boxes{})", eigenvalues_min, n1 * n2,
                                         eigenvalues_min == 0 ? "; 0: no spectrum, only the basins" : ""));
  if (route != "direct" && route != "kernel") throw core::InvalidField("route", "'" + route + "'", "direct or kernel");
}
}  // namespace

std::vector<std::string> TransferRequest::cycle_words() const {
  std::vector<std::string> words;
  for (const auto& item : cycles)
    for (std::size_t at = 0; at <= item.size();) {
      const std::size_t end = std::min(item.find(',', at), item.size());
      if (end > at) words.push_back(item.substr(at, end - at));
      at = end + 1;
    }
  return words;
}

bool TransferRequest::names_an_attractor() const {
  if (p2_level(r) > 0) return true;  // the P2 region exists
  for (const auto& w : cycle_words())
    if (patterns::analyse<double>(patterns::parse_word(w, "cycle"), r).outcome == patterns::Outcome::stable) return true;
  return false;
}

void TransferRequest::validate() const {
  check_common(r, boxes, domain, samples, eigenvalues, route, "r", 0);
  if (!(near_one > 0 && near_one < 1)) throw core::InvalidField("near-one", str(near_one), "a distance in (0, 1)");
  if (w1_range.size() != 2 || !(w1_range[0] < w1_range[1]) || !std::isfinite(w1_range[0]) || !std::isfinite(w1_range[1]))
    throw core::InvalidField("w1-range", fmt::format("{} values", w1_range.size()), "two finite numbers a < b");
  if (measure_orbits < 0 || measure_orbits > 64)
    throw core::InvalidField("measure-orbits", std::to_string(measure_orbits), "0..64 (an NxN grid; 0 skips)");
  if (measure_iterations < 100 || measure_iterations > 100000000)
    throw core::InvalidField("measure-iterations", std::to_string(measure_iterations), "100..1e8");
  if (measure_transient < 0 || measure_transient > 100000000)
    throw core::InvalidField("measure-transient", std::to_string(measure_transient), "0..1e8");
  const auto [n1, n2] = parse_boxes(boxes);
  if (tv_bins < 1 || n1 % tv_bins != 0 || n2 % tv_bins != 0)
    throw core::InvalidField("tv-bins", std::to_string(tv_bins), fmt::format("a divisor of both {} and {}", n1, n2));
  for (const auto& w : cycle_words()) patterns::parse_word(w, "cycle");
  if (eigenvalues == 0 && check_whole)
    throw core::InvalidField("eigenvalues", "0 with check-whole", "1 or more: the cross-check compares spectra");
  if (eigenvalues == 0 && !names_an_attractor())
    throw core::InvalidField("eigenvalues", fmt::format("0 at r = {} with no stable --cycle and no P2 region", str(r)),
                             "1 or more, or an attractor for the basins (0 computes only them)");
  if (measure_orbits > 0)
    iterate::checked_bytes(static_cast<std::size_t>(measure_orbits * measure_orbits) * 2 *
                               static_cast<std::size_t>(measure_iterations),
                           25, "measure-iterations");
}

void TransferRRequest::validate() const {
  check_common(r_min, boxes, domain, samples, eigenvalues, route, "r-min");
  if (!(r_max > r_min && r_max < 1)) throw core::InvalidField("r-max", str(r_max), fmt::format("a value in ({}, 1)", r_min));
  if (r_count < 1 || r_count > 100000) throw core::InvalidField("r-count", std::to_string(r_count), "1..100000");
  if (!(peripheral > 0 && peripheral < 1)) throw core::InvalidField("peripheral", str(peripheral), "a distance in (0, 1)");
}

// ---- btob transfer ----------------------------------------------------------------------------------------
namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Lebesgue measure of the request as box masses (sum 1): on the strip the rectangle w1 in [a, b] x w2 in [-1, 1]
// (uniform in w1, so a column [u0, u1] of atan(w1) weighs |[tan u0, tan u1] cap [a, b]|); uniform on the angles.
std::vector<double> lebesgue(const Partition& p, Domain d, const std::vector<double>& w1) {
  std::vector<double> m(static_cast<std::size_t>(p.size()), 0);
  const double h1 = (p.hi1 - p.lo1) / static_cast<double>(p.n1);
  for (long i1 = 0; i1 < p.n1; ++i1) {
    double w = 1.0 / static_cast<double>(p.n1);
    if (d == Domain::strip) {
      const double u0 = p.lo1 + h1 * static_cast<double>(i1), u1 = u0 + h1;
      const double t0 = i1 == 0 ? -std::numeric_limits<double>::infinity() : std::tan(u0);
      const double t1 = i1 == p.n1 - 1 ? std::numeric_limits<double>::infinity() : std::tan(u1);
      w = std::max(0.0, std::min(t1, w1[1]) - std::max(t0, w1[0])) / (w1[1] - w1[0]);
    }
    for (long i2 = 0; i2 < p.n2; ++i2) m[static_cast<std::size_t>(i1 * p.n2 + i2)] = w / static_cast<double>(p.n2);
  }
  return m;
}

// The Lebesgue measure of the P2 region R = {I < c}, c = 2 - alpha^2 / r, inside the request's rectangle
// w1 in [w1a, w1b] x w2 in [-1, 1], as a fraction of the rectangle: the chord of R at w1 has length
// sqrt(8 c - (32 r - 16 alpha^2) w1^2) / 2 (R lies within |w2| <= 1: it is tangent to w2 = +-1); midpoint rule
// on 2^17 points (the chord's square-root ends: error ~ N^-1.5, below 1e-7).
double p2_region_fraction(double r, double w1a, double w1b) {
  const double al = core::alpha(r), cm = p2_level(r), k = 32 * r - 16 * al * al;
  if (!(cm > 0 && k > 0)) return 0;
  const double half = std::sqrt(8 * cm / k), lo = std::max(w1a, -half), hi = std::min(w1b, half);
  if (!(hi > lo)) return 0;
  const long N = 1L << 17;
  const double dw = (hi - lo) / static_cast<double>(N);
  double s = 0;
  for (long i = 0; i < N; ++i) {
    const double w = lo + (static_cast<double>(i) + 0.5) * dw;
    s += std::sqrt(std::max(0.0, 8 * cm - k * w * w)) / 2;
  }
  return s * dw / (2 * (w1b - w1a));
}

// BiCGSTAB's diagonal preconditioner, polling the run's cancellation token at each application (twice per BiCGSTAB
// iteration, outside Eigen's parallel products): the same numbers as Eigen::DiagonalPreconditioner, and the
// iteration (up to 20000 sparse products) stops within one iteration of a request.
struct CancellableDiagonal : Eigen::DiagonalPreconditioner<double> {
  const core::CancelToken* cancel = nullptr;
  template <class Rhs> auto solve(const Eigen::MatrixBase<Rhs>& b) const {
    core::check_cancel(cancel);
    return Eigen::DiagonalPreconditioner<double>::solve(b);
  }
};

// Basins from the Ulam graph (see BasinInfo in transfer.hpp).
void ulam_basins(const UlamMatrix& P, const Partition& part, Domain dom, const TransferRequest& q,
                 const std::vector<double>& mu, TransferResult& res, const core::CancelToken* cancel = nullptr) {
  const long n = P.n;
  const auto sz = [](long i) { return static_cast<std::size_t>(i); };
  std::vector<std::uint32_t> target(sz(n), 0);
  for (const auto& cc : res.cycles) {
    if (cc.outcome != "stable orbit") continue;  // an unstable or absent cycle attracts nothing
    BasinInfo b;
    b.attractor = cc.word;
    b.kind = "sink";
    const auto id = static_cast<std::uint32_t>(res.basins.size() + 1);
    for (long box : cc.boxes)
      if (box >= 0 && target[sz(box)] == 0) target[sz(box)] = id, ++b.target_boxes;
    if (b.target_boxes > 0) res.basins.push_back(b);
  }
  const double al = core::alpha(q.r), cmax = p2_level(q.r);
  if (cmax > 0) {
    // The boxes inside R: all four corners (R is convex in (w1, w2), and a box of either chart is a rectangle in
    // (atan w1, w2) or (theta, phi); on the strip a box is a rectangle in (w1, w2) too, so the test is exact there).
    BasinInfo b;
    b.attractor = "P2 region";
    b.kind = "P2 invariant curves";
    const auto id = static_cast<std::uint32_t>(res.basins.size() + 1);
    const double h1 = (part.hi1 - part.lo1) / static_cast<double>(part.n1),
                 h2 = (part.hi2 - part.lo2) / static_cast<double>(part.n2);
    const auto I = [&](double a, double bb) {
      double x, y, z;
      chart_to_vector(dom, a, bb, x, y, z);
      const double s = x + z, d = x - z;
      return d > 0 ? (2 * s * s - 4 * al * s * y + 4 * q.r * y * y) / (d * d) : std::numeric_limits<double>::infinity();
    };
    for (long i1 = 0; i1 < part.n1; ++i1)
      for (long i2 = 0; i2 < part.n2; ++i2) {
        const double a0 = part.lo1 + static_cast<double>(i1) * h1, b0 = part.lo2 + static_cast<double>(i2) * h2;
        if (I(a0, b0) < cmax && I(a0 + h1, b0) < cmax && I(a0, b0 + h2) < cmax && I(a0 + h1, b0 + h2) < cmax &&
            target[sz(i1 * part.n2 + i2)] == 0)
          target[sz(i1 * part.n2 + i2)] = id, ++b.target_boxes;
      }
    if (dom == Domain::strip) b.exact = p2_region_fraction(q.r, q.w1_range[0], q.w1_range[1]);
    if (b.target_boxes > 0) res.basins.push_back(b);
  }
  if (res.basins.empty()) return;
  const std::size_t K = res.basins.size();
  // Boxes from which a target can be reached (reverse breadth-first search); the others are absorbed by none.
  std::vector<int> in_ptr(sz(n + 1), 0), in_col(P.col.size());
  for (int j : P.col) ++in_ptr[sz(j + 1)];
  for (long j = 0; j < n; ++j) in_ptr[sz(j + 1)] += in_ptr[sz(j)];
  {
    std::vector<int> fill(in_ptr.begin(), in_ptr.end() - 1);
    for (long i = 0; i < n; ++i)
      for (int e = P.row_ptr[sz(i)]; e < P.row_ptr[sz(i + 1)]; ++e)
        in_col[sz(fill[sz(P.col[sz(e)])]++)] = static_cast<int>(i);
  }
  std::vector<char> reach(sz(n), 0);
  std::vector<long> queue;
  for (long i = 0; i < n; ++i)
    if (target[sz(i)]) reach[sz(i)] = 1, queue.push_back(i);
  for (std::size_t k = 0; k < queue.size(); ++k)
    for (int e = in_ptr[sz(queue[k])]; e < in_ptr[sz(queue[k] + 1)]; ++e)
      if (!reach[sz(in_col[sz(e)])]) reach[sz(in_col[sz(e)])] = 1, queue.push_back(in_col[sz(e)]);
  // The unknowns: boxes that reach a target and are none.  A = I - Q on them, B(:, k) = P 1_k.
  std::vector<int> loc(sz(n), -1);
  int m = 0;
  for (long i = 0; i < n; ++i)
    if (reach[sz(i)] && !target[sz(i)]) loc[sz(i)] = m++;
  // A in compressed rows, built directly: P's columns are sorted in each row and loc is increasing, so the
  // columns of A's rows are sorted; the diagonal 1 is merged in at its place.
  using RowMat = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;
  std::vector<int> a_ptr{0}, a_col;
  std::vector<double> a_val;
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(m, static_cast<long>(K));
  for (long i = 0; i < n; ++i) {
    const int u = loc[sz(i)];
    if (u < 0) continue;
    bool diag = false;
    for (int e = P.row_ptr[sz(i)]; e < P.row_ptr[sz(i + 1)]; ++e) {
      const long j = P.col[sz(e)];
      if (target[sz(j)]) {
        B(u, target[sz(j)] - 1) += P.val[sz(e)];
        continue;
      }
      const int v = loc[sz(j)];
      if (v < 0) continue;
      if (!diag && v >= u) {
        diag = true;
        if (v > u)
          a_col.push_back(u), a_val.push_back(1.0);
        else {
          a_col.push_back(u), a_val.push_back(1.0 - P.val[sz(e)]);
          continue;
        }
      }
      a_col.push_back(v), a_val.push_back(-P.val[sz(e)]);
    }
    if (!diag) a_col.push_back(u), a_val.push_back(1.0);
    a_ptr.push_back(static_cast<int>(a_col.size()));
  }
  const RowMat A =
      Eigen::Map<const RowMat>(m, m, static_cast<int>(a_col.size()), a_ptr.data(), a_col.data(), a_val.data());
  res.basin_of_box.assign(sz(n), 0);
  res.basin_probability.assign(sz(n), 0);
  for (long i = 0; i < n; ++i)
    if (target[sz(i)]) res.basin_of_box[sz(i)] = target[sz(i)], res.basin_probability[sz(i)] = 1;
  double absorbed = 0;
  Eigen::BiCGSTAB<RowMat, CancellableDiagonal> solver;  // diagonal preconditioner
  solver.preconditioner().cancel = cancel;
  // 1e-12 relative residual: the fractions are reported to 1e-6 and the absorption probabilities lie in [0, 1].
  solver.setTolerance(1e-12);
  solver.setMaxIterations(20000);
  if (m > 0) solver.compute(A);
  for (std::size_t k = 0; k < K; ++k) {
    Eigen::VectorXd h = Eigen::VectorXd::Zero(m);
    if (m > 0) {
      h = solver.solve(B.col(static_cast<long>(k)));
      res.basin_iterations += solver.iterations();
      res.basin_residual = std::max(res.basin_residual, solver.error());
    }
    double f = 0;
    for (long i = 0; i < n; ++i) {
      const double p = target[sz(i)] ? (target[sz(i)] == k + 1 ? 1.0 : 0.0)
                                     : (loc[sz(i)] >= 0 ? std::clamp(h(loc[sz(i)]), 0.0, 1.0) : 0.0);
      f += mu[sz(i)] * p;
      if (!target[sz(i)] && p > res.basin_probability[sz(i)])
        res.basin_probability[sz(i)] = p, res.basin_of_box[sz(i)] = static_cast<std::uint32_t>(k + 1);
    }
    res.basins[k].fraction = f;
    res.basin_fraction.push_back(f);
    absorbed += f;
  }
  res.basin_unabsorbed = 1 - absorbed;
}

stats::Measure coarsen(const stats::Measure& m, int b1, int b2) {
  stats::Measure c = m;
  c.bins_u = b1, c.bins_v = b2;
  c.mass.assign(static_cast<std::size_t>(b1) * static_cast<std::size_t>(b2), 0);
  const int f1 = m.bins_u / b1, f2 = m.bins_v / b2;
  for (int i = 0; i < m.bins_u; ++i)
    for (int j = 0; j < m.bins_v; ++j)
      c.mass[static_cast<std::size_t>(i / f1) * b2 + j / f2] += m.mass[static_cast<std::size_t>(i) * m.bins_v + j];
  return c;
}
}  // namespace

namespace {
// The periodic attractor a closed class holds, named by its symbols: from the centre of the class's first box,
// 20000 steps of P_r (the state renormalised each step); the eventual period (<= 1024) of the last 4096 symbols
// gives the word, canonical and in the paper's notation.  "" when the symbols are not periodic (chaos) or the
// word is not a stable periodic orbit at r (the invariant curves of P2 repeat the symbol 2 but are no cycle).
std::string class_attractor(const Partition& part, Domain dom, const Decomposition& d, std::uint32_t cls, double r) {
  long box = -1;
  for (std::size_t i = 0; i < d.class_of_box.size() && box < 0; ++i)
    if (d.class_of_box[i] == cls) box = static_cast<long>(i);
  if (box < 0) return "";
  const double a = part.lo1 + (static_cast<double>(box / part.n2) + 0.5) * (part.hi1 - part.lo1) / static_cast<double>(part.n1);
  const double b = part.lo2 + (static_cast<double>(box % part.n2) + 0.5) * (part.hi2 - part.lo2) / static_cast<double>(part.n2);
  core::Vec3<double> u;
  chart_to_vector(dom, a, b, u(0), u(1), u(2));
  constexpr long steps = 20000, kept = 4096;
  std::vector<std::uint8_t> sym;
  for (long k = 0; k < steps; ++k) {
    const auto st = core::step<double>(u, r);
    u = st.u / st.u.norm();
    if (k >= steps - kept) sym.push_back(static_cast<std::uint8_t>(st.symbol));
  }
  const int p = patterns::eventual_period(sym.data(), kept, 1024);
  if (p == 0) return "";
  const patterns::Word w = patterns::canonical(patterns::Word{std::vector<std::uint8_t>(sym.end() - p, sym.end())});
  if (patterns::analyse<double>(w, r).outcome != patterns::Outcome::stable) return "";
  return patterns::to_paper(w);
}
}  // namespace

TransferResult run(const TransferRequest& q, const core::RunControl& c) {
  q.validate();
  const auto t0 = std::chrono::steady_clock::now();
  TransferResult res;
  res.request = q;
  const Domain dom = parse_domain(q.domain);
  const auto [n1, n2] = parse_boxes(q.boxes);
  res.part = domain_partition(dom, n1, n2);
  const long n = res.part.size();

  const UlamMatrix P = ulam_btob(q.r, dom, res.part, q.samples, q.route, c);
  res.nnz = P.nnz();
  res.lost = P.lost;
  res.matrix_bytes = P.col.size() * sizeof(int) + P.val.size() * sizeof(double) + P.row_ptr.size() * sizeof(int);
  res.seconds_matrix = seconds_since(t0);
  c.check_cancelled();

  const auto t1 = std::chrono::steady_clock::now();
  const Decomposition d = decompose(P);
  res.classes = d.classes;
  const bool spectrum = q.spectrum();
  const auto pairs = spectrum ? leading_eigenpairs(P, d, q.eigenvalues, true, 600, c.cancel) : std::vector<Eigenpair>{};
  for (const auto& e : pairs) {
    res.eig_re.push_back(e.value.real());
    res.eig_im.push_back(e.value.imag());
    res.eig_block.push_back(e.block);
    if (std::abs(e.value - 1.0) <= q.near_one) ++res.near_one_count;
  }
  if (q.check_whole)
    for (const auto& v : leading_eigenvalues_whole(P, q.eigenvalues, c.cancel)) {
    res.whole_re.push_back(v.real());
    res.whole_im.push_back(v.imag());
  }
  res.seconds_spectrum = seconds_since(t1);
  c.check_cancelled();

  // Components: the closed classes, then the almost-invariant transient components (a real eigenvalue of the
  // transient block within near_one of 1: its eigenvector's largest entry names the strongly connected
  // component, which is made absorbing for the projection).
  std::vector<std::vector<double>> dens;  // per component: its density over all boxes (for the cycle checks)
  // Without a spectrum (eigenvalues 0) there are no components, no density and no eigenvector: only the basins.
  if (spectrum) {
    // Absorbers: the closed classes, then the almost-invariant transient components (a real eigenvalue of the
    // transient block within near_one of 1: its eigenvector's largest entry names the strongly connected
    // component, made absorbing for the projection).  absorber_of_box: 0 none, a = absorber a.
    struct Absorber {
      int block = 0;  // class c >= 1, or -s - 1 (transient strongly connected component s)
      double rho = 1;
      std::vector<long> boxes;
      std::vector<double> density;  // on `boxes`, sum 1
    };
    std::vector<Absorber> absorbers;
    std::vector<std::uint32_t> absorber_of_box(static_cast<std::size_t>(n), 0);
    for (int k = 1; k <= res.closed_classes(); ++k) {
      Absorber ab;
      ab.block = k;
      for (long i = 0; i < n; ++i)
        if (d.class_of_box[static_cast<std::size_t>(i)] == static_cast<std::uint32_t>(k)) {
          ab.boxes.push_back(i);
          absorber_of_box[static_cast<std::size_t>(i)] = static_cast<std::uint32_t>(absorbers.size() + 1);
        }
      // The class's eigenvalue-1 vector among the leading pairs (else its own solve).
      const Eigenpair* best = nullptr;
      for (const auto& e : pairs)
        if (e.block == k && std::abs(e.value - 1.0) < 1e-8 && (!best || std::abs(e.value - 1.0) < std::abs(best->value - 1.0))) best = &e;
      std::vector<double> full;
      if (best) {
        full.assign(static_cast<std::size_t>(n), 0);
        double sum = 0, t = 0;
        for (long i : ab.boxes) sum += best->vector[static_cast<std::size_t>(i)].real();
        for (long i : ab.boxes) t += full[static_cast<std::size_t>(i)] = std::max(0.0, best->vector[static_cast<std::size_t>(i)].real() / sum);
        for (auto& x : full) x /= t;
      } else {
        full = class_density(P, d, k, c.cancel);
      }
      for (long i : ab.boxes) ab.density.push_back(full[static_cast<std::size_t>(i)]);
      absorbers.push_back(std::move(ab));
    }
    for (const auto& e : pairs) {
      if (e.block != 0 || std::fabs(e.value.imag()) > 1e-12 || std::abs(e.value - 1.0) > q.near_one) continue;
      long arg = 0;
      for (long i = 1; i < n; ++i)
        if (std::abs(e.vector[static_cast<std::size_t>(i)]) > std::abs(e.vector[static_cast<std::size_t>(arg)])) arg = i;
      const int s = d.scc[static_cast<std::size_t>(arg)];
      if (absorber_of_box[static_cast<std::size_t>(arg)] != 0) continue;  // that component is already one
      Absorber ab;
      ab.block = -s - 1;
      ab.rho = e.value.real();
      double t = 0;
      for (long i = 0; i < n; ++i)
        if (d.scc[static_cast<std::size_t>(i)] == s) {
          ab.boxes.push_back(i);
          ab.density.push_back(std::abs(e.vector[static_cast<std::size_t>(i)]));
          t += ab.density.back();
          absorber_of_box[static_cast<std::size_t>(i)] = static_cast<std::uint32_t>(absorbers.size() + 1);
        }
      for (auto& x : ab.density) x /= t;
      absorbers.push_back(std::move(ab));
    }
    // Projection of Lebesgue measure, step 1: mass starting in an absorber stays there; the rest flows under the
    // chain with the absorbers absorbing until less than 1e-13 is left (or 10^5 steps).  entry[j]: the mass that
    // starts in or enters an absorber at box j.
    std::vector<double> entry(static_cast<std::size_t>(n), 0);
    {
      const std::vector<double> mu = lebesgue(res.part, dom, q.w1_range);
      std::vector<double> x(static_cast<std::size_t>(n), 0), y(static_cast<std::size_t>(n), 0);
      for (long i = 0; i < n; ++i) {
        if (absorber_of_box[static_cast<std::size_t>(i)]) entry[static_cast<std::size_t>(i)] += mu[static_cast<std::size_t>(i)];
        else x[static_cast<std::size_t>(i)] = mu[static_cast<std::size_t>(i)];
      }
      double left = 0;
      for (int it = 0; it < 100000; ++it) {
        left = 0;
        for (long i = 0; i < n; ++i) {
          const double xi = x[static_cast<std::size_t>(i)];
          if (xi == 0) continue;
          for (int e = P.row_ptr[static_cast<std::size_t>(i)]; e < P.row_ptr[static_cast<std::size_t>(i + 1)]; ++e) {
            const int j = P.col[static_cast<std::size_t>(e)];
            const double m = xi * P.val[static_cast<std::size_t>(e)];
            if (absorber_of_box[static_cast<std::size_t>(j)]) entry[static_cast<std::size_t>(j)] += m;
            else y[static_cast<std::size_t>(j)] += m;
          }
        }
        std::swap(x, y);
        std::fill(y.begin(), y.end(), 0.0);
        for (double v : x) left += v;
        if (left < 1e-13) break;
        if (it % 64 == 0) c.check_cancelled();
      }
      res.unabsorbed = left;
    }
    // Step 2: a closed class with several real eigenvalues in (1 - near_one, 1] holds as many almost-invariant
    // sets (the resolution merged attractors that the map keeps apart, through boxes straddling their basins'
    // boundaries): PCCA+ on its right eigenvectors (P h = lambda h) gives memberships chi; a part receives the mass
    // entering the class weighted by chi, and its density is the class's density weighted by chi.
    res.component_of_box.assign(static_cast<std::size_t>(n), 0);
    res.density.assign(static_cast<std::size_t>(n), 0);
    const double h1 = (res.part.hi1 - res.part.lo1) / static_cast<double>(n1), h2 = (res.part.hi2 - res.part.lo2) / static_cast<double>(n2);
    for (const auto& ab : absorbers) {
      std::vector<double> values;  // the near-one real eigenvalues of this absorber (classes only)
      if (ab.block > 0)
        for (const auto& e : pairs)
          if (e.block == ab.block && std::fabs(e.value.imag()) < 1e-12 && e.value.real() > 1 - q.near_one)
            values.push_back(e.value.real());
      Eigen::MatrixXd chi = Eigen::MatrixXd::Ones(static_cast<long>(ab.boxes.size()), 1);
      if (values.size() >= 2) {
        const ColMat A = block_transpose(P, ab.boxes);
        const ColMat Q = A.transpose();
        const int p = static_cast<int>(values.size());
        auto right = block_eigenpairs(Q, p + 2, true, 600, Spectra::SortRule::LargestReal, c.cancel);
        std::stable_sort(right.begin(), right.end(), [](const LocalPair& x, const LocalPair& y) { return x.value.real() > y.value.real(); });
        Eigen::MatrixXd H(static_cast<long>(ab.boxes.size()), p);
        int got = 0;
        for (const auto& r : right)
          if (got < p && std::fabs(r.value.imag()) < 1e-12) H.col(got++) = r.vector.real();
        if (got == p) chi = pcca(H);
      }
      for (long part = 0; part < chi.cols(); ++part) {
        ComponentInfo ci;
        ci.block = ab.block;
        ci.rho = ab.rho;
        ci.period = ab.block > 0 && chi.cols() == 1 ? d.classes[static_cast<std::size_t>(ab.block - 1)].period : 1;
        double frac = 0, t = 0;
        std::vector<double> w(ab.boxes.size());
        for (std::size_t j = 0; j < ab.boxes.size(); ++j) {
          const double x = std::clamp(chi(static_cast<long>(j), part), 0.0, 1.0);  // PCCA+ rows may overshoot [0, 1] slightly
          frac += entry[static_cast<std::size_t>(ab.boxes[j])] * x;
          t += w[j] = ab.density[j] * x;
        }
        ci.lebesgue = frac;
        if (chi.cols() > 1) {
          // Metastability of the part: the chance of staying in it for one step, averaged over its density
          // (sum_i w_i sum_j P_ij chi_j / sum_i w_i, chi extended by 0 outside the class).
          std::vector<double> chi_full(static_cast<std::size_t>(n), 0);
          for (std::size_t j = 0; j < ab.boxes.size(); ++j)
            chi_full[static_cast<std::size_t>(ab.boxes[j])] = std::clamp(chi(static_cast<long>(j), part), 0.0, 1.0);
          double stay = 0;
          for (std::size_t j = 0; j < ab.boxes.size(); ++j) {
            const long i = ab.boxes[j];
            double pc = 0;
            for (int e = P.row_ptr[static_cast<std::size_t>(i)]; e < P.row_ptr[static_cast<std::size_t>(i + 1)]; ++e)
              pc += P.val[static_cast<std::size_t>(e)] * chi_full[static_cast<std::size_t>(P.col[static_cast<std::size_t>(e)])];
            stay += w[j] * pc;
          }
          ci.rho = t > 0 ? stay / t : 0;
        }
        double ca = 0, cb = 0;
        std::vector<double> full(static_cast<std::size_t>(n), 0);
        for (std::size_t j = 0; j < ab.boxes.size(); ++j) {
          const long i = ab.boxes[j];
          const double wn = t > 0 ? w[j] / t : 0;
          full[static_cast<std::size_t>(i)] = wn;
          res.density[static_cast<std::size_t>(i)] += frac * wn;
          ca += wn * (res.part.lo1 + (static_cast<double>(i / n2) + 0.5) * h1);
          cb += wn * (res.part.lo2 + (static_cast<double>(i % n2) + 0.5) * h2);
          long arg = 0;
          for (long k = 1; k < chi.cols(); ++k)
            if (chi(static_cast<long>(j), k) > chi(static_cast<long>(j), arg)) arg = k;
          ci.boxes += arg == part;
          if (arg == part) res.component_of_box[static_cast<std::size_t>(i)] = static_cast<std::uint32_t>(res.components.size() + 1);
        }
        ci.centre = {ca, cb};
        res.components.push_back(ci);
        dens.push_back(std::move(full));
      }
    }
    // Almost-invariant sets: the leading real eigenvalue in (0, 1 - 1e-9) and the sign structure of its vector.
    for (const auto& e : pairs) {
      if (std::fabs(e.value.imag()) > 1e-12 || !(e.value.real() > 0 && e.value.real() < 1 - 1e-9)) continue;
      res.second_value = e.value.real();
      res.second_block = e.block;
      res.second.assign(static_cast<std::size_t>(n), 0);
      double mx = 0, pos = 0, neg = 0;
      for (long i = 0; i < n; ++i) mx = std::max(mx, std::fabs(e.vector[static_cast<std::size_t>(i)].real()));
      for (long i = 0; i < n; ++i) {
        const double v = mx > 0 ? e.vector[static_cast<std::size_t>(i)].real() / mx : 0;
        res.second[static_cast<std::size_t>(i)] = v;
        // Entries below 1e-9 of the maximum are round-off of the eigensolver: no sign.
        if (v > 1e-9) pos += v, ++res.second_positive_boxes;
        else if (v < -1e-9) neg -= v, ++res.second_negative_boxes;
      }
      if (pos + neg > 0) res.second_positive_mass = pos / (pos + neg), res.second_negative_mass = neg / (pos + neg);
      break;
    }
  }
  // Cycles: the boxes of the exact periodic points and the mass around them; without --cycle, the stable
  // periodic attractors the closed classes hold (class_attractor), each once.
  std::vector<std::string> words = q.cycle_words();
  if (q.cycles.empty())
    for (std::uint32_t k = 1; k <= d.classes.size(); ++k) {
      const std::string w = class_attractor(res.part, dom, d, k, q.r);
      if (!w.empty() && std::find(res.attractors_found.begin(), res.attractors_found.end(), w) == res.attractors_found.end())
        res.attractors_found.push_back(w);
    }
  if (q.cycles.empty()) words = res.attractors_found;
  for (const auto& w : words) {
    CycleCheck cc;
    cc.word = w;
    const auto v = patterns::analyse<double>(patterns::parse_word(w, "cycle"), q.r);
    cc.outcome = patterns::outcome_name(v.outcome);
    std::vector<char> in(static_cast<std::size_t>(n), 0), nb(static_cast<std::size_t>(n), 0);
    for (const auto& u : v.orbit) {
      double a, b;
      vector_to_chart(dom, u(0), u(1), u(2), a, b);
      const long box = res.part.locate(a, b);
      cc.boxes.push_back(box);
      cc.a.push_back(a);
      cc.b.push_back(b);
      if (box < 0) continue;
      in[static_cast<std::size_t>(box)] = 1;
      const long i1 = box / n2, i2 = box % n2;
      for (long d1 = -1; d1 <= 1; ++d1)
        for (long d2 = -1; d2 <= 1; ++d2)
          if (i1 + d1 >= 0 && i1 + d1 < n1 && i2 + d2 >= 0 && i2 + d2 < n2)
            nb[static_cast<std::size_t>((i1 + d1) * n2 + i2 + d2)] = 1;
    }
    if (!spectrum) {  // no density: the masses and radii are undefined (empty cells of cycles.csv)
      cc.mass_boxes = cc.mass_neighbourhood = cc.component_share = std::numeric_limits<double>::quiet_NaN();
      // The closed class holding the cycle: a closed class is invariant, so its stationary density (eigenvalue 1) is
      // supported on it; one class per sink is one eigenvalue 1 per sink.
      std::uint32_t cls = 0;
      bool one = true;
      for (long b : cc.boxes) {
        if (b < 0) continue;
        const std::uint32_t k = d.class_of_box[static_cast<std::size_t>(b)];
        if (k == 0 || (cls != 0 && k != cls)) one = false;
        cls = k;
      }
      cc.component = one ? static_cast<int>(cls) : 0;
      res.cycles.push_back(std::move(cc));
      continue;
    }
    double tot = 0;
    for (double x : res.density) tot += x;
    for (long i = 0; i < n; ++i) {
      if (in[static_cast<std::size_t>(i)]) cc.mass_boxes += res.density[static_cast<std::size_t>(i)] / tot;
      if (nb[static_cast<std::size_t>(i)]) cc.mass_neighbourhood += res.density[static_cast<std::size_t>(i)] / tot;
    }
    for (std::size_t k = 0; k < dens.size(); ++k) {
      double m = 0;
      for (long i = 0; i < n; ++i)
        if (nb[static_cast<std::size_t>(i)]) m += dens[k][static_cast<std::size_t>(i)];
      if (m > cc.component_share) cc.component_share = m, cc.component = static_cast<int>(k + 1);
    }
    // Chebyshev distance (boxes) of every box to the nearest cycle box; mass by distance.
    const auto radius = [&](const std::vector<double>& w) -> long {
      std::vector<double> by(static_cast<std::size_t>(std::max(n1, n2) + 1), 0);
      double tw = 0;
      for (long i = 0; i < n; ++i) {
        if (w[static_cast<std::size_t>(i)] == 0) continue;
        long dist = std::max(n1, n2);
        for (long b : cc.boxes)
          if (b >= 0) dist = std::min(dist, std::max(std::labs(i / n2 - b / n2), std::labs(i % n2 - b % n2)));
        by[static_cast<std::size_t>(dist)] += w[static_cast<std::size_t>(i)];
        tw += w[static_cast<std::size_t>(i)];
      }
      double acc = 0;
      for (std::size_t k = 0; k < by.size(); ++k)
        if ((acc += by[k]) >= 0.99 * tw) return static_cast<long>(k);
      return -1;
    };
    if (std::any_of(cc.boxes.begin(), cc.boxes.end(), [](long b) { return b >= 0; })) {
      cc.radius99 = radius(res.density);
      if (cc.component > 0) cc.radius99_component = radius(dens[static_cast<std::size_t>(cc.component - 1)]);
    }
    res.cycles.push_back(std::move(cc));
  }
  // Basins from the Ulam graph: absorption into the named attractors, weighted by Lebesgue measure.
  {
    const auto tb = std::chrono::steady_clock::now();
    ulam_basins(P, res.part, dom, q, lebesgue(res.part, dom, q.w1_range), res, c.cancel);
    res.seconds_basins = seconds_since(tb);
    c.check_cancelled();
  }
  // The empirical measure of `btob measure` (stats module) from an NxN grid of the same Lebesgue rectangle.
  if (q.measure_orbits > 0 && spectrum) {  // (nothing to compare it with without the density)
    const int g = q.measure_orbits;
    std::vector<core::Vec3<double>> u0;
    if (dom == Domain::strip) u0 = iterate::strip_grid(g, g, q.w1_range[0], q.w1_range[1]);
    else
      for (int i = 0; i < g; ++i)
        for (int j = 0; j < g; ++j)
          u0.push_back(core::from_angles<double>(std::numbers::pi / 2 * (i + 0.5) / g, std::numbers::pi * (j + 0.5) / g));
    const auto series = stats::orbit_series(q.r, u0, q.measure_transient, q.measure_iterations, c.threads);
    const stats::Chart chart = dom == Domain::strip ? stats::Chart::strip : stats::Chart::angles;
    // Each orbit weighs its initial condition's share of Lebesgue measure (equal cells: equal weights).
    stats::Measure emp;
    for (std::size_t o = 0; o < series.size(); ++o) {
      const auto m = stats::empirical_measure(series[o], chart, static_cast<int>(n1), static_cast<int>(n2));
      if (o == 0) emp = m, std::fill(emp.mass.begin(), emp.mass.end(), 0.0), emp.outside = 0, emp.points = 0;
      for (std::size_t i = 0; i < m.mass.size(); ++i) emp.mass[i] += m.mass[i] / static_cast<double>(series.size());
      emp.outside += m.outside / static_cast<double>(series.size());
      emp.points += m.points;
    }
    stats::Measure ul = emp;
    double tot = 0;
    for (double v : res.density) tot += v;
    for (std::size_t i = 0; i < ul.mass.size(); ++i) ul.mass[i] = res.density[i] / tot;
    ul.outside = 0;
    res.tv_boxes = stats::total_variation(ul, emp);
    res.tv_coarse = stats::total_variation(coarsen(ul, q.tv_bins, q.tv_bins), coarsen(emp, q.tv_bins, q.tv_bins));
    res.measure_points = emp.points;
  }
  // The arrays of the HDF5 file: "second" all 0 when there is no such eigenvalue, the Lebesgue fractions, the
  // (a, b) of every cycle point.
  if (res.second.empty() && spectrum) res.second.assign(res.density.size(), 0);
  for (const auto& ci : res.components) res.lebesgue.push_back(ci.lebesgue);
  for (const auto& cc : res.cycles)
    for (std::size_t k = 0; k < cc.a.size(); ++k) res.cycle_points.push_back(cc.a[k]), res.cycle_points.push_back(cc.b[k]);
  res.seconds_total = seconds_since(t0);
  return res;
}

// ---- btob transfer-r --------------------------------------------------------------------------------------
TransferRResult run(const TransferRRequest& q, const core::RunControl& c) {
  q.validate();
  const auto t0 = std::chrono::steady_clock::now();
  TransferRResult res;
  res.request = q;
  res.r = iterate::linspace_r(q.r_min, q.r_max, q.r_count);
  res.K = q.eigenvalues;
  const Domain dom = parse_domain(q.domain);
  const auto [n1, n2] = parse_boxes(q.boxes);
  const Partition part = domain_partition(dom, n1, n2);
  const std::size_t R = res.r.size(), K = static_cast<std::size_t>(q.eigenvalues);
  res.re.assign(R * K, std::numeric_limits<double>::quiet_NaN());
  res.im = res.re;
  core::RunControl inner = c;
  inner.progress = nullptr;
  for (std::size_t ir = 0; ir < R; ++ir) {
    c.check_cancelled();
    const UlamMatrix P = ulam_btob(res.r[ir], dom, part, q.samples, q.route, inner);
    const Decomposition d = decompose(P);
    const auto pairs = leading_eigenpairs(P, d, q.eigenvalues, false, 600, c.cancel);
    int per = 0;
    double min_per = 2, max_rest = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      res.re[ir * K + k] = pairs[k].value.real();
      res.im[ir * K + k] = pairs[k].value.imag();
      const double m = std::abs(pairs[k].value);
      if (1 - m < q.peripheral) ++per, min_per = std::min(min_per, m);
      else if (!(max_rest >= m)) max_rest = m;
    }
    res.peripheral_count.push_back(static_cast<std::uint32_t>(per));
    res.closed_classes.push_back(static_cast<std::uint32_t>(d.classes.size()));
    res.rest_modulus.push_back(max_rest);
    res.gap.push_back(per > 0 && std::isfinite(max_rest) ? min_per - max_rest : std::numeric_limits<double>::quiet_NaN());
    if (c.progress) c.progress->update(ir + 1, R);
  }
  for (int n = 1; n <= 12; ++n) {
    res.window_lower.push_back(static_cast<double>(windows::window_lower_bound(n, 12)));
    res.window_upper.push_back(n >= 2 ? static_cast<double>(windows::r_crit2(n, 20)) : std::numeric_limits<double>::quiet_NaN());
  }
  res.seconds = seconds_since(t0);
  return res;
}

}  // namespace btob::transfer
