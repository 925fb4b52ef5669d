// SPDX-License-Identifier: GPL-3.0-or-later
// The one writer of results (commands/execute.hpp).
#include "commands/execute.hpp"

#include "io/result_files.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace btob::commands {

std::string Written::listing() const {
  std::string s;
  for (const auto& f : files) s += (s.empty() ? "" : ", ") + f.string();
  return s;
}

namespace {
// The figure of `rec` drawn into the staged files; false when its script failed (its message is on stderr).
bool draw(const Record& rec, io::ResultFiles& files, const std::string& name) {
  if (rec.plot_inputs.empty()) return rec.contents.arrays.empty() || files.plot(rec.plot);
  std::vector<std::string> inputs;  // the script reads the command line's files, as the command line calls it
  for (const auto& suffix : rec.plot_inputs) inputs.push_back(name + suffix);
  return rec.plot_many ? files.plot_figures(rec.plot, inputs) : files.plot_inputs(rec.plot, inputs);
}
}  // namespace

std::vector<std::filesystem::path> write(const Record& rec, const std::string& out, const std::string& name,
                                         const std::string& title, const WriteOptions& opts) {
  core::Attrs at = rec.attrs;
  at["name"] = name;
  at["title"] = title;
  Args args = rec.request;
  args.emplace_back("name", std::vector<std::string>{name});
  args.emplace_back("title", std::vector<std::string>{title});
  io::ResultFiles files(out, name);
  files.tables(rec.tables);
  if (rec.rows) {  // a split sweep's bulk: NAME.h5 made with every dataset's shape, then each rank writes its rows
    files.h5(rec.contents, at, rec.rows->names());
    for (auto& [k, v] : rec.rows->join(files.staged(name + ".h5").string())) at[k] = v;  // the manifest's
  } else if (io::ResultFiles::has_data(rec.contents)) {
    files.h5(rec.contents, at);
  }
  if (opts.latex) files.latex(opts.command_line, opts.caption);
  if (rec.rows) at["mpi_root_seconds"] = core::seconds_since(rec.rows->since);
  files.manifest(at, rec.command, args);  // lists the files staged so far
  if (opts.plot && !rec.plot.empty() && !draw(rec, files, name) && opts.plot_required)
    throw std::runtime_error(fmt::format(
        "save: the figure's script {} failed (its message is above); nothing was written to {} (plot=False writes "
        "the data alone)",
        rec.plot, out));
  return files.commit();
}

}  // namespace btob::commands
