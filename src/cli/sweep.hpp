// SPDX-License-Identifier: GPL-3.0-or-later
// Runs a sweep request (core/sweep.hpp) on every rank of an MPI job and merges the parts on rank 0:
//
//   const auto res = sweep(req, ctx);   // std::optional<Result>: the result on rank 0, nullopt on the others
//   if (!res) return;                   // other ranks write nothing
//
// Rank k computes the items of part k of a cyclic split (core::cyclic_items), with its own OpenMP threads; rank 0
// gathers the parts (core/pack.hpp) and merges them.  One process (no MPI, or mpirun -n 1) runs run(req) itself.
// With --resume (ctx.checkpoint), the items run in rounds whose parts are kept in a checkpoint (cli/checkpoint.hpp).
#pragma once

#include "cli/checkpoint.hpp"
#include "cli/command.hpp"
#include "cli/mpi.hpp"
#include "core/pack.hpp"
#include "core/sweep.hpp"

#include <chrono>
#include <iostream>
#include <new>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

namespace btob::cli {

template <core::Sweep Req> auto sweep(const Req& req, const Context& ctx) {
  using Part = decltype(run_part(req, std::vector<std::size_t>{}, ctx.control));
  using Result = decltype(merge(req, std::vector<Part>{}));
  if (!mpi::checked()) throw std::logic_error("cli::sweep before the checkpoint of cli::command");
  if (ctx.checkpoint) return run_checkpointed(req, ctx.control, *ctx.checkpoint, true);  // --resume: in rounds
  if (mpi::size() == 1) return std::optional<Result>(run(req, ctx.control));
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t n = core::work_items(req, ctx.control.cancel);  // counting may be long (the atlas): polled
  const auto items =
      core::cyclic_items(n, static_cast<std::size_t>(mpi::rank()), static_cast<std::size_t>(mpi::size()));
  Part mine = io::detail::naming_items(items, n, [&] { return run_part(req, items, ctx.control); });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // Rank 0 keeps its own part as it is; the others send theirs as bytes.
  std::vector<std::vector<char>> bytes =
      mpi::gather(mpi::rank() == 0 ? std::vector<char>{} : core::pack(mine), seconds);
  if (mpi::rank() != 0) return std::optional<Result>();
  const auto t1 = std::chrono::steady_clock::now();
  std::vector<Part> parts;
  parts.push_back(std::move(mine));
  for (std::size_t k = 1; k < bytes.size(); ++k) parts.push_back(core::unpack<Part>(bytes[k]));
  bytes.clear();
  std::optional<Result> res(merge(req, std::move(parts)));
  mpi::Stats& st = mpi::stats();
  st.merge_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  if (!ctx.quiet)
    std::cerr << fmt::format(
        "btob: {} ranks x {} items: work {:.3f}..{:.3f} s per rank; gathered {} bytes in {:.4f} s, "
        "merged in {:.4f} s\n",
        st.ranks, req.work_items(), st.compute_min, st.compute_max, st.bytes_total, st.gather_seconds,
        st.merge_seconds);
  return res;
}

}  // namespace btob::cli
