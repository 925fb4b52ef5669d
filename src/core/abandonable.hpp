// SPDX-License-Identifier: GPL-3.0-or-later
// One call that cannot poll the cancellation token (core/cancel.hpp) from inside, made cancellable from outside: a
// dense eigensolver's O(m^3) steps, one FFTW execution of millions of points.
#pragma once

#include "core/cancel.hpp"

#include <chrono>
#include <future>
#include <memory>
#include <thread>
#include <utility>

namespace btob::core {

// Runs f() on a thread of its own while this thread polls `token` every 5 ms, and returns f's result.  Cancelled,
// this thread throws core::Cancelled at once and abandons the call, which finishes alone (one core for at most the
// call's own time; the command line's exit ends it at once): f must own everything it touches (captured by value
// or by shared_ptr).  The same code on another thread: the same bits.
template <class F> auto run_abandonable(const CancelToken* token, F f) -> decltype(f()) {
  using R = decltype(f());
  auto task = std::make_shared<std::packaged_task<R()>>(std::move(f));
  std::future<R> done = task->get_future();
  std::thread([task] { (*task)(); }).detach();  // the task, and what f owns, live until f returns
  while (done.wait_for(std::chrono::milliseconds(5)) != std::future_status::ready) check_cancel(token);
  return done.get();
}

}  // namespace btob::core
