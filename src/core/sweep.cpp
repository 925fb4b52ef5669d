// SPDX-License-Identifier: GPL-3.0-or-later
// The rows of one rank's parts joined in item order (core/sweep.hpp).
#include "core/sweep.hpp"

#include <array>

#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace btob::core {

namespace {
// Column c of every set, joined into `out` by `order` (item, set, row in its set); the sources are freed.
template <class V>
std::vector<V> join_column(std::vector<RowSet>& sets, std::size_t c,
                           const std::vector<std::array<std::size_t, 3>>& order) {
  std::size_t width = 0;
  for (const RowSet& s : sets)
    if (!s.items.empty()) width = std::max(width, std::get<std::vector<V>>(s.columns[c].data).size() / s.items.size());
  for (const RowSet& s : sets)
    if (std::get<std::vector<V>>(s.columns[c].data).size() != s.items.size() * width)
      throw std::logic_error("sweep rows: column '" + sets[0].columns[c].name + "' is not whole rows of every part");
  std::vector<V> out(order.size() * width);
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::vector<V>& src = std::get<std::vector<V>>(sets[order[k][1]].columns[c].data);
    std::copy_n(src.begin() + static_cast<std::ptrdiff_t>(order[k][2] * width), width,
                out.begin() + static_cast<std::ptrdiff_t>(k * width));
  }
  for (RowSet& s : sets) std::vector<V>().swap(std::get<std::vector<V>>(s.columns[c].data));
  return out;
}
}  // namespace

RowSet join_rows(std::vector<RowSet> sets, std::size_t total) {
  RowSet out;
  out.total = total;
  if (sets.empty()) return out;
  std::vector<std::array<std::size_t, 3>> order;  // (item, set, row in its set), sorted by item
  for (std::size_t s = 0; s < sets.size(); ++s) {
    if (sets[s].columns.size() != sets[0].columns.size())
      throw std::logic_error("sweep rows: parts name different columns");
    for (std::size_t j = 0; j < sets[s].items.size(); ++j) order.push_back({sets[s].items[j], s, j});
  }
  std::sort(order.begin(), order.end());
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k > 0 && order[k][0] == order[k - 1][0]) throw std::logic_error("sweep rows: an item is repeated");
    out.items.push_back(order[k][0]);
  }
  for (std::size_t c = 0; c < sets[0].columns.size(); ++c)
    std::visit(
        [&](const auto& first) {
          using V = typename std::decay_t<decltype(first)>::value_type;
          out.columns.push_back(RowColumn{sets[0].columns[c].name, join_column<V>(sets, c, order)});
        },
        sets[0].columns[c].data);
#ifdef __GLIBC__
  // The parts' rows were many small blocks of the heap, now free but still resident: given back to the system, so
  // that the rank holds its rows once when the collective write's buffers come (else its peak is one share more).
  malloc_trim(0);
#endif
  return out;
}

}  // namespace btob::core
