// SPDX-License-Identifier: GPL-3.0-or-later
// The one path from a request to its result and files, shared by every front end (the command line, `btob run`'s
// scenes and manifests, Python):
//
//   ready(req)                          prepare (Spec::prepare: data files) -> validate -> the overlays' names
//   estimate_* (req, ...)               a dry run: the sweep's sample, or the counted work at the route rates
//   compute(req, how)                   run (split over MPI ranks, or in rounds kept in a checkpoint, or run(req))
//                                       -> Spec::also_write -> the overlays of the result (extras)
//   record(rec, provenance)             Contents, attributes, the request as text, the tables, the figure's script
//   write(rec, out, name, title, opts)  NAME.h5, the CSV (and LaTeX) tables, NAME.json, the figure: all or nothing
//
// A front end adds only what is its own: the command line its flags, MPI, --dry-run's text and the terminal's words
// (Spec::warn, print, report); Python its keywords, the released GIL and the Result object (whose save() is write).
#pragma once

#include "commands/spec.hpp"
#include "core/estimate.hpp"
#include "core/fields.hpp"
#include "core/pack.hpp"
#include "core/request.hpp"
#include "core/run.hpp"
#include "core/sweep.hpp"
#include "core/work.hpp"
#include "extras/extras.hpp"
#include "io/checkpoint.hpp"
#include "io/io.hpp"
#include "io/rates.hpp"

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace btob::commands {

// The result type of a request: what run(req, control) returns (found by argument-dependent lookup).
template <class Req>
using ResultOf = std::decay_t<decltype(run(std::declval<const Req&>(), std::declval<const core::RunControl&>()))>;

// What is written of one result, and what Python holds of it: its Contents (views into the result kept beside it in
// Recorded), attributes, the request as text, its CSV tables and how its figure is drawn (commands/spec.hpp).
struct Record {
  core::Contents contents;
  core::Attrs attrs;
  std::string command;   // the command (the manifest's "command": `btob run NAME.json` runs it again)
  std::string function;  // the Python function
  Args request;          // the request's fields as text (flag names)
  core::Tables tables;   // the CSV files (results with tables())
  std::string plot;      // analyses/plot script, "" for none
  std::vector<std::string> plot_inputs;
  bool plot_many = false;
  std::chrono::steady_clock::time_point start;  // the start of compute (Spec::timed's total_seconds)
  // A sweep split over MPI ranks with parallel HDF5: rank 0's own rows of the datasets the ranks write themselves
  // (null otherwise); write() joins the other ranks' collective write with them.
  std::shared_ptr<struct RankRows> rows;
  // A sweep split over MPI ranks: rank 0's seconds on its own share in extras::share_overlays before the run, the
  // manifest's mpi_share_seconds.
  std::optional<double> share_seconds;
  virtual ~Record() = default;
};

// This rank's rows of a split sweep's named datasets (core::HasRows), written by io::Ranks::write_rows into the
// NAME.h5 that rank 0 creates.  Every rank joins that collective exactly once: the other ranks at the end of their
// part, rank 0 in write(), or, when its record is dropped unwritten (an error, a front end that writes nothing),
// here with no file, so that the other ranks are never left waiting.
struct RankRows {
  core::RowSet mine;
  std::function<core::Attrs(const std::string&, const core::RowSet&)> write;
  bool joined = false;
  // On rank 0: the end of the gather; write() records the seconds since then in the manifest (mpi_root_seconds:
  // what rank 0 does alone after the gather, the unpacking, merge and the ranks' write included).
  std::chrono::steady_clock::time_point since;
  RankRows(core::RowSet m, std::function<core::Attrs(const std::string&, const core::RowSet&)> w,
           std::chrono::steady_clock::time_point gathered)
      : mine(std::move(m)), write(std::move(w)), since(gathered) {}
  RankRows(const RankRows&) = delete;
  RankRows& operator=(const RankRows&) = delete;
  // Joins the collective; what the write cost, for the manifest.
  core::Attrs join(const std::string& path) {
    joined = true;
    return write(path, mine);
  }
  std::set<std::string> names() const {
    std::set<std::string> n;
    for (const auto& c : mine.columns) n.insert(c.name);
    return n;
  }
  ~RankRows() {
    if (joined) return;
    try {
      join("");
    } catch (...) {  // a failing job: the error that dropped the record is the one reported
    }
  }
};
template <class Req> struct Recorded : Record {
  Req req;
  ResultOf<Req> res;
  extras::Extras extras;
};

// Stage 1: the request made ready to run: its data files read, validated, its overlays' names checked (an unknown
// name fails before any work).
template <class Req> void ready(Req& req) {
  Spec<Req>::prepare(req);
  req.validate();
  extras::check(req);
}

// How a request runs: the front end's control (threads, progress, cancellation), the MPI ranks sharing a sweep
// (io::alone() for one process) and the checkpoint of a resumed sweep (null: none).
struct How {
  core::RunControl control;
  io::Ranks ranks = io::alone();
  io::Checkpoint* checkpoint = nullptr;
  // Called on rank 0 after a split sweep's parts are merged: the seconds the merge took (MPI statistics).
  std::function<void(double)> merged;
};

// The end of a sweep over the ranks, from each rank's parts (run_split: the one it computed; a resumed run: those its
// checkpoint files held and those of its rounds): alone, their merge; else one gather to rank 0, the result there
// and nullopt elsewhere.  With io::Ranks::write_rows, the rows the parts name (core::HasRows) stay on their rank
// (core::take_rows, items ascending): the others join rank 0's write of NAME.h5 at once (waiting for it), rank 0
// keeps its own in `kept` for write(), and only the thin rest travels and is merged (core::ThinMerge).
template <core::Sweep Req, class Part>
std::optional<ResultOf<Req>> merge_ranks(const Req& req, const How& how, io::RankParts<Part> mine,
                                         std::shared_ptr<RankRows>* kept) {
  if (how.ranks.ranks == 1) return merge(req, std::move(mine.parts));
  core::RowSet rows;
  if constexpr (core::HasRows<Part>)
    if (how.ranks.write_rows && kept) rows = core::take_rows(mine.parts, mine.items);
  // Rank 0 keeps its own parts as they are; the others send theirs as bytes (and drop them before the write).
  std::vector<char> sent;
  if (how.ranks.rank != 0) {
    sent = core::pack(mine.parts);
    std::vector<Part>().swap(mine.parts);
  }
  std::vector<std::vector<char>> bytes = how.ranks.gather(std::move(sent), mine.seconds);
  if (how.ranks.rank != 0) {
    if (!rows.empty()) how.ranks.write_rows("", rows);
    return std::nullopt;
  }
  const auto t1 = std::chrono::steady_clock::now();
  std::vector<Part> parts = std::move(mine.parts);
  for (std::size_t k = 1; k < bytes.size(); ++k) {
    for (Part& p : core::unpack<std::vector<Part>>(bytes[k])) parts.push_back(std::move(p));
    std::vector<char>().swap(bytes[k]);
  }
  std::optional<ResultOf<Req>> res;
  if (rows.empty()) {
    res.emplace(merge(req, std::move(parts)));
  } else {
    *kept = std::make_shared<RankRows>(std::move(rows), how.ranks.write_rows, t1);  // joins even if merge throws
    core::ThinMerge thin;
    res.emplace(merge(req, std::move(parts)));
  }
  if (how.merged) how.merged(core::seconds_since(t1));
  return res;
}

// A sweep's items split over the ranks (rank k takes items k, k + P, ...; core::cyclic_items), each rank's one part
// ending in merge_ranks.
template <core::Sweep Req>
std::optional<ResultOf<Req>> run_split(const Req& req, const How& how, std::shared_ptr<RankRows>* kept = nullptr) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t n = core::work_items(req, how.control.cancel);  // counting may be long (the atlas): polled
  const auto items = core::cyclic_items(n, how.ranks.rank, how.ranks.ranks);
  using Part = decltype(run_part(req, items, how.control));
  io::RankParts<Part> mine;
  mine.parts.push_back(io::detail::naming_items(items, n, [&] { return run_part(req, items, how.control); }));
  mine.items = n;
  mine.seconds = core::seconds_since(t0);
  return merge_ranks(req, how, std::move(mine), kept);
}

