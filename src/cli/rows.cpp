// SPDX-License-Identifier: GPL-3.0-or-later
// The ranks' collective write of their rows (cli/rows.hpp), with HDF5's C API and its MPI-IO driver.
#include "cli/rows.hpp"

#include "cli/mpi.hpp"
#include "core/result.hpp"

#include <fmt/format.h>
#include <hdf5.h>
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdlib>
#include <filesystem>
#include <numeric>
#include <stdexcept>
#include <thread>
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

// A failure inside the collective ends the job at once (cli/mpi.hpp fail: one line, rank 0's staging folder
// removed, MPI_Abort).  Throwing would unwind through H5Fclose, itself a collective, which the other ranks, still
// in the write, never match: the job would hang instead of failing.
[[noreturn]] void fail(const std::string& path, const std::string& what) {
  mpi::fail(fmt::format("cannot write the ranks' rows into '{}': {}", path, what), 1);
}

// Rank 0's path on every rank.  The other ranks arrive here right after their part and wait for rank 0's merge and
// file: polled with a 1 ms sleep (MPI_Ibcast) rather than a blocking broadcast, which spins, so that a waiting rank
// leaves its core to rank 0 on shared or oversubscribed nodes (as the gather does, cli/mpi.cpp).
std::string broadcast_path(const std::string& mine) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  unsigned long n = rank == 0 ? mine.size() : 0;
  MPI_Request length;
  MPI_Ibcast(&n, 1, MPI_UNSIGNED_LONG, 0, MPI_COMM_WORLD, &length);
  for (int done = 0; MPI_Test(&length, &done, MPI_STATUS_IGNORE), !done;)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
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

// Which rows of the file each rank writes: a block split of the `total` rows, rank q rows [first(q), first(q + 1)).
// The ranks compute in a cyclic split (core::cyclic_items: neighbouring items cost alike), which in the file is a
// selection strided by P; for short rows (one orbit per r value) MPI-IO then moves millions of 8-byte pieces (a
// 72 MB result of 1e6 rows took 26 s on 2 ranks).  So the rows first go to the rank whose block holds them (one
// all-to-all, the classic two-phase exchange done here, where the rows are known), and each rank writes one
// contiguous block: a collective write of P large pieces.
struct Blocks {
  std::size_t total, ranks;
  std::size_t first(std::size_t q) const { return total * q / ranks; }
  std::size_t owner(std::size_t item) const {  // the q with first(q) <= item < first(q + 1)
    std::size_t q = item * ranks / total;
    while (q + 1 < ranks && first(q + 1) <= item) ++q;
    while (q > 0 && first(q) > item) --q;
    return q;
  }
};

// The exchange's plan, the same for every column: how many rows go to and come from each rank, and where each row
// received lands in this rank's block.
struct Plan {
  std::vector<int> send_count, send_at, recv_count, recv_at;
  std::vector<std::size_t> place;  // received row j -> row place[j] of the block
  std::size_t block_first = 0, block_rows = 0;
};

Plan plan_exchange(const core::RowSet& mine, int rank, int ranks) {
  const Blocks b{mine.total, static_cast<std::size_t>(ranks)};
  const auto P = static_cast<std::size_t>(ranks);
  Plan p;
  p.send_count.assign(P, 0);
  for (std::size_t item : mine.items) ++p.send_count[b.owner(item)];  // items ascending: runs per owner, in order
  p.recv_count.assign(P, 0);
  MPI_Alltoall(p.send_count.data(), 1, MPI_INT, p.recv_count.data(), 1, MPI_INT, MPI_COMM_WORLD);
  p.send_at.assign(P, 0);
  p.recv_at.assign(P, 0);
  for (std::size_t q = 1; q < P; ++q) {
    p.send_at[q] = p.send_at[q - 1] + p.send_count[q - 1];
    p.recv_at[q] = p.recv_at[q - 1] + p.recv_count[q - 1];
  }
  const auto r = static_cast<std::size_t>(rank);
  p.block_first = b.first(r);
  p.block_rows = b.first(r + 1) - b.first(r);
  std::vector<unsigned long> sent(mine.items.begin(), mine.items.end()), got(p.block_rows);
  MPI_Alltoallv(sent.data(), p.send_count.data(), p.send_at.data(), MPI_UNSIGNED_LONG, got.data(), p.recv_count.data(),
                p.recv_at.data(), MPI_UNSIGNED_LONG, MPI_COMM_WORLD);
  p.place.resize(got.size());
  for (std::size_t j = 0; j < got.size(); ++j) p.place[j] = got[j] - p.block_first;
  return p;
}

