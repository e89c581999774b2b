// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Exact single-source geodesic distances to all vertices: this package's engine side by side with
// CGAL's exact Surface_mesh_shortest_path and CGAL's approximate Heat_method_3, on CGAL's meshes
// and on fandisk Loop-subdivided twice (207k faces) and three times (829k faces); scanned meshes:
// refined_elephant (89k), and bunny00 refined by PMP::refine (density 3, 261k faces: every scanned
// vertex kept, with its noise and saddles, new vertices between them).
//
// Run:  ./run bench --benchmark_filter=Geodesic
// Memory: the counter `peak_MB` is the growth of the process's peak resident set during one
// iteration (peak reset through /proc/self/clear_refs, freed memory returned with malloc_trim).
// CGAL's exact package is only run up to bunny00 unless IM_BENCH_ALL=1 (it needs minutes and
// many GB beyond; see benchmark/README.md for the anchors).
#include <CGAL/Isophotic_metric/Geodesics/Geodesic_solver.h>
#include <CGAL/Isophotic_metric/Geodesics/compute_geodesic_distances.h>
#include <CGAL/Isophotic_metric/Geodesics/internal/Radix_heap.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Heat_method_3/Surface_mesh_geodesic_distances_3.h>
#include <CGAL/Polygon_mesh_processing/refine.h>
#include <CGAL/Subdivision_method_3/subdivision_methods_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <benchmark/benchmark.h>

#include <malloc.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace IM = CGAL::Isophotic_metric;
typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
typedef boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;

namespace {

// Meshes by name, loaded (and subdivided or refined) once: "<file>_loop<n>" is Loop-subdivided n
// times, "<file>_refine<d>" refined by PMP::refine with density_control_factor d.
const Mesh& mesh(const std::string& name)
{
  static std::map<std::string, std::unique_ptr<Mesh>> cache;
  std::unique_ptr<Mesh>& m = cache[name];
  if(!m)
  {
    m = std::make_unique<Mesh>();
    const std::size_t loop = name.find("_loop"), refine = name.find("_refine"), sqrt3 = name.find("_sqrt3");
    const std::string file = name.substr(0, std::min({loop, refine, sqrt3}));
    if(!CGAL::IO::read_polygon_mesh(CGAL::data_file_path("meshes/" + file + ".off"), *m))
      throw std::runtime_error("cannot read " + file);
    if(loop != std::string::npos)
      CGAL::Subdivision_method_3::Loop_subdivision(*m, CGAL::parameters::number_of_iterations(std::stoi(name.substr(loop + 5))));
    if(sqrt3 != std::string::npos) // then one Sqrt3 step: past 250k faces, triangles no longer regular
      CGAL::Subdivision_method_3::Sqrt3_subdivision(*m, CGAL::parameters::number_of_iterations(1));
    if(refine != std::string::npos)
    {
      std::vector<boost::graph_traits<Mesh>::face_descriptor> new_faces;
      std::vector<vertex_descriptor> new_vertices;
      CGAL::Polygon_mesh_processing::refine(*m, faces(*m), std::back_inserter(new_faces), std::back_inserter(new_vertices),
                                            CGAL::parameters::density_control_factor(std::stod(name.substr(refine + 7))));
    }
  }
  return *m;
}

long resident_kb(const char* field)
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while(std::getline(status, line))
    if(line.rfind(field, 0) == 0)
      return std::atol(line.c_str() + std::string(field).size());
  return 0;
}

// Measures the peak memory growth of one call, timing only the call (resetting the peak walks the
// process's pages: milliseconds, more than a small bounded propagation takes).
template <class F>
double peak_megabytes(benchmark::State& state, F&& f)
{
  state.PauseTiming();
  malloc_trim(0);
  { std::ofstream("/proc/self/clear_refs") << "5"; } // reset the peak resident set
  const long before = resident_kb("VmRSS:");
  state.ResumeTiming();
  f();
  state.PauseTiming();
  const double peak = (resident_kb("VmHWM:") - before) / 1024.0;
  state.ResumeTiming();
  return peak;
}

