// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Morphology benchmarks, metric w = w' = 0.5 with L = bounding-box diagonal:
//  - dilation of one face of fandisk Loop-subdivided 3 times (829k faces) by radii chosen so that
//    the result covers about 0.1 %, 1 % and 10 % of the mesh's AREA (time must follow the band, not
//    the mesh);
//  - CGAL's expand_face_selection (k-ring) from the same face, k chosen so that the k-ring adds about
//    as many faces as each dilation;
//  - the per-face neighbourhood batch (all_face_neighborhoods) on fandisk (12.9k faces), serial and
//    parallel;
//  - the set-up of one-shot calls on armadillo (52k faces) beside one pass computing its edge lengths
//    (BM_setup_*, BM_one_shot_*; run them alone with --benchmark_filter='setup|one_shot');
//  - the same against the in-memory edge-length pass on armadillo, fandisk and a 301k-face mesh
//    (BM_setup_vs_reference, see there).
// Meshes, solvers, radii and k are prepared once, outside the timings; the set-up prints its steps
// with their times to stderr.
//
// Run: cmake --build build --target bench_morphology && build/benchmark/Isophotic_metric/bench_morphology
// Counters: area_% = share of the mesh area selected after the operation (seed included);
// per_face = time per added face; reached_area_% = share of the area the dilation's bounded
// propagation reached (it runs to about twice the radius), windows = windows it propagated;
// clear_ms = forgetting the previous run (Face_band_solver::clear_sources, done untimed before each
// call); peak_MB = growth of the peak resident set during the call, process_MB = whole-process peak
// (see peak_memory.h).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/boost/graph/selection.h>
#include <CGAL/subdivision_method_3.h>

#include <CGAL/Isophotic_metric.h>

#include "peak_memory.h"

#include <benchmark/benchmark.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/task_arena.h>
#endif

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <ctime>
#include <iostream>
#include <map>
#include <memory>
#include <stdexcept>
#include <vector>

namespace {

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
typedef boost::graph_traits<Mesh>::face_descriptor face_descriptor;
namespace IM = CGAL::Isophotic_metric;
namespace PMP = CGAL::Polygon_mesh_processing;

const double w = 0.5, w_prime = 0.5;

struct Stopwatch
{
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  double lap() // seconds since the previous lap
  {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - start).count();
    start = now;
    return s;
  }
};

// fandisk Loop-subdivided `levels` times, with a band solver for the metric (windows stored: the
// dilation's exact point queries need them). Built once per level.
struct Prepared
{
  Mesh mesh;
  double L = 0;
  std::unique_ptr<IM::Face_band_solver<Mesh>> band;
};

Prepared& fandisk(int levels)
{
  static std::map<int, std::unique_ptr<Prepared>> cache;
  std::unique_ptr<Prepared>& p = cache[levels];
  if(!p)
  {
    Stopwatch t;
    p = std::make_unique<Prepared>();
    CGAL::IO::read_polygon_mesh(CGAL::data_file_path("meshes/fandisk.off"), p->mesh);
    CGAL::Subdivision_method_3::Loop_subdivision(p->mesh, CGAL::parameters::number_of_iterations(levels));
    const double subdivision = t.lap();
    p->L = IM::suggested_weight_length_scale(p->mesh);
    p->band = std::make_unique<IM::Face_band_solver<Mesh>>(
      p->mesh, IM::parameters::euclidean_weight(w).isophotic_weight(w_prime).weight_length_scale(p->L).store_windows(true));
    std::cerr << "set-up: fandisk Loop x" << levels << ", " << num_faces(p->mesh) << " faces: subdivision "
              << subdivision << " s, band solver " << t.lap() << " s" << std::endl;
  }
  return *p;
}

