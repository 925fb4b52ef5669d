// SPDX-License-Identifier: GPL-3.0-or-later
// Replays committed fuzz corpora without libFuzzer (the normal gcc build, a CTest test): for each harness
// given as NAME=DIR, feeds every file of DIR to that harness's entry point (LLVMFuzzerTestOneInput renamed
// btob_fuzz_NAME at compile time).  Exit 1 when a directory is missing or empty: a corpus that is not there
// must not pass as "no crash".
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "fuzz_harnesses.hpp"  // BTOB_FUZZ_HARNESSES(X): X(name) for every tests/fuzz/fuzz_<name>.cpp (CMake)
#define BTOB_DECLARE(name) extern "C" int btob_fuzz_##name(const std::uint8_t*, std::size_t);
BTOB_FUZZ_HARNESSES(BTOB_DECLARE)

int main(int argc, char** argv) {
  using Entry = int (*)(const std::uint8_t*, std::size_t);
  const std::map<std::string, Entry> entries = {
#define BTOB_ENTRY(name) {#name, &btob_fuzz_##name},
      BTOB_FUZZ_HARNESSES(BTOB_ENTRY)};
  if (argc < 2) {
    std::fprintf(stderr, "usage: fuzz_replay NAME=CORPUS_DIR...\n");
    return 2;
  }
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    const auto eq = arg.find('=');
    const auto it = entries.find(arg.substr(0, eq));
    if (eq == std::string::npos || it == entries.end()) {
      std::fprintf(stderr, "fuzz_replay: unknown harness in '%s'\n", arg.c_str());
      return 2;
    }
    const std::filesystem::path dir = arg.substr(eq + 1);
    std::vector<std::filesystem::path> files;
    if (std::filesystem::is_directory(dir))
      for (const auto& e : std::filesystem::directory_iterator(dir))
        if (e.is_regular_file()) files.push_back(e.path());
    if (files.empty()) {
      std::fprintf(stderr, "fuzz_replay: %s: no corpus files in %s\n", it->first.c_str(), dir.c_str());
      return 1;
    }
    for (const auto& f : files) {
      std::ifstream in(f, std::ios::binary);
      const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      it->second(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    }
    std::printf("fuzz_replay: %s: %zu inputs, no crash\n", it->first.c_str(), files.size());
  }
  return 0;
}
