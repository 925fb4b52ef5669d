// SPDX-License-Identifier: GPL-3.0-or-later
// The request-based subcommands' shared parts: cancellation, terminal progress, output validation.
#include "cli/command.hpp"
#include "cli/mpi.hpp"
#include "cli/rows.hpp"
#include "io/io.hpp"
#include "io/latex.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <iostream>
#include <stdexcept>

#include <omp.h>

namespace btob::cli {

core::CancelToken& cancel_token() {
  static core::CancelToken t;
  return t;
}

std::map<std::string, SceneCommand>& scene_commands() {
  static std::map<std::string, SceneCommand> m;
  return m;
}

namespace {
struct TerminalProgress : core::ProgressSink {
  io::Progress bar;
  explicit TerminalProgress(const std::string& label) : bar(label) {}
  void update(std::size_t done, std::size_t total) override { bar.update(done, total); }
};
}  // namespace

std::unique_ptr<core::ProgressSink> terminal_progress(const std::string& label) {
  return std::make_unique<TerminalProgress>(label);
}

namespace {
// Whether the ranks write their own rows of NAME.h5 (parallel HDF5); BTOB_MPI_WRITE=gather sends them to rank 0
// instead (the way of a build without parallel HDF5), for comparisons and the scaling model's measurements.
bool parallel_rows() {
#ifdef BTOB_PARALLEL_HDF5
  const char* w = std::getenv("BTOB_MPI_WRITE");
  return !(w && std::string(w) == "gather");
#else
  return false;
#endif
}
}  // namespace

namespace detail {
commands::How how_of(const Output& o, const Context& ctx, bool sweep, core::ProgressSink* bar) {
  commands::How how;
  how.control = ctx.control;
  how.control.progress = bar;
  how.checkpoint = ctx.checkpoint.get();
  if (sweep && mpi::size() > 1) {
    if (!mpi::checked()) throw std::logic_error("a sweep split over MPI ranks before the checkpoint of cli::execute");
    how.ranks.ranks = static_cast<std::size_t>(mpi::size());
    how.ranks.rank = static_cast<std::size_t>(mpi::rank());
    how.ranks.gather = [](std::vector<char> bytes, double seconds) { return mpi::gather(std::move(bytes), seconds); };
    how.ranks.all_gather = [](std::vector<char> bytes) { return mpi::all_gather(std::move(bytes)); };
    const bool quiet = o.quiet;
#ifdef BTOB_PARALLEL_HDF5
    if (parallel_rows()) {
      how.ranks.write_rows = [quiet](const std::string& path, const core::RowSet& mine) {
        const rows::WriteStats w = rows::write(path, mine);
        if (!quiet && mpi::rank() == 0 && !path.empty())
          std::cerr << fmt::format("btob: {} ranks wrote their own rows ({} bytes) in {:.4f} s\n", mpi::size(),
                                   w.bytes_total, w.seconds_max);
        return core::Attrs{{"mpi_rows_bytes", static_cast<long>(w.bytes_total)},
                           {"mpi_rows_seconds", w.seconds_max},
                           {"mpi_rows_seconds_min", w.seconds_min}};
      };
    }
#endif
    how.merged = [quiet](double seconds) {
      mpi::Stats& st = mpi::stats();
      st.merge_seconds = seconds;
      if (!quiet)
        std::cerr << fmt::format(
            "btob: {} ranks: work {:.3f}..{:.3f} s per rank; gathered {} bytes in {:.4f} s, merged in {:.4f} s\n",
            st.ranks, st.compute_min, st.compute_max, st.bytes_total, st.gather_seconds, st.merge_seconds);
    };
  }
  return how;
}

void add_mpi_attrs(core::Attrs& a) {
  if (mpi::size() <= 1) return;
  // threads are per rank; what the split and the gather cost (cli/mpi.hpp)
  const mpi::Stats& st = mpi::stats();
  a["mpi_ranks"] = static_cast<long>(st.ranks);
  a["mpi_compute_seconds_min"] = st.compute_min;
  a["mpi_compute_seconds_max"] = st.compute_max;
  a["mpi_wait_seconds"] = st.wait_seconds;
  a["mpi_gather_seconds"] = st.gather_seconds;
  a["mpi_gathered_bytes"] = static_cast<long>(st.bytes_total);
  a["mpi_merge_seconds"] = st.merge_seconds;
}

void print_latex(const commands::Record& rec, const Context& ctx) {
  if (rec.tables.empty())
    throw UsageError(
        fmt::format("--format: got 'latex', but this '{}' request has no table; expected csv", ctx.command));
  std::string text;
  for (const auto& [role, csv] : rec.tables)
    text += io::latex_document(csv, rec.contents.status, ctx.command_line,
                               ctx.caption() + (role.empty() ? "" : " (" + role + ")"));
  std::cout << text << std::flush;
}

void validate_output(const Output& o) {
  core::require_threads(o.threads);
  if (o.format != "csv" && o.format != "latex")
    throw core::InvalidField("format", "'" + o.format + "'", "csv or latex");
  if (!o.files) return;
  if (o.out.empty()) throw core::InvalidField("out", "''", "an output folder");
  if (o.name.empty() || o.name.find('/') != std::string::npos)
    throw core::InvalidField("name", "'" + o.name + "'", "a file stem without '/'");
}

CLI::App* add_nested(CLI::App& app, const std::string& name, const std::string& help) {
  CLI::App* parent = &app;
  std::string leaf = name;
  for (auto sp = leaf.find(' '); sp != std::string::npos; sp = leaf.find(' ')) {
    const std::string word = leaf.substr(0, sp);
    CLI::App* found = nullptr;
    for (CLI::App* sub : parent->get_subcommands([](CLI::App*) { return true; }))
      if (sub->get_name() == word) found = sub;
    parent = found ? found : parent->add_subcommand(word);
    leaf = leaf.substr(sp + 1);
  }
  return parent->add_subcommand(leaf, help);
}

Context make_context(const std::string& command, const Output& o, const std::string& inv, Args request_args) {
  Context c;
  c.control.threads = o.threads;
  c.control.cancel = &cancel_token();
  c.command_line = inv;
  c.request_args = std::move(request_args);
  c.command = command;
  c.quiet = o.quiet;
  c.title = o.title;
  return c;
}
}  // namespace detail

}  // namespace btob::cli