// Everything the dilation and k-ring cases share: the seed face, a selection map, the radii for the
// area shares, the faces each dilation adds and the k whose k-ring adds about as many.
struct Dilation_cases
{
  static constexpr double area_share[3] = {0.001, 0.01, 0.1};
  Prepared& data = fandisk(3);
  IM::Face_band_solver<Mesh>& band = *data.band;
  const std::vector<face_descriptor> seed{face_descriptor(1000)};
  Mesh::Property_map<face_descriptor, bool> selected = data.mesh.add_property_map<face_descriptor, bool>("f:bench", false).first;
  std::vector<double> area; // per face index of the prepared mesh
  double total_area = 0;
  double radius[3];
  std::size_t faces_added[3];
  unsigned k[3];

  Dilation_cases()
  {
    Stopwatch t;
    area.resize(num_faces(data.mesh));
    for(face_descriptor f : faces(data.mesh))
      area[band.metric_mesh().face_index(f)] = PMP::face_area(f, data.mesh);
    for(double a : area)
      total_area += a;
    choose_radii();
    std::cerr << "set-up: radii " << radius[0] << " " << radius[1] << " " << radius[2] << " (" << t.lap() << " s)";
    restart({});
    for(int i = 0; i < 3; ++i) // also warms the solver up
    {
      const std::vector<face_descriptor> added = dilate(radius[i]);
      faces_added[i] = added.size();
      restart(added);
    }
    std::cerr << ", dilations " << faces_added[0] << " " << faces_added[1] << " " << faces_added[2] << " faces ("
              << t.lap() << " s)";
    choose_k();
    std::cerr << ", k " << k[0] << " " << k[1] << " " << k[2] << " (" << t.lap() << " s)" << std::endl;
  }

  // One bounded propagation from the seed, extended 1.5x at a time from the radius of a flat disc
  // until the faces it reaches cover the largest share. A face counts from its nearest corner
  // (exact once within the bound): about when the dilation takes it in.
  void choose_radii()
  {
    band.clear_sources();
    band.add_source_region(seed);
    std::vector<std::pair<double, double>> reached; // (nearest corner, area)
    double covered = 0;
    for(double bound = std::sqrt(w * area_share[2] * total_area / M_PI); covered < area_share[2] * total_area; bound *= 1.5)
    {
      band.propagate_to(bound);
      reached.clear();
      covered = 0;
      for(std::uint32_t f = 0; f < band.metric_mesh().number_of_faces(); ++f)
      {
        const auto c = band.metric_mesh().corners(f);
        const double d = std::min({vertex_distance(c[0]), vertex_distance(c[1]), vertex_distance(c[2])});
        if(d <= bound)
        {
          reached.push_back({d, area[f]});
          covered += area[f];
        }
      }
    }
    std::sort(reached.begin(), reached.end());
    double sum = 0;
    int i = 0;
    for(const auto& r : reached)
    {
      sum += r.second;
      while(i < 3 && sum >= area_share[i] * total_area)
        radius[i++] = r.first;
    }
    band.clear_sources();
  }

  // k-rings grown one ring at a time from the seed; k[i] is the ring count closest to faces_added[i].
  void choose_k()
  {
    std::vector<face_descriptor> front = seed, all;
    std::size_t previous = 0;
    for(unsigned ring = 1, i = 0; i < 3; ++ring)
    {
      std::vector<face_descriptor> added;
      CGAL::expand_face_selection(front, data.mesh, 1, selected, std::back_inserter(added));
      if(added.empty())
        throw std::runtime_error("the k-ring covers the mesh before reaching a dilation's size");
      previous = all.size();
      all.insert(all.end(), added.begin(), added.end());
      for(; i < 3 && all.size() >= faces_added[i]; ++i)
        k[i] = (all.size() - faces_added[i] <= faces_added[i] - previous) ? ring : ring - 1;
      front.swap(added);
    }
    restart(all);
  }

  // Back to the seed alone, after an operation that added `added` to it.
  void restart(const std::vector<face_descriptor>& added)
  {
    for(face_descriptor f : added)
      put(selected, f, false);
    put(selected, seed[0], true);
  }

