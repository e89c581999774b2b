// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Local solvers of the fast-sweeping schemes: semi-Lagrangian (Hopf-Lax) updates of one grid node
// from a fan of simplices around it, for a metric frozen at the node.
//
// A node x takes the value   min over y on the fan boundary of  d_lin(y) + ||y - x||_M,
// where d_lin interpolates the neighbour values linearly on one segment (2D) or triangle (3D) of
// the fan.  Every candidate below is the exact minimum over one vertex, segment or triangle, so the
// update is monotone and consistent for any positive definite M, whatever the anisotropy.
#ifndef CGAL_ISOPHOTIC_METRIC_CONTINUOUS_INTERNAL_HOPF_LAX_UPDATES_H
#define CGAL_ISOPHOTIC_METRIC_CONTINUOUS_INTERNAL_HOPF_LAX_UPDATES_H

#include <cmath>
#include <limits>

namespace CGAL {
namespace Isophotic_metric {
namespace internal {

// Minimum over the open segment of  (1-l) d0 + l d1 + ||p + l q||_M  with  p = e0, q = e1 - e0,
// given A = q'Mq, B = p'Mq, C = p'Mp.  Returns +inf when the minimum is at an end point
// (the vertex candidates cover those).  If `foot` is given, it receives the minimiser l: the
// update comes from the point p + l q, where the discrete characteristic through the node starts.
inline double segment_update(double d0, double d1, double A, double B, double C, double* foot = nullptr)
{
  const double delta = d0 - d1;         // slope of the linear part along the segment is -delta
  const double slack = A - delta * delta; // > 0 iff the interpolant is "slower" than the metric
  if(slack <= 0.)
    return std::numeric_limits<double>::infinity();
  const double det = A * C - B * B;    // >= 0 (Cauchy-Schwarz), 0 for collinear offsets
  const double l = (-B + delta * std::sqrt((det > 0. ? det : 0.) / slack)) / A;
  if(!(l > 0. && l < 1.))
    return std::numeric_limits<double>::infinity();
  const double sq = C + l * (2. * B + l * A);
  if(foot) *foot = l;
  return d0 - l * delta + std::sqrt(sq > 0. ? sq : 0.);
}

} // namespace internal
} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_CONTINUOUS_INTERNAL_HOPF_LAX_UPDATES_H
