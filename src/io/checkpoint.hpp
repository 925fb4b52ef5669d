// SPDX-License-Identifier: GPL-3.0-or-later
// The checkpoint of a resumable sweep (core/sweep.hpp): its finished parts kept in files while it runs, so that a
// run stopped at any point (SIGKILL, a batch system's time limit, a node failure, Ctrl-C) continues where it was.
// One code for the command line's --resume (cli/checkpoint.hpp adds the MPI ranks) and Python's resume= keyword:
//
//   io::Checkpoint cp;  cp.path = "OUT/NAME.checkpoint";  cp.identity = io::checkpoint_identity(command, args);
//   if (std::string why = io::open_checkpoint_file(cp); !why.empty()) refuse(why);   // another request or build
//   auto mine = io::run_in_rounds(req, control, cp, io::alone());   // appends; this process's parts
//   Result res = merge(req, std::move(mine.parts));                  // (commands::run_request)
//   io::remove_checkpoint(cp);                                       // once the result is kept
//
// The run computes its items in rounds (at most checkpoint_rounds of them, so at most that fraction of the work is
// lost) and appends each finished part to its file; a new run with the same files reads them, refuses them when
// they belong to another request or another build of btob (one line naming what differs), skips their items and
// computes the rest.  merge() of the kept parts and the new ones is the uninterrupted result bitwise: an item's
// numbers depend only on the request and the item (the sweep rule), never on the part that computed it.
//
// Files: one per process that writes, beside the output.  File 0 is OUT/NAME.checkpoint (a single process's only
// file, and rank 0's under mpirun); rank K >= 1 of an MPI job appends to OUT/NAME.checkpoint.K.  Each is written by
// its rank alone: no part travels while the job runs, and no rank holds more than its own parts.  A resumed run of
// P ranks finds the earlier files by listing the folder (any earlier number of ranks; a single process reads them
// all) and rank k reads and locks its own file and every earlier file K with K mod P = k; the ranks then learn the
// union of the finished items (cli/checkpoint.hpp) and split what is left anew.  Rank 0 removes every file once the
// result is committed.  Under mpirun the folder must be one every rank sees (as NAME.h5's collective write needs).
//
// File format: the line "btob-checkpoint 1", then records [uint64 size][uint64 FNV-1a of the payload][payload].  The
// first record is the request's identity text; each further record one part (its items and its packed bytes,
// core/pack.hpp).  The header is written to a temporary file and renamed into place; a part is appended and flushed
// to disk (fsync) before the next round starts.  A record cut short by a kill fails its size or hash and is dropped
// on resume (the file is truncated after the last whole record), so every part read back is one that was finished.
#pragma once

#include "core/fields.hpp"
#include "core/pack.hpp"
#include "core/request.hpp"
#include "core/run.hpp"
#include "core/sweep.hpp"
#include "io/io.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace btob::io {

// An open checkpoint: the files this process reads and appends to (under MPI: one rank's; every rank knows every
// finished item).
struct Checkpoint {
  fs::path path;                         // file 0: OUT/NAME.checkpoint, or ./NAME.checkpoint for a command that prints
  std::string identity;                  // the request and the build it belongs to (checkpoint_identity)
  fs::path own;                          // the file this process appends to (checkpoint_file(path, rank))
  std::vector<fs::path> job;             // every file of the job, earlier runs' included: removed with the result
  std::vector<std::size_t> done;         // items finished by earlier runs (every rank's files), ascending
  std::vector<std::vector<char>> parts;  // the parts of the files this process read, packed (emptied once unpacked)
  std::vector<int> locks;                // the files this process opened, locked (flock) while this run uses them
  bool created = false;                  // `own` was made by this run (removed again when the run is refused)
  Checkpoint() = default;
  Checkpoint(const Checkpoint&) = delete;
  Checkpoint& operator=(const Checkpoint&) = delete;
  ~Checkpoint();
};

// The text a checkpoint is keyed by: btob's version, commit and dirty flag, the command and the request's fields
// as the manifest records them, one "key: values" line each.
std::string checkpoint_identity(const std::string& command, const core::Args& args);

