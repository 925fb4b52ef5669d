// SPDX-License-Identifier: GPL-3.0-or-later
// The transfer operator of P^_r by Ulam's method (Section 8): a box partition of the strip or the angles,
// the sparse matrix of transition probabilities, its ergodic decomposition (closed classes = the ergodic
// components the resolution sees), its leading spectrum (Spectra), the invariant densities and the projection
// of Lebesgue measure on them (basin fractions), and the peripheral spectrum across r.
#pragma once

#include "core/request.hpp"
#include "core/result.hpp"
#include "core/work.hpp"

#include <complex>
#include <cstdint>
#include <string>
#include <vector>

namespace btob::transfer {

// Conventions.
//  * Charts (the ones of stats::empirical_measure, so that both measures live on the same bins):
//      strip:  (a, b) = (atan(w1), w2) = (atan2(y, x - z), (x + z) / (x - z)) in [-pi/2, pi/2] x [-1, 1]
//              (eq. 5.5 with the unbounded w1 folded by atan);
//      angles: (a, b) = (theta, phi) in [0, pi/2] x [0, pi]  (Sections 4 and 5.1).
//  * Boxes: n1 columns in a times n2 rows in b, box index i1 * n2 + i2 (stats::Measure::mass's layout).
//  * Ulam's matrix P is row-stochastic: P(i, j) = (samples of box i whose image lies in box j) / (samples of
//    box i whose image is a finite point of the chart).  A density (mass per box, a row vector) evolves as
//    m -> m P; invariant densities are eigenvectors of P^T for the eigenvalue 1.
//  * Samples: S points per box on the R2 low-discrepancy sequence (Roberts 2018; any S, deterministic).

// A box partition of the rectangle [lo1, hi1] x [lo2, hi2].
struct Partition {
  long n1 = 0, n2 = 0;
  double lo1 = 0, hi1 = 1, lo2 = 0, hi2 = 1;
  long size() const { return n1 * n2; }
  // Box of the point (a, b), or -1 when it is outside the rectangle or not finite (hi edges: last box).
  long locate(double a, double b) const;
  double area() const { return (hi1 - lo1) * (hi2 - lo2) / static_cast<double>(size()); }  // of one box
};

// The sample offsets (in [0, 1)^2, fractions of a box) shared by every box.
std::vector<std::pair<double, double>> sample_offsets(int samples);

// Ulam's matrix in compressed rows (Eigen::Map-able as a RowMajor SparseMatrix<double, int>).
struct UlamMatrix {
  long n = 0;
  std::vector<int> row_ptr, col;  // row_ptr has n + 1 entries
  std::vector<double> val;
  std::uint64_t lost = 0;  // samples whose image was outside the chart or not finite
  long nnz() const { return static_cast<long>(col.size()); }
};

// Ulam's matrix of the map f on the partition: f(a, b, n) replaces the n points (a[k], b[k]) by their images
// in place (it may run OpenMP itself).  The generic route: the same code serves the b-to-b map and the
// validation maps with known invariant densities (transfer_impl.hpp).
//   template <class BatchMap> UlamMatrix ulam(const Partition&, int samples, BatchMap&& f, const core::RunControl&);

// Closed classes of P (the strongly connected components that no transition leaves): each carries exactly
// one invariant density (eigenvalue 1 is as many-fold as there are classes) and, if its period is d, the
// d-th roots of unity.
struct ClassInfo {
  long boxes = 0;
  int period = 1;
};
struct Decomposition {
  std::vector<int> scc;  // strongly connected component of each box, 0-based
  int components = 0;
  std::vector<std::uint32_t> class_of_box;  // 0: transient, c >= 1: closed class c
  std::vector<ClassInfo> classes;           // classes[c - 1]
};
Decomposition decompose(const UlamMatrix& P);

// The spectrum of P: P is block triangular in its strongly connected components, so its spectrum is the union
// of the spectra of the closed classes (each one block) and of the transient block (every other box).  Each
// block goes to Eigen's dense solver when small (<= dense_max boxes), else to Spectra::GenEigsSolver
// (implicitly restarted Arnoldi, SparseGenMatProd, largest magnitude).  Eigenvectors are those of P^T
// (densities), on the boxes of their block, zero elsewhere.
//
// The default dense_max is not a speed crossover (Arnoldi on a closed class of a few hundred boxes is two orders
// of magnitude faster than the dense solve): it bounds the price paid for robustness.  The dense solve returns every
// eigenvalue with nothing to converge (no failure on the clustered peripheral eigenvalues of a periodic class, where
// Arnoldi's small Schur step can fail, and no k + 3 <= m condition), at ~10 m^3 flops and 8 m^2 bytes: seconds and
// 2.9 MB at 600 boxes, where the m^3 growth makes each further doubling of the block cost eight times more.
constexpr long kDenseMaxBoxes = 600;
struct Eigenpair {
  std::complex<double> value;
  int block = 0;                             // 0: transient block, c >= 1: closed class c
  std::vector<std::complex<double>> vector;  // n entries
};
// `cancel` (here and below): polled before every matrix-vector product of the Arnoldi iteration; throws
// core::Cancelled when set.
std::vector<Eigenpair> leading_eigenpairs(const UlamMatrix& P, const Decomposition& d, int k, bool vectors,
                                          long dense_max = kDenseMaxBoxes, const core::CancelToken* cancel = nullptr);
// Spectra on the whole matrix (the cross-check of the block route; unreliable on repeated eigenvalues).
std::vector<std::complex<double>> leading_eigenvalues_whole(const UlamMatrix& P, int k,
                                                            const core::CancelToken* cancel = nullptr);

// The invariant density of closed class c (mass per box, sum 1, zero outside the class).
std::vector<double> class_density(const UlamMatrix& P, const Decomposition& d, int c,
                                  const core::CancelToken* cancel = nullptr);

// ---- The b-to-b map --------------------------------------------------------------------------------------
enum class Domain { strip, angles };
Partition domain_partition(Domain d, long n1, long n2);
// Chart point -> unit vector in Q, and back (the formulas of the conventions).
void chart_to_vector(Domain d, double a, double b, double& x, double& y, double& z);
void vector_to_chart(Domain d, double x, double y, double z, double& a, double& b);
// Ulam's matrix of P^_r: route "direct" (core::step per sample, OpenMP over samples) or "kernel"
// (iterate::run with a recorder of the state after one step, the batched SIMD kernel).
UlamMatrix ulam_btob(double r, Domain d, const Partition& p, int samples, const std::string& route,
                     const core::RunControl& c = {});

// The P2 rotation angle beta of the invariant curves of Section 5: cos(beta) = -(1 - r)^2 / (4 r), defined when
// that is >= -1 (r >= 3 - 2 sqrt 2); NaN below.
double p2_rotation_angle(double r);

// ---- btob transfer ----------------------------------------------------------------------------------------
struct TransferRequest {
  double r = 0.15;                // restitution coefficient, (0, 1)
  std::string boxes = "256x256";  // NxM boxes (N in the first chart coordinate), N, M >= 1
  std::string domain = "strip";   // strip | angles
  int samples = 64;               // sample points per box, 1..65536
  // K leading eigenvalues reported, 1 .. number of boxes; 0: no spectrum, only the basins from the Ulam graph (the
  // outputs that need eigenvectors are left out: spectrum.csv, components.csv, the density, the Lebesgue projection,
  // the cycles' masses, the TV distance); allowed when the request names an attractor and check_whole is off.
  int eigenvalues = 16;
  std::string route = "direct";  // direct | kernel (how sample images are computed)
  double near_one = 1e-2;        // distance to 1 of the eigenvalues counted as ergodic components
  // Lebesgue measure projected on the eigenvectors: the rectangle w1 in [a, b] x w2 in [-1, 1] of the strip
  // (the measure of `btob basins --grid strip`); the whole chart for angles.
  std::vector<double> w1_range{-2, 2};
  int measure_orbits = 16;          // empirical measure: an NxN strip grid of initial conditions (0: skip)
  long measure_iterations = 20000;  // points per orbit after the transient
  long measure_transient = 1000;
  int tv_bins = 64;  // TV distance also on a coarser tv_bins x tv_bins grid (divides N and M)
  // Periodic words whose exact cycles (patterns::analyse) are located in the boxes: the density's mass on
  // their boxes and on the 3x3 neighbourhoods of those boxes, and the component hosting each.
  std::vector<std::string> cycles;
  bool check_whole = false;  // also run Spectra on the whole matrix (cross-check; doubles the time)
  // The words of `cycles`, in order: an item holding commas gives several (--cycle 1322,3122,132^3312^3).
  std::vector<std::string> cycle_words() const;
  // Whether the basins have a target: the P2 region exists at r (r > 3 - 2 sqrt 2) or a cycle word is stable at r.
  bool names_an_attractor() const;
  bool spectrum() const { return eigenvalues > 0; }
  void validate() const;  // throws core::InvalidField
  template <class V> void fields(V&& v) {
    v("r", r, "restitution coefficient in (0, 1)");
    v("boxes", boxes, "NxM boxes of the chart, N, M >= 1");
    v("domain", domain, "strip (atan w1, w2) or angles (theta, phi)");
    v("samples", samples, "sample points per box, 1..65536");
    v("eigenvalues", eigenvalues, "K leading eigenvalues, 1..boxes; 0: no spectrum, only the basins");
    v("route", route, "direct (core step) or kernel (batched SIMD kernel)");
    v("near-one", near_one, "eigenvalues within this distance of 1 count as components, (0, 1)");
    v("w1-range", w1_range, "w1 range a,b of the Lebesgue rectangle projected on the eigenvectors");
    v("measure-orbits", measure_orbits, "NxN strip grid of orbits for the empirical measure, 0..64 (0: skip)");
    v("measure-iterations", measure_iterations, "points per orbit of the empirical measure, >= 100");
    v("measure-transient", measure_transient, "transient of the empirical measure, >= 0");
    v("tv-bins", tv_bins, "coarse grid of the TV distance, divides N and M");
    v("cycle", cycles, "periodic words (e.g. 1133) whose exact cycles are located in the boxes");
    v("check-whole", check_whole, "also run Spectra on the whole matrix (cross-check of the block route)");
  }
};

struct ComponentInfo {
  int block = 0;  // closed class c >= 1, or -s - 1 for an almost-invariant transient component s
  long boxes = 0;
  int period = 1;
  // Mass kept per step: 1 for a whole closed class; the eigenvalue (quasi-stationary rate) of an almost-invariant
  // transient component; for a PCCA+ part of a class, its metastability sum_i w_i (P chi)_i / sum_i w_i.
  double rho = 1;
  double lebesgue = 0;         // projection of Lebesgue measure: fraction of it that ends in this component
  std::vector<double> centre;  // mass-weighted chart centre (a, b)
};

struct CycleCheck {
  std::string word;               // as given
  std::string outcome;            // patterns::analyse at r: stable, unstable or none
  std::vector<long> boxes;        // the boxes of its points (one per point of the cycle)
  std::vector<double> a, b;       // chart coordinates of its points
  double mass_boxes = 0;          // density mass on those boxes (a box counted once)
  double mass_neighbourhood = 0;  // on their 3x3 neighbourhoods
  // Smallest R such that the boxes within Chebyshev distance R (in boxes) of the cycle's boxes hold 99% of the
  // density (of the whole density, and of the hosting component's density): for a sink, Ulam's smearing spreads
  // its mass over a number of boxes that does not shrink with h, so R stays bounded and R h -> 0.
  long radius99 = -1, radius99_component = -1;
  // Component (1-based) whose density puts most mass on the neighbourhoods; without a spectrum, the closed class
  // that holds every box of the cycle (0: none, or boxes in several or in the transient block).
  int component = 0;
  double component_share = 0;  // that component's own density mass on the neighbourhoods
};

// Basins from the Ulam graph: the chain made absorbing on the boxes of the attractors the request names (each
// stable --cycle: the boxes of its exact points; for r > 3 - 2 sqrt 2 on the strip, the P2 region
// R = {I < 2 - alpha^2 / r}, I = 2 w2^2 - 4 alpha w1 w2 + 4 r w1^2 the conserved quantity of P2 (Section 5.2):
// the largest invariant ellipse inside the P2 branch, tangent to its four edges, so R is forward invariant and
// every orbit entering it stays on an invariant curve; its boxes are those inside it).  The absorption
// probability h_k(i) of box i into target k solves (I - Q) h_k = P 1_k on the boxes that reach a target (Q: the
// chain among them; BiCGSTAB); the Lebesgue measure of the request weighted by h_k is the basin fraction that the
// transfer operator gives to attractor k, the counterpart of `btob basins`' counted fractions.
struct BasinInfo {
  std::string attractor;  // the cycle's word, or "P2 region"
  std::string kind;       // "stable" (a sink) or "neutral" (the P2 invariant curves)
  long target_boxes = 0;
  double fraction = 0;  // of the Lebesgue measure of the request
  double exact = -1;    // P2 region: the Lebesgue measure of R itself (closed form by quadrature), -1 else
};

// Without --cycle: the attractors of the closed classes, found by classifying (attractors::classify with
// `btob classify`'s default thresholds) the orbits started at the centres of a class's boxes (at most
// kNameSamples of them, evenly strided in box order).  Verdicts are those of "one orbit, one verdict": stable (a
// stable periodic orbit), collapse, neutral (invariant curves, lambda1 = 0), unstable (chaotic, lambda1 > 0),
// undecided (the classifier's budget ran out, or no attractor holds a majority of the starts).
constexpr std::size_t kNameSamples = 256;  // starts per closed class: each costs ~10^4 map steps
struct ClassAttractor {
  int closed_class = 0;   // 1-based
  std::string attractor;  // periodic: its word in paper notation (mirror-aware); collapse: "1" or "3";
                          // "P2 invariant curves", "invariant curves", "chaotic"; "undecided" for starts not decided
  std::string type;       // attractors::type_name: periodic, collapse, quasi-periodic, chaotic, undecided
  std::string verdict;    // stable, collapse, neutral, unstable or undecided
  long starts = 0;        // starts of the class whose orbit reaches it
};
struct ClassNames {
  std::vector<std::string> name, verdict;  // per closed class: the attractor more than half its starts reach, or
                                           // "undecided"
  std::vector<std::uint32_t> classified, majority;  // per closed class: starts classified, starts reaching it
  std::vector<ClassAttractor> reached;    // every attractor each class's starts reach, by class, then by count
  std::vector<std::string> stable_words;  // the distinct stable periodic words, in order of first class
};

struct TransferResult {
  TransferRequest request;             // the request, as run (validated)
  Partition part;                      // the box partition of the chart (boxes along each coordinate and their ranges)
  long nnz = 0;                        // non-zero entries of the Ulam matrix
  std::uint64_t lost = 0;              // samples whose image left the chart or was not finite
  std::vector<double> eig_re, eig_im;  // K leading eigenvalues by decreasing modulus (block route)
  std::vector<std::uint32_t> eig_block;    // their blocks (0 transient, c closed class)
  std::vector<double> whole_re, whole_im;  // Spectra on the whole matrix (cross-check)
  std::vector<ClassInfo> classes;          // the closed classes' sizes and periods (class c = classes[c - 1])
  int closed_classes() const { return static_cast<int>(classes.size()); }
  int near_one_count = 0;                       // eigenvalues with |lambda - 1| <= near_one
  std::vector<ComponentInfo> components;        // closed classes, then almost-invariant transient components
  std::vector<std::uint32_t> component_of_box;  // n1 x n2 row-major, 0 none, k = components[k - 1]
  std::vector<double> density;                  // n1 x n2: sum_k lebesgue_k * (invariant density of k), mass per box
  double unabsorbed = 0;                        // Lebesgue mass left unresolved by the projection
  // Sign structure of the leading real eigenvector with 0 < lambda < 1 - 1e-9 (almost-invariant sets).
  double second_value = 0;
  int second_block = 0;
  std::vector<double> second;  // n1 x n2, real part, normalised to max |.| = 1 (0 outside its block; all 0
                               // when there is no such eigenvalue)
  double second_positive_mass = 0, second_negative_mass = 0;  // L1 mass of the two signs, sum 1
  long second_positive_boxes = 0,
       second_negative_boxes = 0;  // boxes where the second eigenvector is positive, negative
  // Empirical measure of orbits started on a strip grid (stats::orbit_series / empirical_measure).
  std::vector<CycleCheck> cycles;
  // Without --cycle: the stable periodic attractors found in the closed classes (words, paper notation), which
  // `cycles` then checks and `basins` targets; empty when cycles were named or none was found.
  std::vector<std::string> attractors_found;
  ClassNames class_names;  // without --cycle: how the closed classes were named (empty with --cycle)
  double tv_boxes = -1, tv_coarse = -1;
  long measure_points = 0;
  double seconds_matrix = 0, seconds_spectrum = 0, seconds_total = 0;
  std::size_t matrix_bytes = 0;
  std::vector<double> lebesgue;      // per component: components[k].lebesgue
  std::vector<double> cycle_points;  // (a, b) of every point of every cycle, the cycles in order (rows of 2)
  // Basins from the Ulam graph (empty when the request names no attractor: no stable cycle, no P2 region).
  std::vector<BasinInfo> basins;
  std::vector<std::uint32_t> basin_of_box;  // n1 x n2: the target (1-based) of largest absorption probability, 0: none
  std::vector<double> basin_probability;    // n1 x n2: that probability (1 on the targets; < 1 near basin boundaries)
  std::vector<double> basin_fraction;       // per attractor: basins[k].fraction
  double basin_unabsorbed = 0;              // Lebesgue mass absorbed by no target: 1 - sum of the fractions
  double basin_residual = 0;                // largest relative residual of the solves
  long basin_iterations = 0;                // BiCGSTAB iterations, summed over the targets
  double seconds_basins = 0;

