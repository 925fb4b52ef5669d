// SPDX-License-Identifier: GPL-3.0-or-later
// The geometry of basin boundaries from a label image (attractors.hpp's Basins::labels): basin entropy and boundary
// basin entropy (Daza, Wagemakers, Georgeot, Guery-Odelin, Sanjuan, Sci. Rep. 6, 31416 (2016)), the uncertainty
// exponent and the boundary's box-counting dimension (McDonald, Grebogi, Ott, Yorke, Physica D 17, 125 (1985)), and
// the merging test of the Wada property (Daza, Wagemakers, Sanjuan, Sci. Rep. 8, 9954 (2018)).  Pure functions of
// the image: no map, testable on synthetic images.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace btob::attractors {

// A label image: n2 rows of n1 cells, index j * n1 + i (Basins::labels' layout).  Every label is a colour,
// undecided (0) included.
struct LabelImage {
  const std::vector<std::uint32_t>* labels = nullptr;
  std::size_t n1 = 0, n2 = 0;
  std::uint32_t at(std::size_t i, std::size_t j) const { return (*labels)[j * n1 + i]; }
};

// Basin entropy on boxes of `box` x `box` cells (the whole boxes from the image's corner (0, 0); a remainder of
// fewer than `box` columns or rows is left out; an image smaller than one box has no boxes and entropies 0).  In box b
// the colours have shares p_bj and the box's entropy is S_b = -sum_j p_bj log p_bj (natural log).  Over the N boxes,
// S_b = (1/N) sum_b S_b; over the N_b boxes with S_b > 0 (the boundary boxes), S_bb = (1/N_b) sum S_b (0 when there are
// none).  S_bb > log 2 is the sufficient condition of Daza et al. for a fractal boundary (the "log 2 criterion").
struct BoxEntropy {
  int box = 0;
  std::size_t boxes = 0, boundary_boxes = 0;
  double sb = 0, sbb = 0;
  std::size_t columns = 0;      // boxes a row (n1 / box)
  std::vector<double> per_box;  // each box's entropy, row-major [n2 / box, n1 / box]
  double boundary_share() const { return boxes ? static_cast<double>(boundary_boxes) / static_cast<double>(boxes) : 0; }
  template <class A> void members(A& a) { a(box, boxes, boundary_boxes, sb, sbb, columns, per_box); }
};
// Throws std::invalid_argument when box < 1.
BoxEntropy box_entropy(const LabelImage& img, int box);

// The uncertain fraction f(eps) at eps = e cells: among the cells at least `margin` cells from every edge (the same
// cells for every e), those for which one of the four cells e away along the axes has another label.  For a
// boundary of box-counting dimension D in the plane, f(eps) ~ eps^alpha with alpha = 2 - D (MGOY 1985).
struct UncertainFraction {
  int eps = 0;  // cells
  std::size_t uncertain = 0, points = 0;
  double f = 0, low = 0, high = 0;  // uncertain / points with its Clopper-Pearson 95% interval
  template <class A> void members(A& a) { a(eps, uncertain, points, f, low, high); }
};
std::vector<UncertainFraction> uncertain_fractions(const LabelImage& img, const std::vector<int>& eps, int margin);
// Eight eps log-spaced from 1 to max(1, min(n1, n2) / 8) cells, rounded to distinct integers.
std::vector<int> uncertainty_eps(std::size_t n1, std::size_t n2);

// alpha from the least-squares line log f = alpha log eps + c over the eps with 0 < f <= 1/2 (f saturates towards 1
// at large eps, which would flatten the slope); its 95% interval is
// alpha +- t(0.975, m - 2) se(alpha) (m points; se from the residuals).  Fitted only with at least three points
// spanning a decade of eps (eps_max / eps_min >= 10); `why` says otherwise.  D = 2 - alpha.
struct UncertaintyFit {
  std::vector<UncertainFraction> points;
  bool fitted = false;
  std::string why;  // empty when fitted
  double alpha = 0, low = 0, high = 0, se = 0;
  int eps_min = 0, eps_max = 0;  // the range fitted (cells)
  std::size_t used = 0;          // eps values fitted
  double dimension() const { return 2 - alpha; }
  template <class A> void members(A& a) { a(points, fitted, why, alpha, low, high, se, eps_min, eps_max, used); }
};
UncertaintyFit fit_uncertainty(std::vector<UncertainFraction> points);
// uncertain_fractions at uncertainty_eps with margin eps_max, then fit_uncertainty.
UncertaintyFit uncertainty_exponent(const LabelImage& img);

// The merging test of the Wada property on the basins with labels >= 1 (undecided cells belong to no basin).  For
// each basin i its boundary B_i is the set of cells of the two-colour image (i against the rest merged) with a
// 4-neighbour of the other colour.  The basins are Wada at this resolution when every B_i lies within `cells` cells
// (chessboard distance) of every other B_j: the largest such distance, the Hausdorff distance H of the boundaries, is
// at most `cells` (default: wada_cells, 2% of the grid's smaller side and at least 3 cells: a fractal Wada boundary
// sampled on a grid loses its thinnest filaments, e.g. Newton's z^3 = 1 on 300 x 300 cells has H = 4, while
// boundaries that separate only two basins somewhere sit a finite share of the grid apart).  With fewer than three
// basins the test does not apply.  Also the grid method's first level (Daza et al. 2015): the share of boundary cells
// (a 4-neighbour of another label) that see every basin within `cells` cells.
struct WadaTest {
  int basins = 0;               // basins in the image (labels >= 1 with at least one cell)
  bool applies = false;         // at least three basins
  int hausdorff = 0;            // max over i != j of the largest distance of a cell of B_j from B_i (cells)
  int cells = 0;                // the resolution of the verdict (cells)
  bool wada = false;            // applies and hausdorff <= cells
  double all_basins_share = 0;  // grid method, first level
  std::string verdict() const;  // "Wada at this resolution", "not Wada ...", "not applicable ..."
  template <class A> void members(A& a) { a(basins, applies, hausdorff, cells, wada, all_basins_share); }
};
int wada_cells(std::size_t n1, std::size_t n2);
WadaTest wada_merging(const LabelImage& img, int cells);
inline WadaTest wada_merging(const LabelImage& img) { return wada_merging(img, wada_cells(img.n1, img.n2)); }

// The boundary geometry of a basins run: on the main grid, and S_b, S_bb over the main and replicate grids (mean,
// sample sd and the t interval of the mean at 95%; with one grid the interval is the value itself).
struct Spread {
  double value = 0, mean = 0, sd = 0, low = 0, high = 0;
  template <class A> void members(A& a) { a(value, mean, sd, low, high); }
};
Spread spread(const std::vector<double>& per_grid);  // per_grid[0] is the main grid's value

struct BoundaryGeometry {
  BoxEntropy entropy;              // main grid
  Spread sb, sbb, boundary_share;  // over main and replicate grids
  UncertaintyFit uncertainty;      // main grid
  WadaTest wada;                   // main grid
  template <class A> void members(A& a) { a(entropy, sb, sbb, boundary_share, uncertainty, wada); }
};
// grids[0] is the main grid's image, then the replicates'.
BoundaryGeometry boundary_geometry(const std::vector<std::vector<std::uint32_t>>& grids, std::size_t n1, std::size_t n2,
                                   int box);

}  // namespace btob::attractors
