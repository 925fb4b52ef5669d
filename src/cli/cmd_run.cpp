// SPDX-License-Identifier: GPL-3.0-or-later
// `btob run SCENE.toml` and `btob run results/NAME/NAME.json`: a scene, or the request a result's manifest
// recorded, run again.  Request-based commands (cli/command.hpp) set their fields by name; the others still
// replay their flags through the argument parser.
//
// A manifest's re-run is a reproduction check: it writes into NAME/reproduced/ (or --out, never the original
// folder), then compares its datasets with the original's (io/reproduce.hpp), prints one line "reproduction: N of
// M datasets bit-identical; differ: a, b" and writes the same as reproduction.json beside the re-run's files.
// The exit status is the run's (0 whether or not the data are the same): the report says what differs.
#include "cli/app.hpp"
#include "cli/command.hpp"
#include "cli/common.hpp"
#include "cli/mpi.hpp"
#include "io/io.hpp"
#include "io/reproduce.hpp"
#include "io/scene.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <iostream>

namespace btob::cli {
namespace {

// A manifest's {"request": {"command": ..., "args": {...}}} as a scene (name: the manifest's file stem).
io::Scene read_manifest(const std::string& path) {
  std::ifstream f(path);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(f);
  } catch (const nlohmann::json::exception& e) {
    throw UsageError(fmt::format("manifest {}: not valid JSON ({})", path, e.what()));
  }
  if (!j.contains("request") || !j["request"].is_object() || !j["request"].contains("command"))
    throw UsageError(
        fmt::format("manifest {}: key 'request': missing; expected a manifest written by btob 0.2 or later "
                    "(older manifests record only the command line, under 'command')",
                    path));
  io::Scene s;
  s.name = std::filesystem::path(path).stem().string();
  s.command = j["request"]["command"].get<std::string>();
  for (const auto& [k, v] : j["request"]["args"].items()) {
    std::vector<std::string> vals;
    if (v.is_array())
      for (const auto& e : v) vals.push_back(e.get<std::string>());
    else vals.push_back(v.get<std::string>());
    s.args.push_back({k, vals, false});
  }
  return s;
}

// The older route: the scene's flags through the argument parser of a fresh command line.
void replay_flags(const io::Scene& s, const std::string& path, Args args, std::size_t injected_from) {
  CLI::App fresh{"btob"};
  fresh.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  for (auto& reg : registry()) reg(fresh);
  mpi::guard_root_only(fresh);  // an older command runs on MPI rank 0 alone
  CLI::App* sub = nullptr;
  for (CLI::App* c : fresh.get_subcommands([](CLI::App*) { return true; }))
    if (c->get_name() == s.command) sub = c;
  if (!sub || s.command == "run")
    throw UsageError(fmt::format("scene {}: key 'command': got '{}', expected a btob subcommand", path, s.command));
  std::vector<std::string> argv{s.command};
  for (std::size_t i = 0; i < args.size(); ++i) {
    const auto& [k, vals] = args[i];
    if (i >= injected_from && !sub->get_option_no_throw("--" + k))
      continue;  // `btob run --quiet` etc. where unsupported
    if (!sub->get_option_no_throw("--" + k)) {
      std::string known;
      for (const CLI::Option* o : sub->get_options())
        if (!o->get_lnames().empty() && o->get_lnames()[0] != "help")
          known += (known.empty() ? "" : ", ") + o->get_lnames()[0];
      throw UsageError(
          fmt::format("scene {}: key 'args.{}': not a flag of '{}'; expected one of {}", path, k, s.command, known));
    }
    if (vals.size() == 1 && (vals[0] == "true" || vals[0] == "false") &&
        sub->get_option("--" + k)->get_expected_max() == 0) {
      if (vals[0] == "true") argv.push_back("--" + k);  // a flag
      continue;
    }
    argv.push_back("--" + k);
    for (const auto& v : vals) argv.push_back(v);
  }
  invocation() += " -> btob";
  for (const auto& a : argv) invocation() += " " + a;
  std::reverse(argv.begin(), argv.end());  // CLI11 takes the arguments reversed
  fresh.parse(argv);
}

struct RunFlags {
  std::string path, out;
  int threads = 0;
  bool quiet = false, no_plot = false, dry_run = false;
};

// The folder a manifest's re-run writes to: --out, else reproduced/ beside the manifest; never the manifest's own
// folder, whose result it is compared with.
std::string reproduction_folder(const std::string& manifest, const std::string& out) {
  namespace fs = std::filesystem;
  const fs::path original = fs::path(manifest).parent_path();
  if (out.empty()) return (original / "reproduced").string();
  std::error_code ec;
  if (fs::exists(out) && fs::equivalent(out, original.empty() ? fs::path(".") : original, ec))
    throw UsageError(
        fmt::format("--out: got '{}', the manifest's own folder; expected another folder (a re-run "
                    "never writes over the result it reproduces)",
                    out));
  return out;
}

// After a manifest's re-run into `out`: its datasets against the original's, on stdout and in out/reproduction.json.
void report_reproduction(const std::string& manifest, const std::string& out, const std::string& name, bool quiet) {
  const std::filesystem::path original = std::filesystem::path(manifest).parent_path();
  const io::Reproduction r = io::compare_results(original.empty() ? "." : original, out, name);
  const std::filesystem::path file = std::filesystem::path(out) / "reproduction.json";
  io::write_text_atomic(file, r.json());
  std::cout << "reproduction: " << r.summary() << "\n";
  if (!quiet) std::cerr << "btob: wrote " << file.string() << "\n";
}

// The value of `key` among the scene's arguments ("" when absent).
std::string arg_value(const Args& args, const std::string& key) {
  for (const auto& [k, v] : args)
    if (k == key && !v.empty()) return v.back();
  return "";
}

void run_scene(const RunFlags& f) {
  const std::string& path = f.path;
  if (!std::filesystem::is_regular_file(path))
    throw UsageError(fmt::format("scene: got '{}', expected an existing scene (.toml) or manifest (.json) file", path));
  const bool manifest = std::filesystem::path(path).extension() == ".json";
  const io::Scene s = manifest ? read_manifest(path) : io::read_scene(path);
  const std::string out_override = manifest ? reproduction_folder(path, f.out) : f.out;
  // The request's keys, then the run's own: --out overrides the scene's folder; a scene without one writes to
  // results/<scene name> (a manifest to reproduced/ beside it); the name defaults to the scene's.
  Args args;
  bool has_out = false, has_name = false, has_title = false;
  for (const auto& a : s.args) {
    has_out |= a.key == "out";
    has_name |= a.key == "name";
    has_title |= a.key == "title";
    if (a.key == "out" && !out_override.empty()) continue;
    args.emplace_back(a.key, a.values);
  }
  const auto it = scene_commands().find(s.command);
  // A stdout command writes files when its manifest names them (a result saved by Python, or run with --out).
  const bool writes = it == scene_commands().end() || it->second.files || (manifest && has_name);
  if (!out_override.empty()) args.emplace_back("out", std::vector<std::string>{out_override});
  else if (!has_out && writes) args.emplace_back("out", std::vector<std::string>{"results/" + s.name});
  if (!has_name && writes) args.emplace_back("name", std::vector<std::string>{s.name});
  if (!has_title && !s.title.empty()) args.emplace_back("title", std::vector<std::string>{s.title});
  const std::size_t injected_from = args.size();  // the run's own flags, below
  if (f.threads != 0) args.emplace_back("threads", std::vector<std::string>{std::to_string(f.threads)});
  if (f.quiet) args.emplace_back("quiet", std::vector<std::string>{"true"});
  if (f.no_plot && (it == scene_commands().end() || it->second.files))
    args.emplace_back("no-plot", std::vector<std::string>{"true"});
  if (f.dry_run) {
    if (it != scene_commands().end() && !it->second.dry_run)
      throw UsageError(fmt::format("--dry-run: '{}' has no dry run", s.command));
    args.emplace_back("dry-run", std::vector<std::string>{"true"});
  }
  const auto report = [&] {
    if (manifest && !f.dry_run && mpi::rank() == 0)
      report_reproduction(path, arg_value(args, "out"), arg_value(args, "name"), f.quiet);
  };
  if (it == scene_commands().end()) {
    replay_flags(s, path, args, injected_from);
    return report();
  }
  std::string inv = invocation() + " -> btob " + s.command;
  for (const auto& [k, vals] : args) {
    inv += " --" + k;
    for (const auto& v : vals) inv += " " + shell_quote(v);
  }
  try {
    it->second.run(args, inv);
  } catch (const core::InvalidField& e) {
    throw UsageError(fmt::format("{} {}: {}", manifest ? "manifest" : "scene", path, e.what()));
  } catch (const UsageError& e) {
    throw UsageError(fmt::format("{} {}: {}", manifest ? "manifest" : "scene", path, e.what()));
  }
  report();
}

Register reg([](CLI::App& app) {
  auto f = std::make_shared<RunFlags>();
  CLI::App* c =
      app.add_subcommand("run", "Run a scene file (analyses/scenes/*.toml) or re-run a result's manifest (NAME.json)");
  c->add_option("scene", f->path, "scene file, or a manifest written with a result")->required();
  c->add_option("--out", f->out,
                "output directory (default: the scene's, else results/<scene name>; for a manifest NAME.json, "
                "reproduced/ beside it, never its own folder: the re-run's datasets are then compared with the "
                "original's, the count of bit-identical ones printed and written to reproduction.json)");
  c->add_option("--threads", f->threads, "OpenMP threads (default: all cores)");
  c->add_flag("--quiet", f->quiet, "no progress or summary on stderr");
  c->add_flag("--no-plot", f->no_plot, "write data only");
  c->add_flag("--dry-run", f->dry_run, "the command's --dry-run: its predicted cost, nothing written");
  c->callback([f] { run_scene(*f); });
});

}  // namespace
}  // namespace btob::cli
