// SPDX-License-Identifier: GPL-3.0-or-later
// Each MPI rank writes its own rows of a split sweep's bulk datasets into the one NAME.h5 (parallel HDF5 over
// MPI-IO), instead of sending them to rank 0: the collective behind io::Ranks::write_rows (commands::RankRows).
// Built only with parallel HDF5 (cmake/ParallelHdf5.cmake: BTOB_PARALLEL_HDF5); the command line alone calls it.
#pragma once

#include "core/sweep.hpp"

#include <cstdint>
#include <string>

namespace btob::cli::rows {

// What the last write cost, on every rank (its own) and reduced over the ranks.
struct WriteStats {
  double seconds = 0;                       // this rank: open, write its rows, close
  double seconds_min = 0, seconds_max = 0;  // the fastest and the slowest rank
  std::uint64_t bytes = 0;                  // this rank's rows
  std::uint64_t bytes_total = 0;            // every rank's
};

// A collective over MPI_COMM_WORLD, called once by every rank: rank 0's `path` (an HDF5 file it has created and
// closed, holding every dataset that `mine` names with its full shape) is sent to every rank; "" on rank 0 ends the
// collective with nothing written.  Row j of `mine` is row mine.items[j] of each named dataset that the file holds:
// the rows first move to the rank whose block of the file holds them (one all-to-all per dataset), then every rank
// writes its block in one collective H5Dwrite.  A column of strings is a table's lines (core::RowColumn): rank 0
// has staged the table's header beside `path` (core::table_file); the lines move to the same block owners and each
// rank writes its block's bytes after the header and the blocks before it (MPI-IO, collective).  A failure ends the job
// at once with one line naming the file and HDF5's cause (cli/mpi.hpp fail, MPI_Abort) after removing rank 0's staging
// folder: no partial file, no hanging ranks.
WriteStats write(const std::string& path, const core::RowSet& mine);

}  // namespace btob::cli::rows
