// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Peak resident memory of one call inside a Google Benchmark loop (Linux only), for the bench_*.cpp
// programs of this directory. The kernel's peak (VmHWM) is reset through /proc/self/clear_refs
// before the call; the reset walks the process's pages, so it is done with the timer paused.
#ifndef ISOPHOTIC_METRIC_BENCHMARK_PEAK_MEMORY_H
#define ISOPHOTIC_METRIC_BENCHMARK_PEAK_MEMORY_H

#include <benchmark/benchmark.h>

#include <malloc.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

namespace bench {

// A field of /proc/self/status in MB ("VmRSS:", "VmHWM:"), 0 when absent.
inline double status_megabytes(const char* field)
{
  std::ifstream status("/proc/self/status");
  for(std::string line; std::getline(status, line);)
    if(line.compare(0, std::strlen(field), field) == 0)
      return std::atof(line.c_str() + std::strlen(field)) / 1024.0;
  return 0;
}

struct Peak
{
  double growth_MB = 0;  // peak during the call minus the resident set before it
  double process_MB = 0; // peak of the whole process during the call
};

// Runs `call()` timed, and measures the peak around it untimed.
template <class Call>
Peak measure_peak(benchmark::State& state, Call&& call)
{
  state.PauseTiming();
  malloc_trim(0); // give freed memory back, so that reusing it shows as growth
  std::ofstream("/proc/self/clear_refs") << "5";
  const double before = status_megabytes("VmRSS:");
  state.ResumeTiming();
  call();
  state.PauseTiming();
  Peak p;
  p.process_MB = status_megabytes("VmHWM:");
  p.growth_MB = p.process_MB - before;
  state.ResumeTiming();
  return p;
}

} // namespace bench

#endif // ISOPHOTIC_METRIC_BENCHMARK_PEAK_MEMORY_H
