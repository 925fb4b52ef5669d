// SPDX-License-Identifier: GPL-3.0-or-later
// The processes of an MPI job (`mpirun -n P btob ...`), for the command line only: no analysis module knows of MPI.
// Built with Open MPI when CMake found it (BTOB_MPI); without it, or when btob was not started by mpirun/srun, this
// is one process of rank 0 and nothing here calls MPI.
//
// Life of a job: every rank parses the same command line and validates the same request; checkpoint() is the
// point past which every rank has a valid request (a bad input ends all ranks there with exit 2 and the single
// process's one line).  A sweep (cli/sweep.hpp) then runs its share of the items on every rank; gather() brings
// the parts to rank 0, which alone writes.  A rank that fails after the checkpoint ends the job: one line
// `btob: rank K: <cause>` and MPI_Abort; rank 0 has written nothing by then (files are staged, committed last).
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace btob::cli::mpi {

// MPI_Init_thread (funneled: OpenMP threads inside, MPI from the main thread) when a launcher started this process.
void init(int& argc, char**& argv);
void finalize();
int rank();
int size();
bool available();  // built with MPI

// Every rank got a valid request: returns on all ranks or on none (a rank that failed before it reports in fail()).
void checkpoint();
bool checked();

// Reports an error and ends the process: the single process's line ("btob: " + label + cause) and exit `code`
// when alone or when every rank failed the same way before the checkpoint; else `btob: rank K: <cause>` and
// MPI_Abort (the job ends with a non-zero status).  Codes 130 and 143 (SIGINT, SIGTERM) under mpirun end quietly:
// mpirun sends SIGTERM to every rank when one aborted or when it was interrupted, and the cause was said already.
[[noreturn]] void fail(const std::string& cause, int code, const std::string& label = "error: ");

// While alive, this rank's failure (fail() above, which ends every rank with MPI_Abort) first removes `folder`:
// rank 0's staging folder of the result (io::ResultFiles, `.btob-tmp-...`) that the ranks are writing into
// together.  A rank that fails inside the collective write would otherwise abort rank 0 in mid-write, before its
// own clean-up runs, and leave the hidden folder behind; the result folder itself is untouched either way.  One at
// a time; "" or a path outside a staging folder registers nothing.  The registration ends with the scope, unless an
// exception is leaving it: then it stays for the fail() that reports that exception.
class RemoveOnAbort {
 public:
  explicit RemoveOnAbort(const std::string& staged_file);
  ~RemoveOnAbort();
  RemoveOnAbort(const RemoveOnAbort&) = delete;
  RemoveOnAbort& operator=(const RemoveOnAbort&) = delete;

 private:
  int unwinding_;  // std::uncaught_exceptions() at construction: an exception leaving the scope keeps the folder
};                 // registered for the fail() that follows

// Every rank fails the same way at the same point after the checkpoint (rank 0 found a checkpoint of another
// request and told every rank): rank 0 says the single process's one line, every rank ends with `code`, no abort.
[[noreturn]] void fail_everywhere(const std::string& cause, int code, const std::string& label = "error: ");

// Rank 0's bytes on every rank (a collective: every rank calls it; the others' `bytes` are ignored).
std::vector<char> broadcast(std::vector<char> bytes);

// Every rank's bytes on every rank (index = rank; a collective: every rank calls it).  For small exchanges (a few KB
// per rank): no statistics are kept.
std::vector<std::vector<char>> all_gather(std::vector<char> mine);

// Rank 0 receives every rank's bytes (index = rank, its own moved in); the other ranks send theirs and get {}.
// `compute_seconds` is this rank's work time, kept for the statistics below.
std::vector<std::vector<char>> gather(std::vector<char> mine, double compute_seconds);

// What the last gather cost, on rank 0: recorded in the result's attributes and printed unless --quiet.
struct Stats {
  int ranks = 1;
  double compute_min = 0, compute_max = 0;       // seconds of work per rank
  double wait_seconds = 0;                       // rank 0 waiting at the barrier for the slowest rank
  double gather_seconds = 0;                     // the transfer of all parts to rank 0, after the barrier
  std::uint64_t bytes_total = 0, bytes_max = 0;  // bytes of the parts sent to rank 0 (all, largest per rank)
  double merge_seconds = 0;                      // rank 0 unpacking and merging the parts
};
Stats& stats();

// Thrown on ranks other than 0 by commands that do not split (the older flag-parsing ones): main ends them quietly.
struct RootOnly {};
// Makes the leaf subcommands of `app` that are not request-based run on rank 0 only (rank 0 then works alone).
void guard_root_only(CLI::App& app);
// Subcommands registered by cli::command (request-based: they call checkpoint() and split or run on rank 0).
std::vector<const CLI::App*>& request_apps();

}  // namespace btob::cli::mpi
