// Fast sweeping for anisotropic Riemannian eikonal equations on a 2D grid:
//   (grad d)^T M^{-1} grad d = 1,   d = 0 on the sources,
// with M a symmetric positive definite 2x2 field given at the grid nodes.
#ifndef CGAL_ISOPHOTIC_METRIC_FAST_SWEEPING_2_H
#define CGAL_ISOPHOTIC_METRIC_FAST_SWEEPING_2_H

#include <CGAL/Isophotic_metric/exceptions.h>
#include <CGAL/Isophotic_metric/internal/hopf_lax_updates.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {

/// \ingroup PkgIsophoticMetricRef
/// A regular grid of `nu` x `nv` nodes over the parameter rectangle `[u_min,u_max] x [v_min,v_max]`.
/// Node `(i,j)` sits at `(u_min + i*hu, v_min + j*hv)`; its linear index is `i + nu*j`.
struct Grid_2
{
  double u_min = 0., u_max = 1., v_min = 0., v_max = 1.;
  int nu = 2, nv = 2;

  Grid_2() = default;
  /// \throws Invalid_parameter_error if the rectangle is empty, not finite, or fewer than 3 nodes per side.
  Grid_2(double u_min, double u_max, double v_min, double v_max, int nu, int nv)
    : u_min(u_min), u_max(u_max), v_min(v_min), v_max(v_max), nu(nu), nv(nv)
  {
    if(!(std::isfinite(u_min) && std::isfinite(u_max) && std::isfinite(v_min) && std::isfinite(v_max))
       || !(u_max > u_min) || !(v_max > v_min))
      throw Invalid_parameter_error("Grid_2: the parameter rectangle must be finite and non-empty");
    if(nu < 3 || nv < 3)
      throw Invalid_parameter_error("Grid_2: at least 3 nodes per side are needed, got "
                                    + std::to_string(nu) + " x " + std::to_string(nv));
  }

  double hu() const { return (u_max - u_min) / (nu - 1); }
  double hv() const { return (v_max - v_min) / (nv - 1); }
  std::size_t size() const { return std::size_t(nu) * std::size_t(nv); }
  std::size_t index(int i, int j) const { return std::size_t(i) + std::size_t(nu) * std::size_t(j); }
  Eigen::Vector2d node(int i, int j) const { return {u_min + i * hu(), v_min + j * hv()}; }
  /// Continuous index coordinates of a parameter point (node `(i,j)` has coordinates `(i,j)`).
  Eigen::Vector2d to_index(const Eigen::Vector2d& uv) const
  { return {(uv.x() - u_min) / hu(), (uv.y() - v_min) / hv()}; }
  bool contains(const Eigen::Vector2d& uv) const
  {
    return uv.allFinite() && uv.x() >= u_min && uv.x() <= u_max && uv.y() >= v_min && uv.y() <= v_max;
  }
};

/// \ingroup PkgIsophoticMetricRef
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
  /// of the source singularity.  0 = only the nodes of the source's cell.
  int source_initialization_radius = 3;
  /// 3D only, with `adaptive_stencil`: second-order upwind differences where the solution is
  /// smooth enough (values decreasing monotonically along the two upwind nodes), first order elsewhere.
  bool second_order = true;
  /// Stop when no node changes by more than `tolerance` times its value during a whole sweep.
  double tolerance = 1e-12;
  /// Safety limit on the number of sweeps (one sweep = one pass in one ordering).
  int max_sweeps = 1000;
};

/// \ingroup PkgIsophoticMetricRef
/// The result of `Fast_sweeping_2::solve()`: distances and nearest sources at the grid nodes.
struct Distance_field_2
{
  Grid_2 grid;
  std::vector<double> distance;      ///< per node, `+inf` where no source is reachable
  std::vector<int> nearest_source;   ///< per node, label of the source the distance comes from, -1 if none
  /// position of each point source by label; NaN for the labels of set sources
  std::vector<Eigen::Vector2d> source_points;
  int sweeps = 0;                    ///< number of sweeps done
  bool converged = false;            ///< false if `max_sweeps` was reached

