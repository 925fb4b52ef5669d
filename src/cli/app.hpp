// SPDX-License-Identifier: GPL-3.0-or-later
// The `btob` command: subcommands register themselves here (one src/cli/cmd_<name>.cpp each).
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace btob::cli {

// A usage error (bad flag value, out-of-range argument): main prints it and exits 2.
struct UsageError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

using Registrar = std::function<void(CLI::App&)>;
std::vector<Registrar>& registry();
struct Register {
  explicit Register(Registrar r) { registry().push_back(std::move(r)); }
};

}  // namespace btob::cli
