// SPDX-License-Identifier: GPL-3.0-or-later
// The compiled module btob._btob: a function for every declared request (commands/commands.hpp), bound by the one
// template of bind.hpp in the declarations' order; the building blocks (Map, iterate) and cite beside them.
#include "bind.hpp"
#include "commands/commands.hpp"
#include "io/citation.hpp"

#include <btob/build_info.hpp>

namespace btob::python {

void bind_result(py::module_& m);
void bind_blocks(py::module_& m);

// Binds each declared request through bind<Req>(m).
struct Bind {
  py::module_* m;
  template <class Req> void operator()() const { bind<Req>(*m); }
};

}  // namespace btob::python

PYBIND11_MODULE(_btob, m) {
  using namespace btob;
  using namespace btob::python;
  m.doc() = "btob: the b-to-b map of four inelastic hard spheres (compiled core; import btob instead)";
  m.attr("__version__") = build::version;
  m.attr("git_commit") = build::git_commit;
  m.def(
      "cite", [](const std::string& format) { return io::citation(format); }, pybind11::arg("format") = "bibtex",
      "How to cite btob (the software at this build's version and commit, and the paper): format 'bibtex', 'cff' "
      "or 'text', as `btob cite --format F` prints it");
  m.def(
      "_check_threads", [](pybind11::handle v) { return threads_value(v); },
      "threads as the compiled functions check it: 0 (all cores) or 1..1024, an int; ValueError otherwise");
  bind_result(m);
  commands::for_each_command(Bind{&m});
  bind_blocks(m);
}