  double at(int i, int j) const { return distance[grid.index(i, j)]; }

  /// Bilinear interpolation of the distance at a parameter point (clamped to the rectangle).
  double interpolate(const Eigen::Vector2d& uv) const
  {
    int i, j; double s, t;
    locate(uv, i, j, s, t);
    const double d00 = at(i, j), d10 = at(i + 1, j), d01 = at(i, j + 1), d11 = at(i + 1, j + 1);
    return (1 - t) * ((1 - s) * d00 + s * d10) + t * ((1 - s) * d01 + s * d11);
  }

  /// Label of the nearest source at the grid node closest to `uv`.
  int nearest_source_at(const Eigen::Vector2d& uv) const
  {
    const Eigen::Vector2d x = grid.to_index(uv);
    const int i = std::clamp(int(std::lround(x.x())), 0, grid.nu - 1);
    const int j = std::clamp(int(std::lround(x.y())), 0, grid.nv - 1);
    return nearest_source[grid.index(i, j)];
  }

  /// Cell `(i,j)` containing `uv` and local coordinates `(s,t)` in [0,1]^2.
  void locate(const Eigen::Vector2d& uv, int& i, int& j, double& s, double& t) const
  {
    const Eigen::Vector2d x = grid.to_index(uv);
    i = std::clamp(int(std::floor(x.x())), 0, grid.nu - 2);
    j = std::clamp(int(std::floor(x.y())), 0, grid.nv - 2);
    s = std::clamp(x.x() - i, 0., 1.);
    t = std::clamp(x.y() - j, 0., 1.);
  }
};

/// \ingroup PkgIsophoticMetricRef
/// A curve traced back from a point to a source along `dx/dt = -M^{-1} grad d`.
struct Traced_path_2
{
  std::vector<Eigen::Vector2d> points; ///< from the start point to the source
  bool reached_source = false;         ///< false if the tracing stalled (e.g. on a cut locus)
};

/// \ingroup PkgIsophoticMetricRef
/// Fast-sweeping solver (Gauss-Seidel iterations in the 4 diagonal orderings, Tsai, Cheng, Osher,
/// Zhao 2003) of `(grad d)^T M^{-1} grad d = 1` on a `Grid_2`.
///
/// The local solver is the exact Hopf-Lax update on a fan of 8 or 16 neighbours: the new value of
/// a node is the minimum, over the fan boundary, of the linearly interpolated neighbour value plus
/// the metric length (metric frozen at the node) of the step to it.  It is monotone and first-order
/// accurate for any positive definite metric, however anisotropic; the 16-neighbour fan
/// keeps the error small when the metric's eigen-directions are not aligned with the grid.
/// Values only decrease; the iteration stops when a whole sweep changes nothing (up to the
/// relative tolerance), which is then a fixed point of the discrete scheme.
class Fast_sweeping_2
{
public:
  /// \param grid the parameter grid
  /// \param metric one symmetric matrix per node, indexed by `grid.index(i,j)`
  /// \param options stencil, initialisation and stopping settings
  /// \throws Invalid_parameter_error if `metric` has the wrong size or a matrix is not finite,
  ///         not symmetric or not positive definite (the message names the node)
  Fast_sweeping_2(const Grid_2& grid, std::vector<Eigen::Matrix2d> metric,
                  const Fast_sweeping_options& options = Fast_sweeping_options())
    : grid_(grid), metric_(std::move(metric)), options_(options)
  {
    if(metric_.size() != grid_.size())
      throw Invalid_parameter_error("Fast_sweeping_2: " + std::to_string(metric_.size())
                                    + " metric matrices given for " + std::to_string(grid_.size()) + " nodes");
    if(options_.stencil_radius != 1 && options_.stencil_radius != 2)
      throw Invalid_parameter_error("Fast_sweeping_2: stencil_radius must be 1 or 2");
    if(options_.source_initialization_radius < 0 || !(options_.tolerance >= 0.) || options_.max_sweeps < 1)
      throw Invalid_parameter_error("Fast_sweeping_2: negative source_initialization_radius, tolerance or max_sweeps");
    for(int j = 0; j < grid_.nv; ++j)
      for(int i = 0; i < grid_.nu; ++i)
      {
        const Eigen::Matrix2d& M = metric_[grid_.index(i, j)];
        const double tol = 1e-12 * M.cwiseAbs().maxCoeff();
        if(!M.allFinite() || std::abs(M(0, 1) - M(1, 0)) > tol || !(M(0, 0) > 0.) || !(M.determinant() > 0.))
        {
          std::ostringstream os;
          os << "Fast_sweeping_2: the metric at node (" << i << "," << j << "), (u,v) = ("
             << grid_.node(i, j).transpose() << "), is not symmetric positive definite: ["
             << M(0, 0) << " " << M(0, 1) << "; " << M(1, 0) << " " << M(1, 1) << "]";
          throw Invalid_parameter_error(os.str());
        }
      }
    build_stencil();
    if(options_.adaptive_stencil) build_reduced_bases();
  }