  std::vector<face_descriptor> dilate(double r)
  {
    std::vector<face_descriptor> out;
    IM::dilate_face_selection(seed, data.mesh, r, selected, std::back_inserter(out), IM::parameters::face_band_solver(&band));
    return out;
  }

  double area_percent(const std::vector<face_descriptor>& added) const
  {
    double a = area[band.metric_mesh().face_index(seed[0])];
    for(face_descriptor f : added)
      a += area[band.metric_mesh().face_index(f)];
    return 100 * a / total_area;
  }

  double vertex_distance(std::uint32_t v) const { return band.distance(band.metric_mesh().vertex(v)); }

  // Share of the area the last propagation reached (faces with a corner at finite distance).
  double reached_area_percent() const
  {
    double a = 0;
    for(std::uint32_t f = 0; f < band.metric_mesh().number_of_faces(); ++f)
      for(std::uint32_t v : band.metric_mesh().corners(f))
        if(std::isfinite(vertex_distance(v)))
        {
          a += area[f];
          break;
        }
    return 100 * a / total_area;
  }
};

Dilation_cases& cases()
{
  static Dilation_cases c;
  return c;
}

void report(benchmark::State& state, const Dilation_cases& c, const std::vector<face_descriptor>& added,
            const bench::Peak& peak)
{
  state.counters["faces_added"] = double(added.size());
  state.counters["area_%"] = c.area_percent(added);
  state.counters["per_face"] = benchmark::Counter(double(added.size()), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["peak_MB"] = peak.growth_MB;
  state.counters["process_MB"] = peak.process_MB;
}

// Dilation of the seed by radius[range(0)].
void BM_dilation_829k(benchmark::State& state)
{
  Dilation_cases& c = cases();
  const double r = c.radius[state.range(0)];
  // One untimed run first: after a larger run, freeing its windows leaves the allocator's free lists
  // long, and the first run after it would pay for sorting them (+0.5 s after a 10 % dilation).
  std::vector<face_descriptor> added = c.dilate(r);
  bench::Peak peak;
  double clear_ms = 0;
  for(auto _ : state)
  {
    state.PauseTiming();
    c.restart(added);
    Stopwatch t;
    c.band.clear_sources(); // forgetting the previous run (what it touched), reported apart
    clear_ms = 1000 * t.lap();
    state.ResumeTiming();
    peak = bench::measure_peak(state, [&] { added = c.dilate(r); });
  }
  state.counters["reached_area_%"] = c.reached_area_percent();
  state.counters["windows"] = double(c.band.geodesic_solver().number_of_windows_propagated());
  c.band.clear_sources(); // not to leave this run's windows to the next benchmark
  c.restart(added);
  report(state, c, added, peak);
  state.counters["radius"] = r;
  state.counters["clear_ms"] = clear_ms;
}
BENCHMARK(BM_dilation_829k)->DenseRange(0, 2)->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(3)
  ->ReportAggregatesOnly(true);

// CGAL's k-ring from the seed, k[range(0)]: about as many faces as the dilation of the same index.
void BM_k_ring_829k(benchmark::State& state)
{
  Dilation_cases& c = cases();
  std::vector<face_descriptor> added;
  bench::Peak peak;
  for(auto _ : state)
  {
    state.PauseTiming();
    c.restart(added);
    added.clear();
    state.ResumeTiming();
    peak = bench::measure_peak(state, [&] {
      CGAL::expand_face_selection(c.seed, c.data.mesh, c.k[state.range(0)], c.selected, std::back_inserter(added));
    });
  }
  report(state, c, added, peak);
  c.restart(added);
  state.counters["k"] = c.k[state.range(0)];
}
BENCHMARK(BM_k_ring_829k)->DenseRange(0, 2)->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(3)
  ->ReportAggregatesOnly(true);

// Neighbourhood of radius 0.01 L of every face of fandisk; range(0): parallel (TBB) or not.
void BM_neighborhood_batch(benchmark::State& state)
{
  Prepared& data = fandisk(0);
  std::size_t total = 0;
  bench::Peak peak;
  for(auto _ : state)
    peak = bench::measure_peak(state, [&] {
      auto n = get(CGAL::dynamic_face_property_t<std::vector<IM::Neighborhood_face<face_descriptor>>>(), data.mesh);
      const auto np = IM::parameters::face_band_solver(data.band.get());
      if(state.range(0) != 0)
        IM::all_face_neighborhoods<CGAL::Parallel_if_available_tag>(data.mesh, 0.01 * data.L, n, np);
      else
        IM::all_face_neighborhoods<CGAL::Sequential_tag>(data.mesh, 0.01 * data.L, n, np);
      total = 0;
      for(auto f : faces(data.mesh))
        total += get(n, f).size();
    });
  state.counters["mean_neighbours"] = double(total) / double(num_faces(data.mesh));
  state.counters["peak_MB"] = peak.growth_MB;
}
BENCHMARK(BM_neighborhood_batch)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1)
  ->Repetitions(3)->ReportAggregatesOnly(true);