// File k of the checkpoint at `path`: `path` itself for k = 0, path.K for k >= 1 (rank K of an MPI job).
fs::path checkpoint_file(const fs::path& path, std::size_t k);

// The K >= 1 of the files path.K in path's folder (an earlier MPI run's ranks), ascending.
std::vector<std::size_t> checkpoint_rank_files(const fs::path& path);

// Opens the files of rank `rank` of `ranks`: its own (checkpoint_file(cp.path, rank), started with the header when
// absent) and every file K of `earlier` (checkpoint_rank_files) with K mod ranks = rank; locks and reads them into cp
// (a second run on the same files is refused while the first lives; the lock goes with the process, SIGKILL
// included).  cp.done: the items of this rank's files; cp.job: every file of the job (files 0..ranks-1 and
// `earlier`).  Returns "" or the one line saying why a file is refused (another request or build: the first field
// that differs; in use; unreadable; an item held twice).
std::string open_checkpoint_files(Checkpoint& cp, std::size_t rank, std::size_t ranks,
                                  const std::vector<std::size_t>& earlier);

// A single process (Python's resume=, the command line without mpirun): rank 0 of 1, reading the files of any
// earlier run (an MPI job's included).  A refused checkpoint leaves the files as they were.
std::string open_checkpoint_file(Checkpoint& cp);

// Sorts the union of the finished items; "" or the line saying an item is held twice (files of two runs mixed).
std::string check_done(const fs::path& path, std::vector<std::size_t>& done);

// Removes the file this run started (cp.created) after a refusal, so that a refused run leaves the folder as it was.
void discard_created(const Checkpoint& cp);

// Appends one finished part (its items, its packed bytes) to cp.own and flushes it to disk.
void append_checkpoint(const Checkpoint& cp, const std::vector<std::size_t>& items, const std::vector<char>& part);

// Removes every file of the job (cp.job: the result was committed).  A missing file is not an error.
void remove_checkpoint(const Checkpoint& cp);

// Items per round for a share of `share` items: about 1/checkpoint_rounds of the share, at least `threads` (a
// round's items keep every OpenMP thread busy).  At most checkpoint_rounds rounds, so a kill loses at most ~3%.
inline constexpr std::size_t checkpoint_rounds = 32;
std::size_t checkpoint_chunk(std::size_t share, int threads);

// The processes that share a sweep: `ranks` of them, this one `rank`; gather(bytes, seconds) brings every rank's
// packed parts to rank 0, once at the end of the sweep (called only when ranks > 1; cli/mpi.hpp's gather under
// mpirun).
//
// write_rows(path, mine), when set (the MPI build with parallel HDF5), writes every rank's rows (core::RowSet) into
// the datasets of the HDF5 file at rank 0's `path`, which rank 0 has created with their full shapes: a collective,
// every rank calls it once, rank 0 when its file is written (commands::write), the others after their part; a `path`
// of "" on rank 0 means nothing is written (the others' paths are ignored).  It returns what the write cost, as
// attributes of the result's manifest.  Without it every rank's rows are gathered to rank 0 with the rest of its part.
struct Ranks {
  std::size_t ranks = 1, rank = 0;
  std::function<std::vector<std::vector<char>>(std::vector<char>, double)> gather;
  // Every rank's bytes on every rank, in rank order (a collective; under mpirun only): what the ranks compute in
  // shares for rank 0 before the run (extras::share_overlays).
  std::function<std::vector<std::vector<char>>(std::vector<char>)> all_gather;
  std::function<core::Attrs(const std::string& path, const core::RowSet& mine)> write_rows;
};
inline Ranks alone() { return {}; }