  const Grid_2& grid() const { return grid_; }
  const Fast_sweeping_options& options() const { return options_; }
  const Eigen::Matrix2d& metric(int i, int j) const { return metric_[grid_.index(i, j)]; }

  /// Bilinear interpolation of the metric field.
  Eigen::Matrix2d metric_at(const Eigen::Vector2d& uv) const
  {
    const Eigen::Vector2d x = grid_.to_index(uv);
    const int i = std::clamp(int(std::floor(x.x())), 0, grid_.nu - 2);
    const int j = std::clamp(int(std::floor(x.y())), 0, grid_.nv - 2);
    const double s = std::clamp(x.x() - i, 0., 1.), t = std::clamp(x.y() - j, 0., 1.);
    return (1 - t) * ((1 - s) * metric(i, j) + s * metric(i + 1, j))
           + t * ((1 - s) * metric(i, j + 1) + s * metric(i + 1, j + 1));
  }

  /// Adds a source at a parameter point (not necessarily a node); returns its label.
  /// \throws Invalid_source_error if `uv` is not finite or outside the rectangle
  int add_point_source(const Eigen::Vector2d& uv)
  {
    if(!grid_.contains(uv))
    {
      std::ostringstream os;
      os << "Fast_sweeping_2: point source " << point_sources_.size() + node_sources_.size()
         << " at (u,v) = (" << uv.transpose() << ") is outside the parameter rectangle ["
         << grid_.u_min << "," << grid_.u_max << "] x [" << grid_.v_min << "," << grid_.v_max << "]";
      throw Invalid_source_error(os.str());
    }
    point_sources_.push_back({uv, next_label_});
    return next_label_++;
  }

  /// Adds a set source: every node with `mask[grid.index(i,j)] != 0` gets distance 0.
  /// All nodes of one call share one label, which is returned.
  /// \throws Invalid_source_error if the mask has the wrong size or selects no node
  template <typename Mask>
  int add_node_sources(const Mask& mask)
  {
    if(std::size_t(mask.size()) != grid_.size())
      throw Invalid_source_error("Fast_sweeping_2: source mask of size " + std::to_string(mask.size())
                                 + " for a grid of " + std::to_string(grid_.size()) + " nodes");
    std::vector<std::size_t> nodes;
    for(std::size_t n = 0; n < grid_.size(); ++n)
      if(mask[n]) nodes.push_back(n);
    if(nodes.empty())
      throw Invalid_source_error("Fast_sweeping_2: the source set (label " + std::to_string(next_label_)
                                 + ") selects no grid node");
    node_sources_.push_back({std::move(nodes), next_label_});
    return next_label_++;
  }