// Set-up of one-shot calls on armadillo (52k faces), side by side. The floor: one pass over the mesh
// that reads the corners of every face and computes its three edge lengths. Then the prepared mesh
// (validation, lift, edge lengths, numbering: the whole set-up of a solver), each solver's
// construction, and whole one-shot calls (set-up included) that dilate one face and find one face's
// neighbourhood by 0.01 L (a few dozen faces).
struct Armadillo
{
  Mesh mesh;
  double L = 0;
  Armadillo()
  {
    CGAL::IO::read_polygon_mesh(CGAL::data_file_path("meshes/armadillo.off"), mesh);
    L = IM::suggested_weight_length_scale(mesh);
  }
  auto metric() const { return IM::parameters::euclidean_weight(w).isophotic_weight(w_prime).weight_length_scale(L); }
};

const Armadillo& armadillo()
{
  static const Armadillo a;
  return a;
}

// The length of every halfedge of `m`, face after face, into `length` (3 per face).
void halfedge_length_pass(const Mesh& m, std::vector<double>& length)
{
  length.resize(3 * num_faces(m));
  std::size_t i = 0;
  for(face_descriptor f : faces(m))
    for(auto h : CGAL::halfedges_around_face(halfedge(f, m), m))
      length[i++] = std::sqrt(CGAL::squared_distance(m.point(source(h, m)), m.point(target(h, m))));
  benchmark::DoNotOptimize(length.data());
  benchmark::ClobberMemory();
}

void BM_setup_edge_length_pass(benchmark::State& state)
{
  const Mesh& m = armadillo().mesh;
  std::vector<double> length;
  for(auto _ : state)
    halfedge_length_pass(m, length);
}
BENCHMARK(BM_setup_edge_length_pass)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);

// The same pass after reading the mesh from its file (what a one-shot program does first).
void BM_setup_read_and_edge_length_pass(benchmark::State& state)
{
  std::vector<double> length;
  for(auto _ : state)
  {
    Mesh m;
    CGAL::IO::read_polygon_mesh(CGAL::data_file_path("meshes/armadillo.off"), m);
    halfedge_length_pass(m, length);
  }
}
BENCHMARK(BM_setup_read_and_edge_length_pass)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);

void BM_setup_metric_mesh(benchmark::State& state)
{
  const Armadillo& a = armadillo();
  for(auto _ : state)
  {
    IM::Metric_mesh<Mesh> prepared(a.mesh, a.metric());
    benchmark::DoNotOptimize(&prepared);
  }
}
BENCHMARK(BM_setup_metric_mesh)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);

void BM_setup_geodesic_solver(benchmark::State& state)
{
  const Armadillo& a = armadillo();
  for(auto _ : state)
  {
    IM::Geodesic_solver<Mesh> solver(a.mesh, a.metric());
    benchmark::DoNotOptimize(&solver);
  }
}
BENCHMARK(BM_setup_geodesic_solver)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);