// The run itself: a resumed sweep in rounds kept in its checkpoint, a sweep split over ranks, else run(req) (a
// request that is not a sweep runs on rank 0 alone).  Bit for bit the same result in every case.  `kept`: where
// rank 0 keeps the rows it writes itself (merge_ranks).
template <class Req>
std::optional<ResultOf<Req>> run_request(const Req& req, const How& how, std::shared_ptr<RankRows>* kept = nullptr) {
  if constexpr (core::Sweep<Req>) {
    if (how.checkpoint)
      return merge_ranks(req, how, io::run_in_rounds(req, how.control, *how.checkpoint, how.ranks), kept);
    if (how.ranks.ranks > 1) return run_split(req, how, kept);
  }
  if (how.ranks.rank != 0) return std::nullopt;
  return run(req, how.control);
}

// Stage 3: the run, the files the request itself names (Spec::also_write) and the result's overlays; null on the
// ranks other than 0.
template <class Req> std::shared_ptr<Recorded<Req>> compute(const Req& req, const How& how) {
  const auto start = std::chrono::steady_clock::now();
  // Split over ranks: what rank 0 alone would compute after the run for its overlays, computed in shares first.
  std::optional<double> shared;
  if (how.ranks.ranks > 1 && how.ranks.all_gather)
    shared = extras::share_overlays(req, how.ranks.rank, how.ranks.ranks, how.ranks.all_gather, how.control);
  std::shared_ptr<RankRows> rows;
  std::optional<ResultOf<Req>> res = run_request(req, how, &rows);
  if (!res) return nullptr;
  core::check_cancel(how.control.cancel);
  auto rec = std::make_shared<Recorded<Req>>();
  rec->share_seconds = shared;
  rec->rows = std::move(rows);
  rec->req = req;
  rec->res = std::move(*res);
  rec->start = start;
  if constexpr (requires { Spec<Req>::also_write(req, rec->res); }) Spec<Req>::also_write(req, rec->res);
  rec->extras = extras::of(req, rec->res, how.control);  // the windows' bounds, the orbits' attractors, ...
  return rec;
}

