// Morphology benchmarks:
//  - dilation of a small seed on fandisk Loop-subdivided 3 times (829k faces) for radii covering
//    0.1 %, 1 % and 10 % of the vertices (time must follow the band, not the mesh);
//  - the same growth by CGAL's combinatorial expand_face_selection (k-ring) for comparison;
//  - the per-face neighbourhood batch on fandisk, serial and parallel.
// The geometry (lift, edge lengths) is prepared once per mesh, outside the timings.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/boost/graph/selection.h>
#include <CGAL/subdivision_method_3.h>

#include <CGAL/Isophotic_metric.h>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <iostream>
#include <memory>
#include <vector>

namespace {

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
typedef boost::graph_traits<Mesh>::face_descriptor face_descriptor;
namespace IM = CGAL::Isophotic_metric;

struct Large_fandisk
{
  Mesh mesh;
  std::unique_ptr<IM::Face_band_solver<Mesh>> band;
  std::vector<face_descriptor> seed;
  double radius[3]; // 0.1 %, 1 %, 10 % of the vertices

  Large_fandisk()
  {
    CGAL::IO::read_polygon_mesh(CGAL::data_file_path("meshes/fandisk.off"), mesh);
    CGAL::Subdivision_method_3::Loop_subdivision(mesh, CGAL::parameters::number_of_iterations(3));
    const double L = IM::suggested_weight_length_scale(mesh);
    band = std::make_unique<IM::Face_band_solver<Mesh>>(
      mesh, IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(L).store_windows(true));
    seed = {face_descriptor(1000)};
    // radii from the distances of the vertices to the seed, growing the propagation until 10 % are reached
    band->clear_sources();
    band->add_source_region(std::vector<std::uint32_t>{1000});
    const std::size_t nv = band->number_of_vertices();
    double bound = 0.001 * L;
    std::vector<double> d;
    for(;; bound *= 2)
    {
      band->propagate_to(bound);
      d.clear();
      for(std::uint32_t v = 0; v < nv; ++v)
        if(band->vertex_distance(v) <= bound)
          d.push_back(band->vertex_distance(v));
      if(d.size() >= nv / 10)
        break;
    }
    std::sort(d.begin(), d.end());
    radius[0] = d[nv / 1000];
    radius[1] = d[nv / 100];
    radius[2] = d[nv / 10 - 1];
    std::cerr << "fandisk Loop x3: " << num_faces(mesh) << " faces; radii " << radius[0] << " " << radius[1] << " "
              << radius[2] << std::endl;
  }
};

Large_fandisk& large()
{
  static Large_fandisk data;
  return data;
}

void BM_dilation_large(benchmark::State& state)
{
  Large_fandisk& data = large();
  const double r = data.radius[state.range(0)];
  auto selected = data.mesh.add_property_map<face_descriptor, bool>("f:bench", false).first;
  std::size_t added = 0;
  for(auto _ : state)
  {
    state.PauseTiming();
    for(face_descriptor f : faces(data.mesh))
      selected[f] = false;
    selected[data.seed[0]] = true;
    std::vector<face_descriptor> out;
    state.ResumeTiming();
    IM::dilate_face_selection(data.seed, data.mesh, r, selected, std::back_inserter(out),
                              IM::parameters::face_band_solver(data.band.get()));
    added = out.size();
  }
  data.mesh.remove_property_map(selected);
  state.counters["faces_added"] = double(added);
  state.counters["share_of_mesh_%"] = 100.0 * double(added) / double(num_faces(data.mesh));
}
BENCHMARK(BM_dilation_large)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(3)
  ->ReportAggregatesOnly(true);

// CGAL's k-ring growth to about the same number of faces as the metric dilation of index range(0).
void BM_k_ring_large(benchmark::State& state)
{
  Large_fandisk& data = large();
  auto selected = data.mesh.add_property_map<face_descriptor, bool>("f:bench_k", false).first;
  std::size_t added = 0;
  for(auto _ : state)
  {
    state.PauseTiming();
    for(face_descriptor f : faces(data.mesh))
      selected[f] = false;
    selected[data.seed[0]] = true;
    std::vector<face_descriptor> out;
    state.ResumeTiming();
    CGAL::expand_face_selection(data.seed, data.mesh, static_cast<unsigned>(state.range(0)), selected, std::back_inserter(out));
    added = out.size();
  }
  data.mesh.remove_property_map(selected);
  state.counters["faces_added"] = double(added);
}
BENCHMARK(BM_k_ring_large)->Arg(10)->Arg(30)->Arg(100)->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(3)
  ->ReportAggregatesOnly(true);

void BM_neighborhood_batch(benchmark::State& state)
{
  static Mesh mesh;
  static std::unique_ptr<IM::Face_band_solver<Mesh>> band;
  static double L = 0;
  if(!band)
  {
    CGAL::IO::read_polygon_mesh(CGAL::data_file_path("meshes/fandisk.off"), mesh);
    L = IM::suggested_weight_length_scale(mesh);
    band = std::make_unique<IM::Face_band_solver<Mesh>>(
      mesh, IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(L));
  }
  const bool parallel = state.range(0) != 0;
  std::size_t total = 0;
  for(auto _ : state)
  {
    const auto n = IM::all_face_neighborhoods(mesh, 0.01 * L, IM::Neighborhood_center::FACE,
                                              IM::parameters::face_band_solver(band.get()).parallel_execution(parallel));
    total = 0;
    for(const auto& l : n)
      total += l.size();
  }
  state.counters["mean_neighbours"] = double(total) / double(num_faces(mesh));
}
BENCHMARK(BM_neighborhood_batch)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(3)
  ->ReportAggregatesOnly(true);

} // namespace

BENCHMARK_MAIN();
