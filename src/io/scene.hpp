// SPDX-License-Identifier: GPL-3.0-or-later
// Scene files (analyses/scenes/*.toml): a named, saved invocation of one `btob` subcommand.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace btob::io {

// A scene is
//     command = "bifurcation"          # the subcommand to run
//     title = "Figure 4.1 ..."         # optional, passed as --title when the command has it
//     [args]                           # its flags, by their long names without dashes
//     r-min = 0.0717
//     log = true                       # booleans are flags
//     vline = [0.0718, 0.1716]         # arrays repeat the flag
// Every key must be a flag of the command (checked by the caller against the parser).
struct Scene {
  std::string name;     // file stem
  std::string command;  // subcommand
  std::string title;
  struct Arg {
    std::string key;                  // the flag's long name without dashes
    std::vector<std::string> values;  // text forms; a boolean is "true" or "false"
    bool boolean = false;
  };
  std::vector<Arg> args;
};

// Parses a scene file; throws std::invalid_argument naming the file, the key and what was expected.
Scene read_scene(const std::filesystem::path& path);

}  // namespace btob::io
