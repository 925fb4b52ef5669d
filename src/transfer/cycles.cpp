// SPDX-License-Identifier: GPL-3.0-or-later
// Stage 8 of `btob transfer` (stages.hpp): periodic cycles located in the boxes and the density's mass around them.
#include "transfer/detail.hpp"
#include "transfer/stages.hpp"

#include "patterns/patterns.hpp"

#include <algorithm>
#include <cstdlib>
#include <limits>

namespace btob::transfer {

using detail::at;

namespace {

// The boxes of a cycle and of their 3x3 neighbourhoods, as flags per box.
struct CycleBoxes {
  std::vector<char> own, neighbourhood;
};
CycleBoxes mark_boxes(const std::vector<long>& boxes, const Partition& part) {
  CycleBoxes marks{std::vector<char>(at(part.size()), 0), std::vector<char>(at(part.size()), 0)};
  for (long box : boxes) {
    if (box < 0) continue;
    marks.own[at(box)] = 1;
    const long i1 = box / part.n2, i2 = box % part.n2;
    for (long d1 = -1; d1 <= 1; ++d1)
      for (long d2 = -1; d2 <= 1; ++d2)
        if (i1 + d1 >= 0 && i1 + d1 < part.n1 && i2 + d2 >= 0 && i2 + d2 < part.n2)
          marks.neighbourhood[at((i1 + d1) * part.n2 + i2 + d2)] = 1;
  }
  return marks;
}

// Without a density: the closed class that holds every box of the cycle (0: none, or several, or the transient
// block).  A closed class is invariant, so its stationary density (eigenvalue 1) is supported on it; one class per
// sink is one eigenvalue 1 per sink.
int holding_class(const std::vector<long>& boxes, const Decomposition& d) {
  std::uint32_t cls = 0;
  bool one = true;
  for (long b : boxes) {
    if (b < 0) continue;
    const std::uint32_t k = d.class_of_box[at(b)];
    if (k == 0 || (cls != 0 && k != cls)) one = false;
    cls = k;
  }
  return one ? static_cast<int>(cls) : 0;
}

// Smallest Chebyshev distance R (in boxes) to the cycle's boxes within which w holds 99% of its mass; -1 if none.
long radius99(const std::vector<double>& w, const std::vector<long>& cycle_boxes, const Partition& part) {
  const long n1 = part.n1, n2 = part.n2;
  std::vector<double> by_distance(at(std::max(n1, n2) + 1), 0);
  double total = 0;
  for (long i = 0; i < part.size(); ++i) {
    if (w[at(i)] == 0) continue;
    long dist = std::max(n1, n2);
    for (long b : cycle_boxes)
      if (b >= 0) dist = std::min(dist, std::max(std::labs(i / n2 - b / n2), std::labs(i % n2 - b % n2)));
    by_distance[at(dist)] += w[at(i)];
    total += w[at(i)];
  }
  double acc = 0;
  for (std::size_t k = 0; k < by_distance.size(); ++k)
    if ((acc += by_distance[k]) >= 0.99 * total) return static_cast<long>(k);
  return -1;
}

// The density's mass on the cycle's boxes and neighbourhoods, the component most present there, the radii.
void measure_cycle(CycleCheck& cc, const CycleBoxes& marks, const std::vector<double>& density,
                   const std::vector<std::vector<double>>& densities, const Partition& part) {
  double total = 0;
  for (double x : density) total += x;
  for (std::size_t i = 0; i < density.size(); ++i) {
    if (marks.own[i]) cc.mass_boxes += density[i] / total;
    if (marks.neighbourhood[i]) cc.mass_neighbourhood += density[i] / total;
  }
  for (std::size_t k = 0; k < densities.size(); ++k) {
    double m = 0;
    for (std::size_t i = 0; i < density.size(); ++i)
      if (marks.neighbourhood[i]) m += densities[k][i];
    if (m > cc.component_share) cc.component_share = m, cc.component = static_cast<int>(k + 1);
  }
  if (std::none_of(cc.boxes.begin(), cc.boxes.end(), [](long b) { return b >= 0; })) return;
  cc.radius99 = radius99(density, cc.boxes, part);
  if (cc.component > 0) cc.radius99_component = radius99(densities[at(cc.component - 1)], cc.boxes, part);
}

}  // namespace

CycleCheck check_cycle(const std::string& word, double r, Domain dom, const Partition& part, const Decomposition& d,
                       const std::vector<double>* density, const std::vector<std::vector<double>>& densities) {
  CycleCheck cc;
  cc.word = word;
  const auto verdict = patterns::analyse<double>(patterns::parse_word(word, "cycle"), r);
  cc.outcome = patterns::outcome_name(verdict.outcome);
  for (const auto& u : verdict.orbit) {
    double a, b;
    vector_to_chart(dom, u(0), u(1), u(2), a, b);
    cc.boxes.push_back(part.locate(a, b));
    cc.a.push_back(a);
    cc.b.push_back(b);
  }
  if (!density) {  // no density: the masses and radii are undefined (empty cells of cycles.csv)
    cc.mass_boxes = cc.mass_neighbourhood = cc.component_share = std::numeric_limits<double>::quiet_NaN();
    cc.component = holding_class(cc.boxes, d);
    return cc;
  }
  measure_cycle(cc, mark_boxes(cc.boxes, part), *density, densities, part);
  return cc;
}

}  // namespace btob::transfer
