// `btob run SCENE.toml`: runs the subcommand a scene names with the flags it lists.
#include "cli/app.hpp"
#include "cli/common.hpp"
#include "io/scene.hpp"

#include <fmt/format.h>

namespace btob::cli {
namespace {

void run_scene(const std::string& path, const std::string& out_override) {
  if (!std::filesystem::is_regular_file(path))
    throw UsageError(fmt::format("scene: got '{}', expected an existing TOML scene file", path));
  const io::Scene s = io::read_scene(path);
  CLI::App fresh{"btob"};
  fresh.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  for (auto& reg : registry()) reg(fresh);
  CLI::App* sub = nullptr;
  for (CLI::App* c : fresh.get_subcommands([](CLI::App*) { return true; }))
    if (c->get_name() == s.command) sub = c;
  if (!sub || s.command == "run")
    throw UsageError(fmt::format("scene {}: key 'command': got '{}', expected a btob subcommand", path, s.command));
  std::vector<std::string> argv{s.command};
  bool has_out = false, has_name = false, has_title = false;
  for (const auto& [k, vals] : s.args) {
    if (!sub->get_option_no_throw("--" + k)) {
      std::string known;
      for (const CLI::Option* o : sub->get_options())
        if (!o->get_lnames().empty() && o->get_lnames()[0] != "help") known += (known.empty() ? "" : ", ") + o->get_lnames()[0];
      throw UsageError(fmt::format("scene {}: key 'args.{}': not a flag of '{}'; expected one of {}", path, k, s.command, known));
    }
    has_out |= k == "out";
    has_name |= k == "name";
    has_title |= k == "title";
    if (k == "out" && !out_override.empty()) continue;
    argv.push_back("--" + k);
    for (const auto& v : vals) argv.push_back(v);
  }
  if (!out_override.empty()) {
    argv.push_back("--out");
    argv.push_back(out_override);
  } else if (!has_out && sub->get_option_no_throw("--out")) {
    argv.push_back("--out");
    argv.push_back("results/" + s.name);
  }
  if (!has_name && sub->get_option_no_throw("--name")) {
    argv.push_back("--name");
    argv.push_back(s.name);
  }
  if (!has_title && !s.title.empty() && sub->get_option_no_throw("--title")) {
    argv.push_back("--title");
    argv.push_back(s.title);
  }
  invocation() += " -> btob";
  for (const auto& a : argv) invocation() += " " + a;
  std::reverse(argv.begin(), argv.end());  // CLI11 takes the arguments reversed
  fresh.parse(argv);
}

Register reg([](CLI::App& app) {
  auto path = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  CLI::App* c = app.add_subcommand("run", "Run a scene file (analyses/scenes/*.toml)");
  c->add_option("scene", *path, "scene file")->required();
  c->add_option("--out", *out, "output directory (default: the scene's, or results/<scene name>)");
  c->callback([path, out] { run_scene(*path, *out); });
});

}  // namespace
}  // namespace btob::cli