void BM_setup_face_band_solver(benchmark::State& state)
{
  const Armadillo& a = armadillo();
  for(auto _ : state)
  {
    IM::Face_band_solver<Mesh> band(a.mesh, a.metric());
    benchmark::DoNotOptimize(&band);
  }
}
BENCHMARK(BM_setup_face_band_solver)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);

// range(0) = 1: the one-shot call on an already prepared mesh (named parameter metric_mesh), the
// cost of the operation itself.
void BM_one_shot_dilation(benchmark::State& state)
{
  const Armadillo& a = armadillo();
  const IM::Metric_mesh<Mesh> prepared(a.mesh, a.metric());
  const std::vector<face_descriptor> seed{face_descriptor(1000)};
  auto selected = get(CGAL::dynamic_face_property_t<bool>(), a.mesh);
  std::vector<face_descriptor> added;
  for(auto _ : state)
  {
    state.PauseTiming();
    for(face_descriptor f : faces(a.mesh))
      put(selected, f, false);
    put(selected, seed[0], true);
    added.clear();
    state.ResumeTiming();
    if(state.range(0) == 0)
      IM::dilate_face_selection(seed, a.mesh, 0.01 * a.L, selected, std::back_inserter(added), a.metric());
    else
      IM::dilate_face_selection(seed, a.mesh, 0.01 * a.L, selected, std::back_inserter(added), IM::parameters::metric_mesh(prepared));
  }
  state.counters["faces_added"] = double(added.size());
}
BENCHMARK(BM_one_shot_dilation)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);

void BM_one_shot_neighborhood(benchmark::State& state)
{
  const Armadillo& a = armadillo();
  const IM::Metric_mesh<Mesh> prepared(a.mesh, a.metric());
  std::vector<IM::Neighborhood_face<face_descriptor>> n;
  for(auto _ : state)
  {
    n.clear();
    if(state.range(0) == 0)
      IM::geodesic_neighborhood(face_descriptor(1000), a.mesh, 0.01 * a.L, std::back_inserter(n), a.metric());
    else
      IM::geodesic_neighborhood(face_descriptor(1000), a.mesh, 0.01 * a.L, std::back_inserter(n), IM::parameters::metric_mesh(prepared));
  }
  state.counters["faces"] = double(n.size());
}
BENCHMARK(BM_one_shot_neighborhood)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);

// Set-up of one-shot calls against the reference pass, on three meshes side by side: range(0) = mesh
// (0 armadillo 52k faces, 1 fandisk 12.9k, 2 bunny00 Loop-subdivided once, 301k), range(1) = case
// (0 Metric_mesh Euclidean, 1 Metric_mesh isophotic, 2 one-shot dilation of one face by 0.01 L,
// 3 one-shot neighbourhood of one face by 0.01 L, 4 one-shot compute_geodesic_distances from one
// vertex with max_distance 0.01 L; all single calls from a bare mesh, isophotic with w = w' = 0.5;
// then the floor of the set-up's unavoidable passes, each alone: 5 validate_triangle_mesh, 6 the
// default vertex normals of every vertex, 7 the lifted length of every edge from lifted points
// computed beforehand).
// The reference pass: in memory, single thread, every edge's two points read and its length written
// into a vector. It runs untimed before every iteration of every case, so each case is compared
// with a reference measured at the same moment (the machine's load varies); counters x_cpu and
// x_wall = case / reference, process CPU time (all threads) and wall time.
struct Setup_mesh
{
  Mesh mesh;
  double L = 0;
  face_descriptor face;
  boost::graph_traits<Mesh>::vertex_descriptor vertex;
};