const char* mesh_names[] = {"fandisk", "armadillo", "bunny00", "fandisk_loop2", "fandisk_loop3", "elephant_loop2",
                            "elephant_loop2_sqrt3", "refined_elephant", "bunny00_refine3"};

void report(benchmark::State& state, const Mesh& m, double peak)
{
  state.counters["faces"] = static_cast<double>(num_faces(m));
  state.counters["peak_MB"] = peak;
}

// This package, distance-only mode: what compute_geodesic_distances() runs (set-up, propagation,
// distances copied out), with the solver kept for its window counts.
void Geodesic_ours(benchmark::State& state, double w, double w_prime)
{
  const Mesh& m = mesh(mesh_names[state.range(0)]);
  std::vector<double> d(num_vertices(m));
  auto map = CGAL::make_property_map(d);
  double peak = 0;
  std::size_t created = 0, propagated = 0;
  for(auto _ : state)
    peak = peak_megabytes(state, [&] {
      IM::Geodesic_solver<Mesh> solver(m, IM::parameters::euclidean_weight(w).isophotic_weight(w_prime).store_windows(false));
      solver.add_source(vertex_descriptor(0));
      solver.propagate();
      solver.copy_distances(map);
      created = solver.number_of_windows_created();
      propagated = solver.number_of_windows_propagated();
    });
  report(state, m, peak);
  state.counters["windows_created"] = static_cast<double>(created);
  state.counters["windows_propagated"] = static_cast<double>(propagated);
}

// The propagation alone (the mesh prepared once, outside the timing), distance-only mode, serial
// (threads 0) or in bands on 1, 2, ... threads (propagation_threads). Timed as wall clock with
// the CPU time of the whole process.
void Geodesic_ours_parallel(benchmark::State& state, double w, double w_prime)
{
  const Mesh& m = mesh(mesh_names[state.range(0)]);
  const IM::Metric_mesh<Mesh> metric(m, IM::parameters::euclidean_weight(w).isophotic_weight(w_prime));
  const int threads = static_cast<int>(state.range(1));
  std::size_t created = 0, propagated = 0;
  for(auto _ : state)
  {
    IM::Geodesic_solver<Mesh> solver(metric, IM::parameters::store_windows(false).propagation_threads(threads));
    solver.add_source(vertex_descriptor(0));
    solver.propagate();
    created = solver.number_of_windows_created();
    propagated = solver.number_of_windows_propagated();
    benchmark::DoNotOptimize(solver.distance(vertex_descriptor(1)));
  }
  state.counters["faces"] = static_cast<double>(num_faces(m));
  state.counters["windows_created"] = static_cast<double>(created);
  state.counters["windows_propagated"] = static_cast<double>(propagated);
}

// This package with windows kept for point queries and paths.
void Geodesic_ours_with_paths(benchmark::State& state)
{
  const Mesh& m = mesh(mesh_names[state.range(0)]);
  double peak = 0;
  std::size_t windows = 0, stored = 0;
  for(auto _ : state)
    peak = peak_megabytes(state, [&] {
      IM::Geodesic_solver<Mesh> solver(m, IM::parameters::isophotic_weight(0).store_windows(true));
      solver.add_source(vertex_descriptor(0));
      solver.propagate();
      windows = solver.number_of_windows_propagated();
      stored = solver.number_of_windows_stored();
      benchmark::DoNotOptimize(solver.distance(vertex_descriptor(1)));
    });
  report(state, m, peak);
  state.counters["windows"] = static_cast<double>(windows);
  state.counters["stored"] = static_cast<double>(stored);
}

