// SPDX-License-Identifier: GPL-3.0-or-later
// The checkpoint of a resumable sweep (core/sweep.hpp): its finished parts kept in a file while it runs, so that a
// run stopped at any point (SIGKILL, a batch system's time limit, a node failure, Ctrl-C) continues where it was.
// One code for the command line's --resume (cli/checkpoint.hpp adds the MPI ranks) and Python's resume= keyword:
//
//   io::Checkpoint cp;  cp.path = "OUT/NAME.checkpoint";  cp.identity = io::checkpoint_identity(command, args);
//   if (std::string why = io::open_checkpoint_file(cp); !why.empty()) refuse(why);   // another request or build
//   Result res = io::run_in_rounds(req, control, cp, io::alone());                   // appends, then merges
//   io::remove_checkpoint(cp);                                                       // once the result is kept
//
// The run computes its items in rounds (at most checkpoint_rounds of them, so at most that fraction of the work is
// lost) and appends each finished part to the file; a new run with the same file reads it, refuses it when it
// belongs to another request or another build of btob (one line naming what differs), skips its items and
// computes the rest.  merge() of the kept parts and the new ones is the uninterrupted result bitwise: an item's
// numbers depend only on the request and the item (the sweep rule), never on the part that computed it.
//
// File: the line "btob-checkpoint 1", then records [uint64 size][uint64 FNV-1a of the payload][payload].  The first
// record is the request's identity text; each further record one part (its items and its packed bytes, core/pack.hpp).
// The header is written to a temporary file and renamed into place; a part is appended and flushed to disk
// (fsync) before the next round starts.  A record cut short by a kill fails its size or hash and is dropped on
// resume (the file is truncated after the last whole record), so every part read back is one that was finished.
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
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace btob::io {

// An open checkpoint (the process that writes it holds the parts; under MPI every rank knows the finished items).
struct Checkpoint {
  fs::path path;                         // OUT/NAME.checkpoint, or ./NAME.checkpoint for a command that prints
  std::string identity;                  // the request and the build it belongs to (checkpoint_identity)
  std::vector<std::size_t> done;         // items finished by earlier runs, ascending
  std::vector<std::vector<char>> parts;  // their parts, packed (emptied once unpacked)
  int lock = -1;                         // the open file, locked (flock) while this run uses it
  Checkpoint() = default;
  Checkpoint(const Checkpoint&) = delete;
  Checkpoint& operator=(const Checkpoint&) = delete;
  ~Checkpoint();
};

// The text a checkpoint is keyed by: btob's version, commit and dirty flag, the command and the request's fields
// as the manifest records them, one "key: values" line each.
std::string checkpoint_identity(const std::string& command, const core::Args& args);

// Reads the checkpoint at cp.path into cp when it exists, or else starts it (header only), and locks it for this
// run (a second run on the same file is refused while the first lives; the lock goes with the process, SIGKILL
// included).  Returns "" or the one line saying why the file is refused (another request or build: the first
// field that differs; in use; unreadable).
std::string open_checkpoint_file(Checkpoint& cp);

// Appends one finished part (its items, its packed bytes) and flushes it to disk.
void append_checkpoint(const Checkpoint& cp, const std::vector<std::size_t>& items, const std::vector<char>& part);

// Removes the file (the result was committed).  A missing file is not an error.
void remove_checkpoint(const Checkpoint& cp);

// Items per round for a share of `share` items: about 1/checkpoint_rounds of the share, at least `threads` (a
// round's items keep every OpenMP thread busy).  At most checkpoint_rounds rounds, so a kill loses at most ~3%.
inline constexpr std::size_t checkpoint_rounds = 32;
std::size_t checkpoint_chunk(std::size_t share, int threads);

// The processes that share each round: `ranks` of them, this one `rank`; gather(bytes, seconds) brings every
// rank's packed part to rank 0 (called only when ranks > 1; cli/mpi.hpp's gather under mpirun).
//
// write_rows(path, mine), when set (the MPI build with parallel HDF5), writes every rank's rows (core::RowSet) into
// the datasets of the HDF5 file at rank 0's `path`, which rank 0 has created with their full shapes: a collective,
// every rank calls it once, rank 0 when its file is written (commands::write), the others after their part; a `path`
// of "" on rank 0 means nothing is written (the others' paths are ignored).  It returns what the write cost, as
// attributes of the result's manifest.  Without it every rank's rows are gathered to rank 0 with the rest of its part.
struct Ranks {
  std::size_t ranks = 1, rank = 0;
  std::function<std::vector<std::vector<char>>(std::vector<char>, double)> gather;
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

// Computes the items of `req` that `cp` lacks in rounds, appending each round's parts to the checkpoint, and merges
// them with the parts it held.  Rank k of `ranks` takes every P-th remaining item of each round, rank 0 gathers and
// writes.  The result on rank 0, nullopt elsewhere.
template <core::Sweep Req>
auto run_in_rounds(const Req& req, const core::RunControl& control, Checkpoint& cp, const Ranks& on) {
  using Part = decltype(run_part(req, std::vector<std::size_t>{}, control));
  using Result = decltype(merge(req, std::vector<Part>{}));
  const std::size_t n = core::work_items(req, control.cancel), ranks = on.ranks, me = on.rank;
  const std::vector<std::size_t> left = detail::items_left(n, cp.done);
  std::vector<std::size_t> mine;
  for (std::size_t i = me; i < left.size(); i += ranks) mine.push_back(left[i]);
  const std::size_t share = (left.size() + ranks - 1) / ranks, chunk = checkpoint_chunk(share, control.threads);
  std::vector<Part> parts;
  for (const auto& bytes : cp.parts) parts.push_back(core::unpack<Part>(bytes));
  cp.parts.clear();
  detail::RoundProgress progress;
  progress.sink = control.progress;
  progress.total = left.size();  // this run's own work: the bar's remaining time is at this run's rate
  for (std::size_t at = 0; at < share; at += chunk) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<std::size_t> slice(mine.begin() + static_cast<std::ptrdiff_t>(std::min(at, mine.size())),
                                         mine.begin() + static_cast<std::ptrdiff_t>(std::min(at + chunk, mine.size())));
    progress.before = std::min(at * ranks, left.size());
    progress.width = std::min(std::min(chunk, share - at) * ranks, left.size() - progress.before);
    core::RunControl c = control;
    c.progress = &progress;
    std::optional<Part> p;
    if (!slice.empty()) p = detail::naming_items(slice, n, [&] { return run_part(req, slice, c); });
    if (ranks == 1) {
      append_checkpoint(cp, slice, core::pack(*p));
      parts.push_back(std::move(*p));
      continue;
    }
    const double seconds = core::seconds_since(t0);
    auto bytes = on.gather(p ? core::pack(*p) : std::vector<char>{}, seconds);
    if (me != 0) continue;
    for (auto& b : bytes) {
      if (b.empty()) continue;  // a rank whose share had no item left this round
      Part q = core::unpack<Part>(b);
      append_checkpoint(cp, q.items, b);
      parts.push_back(std::move(q));
    }
  }
  if (me != 0) return std::optional<Result>();
  return std::optional<Result>(merge(req, std::move(parts)));
}

}  // namespace btob::io
