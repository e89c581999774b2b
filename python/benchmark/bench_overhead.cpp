// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The C++ side of the Python overhead measurement (bench_overhead.py runs both): the calls the
// Python module makes, from C++, on the same mesh.
//   bench_overhead <mesh> [Google Benchmark options]
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Isophotic_metric/Geodesics/compute_geodesic_distances.h>
#include <CGAL/Isophotic_metric/Morphology/face_selection_morphology.h>
#include <CGAL/Isophotic_metric/suggested_weight_length_scale.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Surface_mesh.h>

#include <benchmark/benchmark.h>

#include <iostream>
#include <memory>
#include <vector>

namespace IM = CGAL::Isophotic_metric;
typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
typedef Mesh::Vertex_index vertex_descriptor;
typedef Mesh::Face_index face_descriptor;

namespace {

Mesh mesh;

void Distances(benchmark::State& state, double w, double w_prime)
{
  std::vector<double> d(num_vertices(mesh));
  const double L = IM::suggested_weight_length_scale(mesh);
  const vertex_descriptor sources[1] = {vertex_descriptor(0)};
  for(auto _ : state)
    IM::compute_geodesic_distances(sources, mesh, CGAL::make_property_map(d),
                                   IM::parameters::euclidean_weight(w).isophotic_weight(w_prime).weight_length_scale(L));
  state.counters["faces"] = double(num_faces(mesh));
}

void Dilation(benchmark::State& state)
{
  const double L = IM::suggested_weight_length_scale(mesh);
  std::unique_ptr<bool[]> selected(new bool[num_faces(mesh)]); // as the module's numpy mask
  const face_descriptor seed[1] = {face_descriptor(0)};
  for(auto _ : state)
  {
    std::fill(selected.get(), selected.get() + num_faces(mesh), false);
    selected[0] = true;
    IM::dilate_face_selection(seed, mesh, 0.1 * L, CGAL::make_property_map(selected.get()), CGAL::Emptyset_iterator(),
                              IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(L));
  }
}

} // namespace

BENCHMARK_CAPTURE(Distances, euclidean, 1.0, 0.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Distances, isophotic, 0.5, 0.5)->Unit(benchmark::kMillisecond);
BENCHMARK(Dilation)->Unit(benchmark::kMillisecond);

int main(int argc, char** argv)
{
  if(argc < 2 || !CGAL::IO::read_polygon_mesh(argv[1], mesh))
  {
    std::cerr << "usage: bench_overhead <mesh> [benchmark options]" << std::endl;
    return 2;
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
