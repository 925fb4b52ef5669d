// SPDX-License-Identifier: GPL-3.0-or-later
// The ranks' collective write of their rows (cli/rows.hpp), with HDF5's C API and its MPI-IO driver.
#include "cli/rows.hpp"

#include <fmt/format.h>
#include <hdf5.h>
#include <mpi.h>

#include <chrono>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace btob::cli::rows {

namespace {
// An HDF5 identifier closed by its guard (files, datasets, dataspaces, property lists alike).
struct Id {
  hid_t id = -1;
  herr_t (*close)(hid_t) = nullptr;
  Id(hid_t i, herr_t (*c)(hid_t)) : id(i), close(c) {}
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  ~Id() {
    if (id >= 0) close(id);
  }
};

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error(fmt::format("cannot write the ranks' rows into '{}': {}", path, what));
}

std::string broadcast_path(const std::string& mine) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  unsigned long n = rank == 0 ? mine.size() : 0;
  MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG, 0, MPI_COMM_WORLD);
  std::string path(n, '\0');
  if (rank == 0) path = mine;
  if (n > 0) MPI_Bcast(path.data(), static_cast<int>(n), MPI_CHAR, 0, MPI_COMM_WORLD);
  return path;
}

template <class V> hid_t memory_type();
template <> hid_t memory_type<double>() { return H5T_NATIVE_DOUBLE; }
template <> hid_t memory_type<std::uint32_t>() { return H5T_NATIVE_UINT32; }
template <> hid_t memory_type<std::uint64_t>() { return H5T_NATIVE_UINT64; }
template <> hid_t memory_type<std::uint8_t>() { return H5T_NATIVE_UINT8; }

// Selects rows `items` (ascending) of `space`, whole: one strided hyperslab when they are evenly spaced (the cyclic
// split: k, k + P, ...), else their union row by row; none when there are none.
void select_rows(hid_t space, const std::vector<std::size_t>& items, const std::vector<hsize_t>& dims) {
  if (items.empty()) {
    H5Sselect_none(space);
    return;
  }
  std::vector<hsize_t> start(dims.size(), 0), stride(dims.size(), 1), count(dims.size(), 1), block(dims);
  block[0] = 1;
  const hsize_t step = items.size() > 1 ? items[1] - items[0] : 1;
  bool even = true;
  for (std::size_t j = 1; j < items.size(); ++j) even = even && items[j] - items[j - 1] == step;
  if (even) {
    start[0] = items[0];
    stride[0] = step;
    count[0] = items.size();
    H5Sselect_hyperslab(space, H5S_SELECT_SET, start.data(), stride.data(), count.data(), block.data());
    return;
  }
  for (std::size_t j = 0; j < items.size(); ++j) {
    start[0] = items[j];
    H5Sselect_hyperslab(space, j == 0 ? H5S_SELECT_SET : H5S_SELECT_OR, start.data(), nullptr, count.data(),
                        block.data());
  }
}

// This rank's rows of one dataset, in one collective write (every rank calls it, with or without rows).
void write_column(const std::string& path, hid_t file, hid_t dxpl, const core::RowSet& mine,
                  const core::RowColumn& col) {
  Id ds(H5Dopen2(file, col.name.c_str(), H5P_DEFAULT), H5Dclose);
  if (ds.id < 0) fail(path, "no dataset '" + col.name + "'");
  Id space(H5Dget_space(ds.id), H5Sclose);
  std::vector<hsize_t> dims(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space.id)));
  H5Sget_simple_extent_dims(space.id, dims.data(), nullptr);
  if (dims.empty() || dims[0] != mine.total)
    fail(path, fmt::format("dataset '{}' has not one row per item ({} items)", col.name, mine.total));
  const std::size_t width = std::accumulate(dims.begin() + 1, dims.end(), std::size_t{1}, std::multiplies<>());
  if (col.size() != mine.items.size() * width)
    fail(path, fmt::format("dataset '{}': {} values for {} rows of {}", col.name, col.size(), mine.items.size(), width));
  select_rows(space.id, mine.items, dims);
  const hsize_t n = col.size();
  Id mem(H5Screate_simple(1, &n, nullptr), H5Sclose);
  if (n == 0) H5Sselect_none(mem.id);
  std::visit(
      [&](const auto& v) {
        using V = typename std::decay_t<decltype(v)>::value_type;
        static const V none{};
        if (H5Dwrite(ds.id, memory_type<V>(), mem.id, space.id, dxpl, v.empty() ? &none : v.data()) < 0)
          fail(path, "H5Dwrite of '" + col.name + "' failed");
      },
      col.data);
}
}  // namespace

WriteStats write(const std::string& root_path, const core::RowSet& mine) {
  const std::string path = broadcast_path(root_path);  // the other ranks wait here for rank 0's file
  const auto t0 = std::chrono::steady_clock::now();
  WriteStats st;
  if (path.empty()) return st;
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // failures become one line (fail), not HDF5's stack on stderr
  Id fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  H5Pset_fapl_mpio(fapl.id, MPI_COMM_WORLD, MPI_INFO_NULL);
  {
    Id file(H5Fopen(path.c_str(), H5F_ACC_RDWR, fapl.id), H5Fclose);
    if (file.id < 0) fail(path, "H5Fopen with MPI-IO failed");
    Id dxpl(H5Pcreate(H5P_DATASET_XFER), H5Pclose);
    H5Pset_dxpl_mpio(dxpl.id, H5FD_MPIO_COLLECTIVE);
    // Every rank names the same columns (the same Part::rows); a column the result did not describe (an option
    // left off, e.g. raw tails) has no dataset on any rank and is skipped by all alike.
    for (const auto& col : mine.columns) {
      if (H5Lexists(file.id, col.name.c_str(), H5P_DEFAULT) <= 0) continue;
      write_column(path, file.id, dxpl.id, mine, col);
      st.bytes += col.size() * std::visit([](const auto& v) { return sizeof(v[0]); }, col.data);
    }
  }  // H5Fclose: collective, flushes the chunks
  st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  MPI_Allreduce(&st.seconds, &st.seconds_max, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  MPI_Allreduce(&st.seconds, &st.seconds_min, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  unsigned long b = st.bytes, total = 0;
  MPI_Allreduce(&b, &total, 1, MPI_UNSIGNED_LONG, MPI_SUM, MPI_COMM_WORLD);
  st.bytes_total = total;
  return st;
}

}  // namespace btob::cli::rows
