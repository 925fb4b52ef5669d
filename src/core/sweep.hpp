// SPDX-License-Identifier: GPL-3.0-or-later
// Sweeps: requests whose work is a list of independent items (r values, grid rows), computed in parts and merged.
// The one mechanism behind `mpirun -n P btob <command>` (src/cli/sweep.hpp); a module knows nothing of MPI:
//
//   struct Request { ...; std::size_t work_items() const; };        // how many items: r values, grid rows
//   struct Part {                                                    // what items compute, nothing derived
//     std::vector<std::size_t> items;                                // ascending
//     ...                                                            // per-item rows, counts, timings
//     template <class A> void members(A& a) { a(items, ...); }       // core/pack.hpp: sent between processes
//   };
//   Part run_part(const Request&, const std::vector<std::size_t>& items, const core::RunControl&);
//   Result merge(const Request&, std::vector<Part> parts);           // parts cover every item once, any order
//   Result run(const Request& r, const core::RunControl& c) { return merge(r, {run_part(r, all_items(r), c)}); }
//
// The rule that makes the output independent of the partition: an item's numbers depend only on the request and
// the item, never on which other items share its part (random grids are generated for the whole request and then
// sliced; no seed depends on the part).  merge() places rows by item index and sums integer counts, so any
// partition, in any order, gives the single-process result bitwise; a single process is the partition {all}.
#pragma once

#include "core/request.hpp"

#include <algorithm>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace btob::core {

template <class Req>
concept Sweep = requires(const Req& r) {
  { r.work_items() } -> std::convertible_to<std::size_t>;
};

// 0, 1, ..., n - 1.
inline std::vector<std::size_t> all_items(std::size_t n) {
  std::vector<std::size_t> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = i;
  return v;
}
template <Sweep Req> std::vector<std::size_t> all_items(const Req& r) { return all_items(r.work_items()); }

// The item count where counting may take long (the atlas enumerates up to 3^16 words): a request with
// work_items(cancel) polls the run's token while it counts (core::Cancelled); the others count at once.
template <Sweep Req> std::size_t work_items(const Req& r, const CancelToken* cancel) {
  if constexpr (requires { r.work_items(cancel); }) return r.work_items(cancel);
  else return r.work_items();
}

// The items of part k of P in a cyclic split (item i goes to part i mod P): neighbouring items, whose costs are
// alike (nearby r, adjacent rows), land in different parts, so parts cost about the same without measuring.
inline std::vector<std::size_t> cyclic_items(std::size_t n, std::size_t k, std::size_t parts) {
  std::vector<std::size_t> v;
  for (std::size_t i = k; i < n; i += parts) v.push_back(i);
  return v;
}

// For merge(): every part's (item, position in its part) sorted by item, checked to cover 0..n-1 exactly once.
struct ItemRef {
  std::size_t part, index;
};
template <class Part> std::vector<ItemRef> item_order(const std::vector<Part>& parts, std::size_t n) {
  std::vector<ItemRef> at(n, ItemRef{parts.size(), 0});
  for (std::size_t p = 0; p < parts.size(); ++p)
    for (std::size_t j = 0; j < parts[p].items.size(); ++j) {
      const std::size_t i = parts[p].items[j];
      if (i >= n || at[i].part != parts.size()) throw std::logic_error("sweep parts: item out of range or repeated");
      at[i] = ItemRef{p, j};
    }
  for (const auto& a : at)
    if (a.part == parts.size()) throw std::logic_error("sweep parts: an item is missing");
  return at;
}

// ---- Rows written by the ranks themselves (parallel HDF5) -------------------------------------------------------
// A part may name its per-item arrays that are datasets of the result as they are (one row per item, in the
// order of its items), the bulk of a large sweep's result (densities, raw tails, per-orbit values):
//
//   template <class A> void rows(A& a) { a("density", density); a("tail", tail); a("summary", summary_lines); }
//
// The names are the result's datasets (describe()), or for a std::vector<std::string> of one line per item the role
// of one of its CSV tables (tables(): the table is its header and these lines in item order); nothing else the
// result derives (attributes, other tables, overlays) may read them.  Every rank names the same arrays, whatever its
// items (a collective write follows): an array the request leaves empty (no raw tails) is named all the same, and
// skipped where the result describes no such dataset.  Under mpirun with parallel HDF5 each rank then keeps these rows
// and they are written into NAME.h5 by the ranks (cli/rows.hpp), and only the rest of its part (counts, per-item
// summaries, timings) goes to rank 0, whose merge() leaves the named arrays empty (ThinMerge below) while describe()
// still gives their full shape. (The check only names the member template; its body is instantiated with take_rows'
// visitor alone.)
template <class Part>
concept HasRows = requires(Part& p, int& probe) {
  p.rows(probe);
};

