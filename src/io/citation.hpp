// SPDX-License-Identifier: GPL-3.0-or-later
// How to cite btob: the software (this build's version and git commit) and the paper whose map it implements, in
// BibTeX, Citation File Format (CITATION.cff at the repository's root is `btob cite --format cff` without its commit
// line: tests/citation_check.py) or plain text.  `btob cite` and Python's btob.cite() print these strings.
#pragma once

#include <string>
#include <vector>

namespace btob::io {

// The accepted formats, the first the default.
const std::vector<std::string>& citation_formats();

// The citation in `format` (one of citation_formats()); std::invalid_argument naming the field and the accepted
// values otherwise.  `commit` and `dirty` are the build's (build::git_commit, build::git_dirty): a build with
// uncommitted changes says so, since its commit alone does not name the code that ran.
std::string citation(const std::string& format, const std::string& version, const std::string& commit,
                     const std::string& dirty);

// The same for this build (build::version, build::git_commit, build::git_dirty).
std::string citation(const std::string& format);

}  // namespace btob::io
