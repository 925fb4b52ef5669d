// SPDX-License-Identifier: GPL-3.0-or-later
// How a run uses the machine: the number of OpenMP threads it asks for and its wall-clock timer.  What a run
// computes never depends on either (core::RunControl says how to run, never what).
#pragma once

#include <chrono>

namespace btob::core {

// The threads a parallel region runs on: `requested` when positive, else OpenMP's default (all cores): what
// RunControl::threads = 0 means everywhere.
int thread_count(int requested);

// Seconds of steady-clock time since t0 (the seconds columns and attributes of results).
double seconds_since(std::chrono::steady_clock::time_point t0);

}  // namespace btob::core
