// SPDX-License-Identifier: GPL-3.0-or-later
// The command line generated from the declarations of commands/commands.hpp: for each declared request,
//
//   declare<lyapunov::OrbitRequest>();
//
// registers `btob lyapunov` with one flag per field of the request and of its output, and the same command for
// `btob run SCENE.toml` and `btob run results/NAME/NAME.json`, which set the fields by name (an unknown key is an
// error naming it).  Every command then runs through the one path of commands/execute.hpp (ready -> dry run or
// checkpoint -> compute -> record -> write); what this layer adds is the command line's own: flags, MPI ranks,
// --dry-run's text and the terminal's words (the declaration's warn, print and report).
#pragma once

#include "cli/app.hpp"
#include "cli/checkpoint.hpp"
#include "cli/common.hpp"
#include "cli/mpi.hpp"
#include "commands/commands.hpp"
#include "commands/execute.hpp"
#include "core/estimate.hpp"
#include "core/field_types.hpp"
#include "core/fields.hpp"
#include "core/request.hpp"
#include "core/run.hpp"
#include "core/sweep.hpp"
#include "core/work.hpp"
#include "extras/extras.hpp"
#include "io/latex.hpp"
#include "io/rates.hpp"
#include "io/result_files.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <concepts>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace btob::cli {

// A request's fields as (name, text values): core's one vocabulary of fields (core/fields.hpp).
using Args = core::Args;

// How and where a result is written: not part of what is computed, and no result depends on it.
struct Output {
  std::string out;    // output folder
  std::string name;   // file stem of the outputs
  std::string title;  // figure title
  int threads = 0;    // 0: all cores
  bool no_plot = false, quiet = false;
  bool dry_run = false;  // predict the cost from a sample of the items, write nothing (core/estimate.hpp)
  bool resume = false;   // keep finished items in a checkpoint and continue from it (cli/checkpoint.hpp)
  bool sweep = false;    // the request is a sweep (core/sweep.hpp): it has --dry-run and --resume
  bool costed = false;   // the request counts its work (core/work.hpp): it has --dry-run from the cached route rates
  bool tabular = false;  // the result has CSV tables (tables()): it has --format
  std::string format = "csv";  // csv, or latex: the tables also as booktabs LaTeX (io/latex.hpp)
  // false: the command prints its result on stdout; given --out, it writes the result's files instead (NAME.h5
  // when it has arrays, its CSV tables, NAME.json), as Python's save() does, and has no figure (no --no-plot)
  bool files = true;
  static Output to_stdout() {
    Output o;
    o.files = false;
    return o;
  }
  // Whether this run writes files (a file command always; a stdout command given --out).
  bool writes() const { return files || !out.empty(); }
  template <class V> void fields(V&& v) {
    if (files) {
      v("out", out, "output folder (created when the result is complete)");
      v("name", name, "file stem of the outputs");
      v("title", title, "figure title (r range, grid and iterations are added)");
    } else {
      v("out", out, "write NAME.h5, the CSV tables and NAME.json into this folder instead of printing");
      v("name", name, "file stem of the outputs (with --out)");
      v("title", title, "title recorded with the result (with --out)");
    }
    v("threads", threads, "OpenMP threads: " + core::threads_expected());
    if (files) v("no-plot", no_plot, "write data only");
    if (tabular && files)
      v("format", format,
        "csv (the CSV tables) or latex (also each table as a booktabs LaTeX table, NAME.tex beside "
        "NAME.csv: exact decimals as printed, each number's status in a footnote under the table)");
    if (tabular && !files)
      v("format", format,
        "csv (print the CSV table) or latex (print it as a booktabs LaTeX table instead: exact "
        "decimals as printed, each number's status in a footnote under the table; with --out "
        "also NAME.tex beside NAME.csv)");
    v("quiet", quiet, "no progress or summary on stderr");
    if (sweep)
      v("dry-run", dry_run,
        "print the work (items), the predicted time on this machine, the data size and rank 0's peak memory, "
        "calibrated by running a 0.2-1 s sample of this request's own items; write nothing");
    if (costed && !sweep)
      v("dry-run", dry_run,
        "print the work (its units, counted from the fields), the predicted time on this machine, the output size and "
        "the peak memory; the rate of each route is measured the first time by a ~0.1 s fixed probe run and cached "
        "in $XDG_CACHE_HOME/btob/rates.json (~/.cache/btob/rates.json), keyed by btob version and commit, CPU model, "
        "threads and route; write nothing else");
    if (sweep)
      v("resume", resume,
        "keep finished items in OUT/NAME.checkpoint (./NAME.checkpoint when printing) while running, and continue "
        "from that file when it exists (made by the same request and btob build); removed once the result is written");
  }
  // Where --resume keeps the finished items: beside the result's files.
  io::fs::path checkpoint_path() const {
    return writes() ? io::fs::path(out) / (name + ".checkpoint") : io::fs::path(name + ".checkpoint");
  }
};

