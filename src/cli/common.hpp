// SPDX-License-Identifier: GPL-3.0-or-later
// Helpers shared by the subcommands: progress adapter, the invocation string (the named r overlays are in
// src/extras, shared with the Python binding).
#pragma once

#include "io/io.hpp"
#include "iterate/kernel.hpp"

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace btob::cli {

// The whole command line of this process (for provenance).
std::string& invocation();
// `word` as one shell word: as is when it holds only characters no shell treats specially, else in single quotes
// (a ' inside as '\''), so that a recorded command line pasted into a shell runs the same request.
std::string shell_quote(const std::string& word);
inline std::string command_line_of(const CLI::App*) { return invocation(); }

// Adapts io::Progress to the kernel's ProgressSink (one per thread of control, lives as long as `p`).
struct ProgressAdapter : iterate::ProgressSink {
  io::Progress* p;
  explicit ProgressAdapter(io::Progress* p_) : p(p_) {}
  void update(std::size_t done, std::size_t total) override { p->update(done, total); }
};
ProgressAdapter& progress_adapter(io::Progress& p);

// "btob: wrote a, b, c": those of `files` written (modified) since `since`, for commands that write their files one
// by one (plots included); nothing when none was.
void print_written(const std::vector<io::fs::path>& files, io::fs::file_time_type since);
// A start time for print_written: now, less 50 ms (file times come from the kernel's coarse clock).
io::fs::file_time_type start_time();

}  // namespace btob::cli
