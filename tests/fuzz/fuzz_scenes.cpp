// SPDX-License-Identifier: GPL-3.0-or-later
// Fuzz harness: io::read_scene (TOML scene files, analyses/scenes/*.toml).  The input is written to a
// temporary file (read_scene reads a path, as `btob run` does); a parse either throws std::invalid_argument
// naming the file or returns a scene with a non-empty command.
#include "io/scene.hpp"

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 65536) return 0;
  static const std::string path = [] {
    const char* tmp = std::getenv("TMPDIR");
    return std::string(tmp && *tmp ? tmp : "/tmp") + "/btob_fuzz_scene_" + std::to_string(getpid()) + ".toml";
  }();
  {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) std::abort();
    if (size && std::fwrite(data, 1, size, f) != size) std::abort();
    std::fclose(f);
  }
  try {
    const btob::io::Scene s = btob::io::read_scene(path);
    if (s.command.empty()) std::abort();
  } catch (const std::invalid_argument&) {
  }
  std::remove(path.c_str());
  return 0;
}
