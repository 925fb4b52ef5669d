// SPDX-License-Identifier: GPL-3.0-or-later
// The subcommands of every declared request (commands/commands.hpp), registered in the declarations' order.
#include "cli/app.hpp"
#include "cli/command.hpp"
#include "commands/commands.hpp"

namespace btob::cli {
namespace {

// Registers each declared request through declare<Req>().
struct Declare {
  template <class Req> void operator()() const { declare<Req>(); }
};

struct Registration {
  Registration() {
    // `btob windows` itself: only a parent of its subcommands (registered first, so that they find it).
    registry().push_back([](CLI::App& app) {
      app.add_subcommand("windows", "Windows of stability of (ab)^n(cb)^n: Q_n, bounds, checks (Section 4, App. B)")
          ->require_subcommand(1);
    });
    commands::for_each_command(Declare{});
  }
} registration;

}  // namespace
}  // namespace btob::cli
