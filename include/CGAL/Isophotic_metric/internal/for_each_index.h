// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The one loop over independent tasks of the package, run in parallel with TBB when the
// concurrency tag asks for it: every thread works on its own state (a solver sharing the
// prepared mesh, scratch buffers), made once per thread.
#ifndef CGAL_ISOPHOTIC_METRIC_INTERNAL_FOR_EACH_INDEX_H
#define CGAL_ISOPHOTIC_METRIC_INTERNAL_FOR_EACH_INDEX_H

#include <CGAL/Isophotic_metric/internal/Progress_callback.h>
#include <CGAL/tags.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <memory>
#include <type_traits>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#endif

namespace CGAL {
namespace Isophotic_metric {
namespace internal {

// Calls task(state, i) for every i in [0, n), where `state` is a `make_state()` of the calling
// thread. With CGAL::Parallel_tag (what CGAL::Parallel_if_available_tag is when TBB is linked)
// the indices are spread over TBB's threads; with CGAL::Sequential_tag one state serves them all,
// in order. `task` must only write data of its own index. `grain`: indices per TBB task (1 for
// long tasks such as whole distance fields, more for short ones such as small neighbourhoods).
// `progress` hears of the fraction of indices done about a thousand times; when it cancels, the
// Cancelled_error leaves the loop (TBB cancels the other threads' remaining ranges and rethrows it).
template <class ConcurrencyTag, class MakeState, class Task>
void for_each_index(std::size_t n, std::size_t grain, MakeState&& make_state, Task&& task,
                    const Progress_callback& progress = Progress_callback(), const char* what = "loop")
{
  typedef decltype(make_state()) State;
  const std::size_t stride = std::max<std::size_t>(1, n / 1024);
  std::atomic<std::size_t> done{0};
  auto task_and_report = [&](State& state, std::size_t i) {
    task(state, i);
    if(progress)
    {
      const std::size_t k = ++done;
      if(k % stride == 0)
        progress.report(double(k) / double(n), what);
    }
  };
#ifdef CGAL_LINKED_WITH_TBB
  if constexpr(std::is_convertible<ConcurrencyTag, CGAL::Parallel_tag>::value)
  {
    tbb::enumerable_thread_specific<std::unique_ptr<State>> states;
    // a thread's state is made once, on its first range
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain), [&](const tbb::blocked_range<std::size_t>& range) {
      std::unique_ptr<State>& state = states.local();
      if(!state)
        state = std::make_unique<State>(make_state());
      for(std::size_t i = range.begin(); i != range.end(); ++i)
        task_and_report(*state, i);
    });
    return;
  }
#else
  (void)grain;
  static_assert(!std::is_convertible<ConcurrencyTag, CGAL::Parallel_tag>::value,
                "CGAL::Parallel_tag needs TBB (CGAL_LINKED_WITH_TBB)");
#endif
  State state = make_state();
  for(std::size_t i = 0; i < n; ++i)
    task_and_report(state, i);
}

} // namespace internal
} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_INTERNAL_FOR_EACH_INDEX_H
