// SPDX-License-Identifier: GPL-3.0-or-later
// The iterator's check of the windows: orbits of the Section 4 grid inside and just below each window.
#pragma once

#include "core/request.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace btob::windows {

// For each n, four r values: below = lower - 0.05 w and inside_q = lower + q w (q = 1/4, 1/2, 3/4),
// w = r_crit,2(n) - lower.  Every orbit of iterate::paper_grid() runs base + per_n * n steps of the
// batched kernel; it is "on pattern" when the symbols of its last max(tail, 4n) steps are periodic with
// period 2n and one period is a rotation of 1^n 3^n (the pattern (ab)^n(cb)^n).
struct VerifyOptions {
  long base_iterations = 60000, per_n = 400;
  // Below a window the orbit leaves the pattern intermittently, after laminar phases of many periods:
  // with a 10000-step tail 11 of the 124 points below windows n = 2..125 still looked periodic (6 on
  // an earlier build: chaotic orbits differ with the instruction set); with 40000 none does.
  long tail = 40000;
  bool long_double = false;  // run the kernel in long double instead of double
  int threads = 0;
  const core::CancelToken* cancel = nullptr;  // polled by the kernel runs (core::Cancelled)
};

struct VerifyRow {
  int n = 0;
  std::string position;  // below, inside_25, inside_50, inside_75
  double r = 0, lower = 0, upper = 0;
  long iterations = 0, orbits = 0, on_pattern = 0;
  bool expected_on = false;  // inside: all orbits on pattern; below: none
  bool pass() const { return expected_on ? on_pattern == orbits : on_pattern == 0; }
  template <class A> void members(A& a) {
    a(n, position, r, lower, upper, iterations, orbits, on_pattern, expected_on);
  }
};

// Rows for n = first..last (2 <= first <= last); throws core::InvalidField naming the field.
std::vector<VerifyRow> verify_windows(int first, int last, const VerifyOptions& opt = {});

// True when s[0..len) is periodic with period 2n and one period is a rotation of 1^n 3^n.
bool on_pattern(const std::uint8_t* s, long len, int n);

}  // namespace btob::windows