// What a command's body receives besides the request.
struct Context {
  core::RunControl control;  // threads, progress (unless --quiet), the process's cancellation token (SIGINT)
  std::string command_line;  // for provenance
  Args request_args;         // the request as recorded in the manifest
  std::string command;       // the subcommand
  bool quiet = false;        // --quiet (and every MPI rank but 0)
  std::string title;         // --title, the LaTeX tables' caption
  std::shared_ptr<Checkpoint> checkpoint;  // --resume: the sweep's checkpoint (every rank), else null
  // The caption of its LaTeX tables: --title, else "btob COMMAND".
  std::string caption() const { return title.empty() ? "btob " + command : title; }
};

// The process-wide cancellation token, set by SIGINT/SIGTERM (main installs the handler).
core::CancelToken& cancel_token();
// The progress sink of the terminal (a bar on stderr when it is a terminal, else nothing), for one run.
std::unique_ptr<core::ProgressSink> terminal_progress(const std::string& label);

// A request whose result has CSV tables (core::Tables): its command has --format csv|latex.
template <class Req>
concept Tabular = requires(const Req& q, const core::RunControl& c) {
  run(q, c).tables();
};

// A command runnable from a scene or a manifest: sets fields by name and runs.
struct SceneCommand {
  std::function<void(const Args& args, const std::string& invocation)> run;  // later keys override earlier ones
  bool files = true;                                                         // has out and name
  bool dry_run = false;                                                      // has --dry-run (a sweep, or costed)
};
std::map<std::string, SceneCommand>& scene_commands();

namespace detail {
template <class T> std::string joined(const T& v) {
  std::string s;
  for (const auto& t : core::field_text(v)) s += (s.empty() ? "" : " ") + t;
  return s;
}

// Adds one CLI11 option per field, collecting the raw text; apply() then parses it with the field parsers.
struct FlagBinder {
  CLI::App* app;
  std::map<std::string, std::shared_ptr<std::vector<std::string>>>* raw;
  std::map<std::string, CLI::Option*>* opts;
  template <class T> void operator()(const std::string& name, T& member, const std::string& help) {
    add(name, member, help, false);
  }
  template <class T> void operator()(const std::string& name, T& member, const std::string& help, core::Required) {
    add(name, member, help, true);
  }
  template <class T> void operator()(const std::string& name, T& member, const std::string& help, core::Positional) {
    add(name, member, help, true, true);
  }
  template <class T>
  void add(const std::string& name, T& member, const std::string& help, bool required, bool positional = false) {
    static_assert(core::is_field_type_v<T>, "request fields must be of a type core/fields.hpp parses");
    auto store = std::make_shared<std::vector<std::string>>();
    (*raw)[name] = store;
    CLI::Option* o = nullptr;
    if constexpr (std::is_same_v<T, bool>) {
      o = app->add_flag("--" + name, help);
    } else {
      o = app->add_option(positional ? name : "--" + name, *store, help);
      if constexpr (std::is_same_v<T, std::vector<double>> || std::is_same_v<T, std::vector<std::string>> ||
                    std::is_same_v<T, std::vector<core::Decimal>>)
        o->expected(1, -1)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
      else  // one value: a word after it is the next argument (`--periods 10 1133`: 1133 is the positional word)
        o->expected(1)->allow_extra_args(false)->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
      // The field's type (core/field_types.hpp), not CLI11's TEXT for the raw strings collected here; no default
      // shown for a field that must be given (its default is a placeholder, not a value one may rely on).
      o->type_name(core::field_type_name<T>().cli);
      const std::string d = joined(member);
      if (!d.empty() && !required) o->default_str(d);
    }
    if (required && !positional) o->required();  // an empty positional fails validate(), naming the field
    (*opts)[name] = o;
  }
};

// Sets the fields given on the command line.
struct FlagApplier {
  std::map<std::string, std::shared_ptr<std::vector<std::string>>>* raw;
  std::map<std::string, CLI::Option*>* opts;
  template <class T, class... Tag> void operator()(const std::string& name, T& member, const std::string&, Tag...) {
    CLI::Option* o = (*opts)[name];
    if (o->count() == 0) return;
    if constexpr (std::is_same_v<T, bool>) member = true;
    else core::set_field(member, *(*raw)[name], name);
  }
};

// Sets fields from (key, values) pairs; records which keys were used.
struct ArgsApplier {
  const Args* args;
  std::vector<bool>* used;
  template <class T, class... Tag> void operator()(const std::string& name, T& member, const std::string&, Tag...) {
    for (std::size_t i = 0; i < args->size(); ++i)
      if ((*args)[i].first == name) {
        core::set_field(member, (*args)[i].second, name);
        (*used)[i] = true;
      }
  }
};

// Lists the fields' names.
struct NameLister {
  std::string* names;
  template <class T, class... Tag> void operator()(const std::string& name, T&, const std::string&, Tag...) {
    *names += (names->empty() ? "" : ", ") + name;
  }
};

void validate_output(const Output& o);

// Adds subcommand `name` to `app`; a name of several words ("windows bounds") goes under the subcommands named by
// the words before the last, each found or else created (a parent registered earlier keeps its help and settings).
CLI::App* add_nested(CLI::App& app, const std::string& name, const std::string& help);
Context make_context(const std::string& command, const Output& o, const std::string& invocation, Args request_args);
}  // namespace detail