  // What `btob transfer` writes (output.cpp).  Arrays density, second, component, eig_re, eig_im, lebesgue,
  // cycle_points; attributes: the request's fields under their flag names, the partition, the summary numbers.
  void describe(core::Contents& c) const;
  // Without a spectrum (eigenvalues 0) the tables are cycles.csv (its density columns empty) and basins.csv only.
  std::string spectrum_csv() const;    // k,re,im,modulus,block,whole_re,whole_im,whole_modulus (whole_*: check-whole)
  std::string components_csv() const;  // component,kind,boxes,period,rho,lebesgue_fraction,centre_a,centre_b,w1,w2
  std::string cycles_csv() const;      // word,outcome,points,boxes_found,mass_boxes,...; "" when no cycle was asked
  std::string basins_csv() const;      // attractor,kind,target_boxes,fraction,exact; "" when there is no target
  std::string classes_csv() const;     // closed_class,attractor,type,verdict,starts; "" with --cycle
  core::Tables tables() const {        // spectrum.csv, components.csv, cycles.csv, basins.csv (when there are some),
                                       // classes.csv (without --cycle)
    core::Tables t;
    if (request.spectrum()) t = {{"spectrum.csv", spectrum_csv()}, {"components.csv", components_csv()}};
    if (!cycles.empty()) t.emplace_back("cycles.csv", cycles_csv());
    if (!basins.empty()) t.emplace_back("basins.csv", basins_csv());
    if (request.cycles.empty()) t.emplace_back("classes.csv", classes_csv());
    return t;
  }
  std::string summary() const;  // the lines printed on stderr
};
TransferResult run(const TransferRequest& q, const core::RunControl& c = {});
// Its cost (core/work.hpp): Ulam's sample images (boxes x samples), the stages on the matrix (decomposition, Arnoldi,
// components, basins: boxes x eigenvalues), the empirical measure's map steps (measure-orbits^2 x (transient +
// iterations)); each route probed at r = 0.15.
core::Work work(const TransferRequest& q);

// ---- btob transfer-r: the peripheral spectrum across r ------------------------------------------------
struct TransferRRequest {
  double r_min = 0.07, r_max = 0.6;  // in (0, 1), r_min < r_max
  long r_count = 107;                // >= 1
  std::string boxes = "128x128";
  std::string domain = "strip";
  int samples = 16;
  int eigenvalues = 24;
  double peripheral = 1e-2;  // 1 - |lambda| below this: peripheral, (0, 1)
  std::string route = "direct";
  void validate() const;
  template <class V> void fields(V&& v) {
    v("r-min", r_min, "lowest r, in (0, 1)");
    v("r-max", r_max, "highest r, in (r-min, 1)");
    v("r-count", r_count, "number of r values, 1..100000");
    v("boxes", boxes, "NxM boxes of the chart, N, M >= 1");
    v("domain", domain, "strip or angles");
    v("samples", samples, "sample points per box, 1..65536");
    v("eigenvalues", eigenvalues, "K leading eigenvalues per r, 1..boxes");
    v("peripheral", peripheral, "1 - |lambda| below this counts as peripheral, (0, 1)");
    v("route", route, "direct or kernel");
  }
};
struct TransferRResult {
  TransferRRequest request;                     // the request, as run (validated)
  std::vector<double> r;                        // [R]: the r values, ascending
  long K = 0;                                   // eigenvalues kept per r (the request's, at most the number of boxes)
  std::vector<double> re, im;                   // r.size() x K row-major (NaN where fewer converged)
  std::vector<std::uint32_t> peripheral_count;  // per r
  std::vector<std::uint32_t> closed_classes;    // per r
  std::vector<double> gap;                      // min |peripheral| - max |rest| (NaN when no rest within K)
  std::vector<double> rest_modulus;             // max |lambda| outside the peripheral set
  std::vector<double> p2_beta;                  // p2_rotation_angle(r) per r (NaN below 3 - 2 sqrt 2)
  // The windows [root of Q_n, r_crit,2(n)] of (ab)^n(cb)^n (src/windows), n = 1..12 (narrower windows are below
  // the resolution of any r grid we draw); n = 1 has no r_crit,2 (NaN).
  std::vector<double> window_lower, window_upper;
  double seconds = 0;

  // What `btob transfer-r` writes (output.cpp); every value that is not a finite number is an empty cell.
  void describe(core::Contents& c) const;
  std::string spectrum_csv() const;    // r,k,re,im,modulus: every converged eigenvalue
  std::string peripheral_csv() const;  // r,peripheral_count,closed_classes,rest_modulus,gap,p2_beta
  std::string windows_csv() const;     // n,lower,upper
  core::Tables tables() const {
    return {{"spectrum_r.csv", spectrum_csv()}, {"peripheral_r.csv", peripheral_csv()}, {"windows.csv", windows_csv()}};
  }
  std::string summary() const;
};
TransferRResult run(const TransferRRequest& q, const core::RunControl& c = {});
// Its cost (core/work.hpp): per r, Ulam's sample images and the leading eigenvalues (transfer's first two routes).
core::Work work(const TransferRRequest& q);

// Parses "NxM" (field named in errors); throws core::InvalidField.
std::pair<long, long> parse_boxes(const std::string& s, const char* field = "boxes");
Domain parse_domain(const std::string& s, const char* field = "domain");

}  // namespace btob::transfer
