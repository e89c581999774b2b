// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Selling's reduction of a 3x3 positive definite quadratic form: an obtuse superbase
// (e0,e1,e2,e3 of Z^3, e0+e1+e2+e3 = 0, e_i' D e_j <= 0 for i != j) and the decomposition
//   D = sum_{i<j} rho_ij v_ij v_ij',   rho_ij = -e_i' D e_j >= 0,   v_ij = e_k x e_l
// ({i,j,k,l} = {0,1,2,3}).  The six integer offsets v_ij and non-negative weights rho_ij give a
// monotone upwind discretisation of  (grad u)' D grad u = sum rho (v . grad u)^2  whatever the
// anisotropy of D (Selling 1874; used for anisotropic eikonal equations by Mirebeau).
#ifndef CGAL_ISOPHOTIC_METRIC_CONTINUOUS_INTERNAL_SELLING_H
#define CGAL_ISOPHOTIC_METRIC_CONTINUOUS_INTERNAL_SELLING_H

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>

namespace CGAL {
namespace Isophotic_metric {
namespace internal {

struct Selling_decomposition_3
{
  double weight[6];
  std::int16_t offset[6][3];
  std::int16_t reach; // largest |component| of an offset: nodes this far from the border need no clipping
  bool interior;      // set by the solver: the node is at least 2 reach from the grid's border

  // The decomposed form, sum rho v v'.
  Eigen::Matrix3d matrix() const
  {
    Eigen::Matrix3d D = Eigen::Matrix3d::Zero();
    for(int m = 0; m < 6; ++m)
    {
      const Eigen::Vector3d v(offset[m][0], offset[m][1], offset[m][2]);
      D += weight[m] * v * v.transpose();
    }
    return D;
  }
};

// Obtuse superbase of D by Selling's algorithm: while some e_i' D e_j > 0, replace
// (e_i, e_j, e_k, e_l) by (-e_i, e_j, e_k + e_i, e_l + e_i), which lowers sum |e_i|_D^2.
inline std::array<Eigen::Vector3i, 4> obtuse_superbase(const Eigen::Matrix3d& D)
{
  std::array<Eigen::Vector3i, 4> e = {Eigen::Vector3i(-1, -1, -1), Eigen::Vector3i(1, 0, 0),
                                      Eigen::Vector3i(0, 1, 0), Eigen::Vector3i(0, 0, 1)};
  auto dot = [&](const Eigen::Vector3i& a, const Eigen::Vector3i& b) {
    return a.cast<double>().dot(D * b.cast<double>());
  };
  const double tolerance = 1e-13 * D.trace();
  for(int iteration = 0; iteration < 1000; ++iteration)
  {
    bool reduced = false;
    for(int i = 0; i < 4 && !reduced; ++i)
      for(int j = i + 1; j < 4 && !reduced; ++j)
        if(dot(e[i], e[j]) > tolerance)
        {
          const Eigen::Vector3i ei = e[i];
          for(int m = 0; m < 4; ++m)
            if(m != i && m != j) e[m] += ei;
          e[i] = -ei;
          reduced = true;
        }
    if(!reduced) break;
  }
  return e;
}

inline Selling_decomposition_3 selling_decomposition(const Eigen::Matrix3d& D)
{
  const std::array<Eigen::Vector3i, 4> e = obtuse_superbase(D);
  Selling_decomposition_3 s;
  s.reach = 0;
  s.interior = false;
  int m = 0;
  for(int i = 0; i < 4; ++i)
    for(int j = i + 1; j < 4; ++j, ++m)
    {
      int k = 0;
      while(k == i || k == j) ++k;
      int l = k + 1;
      while(l == i || l == j) ++l;
      const Eigen::Vector3i v = e[k].cross(e[l]);
      s.weight[m] = std::max(0., -e[i].cast<double>().dot(D * e[j].cast<double>()));
      for(int c = 0; c < 3; ++c)
      {
        s.offset[m][c] = std::int16_t(v[c]);
        s.reach = std::max<std::int16_t>(s.reach, std::int16_t(std::abs(v[c])));
      }
    }
  return s;
}

// Solution t of  sum_m w_m max(0, t - a_m)^2 = 1  (upwind values a_m, +inf for missing ones).
// Returns the index of the largest term through `dominant` (for the nearest-source label).
// Values with zero weight are ignored.
inline double selling_update(const double a[6], const double w[6], int& dominant)
{
  // Finite values only, sorted by insertion (usually few: the accepted upwind neighbours).
  int order[6], count = 0;
  for(int m = 0; m < 6; ++m)
  {
    if(!(a[m] < std::numeric_limits<double>::infinity()) || !(w[m] > 0.)) continue;
    int q = count++;
    for(; q > 0 && a[order[q - 1]] > a[m]; --q) order[q] = order[q - 1];
    order[q] = m;
  }
  double A = 0., B = 0., C = -1., t = std::numeric_limits<double>::infinity();
  for(int q = 0; q < count; ++q)
  {
    const int o = order[q];
    if(!(a[o] < t)) break;
    A += w[o];
    B += w[o] * a[o];
    C += w[o] * a[o] * a[o];
    const double disc = B * B - A * C;
    t = (B + std::sqrt(disc > 0. ? disc : 0.)) / A;
  }
  double best = -1.;
  dominant = count > 0 ? order[0] : 0;
  for(int q = 0; q < count; ++q)
  {
    const int o = order[q];
    const double term = w[o] * (t - a[o]) * (t - a[o]);
    if(a[o] < t && term > best) { best = term; dominant = o; }
  }
  return t;
}

} // namespace internal
} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_CONTINUOUS_INTERNAL_SELLING_H
