// SPDX-License-Identifier: GPL-3.0-or-later
// The version of the btob library a program is linked against: the CMake project version, the one `btob --version`,
// the Python package (btob.__version__), the packages and the result manifests report.
#pragma once

namespace btob {
// "MAJOR.MINOR.PATCH", defined in the library (not inlined from this header), so a program compiled against the
// headers of one installation and linked against the library of another reports the library's.
const char* version() noexcept;
}  // namespace btob