  /// Runs the sweeps.
  /// \throws Invalid_source_error if no source was added
  Distance_field_2 solve() const
  {
    if(point_sources_.empty() && node_sources_.empty())
      throw Invalid_source_error("Fast_sweeping_2: no source");
    Distance_field_2 field;
    field.grid = grid_;
    field.distance.assign(grid_.size(), std::numeric_limits<double>::infinity());
    field.nearest_source.assign(grid_.size(), -1);
    field.source_points.assign(next_label_, Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN()));
    for(const Point_source& s : point_sources_) field.source_points[s.label] = s.uv;
    initialise_sources(field);
    // Sweep in which each node last decreased (-2: never): a node none of whose neighbours
    // changed since its last update would get the same value again, so it is skipped.
    std::vector<int> changed_in(grid_.size(), -2);
    for(std::size_t n = 0; n < grid_.size(); ++n)
      if(std::isfinite(field.distance[n])) changed_in[n] = -1;

    for(int sweep = 0; sweep < options_.max_sweeps; ++sweep)
    {
      const bool forward_u = (sweep % 4 == 0 || sweep % 4 == 3);
      const bool forward_v = (sweep % 4 < 2);
      const bool changed = sweep_once(field, changed_in, sweep, forward_u, forward_v);
      field.sweeps = sweep + 1;
      if(!changed) { field.converged = true; break; }
    }
    return field;
  }

  /// Traces the curve of steepest descent of `field` (computed by this solver) from `start`
  /// back to its nearest source, integrating `dx/dt = -M^{-1} grad d` with midpoint steps of
  /// half a cell.  The last point is the source point (point sources) or the first point where
  /// the distance is below half a cell's metric length (set sources).
  /// \throws Invalid_source_error if `start` is outside the rectangle or unreachable
  Traced_path_2 trace_back(const Distance_field_2& field, const Eigen::Vector2d& start) const
  {
    if(!grid_.contains(start) || !std::isfinite(field.interpolate(start)))
    {
      std::ostringstream os;
      os << "trace_back: start point (u,v) = (" << start.transpose()
         << ") is outside the parameter rectangle or not reached by the distance field";
      throw Invalid_source_error(os.str());
    }
    const double hu = grid_.hu(), hv = grid_.hv();
    const int k = std::max(1, options_.source_initialization_radius);
    Traced_path_2 path;
    path.points.push_back(start);
    Eigen::Vector2d x = start;

    // Step along -M^{-1} grad d, in parameter units, half a cell long in index units.
    auto direction = [&](const Eigen::Vector2d& p, Eigen::Vector2d& step) {
      const Eigen::Vector2d g = gradient(field, p);
      const Eigen::Vector2d dir = -metric_at(p).ldlt().solve(g);
      const Eigen::Vector2d dir_index(dir.x() / hu, dir.y() / hv);
      const double len = dir_index.norm();
      if(!(len > 0.) || !std::isfinite(len)) return false;
      step = 0.5 * Eigen::Vector2d(dir.x() / len, dir.y() / len);
      return true;
    };

    const int max_steps = 8 * (grid_.nu + grid_.nv) * 4;
    double last_d = field.interpolate(x);
    for(int step_count = 0; step_count < max_steps; ++step_count)
    {
      const int label = field.nearest_source_at(x);
      if(label >= 0 && !std::isnan(field.source_points[label].x()))
      {
        const Eigen::Vector2d& source = field.source_points[label];
        const Eigen::Vector2d gap = grid_.to_index(x) - grid_.to_index(source);
        // Inside the exactly initialised zone the metric is frozen: the geodesic is straight.
        if(std::abs(gap.x()) <= k && std::abs(gap.y()) <= k)
        {
          path.points.push_back(source);
          path.reached_source = true;
          return path;
        }
      }
      else if(label >= 0)
      {
        const double half_cell = 0.5 * std::sqrt(std::min(hu * hu * metric_at(x)(0, 0), hv * hv * metric_at(x)(1, 1)));
        if(field.interpolate(x) <= half_cell) { path.reached_source = true; return path; }
      }
      Eigen::Vector2d s1, s2;
      Eigen::Vector2d next = x;
      if(direction(x, s1))
      {
        const Eigen::Vector2d mid = clamp_to_grid(x + 0.5 * s1);
        if(direction(mid, s2)) next = clamp_to_grid(x + s2);
      }
      double d = field.interpolate(next);
      if(!(d < last_d))
      {
        // The interpolated gradient can stall in narrow valleys of a strongly anisotropic
        // metric (along sharp features): fall back to the best grid neighbour, which always
        // decreases the distance, then resume the continuous descent from there.
        if(!descend_to_best_neighbour(field, x, next, d)) break;
      }
      x = next;
      path.points.push_back(x);
      last_d = d;
    }
    return path;
  }

  /// Gradient of the distance at a parameter point: node gradients by central differences
  /// (one-sided on the border), interpolated bilinearly.
  Eigen::Vector2d gradient(const Distance_field_2& field, const Eigen::Vector2d& uv) const
  {
    int i, j; double s, t;
    field.locate(uv, i, j, s, t);
    auto node_gradient = [&](int a, int b) {
      const int a0 = std::max(a - 1, 0), a1 = std::min(a + 1, grid_.nu - 1);
      const int b0 = std::max(b - 1, 0), b1 = std::min(b + 1, grid_.nv - 1);
      return Eigen::Vector2d((field.at(a1, b) - field.at(a0, b)) / ((a1 - a0) * grid_.hu()),
                             (field.at(a, b1) - field.at(a, b0)) / ((b1 - b0) * grid_.hv()));
    };
    return (1 - t) * ((1 - s) * node_gradient(i, j) + s * node_gradient(i + 1, j))
           + t * ((1 - s) * node_gradient(i, j + 1) + s * node_gradient(i + 1, j + 1));
  }