// Who asked, for the attributes: the command line (or Python call) that reproduces the request, the result's
// name and title, and the threads used.
struct Provenance {
  std::string command_line, name, title;
  long threads = 1;
};

// Stage 4: what is written of the result (and what Python shows of it).
template <class Req> void record(Recorded<Req>& rec, const Provenance& p) {
  using S = Spec<Req>;
  rec.res.describe(rec.contents);
  rec.extras.add_to(rec.contents);
  rec.req.fields(core::ArgsWriter{&rec.request});
  rec.attrs = io::result_attrs(p.command_line, rec.contents, S::kind_of(rec.req), p.name, p.title,
                               S::scalar(rec.req, rec.res), p.threads);
  rec.extras.apply(rec.attrs);
  S::attrs(rec.req, rec.res, rec.attrs);
  if constexpr (S::timed) rec.attrs["total_seconds"] = core::seconds_since(rec.start);
  if (rec.share_seconds) rec.attrs["mpi_share_seconds"] = *rec.share_seconds;
  rec.command = S::command;
  rec.function = S::function;
  if constexpr (requires { rec.res.tables(); }) rec.tables = rec.res.tables();
  rec.plot = S::plot_of(rec.req);
  rec.plot_inputs = S::plot_inputs();
  rec.plot_many = S::plot_many;
}

// How write() treats the figure and the LaTeX tables.
struct WriteOptions {
  bool plot = true;            // draw the figure (when the command has one)
  bool plot_required = false;  // a figure that cannot be drawn is an error and nothing is written (Python's save);
                               // else a warning and the data are kept (the command line)
  bool latex = false;          // each CSV table also as booktabs LaTeX (io/latex.hpp)
  std::string command_line;    // heads the LaTeX tables
  std::string caption;         // their caption
};

// Stage 5, the one writer of results: NAME.h5 (when the result has arrays), the CSV tables, NAME.json (the
// attributes and the request with name and title: `btob run out/NAME.json` reproduces it) and the figure, into a
// temporary folder moved into `out` when complete (io/result_files.hpp).  Returns the files written.
std::vector<std::filesystem::path> write(const Record& rec, const std::string& out, const std::string& name,
                                         const std::string& title, const WriteOptions& opts);

}  // namespace btob::commands
