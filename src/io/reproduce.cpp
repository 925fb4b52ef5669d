// SPDX-License-Identifier: GPL-3.0-or-later
// The comparison of a result with its re-run (io/reproduce.hpp).
#include "io/reproduce.hpp"

#include <fmt/format.h>
#include <hdf5.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace btob::io {
namespace fs = std::filesystem;
namespace {

// An HDF5 identifier closed by `close` when it goes out of scope (negative: failed, nothing to close).
struct Handle {
  hid_t id;
  herr_t (*close)(hid_t);
  Handle(hid_t i, herr_t (*c)(hid_t)) : id(i), close(c) {}
  ~Handle() {
    if (id >= 0) close(id);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
};

// A dataset's contents in a form two files can be compared by: its type's class and size, its dims, and its bytes
// (variable-length strings: each text with its length, not the pointers the library reads them into).
struct Content {
  std::string type;
  std::vector<hsize_t> dims;
  std::string bytes;
  bool operator==(const Content&) const = default;
};

Content read_dataset(hid_t file, const std::string& path) {
  const Handle ds{H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose};
  const Handle type{H5Dget_type(ds.id), H5Tclose};
  const Handle space{H5Dget_space(ds.id), H5Sclose};
  if (ds.id < 0 || type.id < 0 || space.id < 0) throw std::runtime_error("cannot open dataset " + path);
  Content c;
  const int rank = H5Sget_simple_extent_ndims(space.id);
  c.dims.resize(static_cast<std::size_t>(std::max(rank, 0)));
  if (rank > 0) H5Sget_simple_extent_dims(space.id, c.dims.data(), nullptr);
  const auto points = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space.id));
  const std::size_t size = H5Tget_size(type.id);
  const bool vlen = H5Tis_variable_str(type.id) > 0;
  c.type = fmt::format("class {} size {} sign {} order {}{}", static_cast<int>(H5Tget_class(type.id)), size,
                       static_cast<int>(H5Tget_sign(type.id)), static_cast<int>(H5Tget_order(type.id)),
                       vlen ? " variable" : "");
  if (points == 0) return c;
  if (!vlen) {
    c.bytes.resize(points * size);
    if (H5Dread(ds.id, type.id, H5S_ALL, H5S_ALL, H5P_DEFAULT, c.bytes.data()) < 0)
      throw std::runtime_error("cannot read dataset " + path);
    return c;
  }
  std::vector<char*> texts(points, nullptr);
  if (H5Dread(ds.id, type.id, H5S_ALL, H5S_ALL, H5P_DEFAULT, texts.data()) < 0)
    throw std::runtime_error("cannot read dataset " + path);
  for (const char* t : texts) {
    const std::string s = t ? t : "";
    c.bytes += fmt::format("{}:", s.size()) + s;
  }
  H5Dvlen_reclaim(type.id, space.id, H5P_DEFAULT, texts.data());
  return c;
}

herr_t collect(hid_t group, const char* name, const H5L_info_t*, void* out) {
  H5O_info_t info;
  if (H5Oget_info_by_name(group, name, &info, H5P_DEFAULT) >= 0 && info.type == H5O_TYPE_DATASET)
    static_cast<std::vector<std::string>*>(out)->push_back(name);
  return 0;
}

// Every dataset of `path` by its path in the file; empty when the file does not exist.
std::map<std::string, Content> datasets(const fs::path& path) {
  std::map<std::string, Content> out;
  if (!fs::exists(path)) return out;
  const Handle file{H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  if (file.id < 0) throw std::runtime_error(fmt::format("'{}': not an HDF5 file", path.string()));
  std::vector<std::string> names;
  H5Lvisit(file.id, H5_INDEX_NAME, H5_ITER_INC, collect, &names);
  for (const std::string& n : names) out.emplace(n, read_dataset(file.id, n));
  return out;
}

// The CSV tables of result `name` in `dir` (NAME.csv and NAME_*.csv) by file name, with their bytes.
std::map<std::string, std::string> tables(const fs::path& dir, const std::string& name) {
  std::map<std::string, std::string> out;
  if (!fs::is_directory(dir)) return out;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string f = e.path().filename().string();
    if (e.path().extension() != ".csv" || !(f == name + ".csv" || f.rfind(name + "_", 0) == 0)) continue;
    std::ifstream in(e.path(), std::ios::binary);
    out.emplace(f, std::string(std::istreambuf_iterator<char>(in), {}));
  }
  return out;
}

// Sorts the union of a's and b's keys into the report's four lists.
bool is_timing(const std::string& name) { return name.size() >= 7 && name.compare(name.size() - 7, 7, "seconds") == 0; }

template <class Map> void compare(const Map& a, const Map& b, Reproduction& r) {
  for (const auto& [k, v] : a) {
    if (is_timing(k)) {
      r.timings.push_back(k);
      continue;
    }
    const auto it = b.find(k);
    if (it == b.end()) r.only_original.push_back(k);
    else (it->second == v ? r.identical : r.differ).push_back(k);
  }
  for (const auto& [k, v] : b)
    if (!a.count(k) && !is_timing(k)) r.only_reproduction.push_back(k);
}

std::string join(const std::vector<std::string>& v, const std::string& suffix = "") {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x + suffix;
  return s;
}

}  // namespace

std::string Reproduction::summary() const {
  if (!original_has_data)
    return fmt::format("nothing to compare: {} holds no data file of the result (NAME.h5 or a CSV table)", original);
  if (compared() == 0) return "no datasets to compare (the result's NAME.h5 holds attributes only)";
  std::string s = fmt::format("{} of {} datasets bit-identical", identical.size(), compared());
  std::vector<std::string> bad = differ;
  for (const auto& x : only_original) bad.push_back(x + " (only in the original)");
  for (const auto& x : only_reproduction) bad.push_back(x + " (only in the re-run)");
  if (!bad.empty()) s += "; differ: " + join(bad);
  if (!timings.empty()) s += "; wall times not compared: " + join(timings);
  return s;
}

std::string Reproduction::json() const {
  const nlohmann::json j = {{"original", original},
                            {"reproduction", reproduction},
                            {"compared", compared()},
                            {"identical_count", identical.size()},
                            {"reproduced", reproduced()},
                            {"original_has_data", original_has_data},
                            {"identical", identical},
                            {"differ", differ},
                            {"only_original", only_original},
                            {"only_reproduction", only_reproduction},
                            {"timings_not_compared", timings},
                            {"summary", summary()}};
  return j.dump(1) + "\n";
}

Reproduction compare_results(const fs::path& original, const fs::path& reproduction, const std::string& name) {
  Reproduction r;
  r.original = original.string();
  r.reproduction = reproduction.string();
  const auto h5 = datasets(original / (name + ".h5"));
  const auto csv = tables(original, name);
  r.original_has_data = !h5.empty() || !csv.empty();
  compare(h5, datasets(reproduction / (name + ".h5")), r);
  compare(csv, tables(reproduction, name), r);
  return r;
}

}  // namespace btob::io