namespace detail {
// Runs f() (a rank's run_part) and, when it fails, says which items the rank was computing in the error's own
// category (usage errors keep exit status 2): "items 1, 3, 5, ... of 100 (r-max: got ...)".
template <class F> auto naming_items(const std::vector<std::size_t>& items, std::size_t total, F&& f) {
  const auto where = [&] {
    std::string s;
    for (std::size_t i = 0; i < items.size() && i < 3; ++i) s += (i ? ", " : "") + std::to_string(items[i]);
    if (items.size() > 3) s += ", ...";
    return fmt::format("item{} {} of {}: ", items.size() == 1 ? "" : "s", items.empty() ? "none" : s, total);
  };
  try {
    return f();
  } catch (const core::Cancelled&) {
    throw;
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(where() + e.what());
  } catch (const std::domain_error& e) {
    throw std::domain_error(where() + e.what());
  } catch (const std::bad_alloc&) {
    throw std::runtime_error(where() + "out of memory");
  } catch (const std::exception& e) {
    throw std::runtime_error(where() + e.what());
  }
}

// A round's progress (done of total within its run_part) as the run's: `before` items finished by this run's earlier
// rounds, the round's `width` items (over every rank) out of `total`, the items this run computes (not those a
// resumed checkpoint held: the remaining time is then at this run's own rate).
struct RoundProgress : core::ProgressSink {
  core::ProgressSink* sink = nullptr;
  std::size_t before = 0, width = 0, total = 0;
  void update(std::size_t done, std::size_t of) override {
    if (sink) sink->update(before + (of ? done * width / of : width), total);
  }
};

// The items of 0..n-1 not in `done` (ascending).
std::vector<std::size_t> items_left(std::size_t n, const std::vector<std::size_t>& done);
}  // namespace detail

// One rank's parts of a sweep (commands::run_split: the one part it computed; run_in_rounds: the parts its
// checkpoint files held and those of its rounds, their items interleaved), of `items` in all, and the seconds
// its work took (MPI statistics).
template <class Part> struct RankParts {
  std::vector<Part> parts;
  std::size_t items = 0;
  double seconds = 0;
};

// Computes the items of `req` that `cp` lacks in rounds, appending each round's part to this rank's checkpoint file.
// Rank k of `on` takes every P-th remaining item and appends to its own file; no part travels while the sweep runs.
// Returns this rank's parts: those of the files it read and those it computed (commands::run_request merges or
// gathers them at the end).
template <core::Sweep Req>
auto run_in_rounds(const Req& req, const core::RunControl& control, Checkpoint& cp, const Ranks& on) {
  using Part = decltype(run_part(req, std::vector<std::size_t>{}, control));
  const auto t0 = std::chrono::steady_clock::now();
  RankParts<Part> out;
  const std::size_t n = core::work_items(req, control.cancel), ranks = on.ranks, me = on.rank;
  out.items = n;
  const std::vector<std::size_t> left = detail::items_left(n, cp.done);
  std::vector<std::size_t> mine;
  for (std::size_t i = me; i < left.size(); i += ranks) mine.push_back(left[i]);
  const std::size_t share = (left.size() + ranks - 1) / ranks, chunk = checkpoint_chunk(share, control.threads);
  for (auto& bytes : cp.parts) {
    out.parts.push_back(core::unpack<Part>(bytes));
    std::vector<char>().swap(bytes);  // one copy of the earlier parts at a time
  }
  cp.parts.clear();
  detail::RoundProgress progress;
  progress.sink = control.progress;
  progress.total = left.size();  // this run's own work: the bar's remaining time is at this run's rate
  for (std::size_t at = 0; at < mine.size(); at += chunk) {
    const std::vector<std::size_t> slice(mine.begin() + static_cast<std::ptrdiff_t>(at),
                                         mine.begin() + static_cast<std::ptrdiff_t>(std::min(at + chunk, mine.size())));
    // The bar of rank 0 (the others are quiet): the ranks' rounds go at about the same pace.
    progress.before = std::min(at * ranks, left.size());
    progress.width = std::min(std::min(chunk, share - at) * ranks, left.size() - progress.before);
    core::RunControl c = control;
    c.progress = &progress;
    Part p = detail::naming_items(slice, n, [&] { return run_part(req, slice, c); });
    append_checkpoint(cp, slice, core::pack(p));
    out.parts.push_back(std::move(p));
  }
  out.seconds = core::seconds_since(t0);
  return out;
}

}  // namespace btob::io
