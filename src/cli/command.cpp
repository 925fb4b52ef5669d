// SPDX-License-Identifier: GPL-3.0-or-later
// The request-based subcommands' shared parts: cancellation, terminal progress, output validation.
#include "cli/command.hpp"
#include "cli/mpi.hpp"
#include "io/io.hpp"

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

io::Attrs Context::attrs(const Output& o, const core::Contents& c, const std::string& kind,
                         const std::string& scalar) const {
  io::Attrs a = io::result_attrs(command_line, c, kind, o.name, o.title, scalar,
                                 static_cast<long>(control.threads > 0 ? control.threads : omp_get_max_threads()));
  if (mpi::size() > 1) {  // threads are per rank; what the split and the gather cost (cli/mpi.hpp)
    const mpi::Stats& st = mpi::stats();
    a["mpi_ranks"] = static_cast<long>(st.ranks);
    a["mpi_compute_seconds_min"] = st.compute_min;
    a["mpi_compute_seconds_max"] = st.compute_max;
    a["mpi_wait_seconds"] = st.wait_seconds;
    a["mpi_gather_seconds"] = st.gather_seconds;
    a["mpi_gathered_bytes"] = static_cast<long>(st.bytes_total);
    a["mpi_merge_seconds"] = st.merge_seconds;
  }
  return a;
}

namespace detail {
void validate_output(const Output& o, bool threads_given) {
  if (threads_given && (o.threads < 1 || o.threads > core::RunControl::max_threads))
    throw core::InvalidField("threads", std::to_string(o.threads),
                             fmt::format("1..{} (omit the flag for all cores)", core::RunControl::max_threads));
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
  c.latex = o.format == "latex";
  c.title = o.title;
  return c;
}
}  // namespace detail

}  // namespace btob::cli
