// Entry point of `btob`: builds the subcommands and maps errors to exit codes (2 usage, 1 otherwise).
#include "cli/app.hpp"
#include "cli/command.hpp"
#include "cli/common.hpp"
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
// SIGINT/SIGTERM: the first asks the running computation to stop at its next batch (its temporary files are
// removed, nothing is written); a second one ends the process at once.
extern "C" void on_signal(int sig) {
  cancel_token().cancel();
  std::signal(sig, SIG_DFL);
}
}  // namespace
}  // namespace btob::cli

namespace {
// An error was reported: end now, without the libraries' exit-time cleanup (HDF5's would crash on a file whose
// close failed, e.g. on a full disk); every file btob wrote is closed or removed by then.
int failed(int code) {
  std::cout.flush();
  std::cerr.flush();
  std::_Exit(code);
}
}  // namespace

int main(int argc, char** argv) {
  btob::io::init_hdf5();
  CLI::App app{"btob: statistics lab for the b-to-b map P_r of four 1-D inelastic hard spheres"};
  app.set_version_flag("--version", std::string("btob ") + btob::build::version + " (" + btob::build::git_commit + ")");
  app.require_subcommand(1);
  // A flag given twice takes its last value (scenes and scripts can override earlier flags).
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  for (int i = 0; i < argc; ++i) btob::cli::invocation() += (i ? " " : "") + std::string(argv[i]);
  for (auto& reg : btob::cli::registry()) reg(app);
  std::signal(SIGINT, btob::cli::on_signal);
  std::signal(SIGTERM, btob::cli::on_signal);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    std::cerr << "btob: error: " << e.what() << " (see --help)\n";
    return failed(2);
  } catch (const btob::core::Cancelled&) {
    std::cerr << "btob: interrupted; nothing was written\n";
    return failed(130);
  } catch (const std::invalid_argument& e) {  // includes UsageError and core::InvalidField
    std::cerr << "btob: error: " << e.what() << "\n";
    return failed(2);
  } catch (const std::domain_error& e) {
    std::cerr << "btob: error: " << e.what() << "\n";
    return failed(2);
  } catch (const std::length_error& e) {
    std::cerr << "btob: error: " << e.what() << "\n";
    return failed(2);
  } catch (const std::out_of_range& e) {
    std::cerr << "btob: error: " << e.what() << "\n";
    return failed(2);
  } catch (const std::bad_alloc&) {
    std::cerr << "btob: error: out of memory\n";
    return failed(1);
  } catch (const std::exception& e) {
    std::cerr << "btob: error: " << e.what() << "\n";
    return failed(1);
  }
  return 0;
}
