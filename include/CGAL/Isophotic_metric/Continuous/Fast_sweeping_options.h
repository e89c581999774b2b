// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Options of the fast-sweeping solvers, and their validation (shared by the 2D and 3D solvers).
#ifndef CGAL_ISOPHOTIC_METRIC_CONTINUOUS_FAST_SWEEPING_OPTIONS_H
#define CGAL_ISOPHOTIC_METRIC_CONTINUOUS_FAST_SWEEPING_OPTIONS_H

#include <CGAL/Isophotic_metric/exceptions.h>

#include <cmath>
#include <sstream>
#include <string>

namespace CGAL {
namespace Isophotic_metric {

/// \ingroup PkgIsophoticMetricContinuousRef
/// Options of the fast-sweeping solvers (`Fast_sweeping_2`, `Fast_sweeping_3`).
struct Fast_sweeping_options
{
  /// Neighbourhood of the local update.  2D: 1 = 8 neighbours, 2 = 16 neighbours (adds the
  /// knight moves).  3D: 1 = 6 neighbours (octahedron), 2 = 26 neighbours (cube).
  /// Wider stencils resolve more directions and so are more accurate for strong anisotropy.
  int stencil_radius = 2;
  /// 2D: also use, at every node, the hexagon `{+-e1, +-e2, +-(e1+e2)}` of an M-reduced
  /// lattice basis (Lagrange-Gauss reduction with respect to the node's metric).  Its triangles are
  /// M-acute whatever the anisotropy, which keeps the update accurate when the metric is very
  /// elongated along directions the fixed stencil does not contain (sharp features).
  /// 3D: replace the fixed fan by the upwind scheme of the Selling decomposition of the node's
  /// inverse metric (six integer offsets with non-negative weights, Mirebeau's Riemannian scheme),
  /// which is causal and so solved in one pass in increasing order (fast marching) instead of sweeps.
  bool adaptive_stencil = true;
  /// Nodes within this many cells (Chebyshev) of a point source are initialised with the exact
  /// distance of the metric frozen at the source and the node, which removes most of the error
  /// of the source singularity.  0 = only the nodes of the source's cell.  Radii beyond the grid's
  /// size initialise the whole grid.
  int source_initialization_radius = 3;
  /// 3D only, with `adaptive_stencil`: second-order upwind differences where the solution is
  /// smooth enough (values decreasing monotonically along the two upwind nodes), first order elsewhere.
  bool second_order = true;
  /// 3D only, with `adaptive_stencil`: within `4 * source_initialization_radius` cells of a point
  /// source, write the distance as `d0 + u`, with `d0` the cone of the metric frozen at the source,
  /// and difference only `u` (the cone's derivative along each offset is exact).  This removes the
  /// error the second-order differences make at the source's singularity, which otherwise shifts
  /// the whole field (by -0.4 % of the diameter on a sphere band at 41^3).
  bool factor_point_sources = true;
  /// Stop when no node changes by more than `tolerance` times its value during a whole sweep
  /// (sweeping schemes only; the 3D Selling scheme is solved in one pass).  In `[0, 1)`.
  double tolerance = 1e-12;
  /// Safety limit on the number of sweeps (one sweep = one pass in one ordering).
  int max_sweeps = 1000;
};

namespace internal {

// Every option in its domain, or an exception naming the option, its value and what is allowed.
inline void check_fast_sweeping_options(const Fast_sweeping_options& options, const std::string& solver)
{
  auto reject = [&](const std::string& option, const auto& value, const std::string& allowed) {
    std::ostringstream os;
    os << solver << ": Fast_sweeping_options::" << option << " = " << value << " is invalid; " << allowed;
    throw Invalid_parameter_error(os.str());
  };
  if(options.stencil_radius != 1 && options.stencil_radius != 2)
    reject("stencil_radius", options.stencil_radius, "use 1 or 2");
  if(options.source_initialization_radius < 0)
    reject("source_initialization_radius", options.source_initialization_radius, "use a number of cells >= 0");
  if(!(options.tolerance >= 0. && options.tolerance < 1.))
    reject("tolerance", options.tolerance, "use a relative change in [0, 1), e.g. 1e-12");
  if(options.max_sweeps < 1)
    reject("max_sweeps", options.max_sweeps, "use at least 1 sweep");
}

} // namespace internal

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_CONTINUOUS_FAST_SWEEPING_OPTIONS_H