// One column's rows moved to their block's rank (rows of `row_bytes` bytes), in the block's order.
std::vector<char> exchange(const Plan& p, const char* rows, std::size_t row_bytes) {
  MPI_Datatype row;
  MPI_Type_contiguous(static_cast<int>(row_bytes), MPI_BYTE, &row);
  MPI_Type_commit(&row);
  std::vector<char> got(p.block_rows * row_bytes), block(p.block_rows * row_bytes);
  static const char none = 0;
  MPI_Alltoallv(rows ? rows : &none, p.send_count.data(), p.send_at.data(), row, got.empty() ? nullptr : got.data(),
                p.recv_count.data(), p.recv_at.data(), row, MPI_COMM_WORLD);
  MPI_Type_free(&row);
  for (std::size_t j = 0; j < p.place.size(); ++j)
    std::copy_n(got.data() + j * row_bytes, row_bytes, block.data() + p.place[j] * row_bytes);
  return block;
}

// One table's lines (cli/rows.hpp: a column of strings, one line per item) moved to the rank whose block holds them,
// as that block's text in item order, each line ending in '\n': their lengths travel first (the plan's counts), then
// the bytes (counts in bytes from those lengths).
std::string exchange_lines(const std::string& path, const Plan& p, const std::vector<std::string>& lines) {
  const std::size_t P = p.send_count.size();
  std::vector<unsigned long> len(lines.size()), got_len(p.place.size());
  for (std::size_t j = 0; j < lines.size(); ++j) len[j] = lines[j].size() + 1;
  static const unsigned long none = 0;
  MPI_Alltoallv(len.empty() ? &none : len.data(), p.send_count.data(), p.send_at.data(), MPI_UNSIGNED_LONG,
                got_len.empty() ? nullptr : got_len.data(), p.recv_count.data(), p.recv_at.data(), MPI_UNSIGNED_LONG,
                MPI_COMM_WORLD);
  // Bytes to and from each rank, and where each rank's start; MPI counts are int: a rank's share of one table
  // above 2 GiB would need a derived type, refused instead.
  std::vector<int> sc(P), sa(P, 0), rc(P), ra(P, 0);
  const auto bytes = [&](const std::vector<unsigned long>& l, int first, int count) {
    const unsigned long b = std::accumulate(l.begin() + first, l.begin() + first + count, 0UL);
    if (b > INT_MAX) fail(path, "a rank's share of a table's lines exceeds 2 GiB");
    return static_cast<int>(b);
  };
  for (std::size_t q = 0; q < P; ++q) {
    sc[q] = bytes(len, p.send_at[q], p.send_count[q]);
    rc[q] = bytes(got_len, p.recv_at[q], p.recv_count[q]);
    if (q > 0 &&
        (static_cast<long>(sa[q - 1]) + sc[q - 1] > INT_MAX || static_cast<long>(ra[q - 1]) + rc[q - 1] > INT_MAX))
      fail(path, "a rank's share of a table's lines exceeds 2 GiB");
    if (q > 0) sa[q] = sa[q - 1] + sc[q - 1], ra[q] = ra[q - 1] + rc[q - 1];
  }
  std::string sent, got(static_cast<std::size_t>(ra[P - 1]) + static_cast<std::size_t>(rc[P - 1]), '\0');
  for (const std::string& line : lines) (sent += line) += '\n';
  MPI_Alltoallv(sent.data(), sc.data(), sa.data(), MPI_CHAR, got.data(), rc.data(), ra.data(), MPI_CHAR,
                MPI_COMM_WORLD);
  // Received line j (from rank q in q's item order) is row place[j] of the block.
  std::vector<std::size_t> at(p.block_rows), n(p.block_rows);
  std::size_t off = 0;
  for (std::size_t j = 0; j < got_len.size(); ++j) {
    at[p.place[j]] = off;
    n[p.place[j]] = got_len[j];
    off += got_len[j];
  }
  std::string block;
  block.reserve(got.size());
  for (std::size_t k = 0; k < p.block_rows; ++k) block.append(got, at[k], n[k]);
  return block;
}

