// SPDX-License-Identifier: GPL-3.0-or-later
// Output with provenance: HDF5 arrays with attributes, CSV tables, manifests; atomic (temp + rename).
#pragma once

#include "core/result.hpp"

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <variant>
#include <vector>

namespace btob::io {

namespace fs = std::filesystem;

// Attribute values recorded with every result.
using Attr = core::AttrValue;
using Attrs = core::Attrs;

// Call first in main(): HDF5 then installs no exit-time cleanup, which would crash on a file whose close failed
// (disk full) after the error has been reported; every file btob writes is closed explicitly.
void init_hdf5();

// The provenance every result carries: version, git commit and git_dirty of the build (recorded when the binary was
// built, cmake/GitCommit.cmake), run_dirty (analyses/ had uncommitted changes when the result was made), compiler,
// kernel flags, date, command line.
Attrs provenance(const std::string& command);

// The attributes of a result as the command line and Python record them: the provenance of `command`, the result's
// own attributes (describe()), then kind, name, title, scalar_type and threads (threads actually used).
Attrs result_attrs(const std::string& command, const core::Contents& c, const std::string& kind,
                   const std::string& name, const std::string& title, const std::string& scalar, long threads);

// Creates `dir` (and parents) or throws std::runtime_error naming it.
void ensure_dir(const fs::path& dir);

// An HDF5 file written atomically: datasets go to `<path>.tmp-<pid>`, renamed onto `path` by commit().
// If the object is destroyed without commit() the temporary file is removed (no partial output).
class H5Writer {
 public:
  explicit H5Writer(fs::path path);
  ~H5Writer();
  H5Writer(const H5Writer&) = delete;
  H5Writer& operator=(const H5Writer&) = delete;
  void attrs(const Attrs& a);  // file-level attributes
  void dataset(const std::string& name, const std::vector<double>& data, const std::vector<std::size_t>& dims);
  void dataset(const std::string& name, const std::vector<std::uint32_t>& data, const std::vector<std::size_t>& dims);
  void dataset(const std::string& name, const std::vector<std::uint8_t>& data, const std::vector<std::size_t>& dims);
  void dataset(const std::string& name, const std::vector<std::uint64_t>& data, const std::vector<std::size_t>& dims);
  void commit();

 private:
  void write_attrs(const Attrs& a);
  struct Impl;
  Impl* impl_;
  fs::path path_, tmp_;
  bool committed_ = false;
};

// Writes `text` to `path` atomically (temp file + rename).
void write_text_atomic(const fs::path& path, const std::string& text);

// A manifest (key: value lines, JSON object) beside a result.
void write_manifest(const fs::path& path, const Attrs& a);

// A progress bar on stderr, shown only when stderr is a terminal; quiet otherwise.  A run that, after 2 s and 1% of its
// work (or 30 s), has more than 10 minutes left at the rate so far says so once, terminal or not ("btob: LABEL: about
// N min left").
class Progress {
 public:
  explicit Progress(std::string label);
  ~Progress();
  void update(std::size_t done, std::size_t total);

 private:
  std::string label_;
  bool tty_;
  int last_percent_ = -1;
  bool open_ = false;   // a bar is drawn on the current line (ended by 100% or the destructor)
  bool noted_ = false;  // the long run's remaining time was said
  double start_;
};

// The path of a file the program ships (`plot/<script>.py`, `reference/<table>.csv`), found without the source
// tree: $BTOB_DATA_DIR/<rel>, then <executable's folder>/share/btob/<rel> (the build tree), then
// <executable's folder>/../share/btob/<rel> (an installed prefix), then the source tree it was built from.
// Throws std::runtime_error naming the file and the places searched when none has it.
fs::path data_file(const std::string& rel);

// The text of the file `path`, or of the shipped data file `default_rel` (data_file) when `path` is empty; "" when
// the file cannot be read (the caller says what is missing).
std::string data_text(const std::string& path, const std::string& default_rel);

// Runs the matplotlib script analyses/plot/<script> on `args`; returns false (with a one-line
// warning) when no Python with matplotlib is available.  The interpreter is $BTOB_PYTHON or the
// system python3 (Debian's python3-matplotlib).
bool run_plot(const std::string& script, const std::vector<std::string>& args);

}  // namespace btob::io