// Distance-bounded propagation: the cost must follow the explored area. The bound is the distance
// reaching the given per-mille of the vertices (taken from a full run done once, outside timing).
// The solver is prepared once (linear in the mesh size, reported as `setup_ms`) and reused, as a
// user running many bounded queries does; the timing covers clear_sources + propagate(bound).
void Geodesic_ours_bounded(benchmark::State& state)
{
  const Mesh& m = mesh(mesh_names[state.range(0)]);
  const double per_mille = static_cast<double>(state.range(1));
  const auto start = std::chrono::steady_clock::now();
  IM::Geodesic_solver<Mesh> solver(m, IM::parameters::isophotic_weight(0).store_windows(false));
  const double setup_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  solver.add_source(vertex_descriptor(0));
  solver.propagate();
  std::vector<double> sorted;
  for(vertex_descriptor v : vertices(m))
    sorted.push_back(solver.distance(v));
  std::sort(sorted.begin(), sorted.end());
  const double bound = sorted[std::min(sorted.size() - 1, static_cast<std::size_t>(sorted.size() * per_mille / 1000))];
  solver.clear_sources(); // forgetting the full run costs the whole mesh: not part of a bounded query
  double peak = 0;
  std::size_t windows = 0;
  for(auto _ : state)
    peak = peak_megabytes(state, [&] {
      solver.clear_sources();
      solver.add_source(vertex_descriptor(0));
      solver.propagate(bound);
      windows = solver.number_of_windows_propagated();
    });
  report(state, m, peak);
  state.counters["explored_permille"] = per_mille;
  state.counters["setup_ms"] = setup_ms;
  state.counters["windows"] = static_cast<double>(windows);
}

void Geodesic_cgal_shortest_path(benchmark::State& state)
{
  if(state.range(0) > 2 && !std::getenv("IM_BENCH_ALL"))
  {
    state.SkipWithError("skipped (minutes, many GB); set IM_BENCH_ALL=1");
    return;
  }
  const Mesh& m = mesh(mesh_names[state.range(0)]);
  typedef CGAL::Surface_mesh_shortest_path<CGAL::Surface_mesh_shortest_path_traits<K, Mesh>> Shortest_path;
  double peak = 0;
  for(auto _ : state)
    peak = peak_megabytes(state, [&] {
      Shortest_path shortest_path(m);
      shortest_path.add_source_point(vertex_descriptor(0));
      shortest_path.build_sequence_tree();
      double sum = 0;
      for(vertex_descriptor v : vertices(m))
        sum += shortest_path.shortest_distance_to_source_points(v).first;
      benchmark::DoNotOptimize(sum);
    });
  report(state, m, peak);
}

// Approximate; includes its precomputation (a sparse factorisation), as a one-shot user pays it.
void Geodesic_cgal_heat_method(benchmark::State& state)
{
  const Mesh& m = mesh(mesh_names[state.range(0)]);
  std::vector<double> d(num_vertices(m));
  double peak = 0;
  for(auto _ : state)
    peak = peak_megabytes(state, [&] {
      CGAL::Heat_method_3::Surface_mesh_geodesic_distances_3<Mesh> heat(m);
      heat.add_source(vertex_descriptor(0));
      heat.estimate_geodesic_distances(CGAL::make_property_map(d));
    });
  report(state, m, peak);
}

// The propagation's queue alone, on a workload of its shape: each entry taken out puts two back a
// little farther (keys from a fixed table of steps), 2^20 times, then the queue drains; up to half
// a million entries wait at once. With range(0) = 1, each removal is preceded by a look at the
// smallest key, as a distance-bounded propagation does.
void Radix_heap_operations(benchmark::State& state)
{
  struct Entry
  {
    double key;
    std::uint32_t index;
  };
  const bool peek = state.range(0) != 0;
  std::mt19937_64 random(1);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<double> steps(1 << 16);
  for(double& s : steps)
    s = uniform(random) * uniform(random);
  IM::internal::Radix_heap<Entry> heap;
  std::size_t operations = 0;
  for(auto _ : state)
  {
    heap.clear();
    std::size_t pushed = 0, next_step = 0;
    double smallest_seen = 0;
    for(std::uint32_t i = 0; i < 1000; ++i, ++pushed)
      heap.push({steps[next_step++], i});
    while(!heap.empty())
    {
      if(peek)
        smallest_seen += heap.min_key();
      const Entry e = heap.top();
      heap.pop();
      for(int child = 0; child < 2 && pushed < (std::size_t(1) << 20); ++child, ++pushed)
        heap.push({e.key + steps[next_step++ % steps.size()], e.index});
      ++operations;
    }
    benchmark::DoNotOptimize(smallest_seen);
  }
  state.counters["pops_per_s"] = benchmark::Counter(static_cast<double>(operations), benchmark::Counter::kIsRate);
}

