// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// A reusable barrier for a fixed set of long-lived threads that meet thousands of times a second
// (the phases of a propagation in bands last tens of microseconds). A thread that arrives early
// spins for a few microseconds, the usual wait when every thread has a core, then sleeps on a
// condition variable: spinning alone made a loaded machine, where the threads share cores, 80x
// slower (a spinning thread takes the core of the one it waits for).
#ifndef CGAL_ISOPHOTIC_METRIC_GEODESICS_INTERNAL_PHASE_BARRIER_H
#define CGAL_ISOPHOTIC_METRIC_GEODESICS_INTERNAL_PHASE_BARRIER_H

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>

#if defined(__x86_64__) || defined(_M_X64) || defined(__i386__)
#include <immintrin.h>
#endif

namespace CGAL {
namespace Isophotic_metric {
namespace internal {

class Phase_barrier
{
public:
  explicit Phase_barrier(unsigned threads) : threads_(threads) {}

  /// Returns once every thread has called it (the writes before it are then seen after it).
  void wait()
  {
    const std::uint64_t phase = phase_.load(std::memory_order_acquire);
    if(arrived_.fetch_add(1, std::memory_order_acq_rel) + 1 == threads_)
    {
      arrived_.store(0, std::memory_order_relaxed); // (the others leave only once the phase changes)
      {
        std::lock_guard<std::mutex> lock(mutex_);
        phase_.store(phase + 1, std::memory_order_release);
      }
      wake_.notify_all();
      return;
    }
    for(int i = 0; i < spin_rounds; ++i)
    {
      if(phase_.load(std::memory_order_acquire) != phase)
        return;
      pause();
    }
    std::unique_lock<std::mutex> lock(mutex_);
    wake_.wait(lock, [&] { return phase_.load(std::memory_order_acquire) != phase; });
  }

private:
  static constexpr int spin_rounds = 4096; // a few microseconds of pause instructions

  static void pause()
  {
#if defined(__x86_64__) || defined(_M_X64) || defined(__i386__)
    _mm_pause();
#endif
  }

  const unsigned threads_;
  std::atomic<unsigned> arrived_{0};
  std::atomic<std::uint64_t> phase_{0};
  std::mutex mutex_;
  std::condition_variable wake_;
};

} // namespace internal
} // namespace Isophotic_metric
} // namespace CGAL

#endif