const Setup_mesh& setup_mesh(int i)
{
  static std::map<int, std::unique_ptr<Setup_mesh>> cache;
  std::unique_ptr<Setup_mesh>& m = cache[i];
  if(!m)
  {
    m = std::make_unique<Setup_mesh>();
    const char* name[3] = {"meshes/armadillo.off", "meshes/fandisk.off", "meshes/bunny00.off"};
    CGAL::IO::read_polygon_mesh(CGAL::data_file_path(name[i]), m->mesh);
    if(i == 2)
      CGAL::Subdivision_method_3::Loop_subdivision(m->mesh, CGAL::parameters::number_of_iterations(1));
    m->L = IM::suggested_weight_length_scale(m->mesh);
    m->face = face_descriptor(static_cast<std::uint32_t>(num_faces(m->mesh) / 3));
    m->vertex = target(halfedge(m->face, m->mesh), m->mesh);
  }
  return *m;
}

double process_cpu_seconds()
{
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// (time of the call in process CPU seconds, in wall seconds)
template <class Call>
std::pair<double, double> timed(const Call& call)
{
  const double cpu = process_cpu_seconds();
  Stopwatch wall;
  call();
  const double wall_s = wall.lap();
  return {process_cpu_seconds() - cpu, wall_s};
}

void reference_pass(const Mesh& m, std::vector<double>& length)
{
  length.resize(num_edges(m));
  std::size_t i = 0;
  for(auto e : edges(m))
  {
    const auto h = halfedge(e, m);
    length[i++] = std::sqrt(CGAL::squared_distance(m.point(source(h, m)), m.point(target(h, m))));
  }
  benchmark::DoNotOptimize(length.data());
  benchmark::ClobberMemory();
}

void BM_setup_vs_reference(benchmark::State& state)
{
  const Setup_mesh& s = setup_mesh(static_cast<int>(state.range(0)));
  const int which = static_cast<int>(state.range(1));
  const auto isophotic = IM::parameters::euclidean_weight(w).isophotic_weight(w_prime).weight_length_scale(s.L);
  const double r = 0.01 * s.L;
  auto selected = get(CGAL::dynamic_face_property_t<bool>(), s.mesh);
  auto distance = get(CGAL::dynamic_vertex_property_t<double>(), s.mesh);
  std::vector<double> length;
  std::vector<face_descriptor> added;
  std::vector<IM::Neighborhood_face<face_descriptor>> neighbours;
  std::vector<std::array<double, 3>> normals(num_vertices(s.mesh));
  auto lifted = get(CGAL::dynamic_vertex_property_t<IM::Lifted_point>(), s.mesh);
  if(which == 7)
    IM::compute_lifted_embedding(s.mesh, lifted, isophotic);
  double reference_cpu = 0, reference_wall = 0, case_cpu = 0, case_wall = 0;
  std::size_t output = 0;
  for(auto _ : state)
  {
    state.PauseTiming();
    const auto ref = timed([&] { reference_pass(s.mesh, length); });
    reference_cpu += ref.first;
    reference_wall += ref.second;
    for(face_descriptor f : faces(s.mesh))
      put(selected, f, false);
    put(selected, s.face, true);
    added.clear();
    neighbours.clear();
    state.ResumeTiming();
    const auto t = timed([&] {
      switch(which)
      {
      case 0:
      {
        IM::Metric_mesh<Mesh> prepared(s.mesh, IM::parameters::euclidean_weight(1).isophotic_weight(0));
        output = prepared.number_of_faces();
        break;
      }
      case 1:
      {
        IM::Metric_mesh<Mesh> prepared(s.mesh, isophotic);
        output = prepared.number_of_faces();
        break;
      }
      case 2:
        IM::dilate_face_selection(std::vector<face_descriptor>{s.face}, s.mesh, r, selected, std::back_inserter(added), isophotic);
        output = added.size();
        break;
      case 3:
        IM::geodesic_neighborhood(s.face, s.mesh, r, std::back_inserter(neighbours), isophotic);
        output = neighbours.size();
        break;
      case 5:
        IM::validate_triangle_mesh(s.mesh);
        output = num_faces(s.mesh);
        break;
      case 6:
      {
        std::size_t i = 0;
        for(auto v : vertices(s.mesh))
          normals[i++] = IM::internal::sphere_exact_vertex_normal(v, s.mesh, s.mesh.points());
        benchmark::DoNotOptimize(normals.data());
        output = i;
        break;
      }
      case 7:
      {
        std::size_t i = 0;
        for(auto e : edges(s.mesh))
          length[i++] = IM::internal::distance(get(lifted, source(e, s.mesh)), get(lifted, target(e, s.mesh)));
        benchmark::DoNotOptimize(length.data());
        output = i;
        break;
      }
      default:
      {
        const std::vector<boost::graph_traits<Mesh>::vertex_descriptor> source{s.vertex};
        IM::compute_geodesic_distances(source, s.mesh, distance, isophotic.max_distance(r));
        output = 0;
        for(auto v : vertices(s.mesh))
          output += std::isfinite(get(distance, v)) ? 1 : 0;
      }
      }
    });
    case_cpu += t.first;
    case_wall += t.second;
  }
  state.counters["faces"] = double(num_faces(s.mesh));
  state.counters["output"] = double(output); // faces built / added / in the neighbourhood, vertices reached
  state.counters["reference_ms"] = 1000 * reference_cpu / double(state.iterations());
  state.counters["x_cpu"] = case_cpu / reference_cpu;
  state.counters["x_wall"] = case_wall / reference_wall;
}
BENCHMARK(BM_setup_vs_reference)->ArgsProduct({{0, 1, 2}, {0, 1, 2, 3, 4, 5, 6, 7}})->Unit(benchmark::kMillisecond)
  ->Repetitions(3)->ReportAggregatesOnly(true);

// The cost of the robust vertex normals (estimate_vertex_normals at two mean edges; armadillo,
// fandisk: one run each, seconds per call on armadillo) by
// estimator: range(1) = 0 the default (guidance chosen per face), 1 the Gaussian guidance for all
// faces (use_patch_guidance(false), the default before), 2 the patch guidance for all faces
// (use_patch_guidance(true)); range(2) = 0 CGAL::Sequential_tag, 1 CGAL::Parallel_tag (TBB's threads,
// `threads` of them; the same normals bit for bit, see test_scans.cpp). robust_ms = process CPU,
// wall_ms = wall time, peak_MB / process_MB as above (the whole call); x_cgal_normals = CPU time over
// CGAL's Polygon_mesh_processing::compute_vertex_normals() on the same mesh, measured alongside.
void BM_robust_normals(benchmark::State& state)
{
  const Setup_mesh& s = setup_mesh(static_cast<int>(state.range(0)));
  const int estimator = static_cast<int>(state.range(1));
  const bool parallel = state.range(2) == 1;
#ifndef CGAL_LINKED_WITH_TBB
  if(parallel)
  {
    state.SkipWithError("no TBB: CGAL::Parallel_tag is not available");
    return;
  }
#endif
  double edge_sum = 0; // (clean meshes get no suggested scale: two mean edges, as for a scan)
  for(auto e : edges(s.mesh))
    edge_sum += CGAL::Polygon_mesh_processing::edge_length(e, s.mesh);
  const double scale = 2 * edge_sum / double(num_edges(s.mesh));
  auto normals = get(CGAL::dynamic_vertex_property_t<K::Vector_3>(), s.mesh);
  auto robust = [&](auto tag) {
    typedef decltype(tag) Tag;
    if(estimator == 0)
      IM::estimate_vertex_normals<Tag>(s.mesh, scale, normals);
    else
      IM::estimate_vertex_normals<Tag>(s.mesh, scale, normals, IM::parameters::use_patch_guidance(estimator == 2));
  };
  double robust_cpu = 0, robust_wall = 0, plain_cpu = 0;
  bench::Peak peak;
  for(auto _ : state)
  {
    plain_cpu += timed([&] { CGAL::Polygon_mesh_processing::compute_vertex_normals(s.mesh, normals); }).first;
    peak = bench::measure_peak(state, [&] {
      const auto t = timed([&] {
#ifdef CGAL_LINKED_WITH_TBB
        if(parallel)
          robust(CGAL::Parallel_tag());
        else
#endif
          robust(CGAL::Sequential_tag());
      });
      robust_cpu += t.first;
      robust_wall += t.second;
    });
    benchmark::DoNotOptimize(get(normals, s.vertex));
  }
  state.counters["faces"] = double(num_faces(s.mesh));
#ifdef CGAL_LINKED_WITH_TBB
  state.counters["threads"] = parallel ? double(tbb::this_task_arena::max_concurrency()) : 1.;
#else
  state.counters["threads"] = 1.;
#endif
  state.counters["robust_ms"] = 1000 * robust_cpu / double(state.iterations());
  state.counters["wall_ms"] = 1000 * robust_wall / double(state.iterations());
  state.counters["peak_MB"] = peak.growth_MB;
  state.counters["process_MB"] = peak.process_MB;
  state.counters["x_cgal_normals"] = robust_cpu / plain_cpu;
}
BENCHMARK(BM_robust_normals)->ArgsProduct({{0, 1}, {0, 1, 2}, {0, 1}})->Unit(benchmark::kMillisecond)->Iterations(1)
  ->UseRealTime();

// Where a bounded one-shot call stops paying for preparing only its reach: the neighbourhood of one
// face (isophotic) with radius range(1) / 1000 of L, from a bare mesh (range(2) = 0: the call as
// it is, on the region its bound reaches while that region holds at most
// internal::reach_region_max_share of the faces) and with the whole mesh prepared in the timing
// (range(2) = 1: Metric_mesh, then the call on it). region_% = share of the faces within the
// radius plus the call's margin (the region's own faces, counted from the call's distances).
void BM_reach_crossover(benchmark::State& state)
{
  const Setup_mesh& s = setup_mesh(static_cast<int>(state.range(0)));
  const auto isophotic = IM::parameters::euclidean_weight(w).isophotic_weight(w_prime).weight_length_scale(s.L);
  const double r = 1e-3 * double(state.range(1)) * s.L;
  const bool whole = state.range(2) == 1;
  std::vector<IM::Neighborhood_face<face_descriptor>> neighbours;
  for(auto _ : state)
  {
    neighbours.clear();
    if(whole)
    {
      IM::Metric_mesh<Mesh> prepared(s.mesh, isophotic);
      IM::geodesic_neighborhood(s.face, s.mesh, r, std::back_inserter(neighbours), IM::parameters::metric_mesh(prepared));
    }
    else
      IM::geodesic_neighborhood(s.face, s.mesh, r, std::back_inserter(neighbours), isophotic);
  }
  // the region the call prepares: the faces meeting the ball of its reach (radius plus margin) over sqrt(w)
  IM::internal::Reach_sources<Mesh> sources;
  sources.faces.push_back(s.face);
  const double reach = r + 0.5 * std::sqrt(w) * IM::internal::longest_source_edge(s.mesh, isophotic, sources);
  IM::internal::Reach_region<Mesh> region;
  IM::internal::Reach_region_walk<K::Point_3, decltype(s.mesh.points())>(s.mesh, s.mesh.points())
    .gather(sources, reach / std::sqrt(w), num_faces(s.mesh), region);
  state.counters["region_%"] = 100. * double(region.faces.size()) / double(num_faces(s.mesh));
}
BENCHMARK(BM_reach_crossover)->ArgsProduct({{0, 2}, {20, 50, 100, 150, 200, 250, 300}, {0, 1}})->Unit(benchmark::kMillisecond)
  ->Repetitions(3)->ReportAggregatesOnly(true);

} // namespace

BENCHMARK_MAIN();
