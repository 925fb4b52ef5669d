// SPDX-License-Identifier: GPL-3.0-or-later
// The checkpoint of a resumable sweep under MPI (cli/checkpoint.hpp): rank 0 opens the file (io/checkpoint.hpp),
// every rank learns the finished items or the refusal.
#include "cli/checkpoint.hpp"
#include "cli/app.hpp"

namespace btob::cli {
namespace {
// Everything rank 0 learns from the file: what the other ranks need (an error, or the finished items).
struct Opened {
  std::string error;
  std::vector<std::size_t> done;
  template <class A> void members(A& a) { a(error, done); }
};
}  // namespace

std::shared_ptr<Checkpoint> open_checkpoint(const io::fs::path& path, const std::string& identity) {
  auto cp = std::make_shared<Checkpoint>();
  cp->path = path;
  cp->identity = identity;
  Opened o;
  if (mpi::rank() == 0) {
    o.error = io::open_checkpoint_file(*cp);
    o.done = cp->done;
  }
  o = core::unpack<Opened>(mpi::broadcast(mpi::rank() == 0 ? core::pack(o) : std::vector<char>{}));
  if (!o.error.empty()) {
    if (mpi::size() > 1) mpi::fail_everywhere(o.error, 2);
    throw UsageError(o.error);
  }
  cp->done = std::move(o.done);
  return cp;
}

}  // namespace btob::cli
