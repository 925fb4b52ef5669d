// SPDX-License-Identifier: GPL-3.0-or-later
// `btob cite`: how to cite btob (io/citation.hpp), the software at this build's version and git commit and the paper
// whose map it implements, printed to standard output; it writes no file and computes nothing.
#include "cli/app.hpp"
#include "io/citation.hpp"

#include <iostream>
#include <memory>

namespace btob::cli {
namespace {

Register reg([](CLI::App& app) {
  auto format = std::make_shared<std::string>(io::citation_formats().front());
  CLI::App* c = app.add_subcommand("cite",
                                   "Print how to cite btob: the software (this version and git commit) and the "
                                   "paper whose b-to-b map it implements");
  c->add_option("--format", *format, "bibtex (BibTeX entries), cff (Citation File Format, CITATION.cff) or text")
      ->check(CLI::IsMember(io::citation_formats()))
      ->capture_default_str();
  c->callback([format] { std::cout << io::citation(*format); });
});

}  // namespace
}  // namespace btob::cli
