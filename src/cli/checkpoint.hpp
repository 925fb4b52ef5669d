// SPDX-License-Identifier: GPL-3.0-or-later
// `--resume`: a sweep (core/sweep.hpp) keeps its finished parts in a checkpoint file while it runs, so that a run
// stopped at any point (SIGKILL, a batch system's time limit, a node failure) continues where it was:
//
//   btob bifurcation ... --out results/b --resume      # OUT/NAME.checkpoint while it runs, removed once written
//
// The files, their rounds, their validation and their refusal are io/checkpoint.hpp's (Python's resume= uses the
// same); a refused checkpoint is one line naming what differs, exit 2.  This layer opens the files on every rank;
// the rounds run through commands::compute, given the MPI ranks by the command line (cli::detail::how_of).
//
// Under mpirun each rank appends its own finished parts to its own file (rank 0: OUT/NAME.checkpoint, rank K:
// OUT/NAME.checkpoint.K): no gather per round, no rank holding more than its parts.  At the end the parts meet once,
// as those of a split sweep do (commands::run_request): a part's named rows stay on their rank and are written into
// NAME.h5 by the ranks (io::Ranks::write_rows), the thin rest goes to rank 0; without write_rows the parts go to rank
// 0.  A job may resume with another number of ranks: the earlier files are shared out (file K to rank K mod P),
// every rank learns the union of the finished items (an allgather of the item lists) and the items left are split
// anew.
#pragma once

#include "cli/mpi.hpp"
#include "core/request.hpp"
#include "core/sweep.hpp"
#include "io/checkpoint.hpp"

#include <memory>
#include <string>

namespace btob::cli {

using io::Checkpoint;
using io::checkpoint_identity;
using io::remove_checkpoint;

// Opens the checkpoint at `path` on every rank (a collective under mpirun): rank 0 lists the earlier runs' files,
// each rank reads its own file when it exists or else starts it (header only) and reads the earlier files that fall
// to it, and locks them for this run (a second run on the same files is refused while the first lives, e.g. ranks
// of a killed mpirun still running; the lock goes with the process, SIGKILL included); every rank then knows every
// finished item.  A file of another request or build is refused: a UsageError naming the first field that differs
// (under mpirun the same line from rank 0 and exit 2 on every rank), the files as they were.
std::shared_ptr<Checkpoint> open_checkpoint(const io::fs::path& path, const std::string& identity);

}  // namespace btob::cli