// One named dataset's rows of one rank: its items' rows, row-major, in item order (moved out of the part).  A column
// of strings is a table's lines instead: one line of the CSV table `name` (the result's table of that role,
// core::table_file) per item, without its newline; rank 0 writes the table's header, the ranks its lines after it.
struct RowColumn {
  std::string name;
  std::variant<std::vector<double>, std::vector<std::uint32_t>, std::vector<std::uint64_t>, std::vector<std::uint8_t>,
               std::vector<std::string>>
      data;
  std::size_t size() const {
    return std::visit([](const auto& v) { return v.size(); }, data);
  }
  bool is_table() const { return std::holds_alternative<std::vector<std::string>>(data); }
};
// A rank's rows: its items (ascending) of the sweep's `total`, and each named dataset's rows.
struct RowSet {
  std::vector<std::size_t> items;
  std::size_t total = 0;
  std::vector<RowColumn> columns;
  bool empty() const { return columns.empty(); }
};

// Moves the rows a part names (Part::rows) out of it: the part keeps everything else, the arrays named stay empty.
template <class Part> RowSet take_rows(Part& part, std::size_t total) {
  RowSet rs;
  rs.items = part.items;
  rs.total = total;
  const auto take = [&](const std::string& name, auto& vec) {
    using V = typename std::decay_t<decltype(vec)>::value_type;
    RowColumn col{name, std::vector<V>{}};
    std::get<std::vector<V>>(col.data).swap(vec);
    rs.columns.push_back(std::move(col));
  };
  part.rows(take);
  return rs;
}

// The rows of several RowSets of one rank (of the same `total`), as one in ascending item order: the row order
// cli/rows.hpp needs.  Each column is copied into place and its sources freed before the next, so the rank holds
// its rows once plus one column.  Throws std::logic_error when an item repeats or a column's size is not a whole
// number of rows.
RowSet join_rows(std::vector<RowSet> sets, std::size_t total);

// take_rows over every part of one rank (a resumed run's rank holds the parts its checkpoint files kept and those of
// its rounds, their items interleaved): one RowSet, items ascending.  A rank without parts names the same columns,
// empty (its rows join the collective write like the others').
template <class Part> RowSet take_rows(std::vector<Part>& parts, std::size_t total) {
  if (parts.size() == 1) return take_rows(parts[0], total);
  std::vector<RowSet> sets;
  if (parts.empty()) {
    Part none{};
    sets.push_back(take_rows(none, total));
  }
  for (Part& p : parts) sets.push_back(take_rows(p, total));
  return join_rows(std::move(sets), total);
}

namespace detail {
inline int& thin_merges() {
  thread_local int depth = 0;
  return depth;
}
}  // namespace detail
// While alive (on the merging thread), merge_rows() gives an empty array for rows that every part left empty: a
// merge of parts whose named rows the ranks keep (take_rows).  Outside it a missing row is a logic error.
struct ThinMerge {
  ThinMerge() { ++detail::thin_merges(); }
  ~ThinMerge() { --detail::thin_merges(); }
  ThinMerge(const ThinMerge&) = delete;
  ThinMerge& operator=(const ThinMerge&) = delete;
};

// Rows of `width` values per item, in item order: the part of item i holds its row at index j of its own rows.
template <class Part, class V, class Get>
std::vector<V> merge_rows(const std::vector<Part>& parts, const std::vector<ItemRef>& order, std::size_t width,
                          Get get) {
  if (detail::thin_merges() > 0 &&
      std::all_of(parts.begin(), parts.end(), [&](const Part& p) { return get(p).empty(); }))
    return {};
  std::vector<V> out(order.size() * width);
  for (std::size_t i = 0; i < order.size(); ++i) {
    const std::vector<V>& src = get(parts[order[i].part]);
    if (src.size() < (order[i].index + 1) * width) throw std::logic_error("sweep parts: a row is missing");
    std::copy_n(src.begin() + static_cast<std::ptrdiff_t>(order[i].index * width), width,
                out.begin() + static_cast<std::ptrdiff_t>(i * width));
  }
  return out;
}

}  // namespace btob::core
