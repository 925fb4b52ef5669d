// SPDX-License-Identifier: GPL-3.0-or-later
// The checkpoint of a resumable sweep under MPI (cli/checkpoint.hpp): every rank opens its files
// (io/checkpoint.hpp), every rank learns the finished items or the refusal.
#include "cli/checkpoint.hpp"
#include "cli/app.hpp"

namespace btob::cli {
namespace {
// What a rank learns from its files, and then every rank from all of them: an error, or the finished items.
struct Opened {
  std::string error;
  std::vector<std::size_t> done;
  template <class A> void members(A& a) { a(error, done); }
};

// Every rank's Opened on every rank, as one: the first error by rank (rank 0's when it has one, as a single
// process would say it), else the union of the finished items, checked for an item held twice.  The item lists
// travel, not the parts: 8 bytes per finished item, where reading every file on every rank would read the whole
// checkpoint P times.
Opened agree(const Opened& mine, const io::fs::path& path) {
  const auto all = mpi::gather(core::pack(mine), 0.0);
  Opened o;
  for (const auto& bytes : all) {
    if (!o.error.empty()) break;
    Opened k = core::unpack<Opened>(bytes);
    o.error = std::move(k.error);
    o.done.insert(o.done.end(), k.done.begin(), k.done.end());
  }
  if (mpi::rank() == 0 && o.error.empty()) o.error = io::check_done(path, o.done);
  return core::unpack<Opened>(mpi::broadcast(mpi::rank() == 0 ? core::pack(o) : std::vector<char>{}));
}
}  // namespace

std::shared_ptr<Checkpoint> open_checkpoint(const io::fs::path& path, const std::string& identity) {
  auto cp = std::make_shared<Checkpoint>();
  cp->path = path;
  cp->identity = identity;
  const auto ranks = static_cast<std::size_t>(mpi::size()), rank = static_cast<std::size_t>(mpi::rank());
  // The earlier runs' rank files as rank 0 finds them: every rank opens its share of the same list.
  std::vector<std::size_t> earlier;
  if (rank == 0) earlier = io::checkpoint_rank_files(path);
  if (ranks > 1) earlier = core::unpack<std::vector<std::size_t>>(mpi::broadcast(core::pack(earlier)));
  Opened o;
  o.error = io::open_checkpoint_files(*cp, rank, ranks, earlier);
  o.done = cp->done;
  if (ranks > 1) o = agree(o, path);
  if (!o.error.empty()) {
    io::discard_created(*cp);  // a refused run leaves the folder as it was
    if (ranks > 1) mpi::fail_everywhere(o.error, 2);
    throw UsageError(o.error);
  }
  cp->done = std::move(o.done);
  return cp;
}

}  // namespace btob::cli
