// SPDX-License-Identifier: GPL-3.0-or-later
// Whether a re-run reproduced a result (`btob run results/NAME/NAME.json`): every dataset of the original NAME.h5
// against the re-run's, bit for bit, and every CSV table of the result byte for byte.  Attributes are not compared:
// they hold provenance (date, command line, timings) that differs between any two runs; nor are datasets of wall
// times (NAME ending in "seconds").  Figures (PNG) are not
// compared either: they are drawn from the data, by a plotting library whose output is not part of the result.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace btob::io {

struct Reproduction {
  std::string original, reproduction;  // the two folders
  // Dataset paths of NAME.h5 ("density", "lower_text") and CSV file names, each in exactly one list.
  std::vector<std::string> identical;          // the same type, shape and bytes (strings: the same texts)
  std::vector<std::string> differ;             // in both, with another type, shape or content
  std::vector<std::string> only_original;      // missing from the re-run
  std::vector<std::string> only_reproduction;  // new in the re-run
  // Datasets of wall times (a name ending in "seconds": how long a stage took, not what it computed), listed and
  // not compared: no two runs take the same time.
  std::vector<std::string> timings;
  bool original_has_data = false;  // the original folder holds NAME.h5 or a CSV table (else nothing to compare)
  std::size_t compared() const {
    return identical.size() + differ.size() + only_original.size() + only_reproduction.size();
  }
  bool reproduced() const { return compared() > 0 && identical.size() == compared(); }
  // One line: "N of M datasets bit-identical" and, when some are not, "; differ: a, b" (missing ones included,
  // marked "(only in the original)" or "(only in the re-run)"); "nothing to compare: ..." when the original folder
  // holds no data file (a result whose NAME.h5 was not kept).
  std::string summary() const;
  // The same as a JSON object (reproduction.json): folders, the four lists, compared, identical count, reproduced.
  std::string json() const;
};

// Compares `original`/NAME.h5 and its CSV tables (NAME.csv, NAME_*.csv) with the same files in `reproduction`.
// Throws std::runtime_error naming a file that exists but cannot be read as HDF5.
Reproduction compare_results(const std::filesystem::path& original, const std::filesystem::path& reproduction,
                             const std::string& name);

}  // namespace btob::io
