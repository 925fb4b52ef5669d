// SPDX-License-Identifier: GPL-3.0-or-later
// The cancellation token that io's long waits and commits obey (the command line's process-wide token, set by
// SIGINT/SIGTERM): a plot script being run is ended and ResultFiles::commit() refuses, so a run stopped while its
// files were being written leaves nothing, as one stopped during its computation.
#pragma once

#include "core/request.hpp"

namespace btob::io {

// From now on run_plot and ResultFiles::commit() throw core::Cancelled once `token` is set (nullptr: never).
void stop_on(const core::CancelToken* token);
// Throws core::Cancelled when the token given to stop_on is set.
void check_stop();

}  // namespace btob::io
