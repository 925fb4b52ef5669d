// SPDX-License-Identifier: GPL-3.0-or-later
// Shared helpers of the subcommands.
#include "cli/common.hpp"
#include "cli/app.hpp"

#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>

namespace btob::cli {

std::string& invocation() {
  static std::string s;
  return s;
}

std::string shell_quote(const std::string& word) {
  const bool plain = !word.empty() && word.find_first_not_of(
                                          "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                          "0123456789_-+=.,:/@%^") == std::string::npos;
  if (plain) return word;
  std::string q = "'";
  for (char c : word) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

ProgressAdapter& progress_adapter(io::Progress& p) {
  thread_local std::unique_ptr<ProgressAdapter> a;
  a = std::make_unique<ProgressAdapter>(&p);
  return *a;
}

io::fs::file_time_type start_time() { return io::fs::file_time_type::clock::now() - std::chrono::milliseconds(50); }

void print_written(const std::vector<io::fs::path>& files, io::fs::file_time_type since) {
  std::string s;
  for (const auto& f : files) {
    std::error_code ec;
    const auto t = io::fs::last_write_time(f, ec);
    if (!ec && t >= since) s += (s.empty() ? "" : ", ") + f.string();
  }
  if (!s.empty()) std::cerr << "btob: wrote " << s << "\n";
}

}  // namespace btob::cli
