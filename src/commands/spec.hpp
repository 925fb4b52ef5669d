// SPDX-License-Identifier: GPL-3.0-or-later
// The declaration of a command: everything about a request that is not in the request itself (its fields(),
// validate(), run(), and its result's describe() and tables() are the module's).  One specialisation of Spec per
// request, all in commands/commands.hpp; the command line (src/cli), scenes and manifests (`btob run`), and the
// Python module (python/) are generated from them by commands::for_each_command, and all of them execute a request
// through the one path of commands/execute.hpp.
//
//   template <> struct Spec<stats::MeasureRequest> : SpecBase<stats::MeasureRequest, Spec<stats::MeasureRequest>> {
//     static constexpr const char* command = "measure";            // `btob measure`, command = "measure" in scenes
//     static constexpr const char* function = "measure";           // btob.measure(...) in Python
//     static constexpr const char* summary = "Empirical measures ...";  // --help and the docstring's first line
//     static constexpr const char* folder = "results/stats";       // a file command's default --out
//     static constexpr const char* stem = "measure";               // its default --name
//     static constexpr const char* kind = "measure";               // the result's `kind` attribute
//     static constexpr const char* plot = "stats_measure.py";      // analyses/plot script ("" for none)
//   };
#pragma once

#include "core/fields.hpp"
#include "core/request.hpp"
#include "core/result.hpp"

#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

namespace btob::commands {

using Args = core::Args;

// What the command line's closing report of a file command is given: the files written, and whether it is quiet.
struct Written {
  std::vector<std::filesystem::path> files;
  bool quiet = false;
  long threads = 1;  // the threads the run used
  // "a, b, c": the files, for the closing line.
  std::string listing() const;
};

// The declaration of request type Req: specialised in commands/commands.hpp (and nowhere else).
template <class Req> struct Spec;

// The defaults of a declaration; a specialisation derives from SpecBase<Req, Spec<Req>> and overrides what differs.
template <class Req, class Derived> struct SpecBase {
  using Request = Req;
  // A file command writes NAME.h5, its CSV tables, NAME.json and the figure into `folder`; a stdout command
  // (folder = nullptr) prints its result, and writes those files only when given an output folder.
  static constexpr const char* folder = nullptr;
  static constexpr const char* stem = "";  // "": the request's default_name(), else the command's last word
  static constexpr const char* plot = "";  // analyses/plot/<plot> draws the result ("" for none)
  // How the plot script reads the result: {} from NAME.h5 as draw(f); else the files it is given, as suffixes of
  // NAME (".h5"), in that order, before NAME.png; plot_many: it writes several figures into the folder.
  static std::vector<std::string> plot_inputs() { return {}; }
  static constexpr bool plot_many = false;
  // Whether the attributes record total_seconds, the time from the start of the run to its record.
  static constexpr bool timed = false;
  // Whether `btob explore` runs the command for its page (GET /api/run?command=...): only commands that read and
  // write no file of their own (no prepare, no also_write), since anyone who reaches the server may ask.
  static constexpr bool served = false;

  // The request's defaults (the command line's flags' defaults, Python's keywords').
  static Req defaults() { return Req{}; }
  // Data the request reads before it is validated (a request does no I/O of its own): Table 6.1 of basins-r.
  static void prepare(Req&) {}
  // The result's `kind` attribute, its figure's script and its default file stem, where the request chooses them.
  static std::string kind_of(const Req&) { return Derived::kind; }
  static std::string plot_of(const Req&) { return Derived::plot; }
  static std::string stem_of(const Req& req) {
    if (std::string(Derived::stem) != "") return Derived::stem;
    if constexpr (requires { std::string(req.default_name()); }) return req.default_name();
    const std::string c = Derived::command;
    return c.substr(c.rfind(' ') + 1);
  }
  // The `scalar_type` attribute: the result's own, else the request's precision, else double.
  template <class Res> static std::string scalar(const Req& req, const Res& res) {
    if constexpr (requires { std::string(res.scalar_type); }) return res.scalar_type;
    else if constexpr (requires { std::string(req.precision); }) return req.precision;
    else return "double";
  }
  // Attributes of the request that describe() cannot know (presentation fields such as a figure's range).
  template <class Res> static void attrs(const Req&, const Res&, core::Attrs&) {}

  // The command line's words around a run (presentation only: nothing here is part of the result).
  // Warnings about the result, on stderr before it is written (--quiet does not silence a warning).
  template <class Res> static void warn(const Req&, const Res&, const core::RunControl&) {}
  // A stdout command's text (CSV or text) on stdout.
  template <class Res> static void print(const Req&, const Res&) {}
  // A file command's closing lines on stderr, after its files are written.
  template <class Res> static void report(const Req&, const Res&, const core::Contents&, const Written& w) {
    if (!w.quiet) std::cerr << "btob: wrote " << w.listing() << "\n";
  }
};

// Whether Spec<Req> declares a file command.
template <class Req> constexpr bool writes_files() { return Spec<Req>::folder != nullptr; }

}  // namespace btob::commands
