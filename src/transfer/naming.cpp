// SPDX-License-Identifier: GPL-3.0-or-later
// Stage 8a of `btob transfer` (stages.hpp), without --cycle: the attractors of the closed classes, found by
// classifying (attractors::classify, `btob classify`'s defaults) the orbits started at the centres of their boxes.
#include "transfer/detail.hpp"
#include "transfer/stages.hpp"

#include "attractors/attractors.hpp"
#include "attractors/requests.hpp"

#include <algorithm>
#include <string_view>

namespace btob::transfer {

using detail::at;

namespace {

// The centres of the boxes of closed class k, at most kNameSamples of them, evenly strided in box order.
std::vector<core::Vec3<double>> class_starts(const Partition& part, Domain dom, const Decomposition& d,
                                             std::uint32_t k) {
  std::vector<long> boxes;
  for (std::size_t i = 0; i < d.class_of_box.size(); ++i)
    if (d.class_of_box[i] == k) boxes.push_back(static_cast<long>(i));
  const std::size_t stride = (boxes.size() + kNameSamples - 1) / kNameSamples;
  const double h1 = (part.hi1 - part.lo1) / static_cast<double>(part.n1);
  const double h2 = (part.hi2 - part.lo2) / static_cast<double>(part.n2);
  std::vector<core::Vec3<double>> starts;
  for (std::size_t j = 0; j < boxes.size(); j += stride) {
    const long box = boxes[j];
    const double a = part.lo1 + (static_cast<double>(box / part.n2) + 0.5) * h1;
    const double b = part.lo2 + (static_cast<double>(box % part.n2) + 0.5) * h2;
    core::Vec3<double> u;
    chart_to_vector(dom, a, b, u(0), u(1), u(2));
    starts.push_back(u / u.norm());
  }
  return starts;
}

// The verdict word (docs/ARCHITECTURE.md, "One orbit, one verdict") of an attractor the classifier found.
std::string verdict_of(const attractors::Attractor& a) {
  switch (a.type) {
    case attractors::Type::periodic:
      return std::string_view(a.stability).starts_with("stable") ? "stable" : "undecided";
    case attractors::Type::collapse: return "collapse";
    case attractors::Type::quasi_periodic: return "neutral";
    case attractors::Type::chaotic: return "unstable";
    default: return "undecided";
  }
}

// The attractors the class's starts reach, by decreasing count (ties: the classifier's order), and the undecided.
void name_class(std::uint32_t k, const std::vector<attractors::OrbitVerdict>& verdicts, double r, ClassNames& out) {
  auto found = attractors::collect(verdicts, r, nullptr);
  std::stable_sort(found.begin(), found.end(), [](const auto& x, const auto& y) { return x.count > y.count; });
  long decided = 0;
  for (const auto& a : found) {
    out.reached.push_back(
        {static_cast<int>(k), a.pattern, attractors::type_name(a.type), verdict_of(a), static_cast<long>(a.count)});
    decided += static_cast<long>(a.count);
    if (verdict_of(a) == "stable" &&
        std::find(out.stable_words.begin(), out.stable_words.end(), a.pattern) == out.stable_words.end())
      out.stable_words.push_back(a.pattern);
  }
  const long classified = static_cast<long>(verdicts.size());
  if (classified > decided)
    out.reached.push_back({static_cast<int>(k), "undecided", attractors::type_name(attractors::Type::undecided),
                           "undecided", classified - decided});
  // The class's name: the attractor more than half of its starts reach, else "undecided".
  const bool majority = !found.empty() && 2 * static_cast<long>(found[0].count) > classified;
  out.name.push_back(majority ? found[0].pattern : "undecided");
  out.verdict.push_back(majority ? verdict_of(found[0]) : "undecided");
  out.classified.push_back(static_cast<std::uint32_t>(classified));
  out.majority.push_back(majority ? static_cast<std::uint32_t>(found[0].count) : 0);
}

}  // namespace

ClassNames name_closed_classes(const Partition& part, Domain dom, const Decomposition& d, double r,
                               const core::RunControl& control) {
  ClassNames out;
  const attractors::Options options = attractors::run_options(attractors::Options{}, control);
  for (std::uint32_t k = 1; k <= d.classes.size(); ++k) {
    iterate::Ensemble ensemble;
    ensemble.r = {r};
    ensemble.initial = class_starts(part, dom, d, k);
    name_class(k, attractors::classify(ensemble, options), r, out);
  }
  return out;
}

}  // namespace btob::transfer