// This rank's block of one table's lines written after the header rank 0 wrote (`header` bytes): MPI-IO, each rank
// at the header plus the bytes of the blocks before its own (MPI_Exscan), in collective writes of at most 1 GiB.
// Returns the bytes this rank wrote.
std::uint64_t write_table(const std::string& csv, const Plan& plan, const std::vector<std::string>& lines,
                          unsigned long header) {
  const std::string block = exchange_lines(csv, plan, lines);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  unsigned long mine = block.size(), before = 0;
  MPI_Exscan(&mine, &before, 1, MPI_UNSIGNED_LONG, MPI_SUM, MPI_COMM_WORLD);
  if (rank == 0) before = 0;  // MPI_Exscan leaves rank 0's undefined
  constexpr unsigned long kChunk = 1UL << 30;
  unsigned long chunks = (mine + kChunk - 1) / kChunk, most = 0;
  MPI_Allreduce(&chunks, &most, 1, MPI_UNSIGNED_LONG, MPI_MAX, MPI_COMM_WORLD);  // every rank calls as often
  MPI_File fh;
  if (MPI_File_open(MPI_COMM_WORLD, csv.c_str(), MPI_MODE_WRONLY, MPI_INFO_NULL, &fh) != MPI_SUCCESS)
    fail(csv, "MPI_File_open failed");
  for (unsigned long c = 0; c < most; ++c) {
    const unsigned long from = std::min(mine, c * kChunk), count = std::min(mine - from, kChunk);
    if (MPI_File_write_at_all(fh, static_cast<MPI_Offset>(header + before + from), block.data() + from,
                              static_cast<int>(count), MPI_CHAR, MPI_STATUS_IGNORE) != MPI_SUCCESS)
      fail(csv, "MPI_File_write_at_all failed");
  }
  if (MPI_File_close(&fh) != MPI_SUCCESS) fail(csv, "MPI_File_close failed");
  return mine;
}

// The tables among `mine`'s columns, each written where rank 0 staged its header (beside NAME.h5, as
// core::table_file names it); a table rank 0 did not stage (the request has none, a lyapunov-strip's summary) is
// skipped by every rank alike (rank 0 says which).
std::uint64_t write_tables(const std::string& path, const core::RowSet& mine, const Plan& plan) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const std::filesystem::path h5(path);
  std::uint64_t bytes = 0;
  for (const auto& col : mine.columns) {
    if (!col.is_table()) continue;
    const std::string csv = (h5.parent_path() / core::table_file(h5.stem().string(), col.name)).string();
    long header = -1;  // the staged header's size; -1: no such table
    std::error_code ec;
    if (rank == 0 && std::filesystem::exists(csv, ec)) header = static_cast<long>(std::filesystem::file_size(csv, ec));
    if (ec) fail(csv, ec.message());
    MPI_Bcast(&header, 1, MPI_LONG, 0, MPI_COMM_WORLD);
    if (header < 0) continue;
    bytes += write_table(csv, plan, std::get<std::vector<std::string>>(col.data), static_cast<unsigned long>(header));
  }
  return bytes;
}