namespace detail {
// The output's defaults a request fills in: its declared file stem (commands::SpecBase::stem_of: e.g.
// hyperbolicity_strip_r<r>, or the command's last word for a stdout command); then the output checked.
template <class Req> void complete_output(const Req& req, Output& out) {
  if (out.name.empty()) out.name = commands::Spec<Req>::stem_of(req);
  validate_output(out);
}

// The request as the manifest records it: its fields, and name and title when the run writes files (what the
// figure says belongs to the record; where it went and how fast does not).
template <class Req> Args recorded_request(Req& req, const Output& out) {
  Args recorded;
  req.fields(core::ArgsWriter{&recorded});
  if (out.writes()) {
    recorded.emplace_back("name", std::vector<std::string>{out.name});
    recorded.emplace_back("title", std::vector<std::string>{out.title});
  }
  return recorded;
}

// --dry-run: the sweep's predicted cost from a sample of its own items, on rank 0's stdout; nothing written.
template <class Req>
void print_estimate(const std::string& name, const Req& req, const Output& out, const Context& ctx) {
  const int threads = core::thread_count(out.threads);
  if (mpi::rank() == 0)
    std::cout
        << core::estimate_sweep(req, ctx.control, mpi::size(), static_cast<std::size_t>(threads)).text(name, threads);
}

// --dry-run of a request that is not a sweep: its work at the cached (else calibrated) route rates, on stdout.
template <class Req>
void print_work_estimate(const std::string& name, const Req& req, const Output& out, const Context& ctx) {
  const int threads = core::thread_count(out.threads);
  std::cout << io::estimate_work(work(req), ctx.control, threads).text(name);
}

// Before a run predicted over 10 minutes, its estimate on stderr (a route not yet calibrated costs its ~0.1 s probe,
// once per machine, build and thread count).  Not for a request whose probe is itself (core::self_term): pricing it
// would run it first.
constexpr double long_run_seconds = 600;
template <class Req>
void note_long_run(const std::string& name, const Req& req, const Output& out, const Context& ctx) {
  const int threads = core::thread_count(out.threads);
  core::Work w = work(req);
  for (const core::Term& t : w.terms)
    if (t.probe_is_request || t.sized_run) return;  // pricing would run it, or instances of it for a second
  try {
    const io::WorkEstimate e = io::estimate_work(std::move(w), ctx.control, threads);
    if (e.predicted_seconds > long_run_seconds) std::cerr << e.text(name, false) << std::flush;
  } catch (const core::Cancelled&) {
    throw;
  } catch (const std::exception& e) {  // a probe that fails is no reason not to run the request
    std::cerr << "btob: warning: no estimate before the run (" << e.what() << ")\n";
  }
}

// Before a sweep that may take over 10 minutes, the estimate from its sample on stderr (rank 0; the other ranks go
// on to the sweep and wait for it there): core::StepCounted says when it is worth the sample's 0.2-2 s.
template <class Req>
void note_long_sweep(const std::string& name, const Req& req, const Output& out, const Context& ctx) {
  if constexpr (core::StepCounted<Req>) {
    if (out.quiet || mpi::rank() != 0) return;
    const int threads = core::thread_count(out.threads);
    const double fastest = core::fastest_steps_per_second(req.precision) * threads * mpi::size();
    if (req.map_steps() / fastest < 60) return;
    const core::SweepEstimate e =
        core::estimate_sweep(req, ctx.control, mpi::size(), static_cast<std::size_t>(threads));
    if (e.predicted_seconds > long_run_seconds) std::cerr << e.text(name, threads, false) << std::flush;
  }
}

// A request that is its own probe (every term a core::self_term: a word's analysis, the precision study) keeps the
// time of a completed run in the rate cache: its dry run afterwards reads it instead of running the request again.
template <class Req> void remember_self_rate(const Req& req, const Output& out, double seconds) {
  if constexpr (core::Costed<Req> && !core::Sweep<Req>) {
    const core::Work w = work(req);
    if (w.terms.empty() ||
        !std::all_of(w.terms.begin(), w.terms.end(), [](const core::Term& t) { return t.probe_is_request; }))
      return;
    const int threads = core::thread_count(out.threads);
    for (const core::Term& t : w.terms)
      io::remember_rate(t, threads, t.units, seconds / static_cast<double>(w.terms.size()));
  }
}

// How this process runs its share: threads, the terminal's bar (unless --quiet), SIGINT's token, the MPI ranks
// (a sweep splits over them), the checkpoint of --resume, and the MPI statistics of the merge.
commands::How how_of(const Output& o, const Context& ctx, bool sweep, core::ProgressSink* bar);

// The attributes the command line adds to a record: the MPI job's split and gather (cli/mpi.hpp), under mpirun.
void add_mpi_attrs(core::Attrs& at);

// A stdout command given --format latex (and no --out): its tables as booktabs LaTeX on stdout instead of its text
// (io/latex.hpp), the status of each number from the result's Contents.
void print_latex(const commands::Record& rec, const Context& ctx);

// The body every command runs: compute (this process's share; null on the other ranks) -> the declaration's warnings
// -> the files (a file command; a stdout command given --out) -> the declaration's text on stdout and closing report.
template <class Req> void run_body(const Req& req, const Output& o, const Context& ctx) {
  using S = commands::Spec<Req>;
  std::shared_ptr<commands::Recorded<Req>> rec;
  {
    const auto bar = terminal_progress(S::command);
    rec = commands::compute(req, how_of(o, ctx, core::Sweep<Req>, o.quiet ? nullptr : bar.get()));
  }                  // the bar ends its line before anything else is said
  if (!rec) return;  // another MPI rank: rank 0 writes
  S::warn(req, rec->res, ctx.control);
  const bool latex_text = !o.files && o.out.empty() && o.format == "latex";
  if (!o.writes() && !latex_text) return S::print(req, rec->res);
  commands::record(*rec, commands::Provenance{ctx.command_line, o.name, o.title, core::thread_count(o.threads)});
  add_mpi_attrs(rec->attrs);
  if (latex_text) return print_latex(*rec, ctx);
  const commands::WriteOptions opts{o.files && !o.no_plot, false, o.format == "latex", ctx.command_line, ctx.caption()};
  const commands::Written w{commands::write(*rec, o.out, o.name, o.title, opts), o.quiet,
                            core::thread_count(o.threads)};
  if (!o.files) {  // a stdout command given --out writes its files instead of printing, as Python's save() does
    if (!o.quiet) std::cerr << "btob: wrote " << w.listing() << "\n";
    return;
  }
  S::print(req, rec->res);
  S::report(req, rec->res, rec->contents, w);
}

// The command line's stages around commands::ready and run_body: the output completed and checked, the request
// recorded, the MPI ranks' checkpoint, then --dry-run, or --resume's checkpoint, then the body.
template <class Req> void execute(Req req, Output out, const std::string& invocation) {
  const std::string name = commands::Spec<Req>::command;
  commands::ready(req);
  complete_output(req, out);
  Args recorded = recorded_request(req, out);
  // Under mpirun every rank got here with a valid request (cli/mpi.hpp).  A sweep splits across the ranks; any other
  // request runs on rank 0 alone.  Only rank 0 speaks.
  mpi::checkpoint();
  if (mpi::rank() != 0) {
    if constexpr (!core::Sweep<Req>) return;
    out.quiet = true;
  }
  Context ctx = make_context(name, out, invocation, std::move(recorded));
  if constexpr (core::Sweep<Req>) {
    if (out.dry_run) return print_estimate(name, req, out, ctx);
    if (!out.resume) note_long_sweep(name, req, out, ctx);  // a resumed run's bar says what is left at its own rate
    if (out.resume)  // a collective under mpirun: each rank reads its files, every rank learns every finished item
      ctx.checkpoint = open_checkpoint(out.checkpoint_path(), checkpoint_identity(name, ctx.request_args));
  } else if constexpr (core::Costed<Req>) {  // runs on rank 0 alone (returned above on the others)
    if (out.dry_run) return print_work_estimate(name, req, out, ctx);
    if (!out.quiet) note_long_run(name, req, out, ctx);
  }
  const auto t0 = std::chrono::steady_clock::now();
  try {
    run_body(req, out, ctx);
  } catch (const core::Cancelled&) {
    if (ctx.checkpoint && mpi::rank() == 0 && !out.quiet)
      std::cerr << "btob: the finished items are kept in " << ctx.checkpoint->path.string()
                << (mpi::size() > 1 ? " and its ranks' files beside it (.1, .2, ...)" : "")
                << "; the same command with --resume continues\n";
    throw;
  }
  // The result is written (or printed; under mpirun by the ranks' collective write too): the finished items are no
  // longer needed, and rank 0 removes every rank's file.
  if (ctx.checkpoint && mpi::rank() == 0) remove_checkpoint(*ctx.checkpoint);
  remember_self_rate(req, out, core::seconds_since(t0));
}

// The output's flags and defaults of a declared request: a file command's folder and stem, or a stdout command.
template <class Req> Output output_defaults() {
  using S = commands::Spec<Req>;
  Output o = commands::writes_files<Req>() ? Output{} : Output::to_stdout();
  if (commands::writes_files<Req>()) {
    o.out = S::folder;
    o.name = S::stem;
  }
  o.sweep = core::Sweep<Req>;
  o.costed = core::Costed<Req>;
  o.tabular = Tabular<Req>;
  return o;
}

// The subcommand on the command line: a flag per field of the request and of the output, applied when it runs.
template <class Req> void add_flags_command(CLI::App& app) {
  using S = commands::Spec<Req>;
  struct State {
    Req req;
    Output out;
    std::map<std::string, std::shared_ptr<std::vector<std::string>>> raw;
    std::map<std::string, CLI::Option*> opts;
  };
  auto s = std::make_shared<State>(State{S::defaults(), output_defaults<Req>(), {}, {}});
  CLI::App* c = add_nested(app, S::command, S::summary);
  mpi::request_apps().push_back(c);
  s->req.fields(FlagBinder{c, &s->raw, &s->opts});
  s->out.fields(FlagBinder{c, &s->raw, &s->opts});
  c->callback([s, c] {
    if (!c->get_subcommands().empty()) return;  // `btob pattern atlas` runs the atlas, not `pattern`
    s->req.fields(FlagApplier{&s->raw, &s->opts});
    s->out.fields(FlagApplier{&s->raw, &s->opts});
    execute<Req>(s->req, s->out, invocation());
  });
}

// The command from a scene or a manifest: fields set by name; a key that is no field is an error listing the known.
template <class Req> void run_from_args(const Args& args, const std::string& invocation) {
  using S = commands::Spec<Req>;
  Req req = S::defaults();
  Output out = output_defaults<Req>();
  std::vector<bool> used(args.size(), false);
  req.fields(ArgsApplier{&args, &used});
  out.fields(ArgsApplier{&args, &used});
  for (std::size_t i = 0; i < args.size(); ++i)
    if (!used[i]) {
      std::string known;
      req.fields(NameLister{&known});
      out.fields(NameLister{&known});
      throw UsageError(
          fmt::format("key '{}': not a field of '{}'; expected one of {}", args[i].first, S::command, known));
    }
  execute<Req>(std::move(req), std::move(out), invocation);
}
}  // namespace detail

// Registers the declared request Req (commands/commands.hpp) as a subcommand and as a command of scenes and
// manifests.  A name of several words, "windows bounds", is a subcommand of a subcommand: the command line reads
// `btob windows bounds ...`, and scenes and manifests name it in full (command = "windows bounds").
template <class Req> void declare() {
  registry().push_back([](CLI::App& app) { detail::add_flags_command<Req>(app); });
  scene_commands()[commands::Spec<Req>::command] =
      SceneCommand{[](const Args& args, const std::string& inv) { detail::run_from_args<Req>(args, inv); },
                   commands::writes_files<Req>(), core::Sweep<Req> || core::Costed<Req>};
}

}  // namespace btob::cli