// Median of 3 runs; the 829k-face mesh (index 4) is registered separately with one run.
void meshes(benchmark::internal::Benchmark* b)
{
  for(int i = 0; i < 4; ++i)
    b->Arg(i);
  b->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(3)->ReportAggregatesOnly(true);
}
// Stored windows side by side with distances only: a scan (bunny00), fandisk Loop x2 (207k), elephant
// Loop x2 (89k), that elephant after one more Sqrt3 step (267k) and bunny00 refined (261k).
void stored_window_meshes(benchmark::internal::Benchmark* b)
{
  for(int i : {2, 3, 5, 6, 8})
    b->Arg(i);
  b->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(3)->ReportAggregatesOnly(true);
}
void largest_mesh(benchmark::internal::Benchmark* b)
{
  b->Arg(4)->Unit(benchmark::kMillisecond)->Iterations(1);
}
// The scanned meshes (refined_elephant, bunny00 refined to 261k faces), median of 3.
void scans(benchmark::internal::Benchmark* b)
{
  b->Arg(7)->Arg(8)->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(3)->ReportAggregatesOnly(true);
}

} // namespace

BENCHMARK_CAPTURE(Geodesic_ours, euclidean, 1.0, 0.0)->Apply(meshes);
BENCHMARK_CAPTURE(Geodesic_ours, isophotic_w0_5, 0.5, 0.5)->Apply(meshes);
BENCHMARK(Geodesic_ours_with_paths)->Apply(meshes);
BENCHMARK(Geodesic_cgal_shortest_path)->Apply(meshes);
BENCHMARK(Geodesic_cgal_heat_method)->Apply(meshes);
BENCHMARK_CAPTURE(Geodesic_ours, euclidean, 1.0, 0.0)->Apply(scans);
BENCHMARK_CAPTURE(Geodesic_ours, isophotic_w0_5, 0.5, 0.5)->Apply(scans);
BENCHMARK(Geodesic_cgal_shortest_path)->Apply(scans);
BENCHMARK(Geodesic_cgal_heat_method)->Apply(scans);
BENCHMARK_CAPTURE(Geodesic_ours, euclidean, 1.0, 0.0)->Apply(largest_mesh);
BENCHMARK_CAPTURE(Geodesic_ours, isophotic_w0_5, 0.5, 0.5)->Apply(largest_mesh);
BENCHMARK(Geodesic_cgal_heat_method)->Apply(largest_mesh);
BENCHMARK_CAPTURE(Geodesic_ours, stored_windows_distances_only, 1.0, 0.0)->Apply(stored_window_meshes);
BENCHMARK(Geodesic_ours_with_paths)->Name("Geodesic_ours_stored_windows")->Apply(stored_window_meshes);
// fandisk Loop x2 (207k faces) and bunny00 refined (261k) x threads (0: serial).
void parallel_meshes(benchmark::internal::Benchmark* b)
{
  b->ArgsProduct({{3, 8}, {0, 1, 2}})->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(3)->ReportAggregatesOnly(true);
  b->MeasureProcessCPUTime()->UseRealTime();
}
BENCHMARK_CAPTURE(Geodesic_ours_parallel, euclidean, 1.0, 0.0)->Apply(parallel_meshes);
BENCHMARK_CAPTURE(Geodesic_ours_parallel, isophotic_w0_5, 0.5, 0.5)->Apply(parallel_meshes);
BENCHMARK(Radix_heap_operations)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(Geodesic_ours_bounded)
  ->ArgsProduct({{3, 4}, {1, 10, 100, 1000}})
  ->Unit(benchmark::kMillisecond)
  ->Iterations(1)
  ->Repetitions(3)
  ->ReportAggregatesOnly(true);

BENCHMARK_MAIN();