// This rank's block of one dataset, in one collective write (every rank calls it, with or without rows).
void write_column(const std::string& path, hid_t file, hid_t dxpl, const core::RowSet& mine, const Plan& plan,
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
    fail(path,
         fmt::format("dataset '{}': {} values for {} rows of {}", col.name, col.size(), mine.items.size(), width));
  std::visit(
      [&](const auto& v) {
        using V = typename std::decay_t<decltype(v)>::value_type;
        if constexpr (std::is_same_v<V, std::string>) {
          fail(path, "'" + col.name + "' is a table's lines, not a dataset");
        } else {
          const std::vector<char> block = exchange(plan, reinterpret_cast<const char*>(v.data()), width * sizeof(V));
          std::vector<hsize_t> start(dims.size(), 0), count(dims);
          start[0] = plan.block_first;
          count[0] = plan.block_rows;
          const hsize_t n = plan.block_rows * width;
          if (n > 0) H5Sselect_hyperslab(space.id, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr);
          else H5Sselect_none(space.id);
          Id mem(H5Screate_simple(1, &n, nullptr), H5Sclose);
          if (n == 0) H5Sselect_none(mem.id);
          static const V none{};
          const void* data = n ? static_cast<const void*>(block.data()) : &none;
          if (H5Dwrite(ds.id, memory_type<V>(), mem.id, space.id, dxpl, data) < 0)
            fail(path, "H5Dwrite of '" + col.name + "' failed");
        }
      },
      col.data);
}
}  // namespace

WriteStats write(const std::string& root_path, const core::RowSet& mine) {
  const std::string path = broadcast_path(root_path);  // the other ranks wait here for rank 0's file
  const auto t0 = std::chrono::steady_clock::now();
  WriteStats st;
  if (path.empty()) return st;
  const mpi::RemoveOnAbort staging(path);       // a rank failing from here on removes rank 0's staging folder first
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // failures become one line (fail), not HDF5's stack on stderr
  Id fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  H5Pset_fapl_mpio(fapl.id, MPI_COMM_WORLD, MPI_INFO_NULL);
  Plan plan;
  {
    Id file(H5Fopen(path.c_str(), H5F_ACC_RDWR, fapl.id), H5Fclose);
    if (file.id < 0) fail(path, "H5Fopen with MPI-IO failed");
    Id dxpl(H5Pcreate(H5P_DATASET_XFER), H5Pclose);
    H5Pset_dxpl_mpio(dxpl.id, H5FD_MPIO_COLLECTIVE);
    // Every rank names the same columns (the same Part::rows); a column the result did not describe (an option
    // left off, e.g. raw tails) has no dataset on any rank and is skipped by all alike.
    int rank = 0, ranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    plan = plan_exchange(mine, rank, ranks);
    // Fault injection for the tests (tests/mpi_sweeps.sh): BTOB_MPI_ROWS_FAIL=K makes rank K fail here, inside the
    // collective with the file open on every rank, as a full disk or a lost node would.
    if (const char* f = std::getenv("BTOB_MPI_ROWS_FAIL"); f && std::to_string(rank) == f)
      fail(path, "failed on purpose (BTOB_MPI_ROWS_FAIL)");
    for (const auto& col : mine.columns) {
      if (col.is_table() || H5Lexists(file.id, col.name.c_str(), H5P_DEFAULT) <= 0) continue;
      write_column(path, file.id, dxpl.id, mine, plan, col);
      st.bytes += std::visit([](const auto& v) { return v.size() * sizeof(v[0]); }, col.data);
    }
  }  // H5Fclose: collective, flushes the chunks
  st.bytes += write_tables(path, mine, plan);
  st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  MPI_Allreduce(&st.seconds, &st.seconds_max, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  MPI_Allreduce(&st.seconds, &st.seconds_min, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  unsigned long b = st.bytes, total = 0;
  MPI_Allreduce(&b, &total, 1, MPI_UNSIGNED_LONG, MPI_SUM, MPI_COMM_WORLD);
  st.bytes_total = total;
  return st;
}

}  // namespace btob::cli::rows
