// SPDX-License-Identifier: GPL-3.0-or-later
// What a result holds, as named arrays and attributes: the one view through which the writers (HDF5, manifest),
// the Python binding and the MPI gather read every result type.  A result type provides
//     void describe(core::Contents& c) const;   // c.array(...) for every array, c.attr(...) for every summary value
// The arrays are views of the result's own vectors (no copy); the result must outlive its Contents.  Coordinates
// that only describe (bin and box centres, from the request's extent) are computed by describe() and kept by the
// Contents itself (Contents::coordinate_array), shared by its copies.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace btob::core {

using AttrValue = std::variant<std::string, double, long>;
using Attrs = std::map<std::string, AttrValue>;

struct ArrayView {
  std::string name;               // HDF5 dataset name, CSV column, Python attribute
  std::vector<std::size_t> dims;  // row-major shape; the product is the number of elements
  std::string axes;               // what each dimension runs over, e.g. "r, initial condition"
  std::string units;              // e.g. "1/iteration (natural log)", "count", "rad", "1"
  std::string description;        // one line
  std::variant<const std::vector<double>*, const std::vector<std::uint32_t>*, const std::vector<std::uint64_t>*,
               const std::vector<std::uint8_t>*>
      data;

  std::size_t size() const {
    return std::visit([](const auto* v) { return v->size(); }, data);
  }
};

// What kind of number a dataset (or a root attribute) holds (docs/reference/numbers.md): every number computed
// beyond double says it, as the HDF5 attributes `status`, `basis` and `confidence` of its datasets, Python's
// res.status[name] and a column of the CSV.
//   certified    proved: `basis` names the certificate (datasets or the exact argument) that proves it
//   estimated    measured or computed with an error bar: `basis` says what the bar is, `confidence` its level
//   conjectured  a value the paper conjectures (window upper bounds r_crit,2(n)): `basis` names the conjecture
struct Status {
  std::string kind, basis, confidence;
};
inline Status certified(std::string basis) { return {"certified", std::move(basis), ""}; }
inline Status estimated(std::string basis, std::string confidence) {
  return {"estimated", std::move(basis), std::move(confidence)};
}
inline Status conjectured(std::string basis) { return {"conjectured", std::move(basis), ""}; }

// Exact decimal numbers as text (multiprecision values: window bounds, thresholds), one per element: Python
// returns them as decimal.Decimal, never rounded to double; the HDF5 writer stores them as string datasets.
// The same view holds names that are data (Contents::texts: words, overlay names), strings in Python and HDF5.
struct DecimalView {
  std::string name, axes, units, description;
  const std::vector<std::string>* data;
};

// The CSV tables of a result as (role, text): the command line and Python's save() write each to NAME.csv (role ""),
// NAME_role.csv, or to the role itself when it is a file name ending in .csv (a name fixed by convention, e.g.
// table_6_1_comparison.csv), through table_file().  Results with tables have `Tables tables() const`.
using Tables = std::vector<std::pair<std::string, std::string>>;
inline std::string table_file(const std::string& name, const std::string& role) {
  if (role.size() > 4 && role.compare(role.size() - 4, 4, ".csv") == 0) return role;
  return name + (role.empty() ? "" : "_" + role) + ".csv";
}

// The centres of n equal bins of [lo, hi] (a histogram's bins, a partition's boxes): coordinates of their axis.
inline std::vector<double> bin_centres(double lo, double hi, std::size_t n) {
  std::vector<double> c(n);
  for (std::size_t k = 0; k < n; ++k) c[k] = lo + (static_cast<double>(k) + 0.5) * (hi - lo) / static_cast<double>(n);
  return c;
}

struct Contents {
  std::vector<ArrayView> arrays;
  std::vector<DecimalView> decimals;
  std::vector<DecimalView> texts;  // 1-D string data (word names, overlay names)
  Attrs attrs;
  // Coordinates of axes: axis label (as an array's `axes` names it) -> the 1-D array holding that axis's values.
  // An axis label that is itself the name of a 1-D array of the right length needs no entry.  The HDF5 writer
  // attaches these arrays as dimension scales (H5DS) to every dataset with that axis.
  std::map<std::string, std::string> coordinates;
  // Dataset or root attribute name -> what kind of number it holds (decimal() requires one; status_of()).
  std::map<std::string, Status> status;

  template <class V>
  void array(std::string name, const std::vector<V>& v, std::vector<std::size_t> dims, std::string axes,
             std::string units, std::string description) {
    arrays.push_back({std::move(name), std::move(dims), std::move(axes), std::move(units), std::move(description), &v});
  }
  // A decimal column says what kind of number it holds: it is computed beyond double, and its digits are worth
  // only what its status says (the double twin, when there is one, gets the same status with status_of()).
  void decimal(std::string name, const std::vector<std::string>& v, std::string axes, std::string units,
               std::string description, Status s) {
    status[name] = std::move(s);
    decimals.push_back({std::move(name), std::move(axes), std::move(units), std::move(description), &v});
  }
  // The status of array or attribute `name` (a decimal's double twin, an estimate kept as an attribute).
  void status_of(const std::string& name, Status s) { status[name] = std::move(s); }
  void text(std::string name, const std::vector<std::string>& v, std::string axes, std::string units,
            std::string description) {
    texts.push_back({std::move(name), std::move(axes), std::move(units), std::move(description), &v});
  }
  void attr(const std::string& name, AttrValue v) { attrs[name] = std::move(v); }
  // Declares array `array` (added with array()) as the coordinates of axis `label`.
  void coordinate(const std::string& label, const std::string& array) { coordinates[label] = array; }
  // A 1-D array computed for the description (the centres of a histogram's bins or of a partition's boxes), held
  // by these Contents (a deque: its elements never move), added as array `name` and declared the coordinates of
  // every axis in `labels`.
  void coordinate_array(const std::string& name, std::vector<double> values, const std::vector<std::string>& labels,
                        std::string units, std::string description) {
    owned->push_back(std::move(values));
    const std::vector<double>& v = owned->back();
    array(name, v, {v.size()}, name, std::move(units), std::move(description));
    for (const auto& l : labels) coordinate(l, name);
  }
  std::shared_ptr<std::deque<std::vector<double>>> owned = std::make_shared<std::deque<std::vector<double>>>();
  const ArrayView* find(const std::string& name) const {
    for (const auto& a : arrays)
      if (a.name == name) return &a;
    return nullptr;
  }
};

}  // namespace btob::core
