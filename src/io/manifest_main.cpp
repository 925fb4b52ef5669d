// SPDX-License-Identifier: GPL-3.0-or-later
// btob_manifest OUT.json COMMAND FILE...: the manifest of a result written by a script rather than by a btob
// subcommand (`btob windows bounds > bounds_certified.csv`, the Google Benchmark JSON): this build's provenance
// (io::provenance: commit and git_dirty of the build, run_dirty, compiler, flags, date), the command that made
// the files, and the files it describes ("files", comma-separated names in OUT's folder).  Built with btob from
// the same tree and commit, so it records btob's provenance.  Exit 2 on a usage error or a missing file.
#include "io/io.hpp"

#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  if (argc < 4) {
    std::fprintf(stderr, "usage: btob_manifest OUT.json COMMAND FILE...  (FILE: in OUT's folder)\n");
    return 2;
  }
  const fs::path out = argv[1];
  std::string files;
  for (int i = 3; i < argc; ++i) {
    const fs::path f = argv[i];
    const fs::path in_folder = out.parent_path() / f.filename();
    if (!fs::is_regular_file(in_folder)) {
      std::fprintf(stderr, "btob_manifest: files: got '%s', expected an existing file in '%s'\n", argv[i],
                   out.parent_path().c_str());
      return 2;
    }
    files += (files.empty() ? "" : ",") + f.filename().string();
  }
  try {
    btob::io::Attrs a = btob::io::provenance(argv[2]);
    a["files"] = files;
    a["kind"] = std::string("script");
    btob::io::write_manifest(out, a);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "btob_manifest: %s\n", e.what());
    return 1;
  }
  return 0;
}
