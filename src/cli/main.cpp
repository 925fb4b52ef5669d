// SPDX-License-Identifier: GPL-3.0-or-later
// Entry point of `btob`: builds the subcommands and maps errors to exit codes (2 usage, 1 otherwise).
#include "cli/app.hpp"
#include "cli/command.hpp"
#include "cli/common.hpp"
#include "cli/mpi.hpp"
#include "io/cancel.hpp"
#include "io/io.hpp"

#include <btob/build_info.hpp>

#include <boost/throw_exception.hpp>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <new>

namespace btob::cli {
std::vector<Registrar>& registry() {
  static std::vector<Registrar> r;
  return r;
}

namespace {
// The signal that asked the run to stop (0: none yet); the exit status is 128 + its number, as a shell reports a
// process that signal ended: 130 for SIGINT (Ctrl-C), 143 for SIGTERM (timeout, kill, a batch system).
volatile std::sig_atomic_t stop_signal = 0;

// SIGINT/SIGTERM: the first asks the running computation to stop (every long loop polls the token, see
// core/cancel.hpp; its temporary files are removed, nothing is written); a second one ends the process at once.
extern "C" void on_signal(int sig) {
  stop_signal = sig;
  cancel_token().cancel();
  std::signal(sig, SIG_DFL);
}
// 128 + the signal that stopped the run (a Cancelled without a signal, e.g. a test's token: SIGINT's 130).
int stop_status() { return 128 + (stop_signal ? static_cast<int>(stop_signal) : SIGINT); }
}  // namespace
}  // namespace btob::cli

namespace {
// An error was reported: one line, then the end, without the libraries' exit-time cleanup (HDF5's would crash on a
// file whose close failed, e.g. on a full disk); every file btob wrote is closed or removed by then.  Under mpirun
// cli::mpi::fail says which rank failed and ends the job (cli/mpi.hpp).
[[noreturn]] void failed(const std::string& cause, int code, const std::string& label = "error: ") {
  btob::cli::mpi::fail(cause, code, label);
}
}  // namespace

int main(int argc, char** argv) {
  namespace mpi = btob::cli::mpi;
  mpi::init(argc, argv);
  btob::io::init_hdf5();
  CLI::App app{"btob: statistics lab for the b-to-b map P_r of four 1-D inelastic hard spheres"};
  app.set_version_flag("--version", std::string("btob ") + btob::build::version + " (" + btob::build::git_commit + ")");
  app.require_subcommand(1);
  // A flag given twice takes its last value (scenes and scripts can override earlier flags).
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  for (int i = 0; i < argc; ++i) btob::cli::invocation() += (i ? " " : "") + btob::cli::shell_quote(argv[i]);
  for (auto& reg : btob::cli::registry()) reg(app);
  mpi::guard_root_only(app);
  std::signal(SIGINT, btob::cli::on_signal);
  std::signal(SIGTERM, btob::cli::on_signal);
  btob::io::stop_on(&btob::cli::cancel_token());  // plots and commits obey the same token
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) {  // --help, --version: said once
      const int code = mpi::rank() == 0 ? app.exit(e) : 0;
      mpi::finalize();
      return code;
    }
    failed(std::string(e.what()) + " (see --help)", 2);
  } catch (const mpi::RootOnly&) {  // a command that runs on rank 0 alone, and this is another rank
    mpi::finalize();
    return 0;
  } catch (const btob::core::Cancelled&) {
    failed("interrupted; nothing was written", btob::cli::stop_status(), "");
  } catch (const std::invalid_argument& e) {  // includes UsageError and core::InvalidField
    failed(e.what(), 2);
  } catch (const std::domain_error& e) {
    failed(e.what(), 2);
  } catch (const std::length_error& e) {
    failed(e.what(), 2);
  } catch (const std::out_of_range& e) {
    failed(e.what(), 2);
  } catch (const std::bad_alloc&) {
    failed("out of memory", 1);
  } catch (const std::exception& e) {
    failed(e.what(), 1);
  }
  mpi::finalize();
  return 0;
}