private:
  struct Point_source { Eigen::Vector2d uv; int label; };
  struct Node_source { std::vector<std::size_t> nodes; int label; };

  // Moves to the stencil neighbour (of the node closest to x) with the smallest distance.
  bool descend_to_best_neighbour(const Distance_field_2& field, const Eigen::Vector2d& x,
                                 Eigen::Vector2d& next, double& d) const
  {
    const Eigen::Vector2d c = grid_.to_index(x);
    const int i = std::clamp(int(std::lround(c.x())), 0, grid_.nu - 1);
    const int j = std::clamp(int(std::lround(c.y())), 0, grid_.nv - 1);
    bool found = false;
    d = field.at(i, j);
    if(d < field.interpolate(x) && (grid_.node(i, j) - x).norm() > 0.) { next = grid_.node(i, j); found = true; }
    // The neighbours the node's value may come from: fixed stencil and reduced hexagon.
    std::vector<std::array<int, 2>> neighbours(offsets_.begin(), offsets_.end());
    if(options_.adaptive_stencil)
    {
      const std::array<int, 4>& r = reduced_[grid_.index(i, j)];
      for(int sign : {-1, 1})
      {
        neighbours.push_back({sign * r[0], sign * r[1]});
        neighbours.push_back({sign * r[2], sign * r[3]});
        neighbours.push_back({sign * (r[0] + r[2]), sign * (r[1] + r[3])});
      }
    }
    for(const auto& o : neighbours)
    {
      const int a = i + o[0], b = j + o[1];
      if(a < 0 || b < 0 || a >= grid_.nu || b >= grid_.nv) continue;
      if(field.at(a, b) < d) { d = field.at(a, b); next = grid_.node(a, b); found = true; }
    }
    return found;
  }

  Eigen::Vector2d clamp_to_grid(const Eigen::Vector2d& uv) const
  {
    return {std::clamp(uv.x(), grid_.u_min, grid_.u_max), std::clamp(uv.y(), grid_.v_min, grid_.v_max)};
  }

  void build_stencil()
  {
    // Neighbour offsets in counter-clockwise order; consecutive offsets span unimodular
    // triangles, so the fan tiles a neighbourhood of the node without overlap.
    if(options_.stencil_radius == 1)
      offsets_ = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
    else
      offsets_ = {{1, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 1}, {-1, 2}, {-1, 1}, {-2, 1},
                  {-1, 0}, {-2, -1}, {-1, -1}, {-1, -2}, {0, -1}, {1, -2}, {1, -1}, {2, -1}};
  }

  // Lagrange-Gauss reduction of the integer lattice for the scalar product of M in index units,
  // then a sign flip so that e1' M e2 <= 0: (e1, e2, -e1-e2) is then an M-obtuse superbase.
  void build_reduced_bases()
  {
    const double hu = grid_.hu(), hv = grid_.hv();
    reduced_.resize(grid_.size());
    for(std::size_t n = 0; n < grid_.size(); ++n)
    {
      const Eigen::Matrix2d& M = metric_[n];
      // Piecewise constant fields are common: reuse the previous node's reduction.
      if(n > 0 && M == metric_[n - 1]) { reduced_[n] = reduced_[n - 1]; continue; }
      const double m11 = M(0, 0) * hu * hu, m12 = M(0, 1) * hu * hv, m22 = M(1, 1) * hv * hv;
      auto dot = [&](const std::array<long, 2>& a, const std::array<long, 2>& b) {
        return m11 * a[0] * b[0] + m12 * (a[0] * b[1] + a[1] * b[0]) + m22 * a[1] * b[1];
      };
      std::array<long, 2> a{1, 0}, b{0, 1};
      if(dot(a, a) > dot(b, b)) std::swap(a, b);
      for(int iteration = 0; iteration < 64; ++iteration)
      {
        const long q = std::lround(dot(a, b) / dot(a, a));
        b = {b[0] - q * a[0], b[1] - q * a[1]};
        if(dot(b, b) >= dot(a, a)) break;
        std::swap(a, b);
      }
      if(dot(a, b) > 0.) b = {-b[0], -b[1]};
      const int max_offset = 64; // beyond, the metric is too extreme for the grid anyway
      if(std::abs(a[0]) + std::abs(a[1]) + std::abs(b[0]) + std::abs(b[1]) > max_offset)
        reduced_[n] = {0, 0, 0, 0};
      else
        reduced_[n] = {int(a[0]), int(a[1]), int(b[0]), int(b[1])};
    }
  }

  void initialise_sources(Distance_field_2& field) const
  {
    for(const Node_source& s : node_sources_)
      for(std::size_t n : s.nodes)
      {
        field.distance[n] = 0.;
        field.nearest_source[n] = s.label;
      }
    const int k = options_.source_initialization_radius;
    for(const Point_source& s : point_sources_)
    {
      const Eigen::Vector2d x = grid_.to_index(s.uv);
      const Eigen::Matrix2d Ms = metric_at(s.uv);
      const int i0 = std::max(0, int(std::ceil(x.x())) - std::max(k, 1));
      const int i1 = std::min(grid_.nu - 1, int(std::floor(x.x())) + std::max(k, 1));
      const int j0 = std::max(0, int(std::ceil(x.y())) - std::max(k, 1));
      const int j1 = std::min(grid_.nv - 1, int(std::floor(x.y())) + std::max(k, 1));
      for(int j = j0; j <= j1; ++j)
        for(int i = i0; i <= i1; ++i)
        {
          const std::size_t n = grid_.index(i, j);
          // Metric averaged between source and node: exact for constant metrics, and
          // third-order accurate (in the distance to the source) for smooth ones.
          const Eigen::Vector2d delta = grid_.node(i, j) - s.uv;
          const double d = std::sqrt(delta.dot(0.5 * (Ms + metric_[n]) * delta));
          if(d < field.distance[n])
          {
            field.distance[n] = d;
            field.nearest_source[n] = s.label;
          }
        }
    }
  }

  // One Gauss-Seidel pass in one ordering; returns true if some node changed noticeably.
  bool sweep_once(Distance_field_2& field, std::vector<int>& changed_in, int sweep, bool forward_u, bool forward_v) const
  {
    const int nu = grid_.nu, nv = grid_.nv;
    const double hu = grid_.hu(), hv = grid_.hv();
    const int K = int(offsets_.size());
    const int R = options_.stencil_radius;
    const double inf = std::numeric_limits<double>::infinity();
    double* d = field.distance.data();
    int* label = field.nearest_source.data();
    int* stamp = changed_in.data();
    bool changed = false;

    std::array<double, 16> nd;     // neighbour values
    std::array<double, 16> C;      // e_k' M e_k
    std::array<double, 16> X;      // e_k' M e_{k+1}
    std::array<std::ptrdiff_t, 16> shift;
    // Coefficients of (m11, m12, m22) in e_k' M e_k and e_k' M e_{k+1}: the forms are then 3 products.
    std::array<std::array<double, 3>, 16> cc, cx;
    for(int k = 0; k < K; ++k)
    {
      const int k1 = (k + 1 == K) ? 0 : k + 1;
      const int a = offsets_[k][0], b = offsets_[k][1], c = offsets_[k1][0], e = offsets_[k1][1];
      shift[k] = a + std::ptrdiff_t(nu) * b;
      cc[k] = {double(a * a), double(2 * a * b), double(b * b)};
      cx[k] = {double(a * c), double(a * e + b * c), double(b * e)};
    }

    for(int jj = 0; jj < nv; ++jj)
    {
      const int j = forward_v ? jj : nv - 1 - jj;
      const bool interior_j = (j >= R && j < nv - R);
      for(int ii = 0; ii < nu; ++ii)
      {
        const int i = forward_u ? ii : nu - 1 - ii;
        const std::size_t n = grid_.index(i, j);
        const double old = d[n];
        double best = old;
        if(best == 0.) continue;
        const bool interior = interior_j && i >= R && i < nu - R;
        static const std::array<int, 4> none{0, 0, 0, 0};
        const std::array<int, 4>& r = options_.adaptive_stencil ? reduced_[n] : none;
        const bool hexagon_used = (r[0] | r[1]) != 0;
        const int hexagon[6][2] = {{r[0], r[1]}, {r[0] + r[2], r[1] + r[3]}, {r[2], r[3]},
                                   {-r[0], -r[1]}, {-r[0] - r[2], -r[1] - r[3]}, {-r[2], -r[3]}};
        // The hexagon is symmetric: its reach is that of its first three vertices.
        const int reach = std::max({std::abs(r[0]), std::abs(r[1]), std::abs(r[2]), std::abs(r[3]),
                                    std::abs(r[0] + r[2]), std::abs(r[1] + r[3])});
        const bool hexagon_interior = i >= reach && i < nu - reach && j >= reach && j < nv - reach;
        bool hexagon_inside[6] = {false, false, false, false, false, false};
        std::ptrdiff_t hexagon_shift[6] = {0, 0, 0, 0, 0, 0};

        // Skip the node if no neighbour changed since the previous sweep.
        const int since = sweep - 1;
        bool recent = false;
        if(interior)
          for(int k = 0; k < K; ++k) recent |= stamp[n + shift[k]] >= since;
        else
          for(int k = 0; k < K; ++k)
            if(i + offsets_[k][0] >= 0 && i + offsets_[k][0] < nu && j + offsets_[k][1] >= 0 && j + offsets_[k][1] < nv)
              recent |= stamp[n + shift[k]] >= since;
        if(hexagon_used)
          for(int k = 0; k < 6; ++k)
          {
            hexagon_shift[k] = hexagon[k][0] + std::ptrdiff_t(nu) * hexagon[k][1];
            hexagon_inside[k] = hexagon_interior || (i + hexagon[k][0] >= 0 && i + hexagon[k][0] < nu
                                                     && j + hexagon[k][1] >= 0 && j + hexagon[k][1] < nv);
            if(hexagon_inside[k]) recent |= stamp[n + hexagon_shift[k]] >= since;
          }
        if(!recent) continue;
        for(int k = 0; k < K; ++k)
          nd[k] = (interior || (i + offsets_[k][0] >= 0 && i + offsets_[k][0] < nu && j + offsets_[k][1] >= 0
                                && j + offsets_[k][1] < nv)) ? d[n + shift[k]] : inf;

        // Metric in index units: M' = diag(h) M diag(h).
        const Eigen::Matrix2d& M = metric_[n];
        const double m11 = M(0, 0) * hu * hu, m12 = M(0, 1) * hu * hv, m22 = M(1, 1) * hv * hv;
        auto form = [&](int a, int b, int c, int e) { // (a,b)' M' (c,e)
          return m11 * a * c + m12 * (a * e + b * c) + m22 * b * e;
        };

        int best_label = label[n];
        for(int k = 0; k < K; ++k)
        {
          C[k] = cc[k][0] * m11 + cc[k][1] * m12 + cc[k][2] * m22;
          if(!(nd[k] < best)) continue;
          const double vertex = nd[k] + std::sqrt(C[k]);
          if(vertex < best) { best = vertex; best_label = label[n + shift[k]]; }
        }
        for(int k = 0; k < K; ++k)
        {
          const int k1 = (k + 1 == K) ? 0 : k + 1;
          const double d0 = nd[k], d1 = nd[k1];
          if(!(std::min(d0, d1) < best) || !(std::max(d0, d1) < inf)) continue;
          X[k] = cx[k][0] * m11 + cx[k][1] * m12 + cx[k][2] * m22;
          const double A = C[k1] - 2. * X[k] + C[k];
          const double B = X[k] - C[k];
          const double value = internal::segment_update(d0, d1, A, B, C[k]);
          if(value < best) { best = value; best_label = label[n + (d0 <= d1 ? shift[k] : shift[k1])]; }
        }
        if(hexagon_used)
        {
          double hd[6], hc[6];
          int hl[6];
          for(int k = 0; k < 6; ++k)
          {
            if(!hexagon_inside[k]) { hd[k] = inf; continue; }
            const std::size_t m = n + hexagon_shift[k];
            hd[k] = d[m];
            hl[k] = label[m];
            hc[k] = form(hexagon[k][0], hexagon[k][1], hexagon[k][0], hexagon[k][1]);
            if(hd[k] < best)
            {
              const double vertex = hd[k] + std::sqrt(hc[k]);
              if(vertex < best) { best = vertex; best_label = hl[k]; }
            }
          }
          for(int k = 0; k < 6; ++k)
          {
            const int k1 = (k + 1 == 6) ? 0 : k + 1;
            const double d0 = hd[k], d1 = hd[k1];
            if(!(std::min(d0, d1) < best) || !(std::max(d0, d1) < inf)) continue;
            const double Y = form(hexagon[k][0], hexagon[k][1], hexagon[k1][0], hexagon[k1][1]);
            const double value = internal::segment_update(d0, d1, hc[k1] - 2. * Y + hc[k], Y - hc[k], hc[k]);
            if(value < best) { best = value; best_label = d0 <= d1 ? hl[k] : hl[k1]; }
          }
        }
        if(best < old)
        {
          d[n] = best;
          label[n] = best_label;
          stamp[n] = sweep;
          if(!(old - best <= options_.tolerance * best)) changed = true;
        }
      }
    }
    return changed;
  }

  Grid_2 grid_;
  std::vector<Eigen::Matrix2d> metric_;
  Fast_sweeping_options options_;
  std::vector<std::array<int, 2>> offsets_;
  std::vector<std::array<int, 4>> reduced_; // per node: e1 = (r0,r1), e2 = (r2,r3) in index units
  std::vector<Point_source> point_sources_;
  std::vector<Node_source> node_sources_;
  int next_label_ = 0;
};

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_FAST_SWEEPING_2_H
