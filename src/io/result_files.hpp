// SPDX-License-Identifier: GPL-3.0-or-later
// The files of one result, written together or not at all: every file goes to a private temporary folder, and
// commit() moves them into the output folder (created only then), the manifest last.  A run that fails or is
// cancelled leaves nothing behind: no partial file, no empty folder, and an existing result stays intact.
#pragma once

#include "core/result.hpp"
#include "io/io.hpp"

#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace btob::io {

class ResultFiles {
 public:
  // `out`: the output folder (need not exist); `name`: the file stem of the result (NAME.h5, NAME.json, ...).
  ResultFiles(fs::path out, std::string name);
  ~ResultFiles();  // without commit(): removes the temporary folder and everything in it
  ResultFiles(const ResultFiles&) = delete;
  ResultFiles& operator=(const ResultFiles&) = delete;

  const std::string& name() const { return name_; }
  const fs::path& out() const { return out_; }
  // Where to write `filename` now (inside the temporary folder); it lands at out/filename on commit().
  fs::path staged(const std::string& filename);
  // Where `filename` will be after commit() (for messages and manifests).
  fs::path final_path(const std::string& filename) const { return out_ / filename; }

  // NAME.h5: every array of `c` with its dims, its decimals and texts as string datasets, on each dataset the
  // string attributes units, axes and description, and each axis's coordinates attached as an HDF5 dimension
  // scale (Contents::coordinates); `attrs` (provenance and summary) as file attributes.
  // `by_ranks`: arrays only made (their shape, layout and attributes), for the MPI ranks to write their rows into
  // afterwards (commands::RankRows); their views hold no data.  With a non-empty `by_ranks` the other arrays are
  // written contiguous rather than deflated (rank 0 alone writes them while every rank waits): the same data.
  void h5(const core::Contents& c, const Attrs& attrs, const std::set<std::string>& by_ranks = {});
  // Whether `c` has anything for NAME.h5 (arrays, decimals, texts, or only attributes: a verdict).
  static bool has_data(const core::Contents& c) {
    return !c.arrays.empty() || !c.decimals.empty() || !c.texts.empty() || !c.attrs.empty();
  }
  // A text file (CSV, ...).
  void text(const std::string& filename, const std::string& content);
  // A result's CSV tables (core::Tables), each to its core::table_file(NAME, role).
  void tables(const core::Tables& t);
  // --format latex: each table given to tables() also as a booktabs LaTeX table (io/latex.hpp) beside its CSV
  // (NAME.tex, NAME_role.tex), read back from the staged CSV (whose lines MPI ranks may have written after the header
  // given to tables()), the status of its numbers from the Contents given to h5(); `command_line` heads it,
  // `caption` (with the table's role) is its caption.
  void latex(const std::string& command_line, const std::string& caption);
  // NAME.json: the attributes, and the request that made the result as {"command": ..., "args": {...}}.
  void manifest(const Attrs& attrs, const std::string& command,
                const std::vector<std::pair<std::string, std::vector<std::string>>>& args);
  // Runs analyses/plot/<script> on the staged NAME.h5 writing the staged NAME.png (a warning, not an error, when
  // matplotlib is missing or the script fails); true when the figure was written.
  bool plot(const std::string& script);
  // The same on the staged file `input` of this result (a CSV, say) instead of NAME.h5.
  bool plot(const std::string& script, const std::string& input);
  // The same on several staged files of this result, passed in this order before NAME.png.
  bool plot_inputs(const std::string& script, const std::vector<std::string>& inputs);
  // A script that draws several figures: runs it on the staged `inputs` and the staging folder (last argument),
  // and keeps every PNG and GIF it wrote there (figure families such as Figures 7.1-7.8, animations).
  bool plot_figures(const std::string& script, const std::vector<std::string>& inputs);

  // Moves every staged file into out/ (creating it), the manifest last; returns the final paths.  Throws with
  // the file and the cause when the output folder cannot be made or written.
  std::vector<fs::path> commit();

 private:
  fs::path out_, tmp_;
  std::string name_;
  std::vector<std::string> files_;
  std::vector<std::string> table_roles_;        // the tables tables() staged, for latex() (which reads them back)
  std::map<std::string, core::Status> status_;  // the status of the numbers h5() wrote, for latex()
  bool committed_ = false;
};

// A file-system error as one line naming the file and the cause (disk full, permission denied, ...).
[[noreturn]] void throw_file_error(const std::string& what, const fs::path& path, const std::error_code& ec);

}  // namespace btob::io
