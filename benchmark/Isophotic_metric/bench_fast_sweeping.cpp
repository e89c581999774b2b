// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Fast sweeping on the setting of the Hamiltonian Fast Marching anchor: constant metric of
// anisotropy 10 (eigenvalues 1 and 100, rotated), point source at the centre of [-1,1]^d.
// Counter "error_pct": max |d_h - d| / max d over the grid nodes, in percent.
#include <CGAL/Isophotic_metric/Continuous/Fast_sweeping_2.h>
#include <CGAL/Isophotic_metric/Continuous/Fast_sweeping_3.h>

#include <benchmark/benchmark.h>

#include <cmath>

namespace IM = CGAL::Isophotic_metric;

static void BM_fast_sweeping_2(benchmark::State& state)
{
  const int n = int(state.range(0));
  const double angle = 0.5;
  Eigen::Matrix2d R;
  R << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  const Eigen::Matrix2d M = R * Eigen::Vector2d(1., 100.).asDiagonal() * R.transpose();
  const IM::Grid_2 grid(-1., 1., -1., 1., n, n);
  double error = 0.;
  int sweeps = 0;
  for(auto _ : state)
  {
    IM::Fast_sweeping_2 solver(grid, std::vector<Eigen::Matrix2d>(grid.size(), M));
    solver.add_point_source(Eigen::Vector2d(0., 0.));
    const IM::Distance_field_2 field = solver.solve();
    state.PauseTiming();
    double max_error = 0., max_distance = 0.;
    for(int j = 0; j < n; ++j)
      for(int i = 0; i < n; ++i)
      {
        const Eigen::Vector2d x = grid.node(i, j);
        const double exact = std::sqrt(x.dot(M * x));
        max_error = std::max(max_error, std::abs(field.at(i, j) - exact));
        max_distance = std::max(max_distance, exact);
      }
    error = 100. * max_error / max_distance;
    sweeps = field.sweeps;
    state.ResumeTiming();
  }
  state.counters["error_pct"] = error;
  state.counters["sweeps"] = sweeps;
}
BENCHMARK(BM_fast_sweeping_2)->Arg(201)->Arg(401)->Arg(801)->Unit(benchmark::kMillisecond);

static void BM_fast_sweeping_3(benchmark::State& state)
{
  const int n = int(state.range(0));
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Matrix3d M = Q * Eigen::Vector3d(1., 1., 100.).asDiagonal() * Q.transpose();
  const IM::Grid_3 grid(Eigen::Vector3d::Constant(-1.), 2. / (n - 1), n, n, n);
  double error = 0.;
  for(auto _ : state)
  {
    IM::Fast_sweeping_3 solver(grid, std::vector<char>(grid.size(), 1), std::vector<Eigen::Matrix3d>(grid.size(), M));
    solver.add_point_source(Eigen::Vector3d::Zero());
    const IM::Distance_field_3 field = solver.solve();
    state.PauseTiming();
    double max_error = 0., max_distance = 0.;
    for(int k = 0; k < n; ++k)
      for(int j = 0; j < n; ++j)
        for(int i = 0; i < n; ++i)
        {
          const Eigen::Vector3d x = grid.node(i, j, k);
          const double exact = std::sqrt(x.dot(M * x));
          max_error = std::max(max_error, std::abs(field.at(i, j, k) - exact));
          max_distance = std::max(max_distance, exact);
        }
    error = 100. * max_error / max_distance;
    state.ResumeTiming();
  }
  state.counters["error_pct"] = error;
}
BENCHMARK(BM_fast_sweeping_3)->Arg(51)->Arg(101)->Unit(benchmark::kMillisecond)->Iterations(1);

BENCHMARK_MAIN();
