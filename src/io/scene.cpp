// SPDX-License-Identifier: GPL-3.0-or-later
// Scene files: TOML (toml++) to a subcommand and its flags.
#include "io/scene.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <stdexcept>

namespace btob::io {

namespace {
std::string scalar_text(const toml::node& n, const std::string& where) {
  if (auto s = n.value<std::string>()) return *s;
  if (n.is_integer()) return std::to_string(*n.value<long long>());
  // A TOML float reaches us as a double: its shortest round-trip form is the decimal the scene wrote whenever that
  // has at most 15 significant digits (r = 0.1 stays "0.1", which a float128 run reads as float128's 0.1; 17 digits
  // would give it 0.10000000000000001).  A value with more digits than a double holds is written as a string.
  if (n.is_floating_point()) return fmt::format("{}", *n.value<double>());
  throw std::invalid_argument(fmt::format("{}: expected a string, number or boolean", where));
}
}  // namespace

Scene read_scene(const std::filesystem::path& path) {
  toml::table t;
  try {
    t = toml::parse_file(path.string());
  } catch (const toml::parse_error& e) {
    throw std::invalid_argument(fmt::format("scene {}:{}:{}: {}", path.string(), e.source().begin.line,
                                            e.source().begin.column, e.description()));
  }
  Scene s;
  s.name = path.stem().string();
  for (const auto& [key, node] : t) {
    const std::string k(key.str());
    const std::string where = fmt::format("scene {}: key '{}'", path.string(), k);
    if (k == "command") {
      if (!node.is_string()) throw std::invalid_argument(where + ": expected a string naming a btob subcommand");
      s.command = *node.value<std::string>();
    } else if (k == "title") {
      if (!node.is_string()) throw std::invalid_argument(where + ": expected a string");
      s.title = *node.value<std::string>();
    } else if (k == "args") {
      if (!node.is_table()) throw std::invalid_argument(where + ": expected a table [args] of flags");
      for (const auto& [ak, an] : *node.as_table()) {
        const std::string a(ak.str());
        const std::string w = fmt::format("scene {}: key 'args.{}'", path.string(), a);
        std::vector<std::string> vals;
        bool boolean = false;
        if (an.is_boolean()) {
          vals.push_back(*an.value<bool>() ? "true" : "false");
          boolean = true;
        } else if (an.is_array()) {
          for (const auto& e : *an.as_array()) vals.push_back(scalar_text(e, w));
          if (vals.empty()) continue;
        } else {
          vals.push_back(scalar_text(an, w));
        }
        s.args.push_back({a, std::move(vals), boolean});
      }
    } else {
      throw std::invalid_argument(where + ": unknown key, expected command, title or [args]");
    }
  }
  if (s.command.empty())
    throw std::invalid_argument(
        fmt::format("scene {}: key 'command' missing, expected the btob subcommand to run", path.string()));
  return s;
}

}  // namespace btob::io
