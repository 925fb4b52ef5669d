// SPDX-License-Identifier: GPL-3.0-or-later
// `--resume`: a sweep (core/sweep.hpp) keeps its finished parts in a checkpoint file while it runs, so that a run
// stopped at any point (SIGKILL, a batch system's time limit, a node failure) continues where it was:
//
//   btob bifurcation ... --out results/b --resume      # OUT/NAME.checkpoint while it runs, removed once written
//
// The file, its rounds, its validation and its refusal are io/checkpoint.hpp's (Python's resume= uses the same);
// a refused file is one line naming what differs, exit 2.  This layer opens the file on every rank; the rounds run
// through commands::compute, given the MPI ranks by the command line (cli::detail::how_of).
//
// Under mpirun, rank 0 alone reads and writes the one checkpoint: each round every rank computes its share of the
// round's items and rank 0 gathers and appends them.  One file for the job rather than one per rank: it needs no
// shared file system (only rank 0 touches the disk, as for the output), and a job may resume with another number of
// ranks (the remaining items are split anew).
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

// Opens the checkpoint at `path` on every rank (a collective under mpirun): rank 0 reads it when it exists or else
// starts it (header only), and locks it for this run (a second run on the same file is refused while the first
// lives, e.g. ranks of a killed mpirun still running; the lock goes with the process, SIGKILL included).  A file of
// another request or build is refused: a UsageError naming the first field that differs (under mpirun the same line
// from rank 0 and exit 2 on every rank).
std::shared_ptr<Checkpoint> open_checkpoint(const io::fs::path& path, const std::string& identity);

}  // namespace btob::cli
