// Shared helpers of the subcommands.
#include "cli/common.hpp"
#include "cli/app.hpp"

#include <fmt/format.h>

#include <memory>

namespace btob::cli {

std::string& invocation() {
  static std::string s;
  return s;
}

ProgressAdapter& progress_adapter(io::Progress& p) {
  thread_local std::unique_ptr<ProgressAdapter> a;
  a = std::make_unique<ProgressAdapter>(&p);
  return *a;
}

}  // namespace btob::cli
