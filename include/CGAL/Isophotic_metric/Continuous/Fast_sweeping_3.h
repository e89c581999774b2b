// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Fast sweeping for anisotropic Riemannian eikonal equations on a 3D grid, restricted to a
// narrow band of active nodes:   (grad d)^T M^{-1} grad d = 1,   d = 0 on the sources.
#ifndef CGAL_ISOPHOTIC_METRIC_CONTINUOUS_FAST_SWEEPING_3_H
#define CGAL_ISOPHOTIC_METRIC_CONTINUOUS_FAST_SWEEPING_3_H

#include <CGAL/Isophotic_metric/Continuous/Fast_sweeping_options.h>
#include <CGAL/Isophotic_metric/exceptions.h>
#include <CGAL/Isophotic_metric/Continuous/internal/hopf_lax_updates.h>
#include <CGAL/Isophotic_metric/Continuous/internal/metric_tensor.h>
#include <CGAL/Isophotic_metric/Continuous/internal/selling.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <cstdint>
#include <functional>
#include <map>
#include <queue>
#include <utility>
#include <sstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {

/// \ingroup PkgIsophoticMetricContinuousRef
/// A regular grid of `nx` x `ny` x `nz` nodes with cubic cells of side `h`; node `(i,j,k)` sits at
/// `origin + h (i,j,k)`; its linear index is `i + nx (j + ny k)`.
/// A grid is checked when it is made and cannot be changed afterwards (assign another grid instead).
class Grid_3
{
public:
  /// The unit cube with 3 x 3 x 3 nodes (`h = 0.5`).
  Grid_3() = default;
  /// \throws Invalid_parameter_error on a non-finite origin, a non-positive or non-finite spacing,
  ///         fewer than 3 nodes per side, more than 2^32 nodes, or a grid whose far corner is not finite
  Grid_3(const Eigen::Vector3d& origin, double h, int nx, int ny, int nz)
    : origin_(origin), h_(h), nx_(nx), ny_(ny), nz_(nz)
  {
    if(!origin.allFinite() || !std::isfinite(h) || !(h > 0.))
    {
      std::ostringstream os;
      os << "Grid_3: origin (" << origin.transpose() << ") and spacing h = " << h
         << " must be finite, the spacing positive";
      throw Invalid_parameter_error(os.str());
    }
    if(nx < 3 || ny < 3 || nz < 3)
      throw Invalid_parameter_error("Grid_3: at least 3 nodes per side are needed, got " + std::to_string(nx) + " x "
                                    + std::to_string(ny) + " x " + std::to_string(nz));
    if(std::size_t(nx) * std::size_t(ny) * std::size_t(nz) > (std::size_t(1) << 32))
      throw Invalid_parameter_error("Grid_3: " + std::to_string(nx) + " x " + std::to_string(ny) + " x "
                                    + std::to_string(nz) + " nodes, more than 2^32: use a coarser grid");
    if(!node(nx - 1, ny - 1, nz - 1).allFinite())
      throw Invalid_parameter_error("Grid_3: the far corner of the grid is not finite (spacing too large)");
  }
  /// A grid with cubic cells of side `h` covering the box `[lo, hi]` (enlarged to a whole number of cells).
  /// \throws Invalid_parameter_error as the constructor, or if the box is not finite or `lo > hi`
  static Grid_3 covering(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double h)
  {
    const Eigen::Vector3d cells = (hi - lo) / h;
    if(!lo.allFinite() || !hi.allFinite() || !std::isfinite(h) || !(h > 0.) || !cells.allFinite()
       || !(cells.minCoeff() >= 0.) || !(cells.maxCoeff() < double(std::numeric_limits<int>::max() - 1)))
    {
      std::ostringstream os;
      os << "Grid_3::covering: the box [(" << lo.transpose() << "), (" << hi.transpose() << ")] with cells of side "
         << h << " is not a finite box (lo <= hi) with a positive spacing";
      throw Invalid_parameter_error(os.str());
    }
    // At least 3 nodes per side, as the constructor requires.
    auto nodes = [](double c) { return std::max(3, int(std::ceil(c)) + 1); };
    return Grid_3(lo, h, nodes(cells.x()), nodes(cells.y()), nodes(cells.z()));
  }

  const Eigen::Vector3d& origin() const { return origin_; }
  double h() const { return h_; }
  int nx() const { return nx_; }
  int ny() const { return ny_; }
  int nz() const { return nz_; }
  std::size_t size() const { return std::size_t(nx_) * ny_ * nz_; }
  std::size_t index(int i, int j, int k) const
  { return std::size_t(i) + std::size_t(nx_) * (std::size_t(j) + std::size_t(ny_) * k); }
  Eigen::Vector3d node(int i, int j, int k) const { return origin_ + h_ * Eigen::Vector3d(i, j, k); }
  Eigen::Vector3d to_index(const Eigen::Vector3d& x) const { return (x - origin_) / h_; }
  bool contains(const Eigen::Vector3d& x) const
  {
    const Eigen::Vector3d c = to_index(x);
    return x.allFinite() && c.x() >= 0 && c.y() >= 0 && c.z() >= 0 && c.x() <= nx_ - 1 && c.y() <= ny_ - 1
           && c.z() <= nz_ - 1;
  }

private:
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  double h_ = 0.5;
  int nx_ = 3, ny_ = 3, nz_ = 3;
};

/// \ingroup PkgIsophoticMetricContinuousRef
/// The result of `Fast_sweeping_3::solve()`.  Inactive nodes (outside the band) hold `+inf`.
struct Distance_field_3
{
  Grid_3 grid;
  std::vector<double> distance;    ///< per node, `+inf` outside the band or where unreachable
  std::vector<int> nearest_source; ///< per node, label of the nearest source, -1 if none
  int sweeps = 0;
  bool converged = false;

  double at(int i, int j, int k) const { return distance[grid.index(i, j, k)]; }

  /// Trilinear interpolation over the finite corners of the cell containing `x`
  /// (weights renormalised next to the band's border); `+inf` if no corner is finite.
  double interpolate(const Eigen::Vector3d& x) const
  {
    const Eigen::Vector3d c = grid.to_index(x);
    const int i = std::clamp(int(std::floor(c.x())), 0, grid.nx() - 2);
    const int j = std::clamp(int(std::floor(c.y())), 0, grid.ny() - 2);
    const int k = std::clamp(int(std::floor(c.z())), 0, grid.nz() - 2);
    const double s = std::clamp(c.x() - i, 0., 1.), t = std::clamp(c.y() - j, 0., 1.), r = std::clamp(c.z() - k, 0., 1.);
    double sum = 0., weight = 0.;
    for(int corner = 0; corner < 8; ++corner)
    {
      const int a = corner & 1, b = (corner >> 1) & 1, e = (corner >> 2) & 1;
      const double value = at(i + a, j + b, k + e);
      const double wgt = (a ? s : 1 - s) * (b ? t : 1 - t) * (e ? r : 1 - r);
      if(std::isfinite(value) && wgt > 0.) { sum += wgt * value; weight += wgt; }
    }
    return weight > 1e-12 ? sum / weight : std::numeric_limits<double>::infinity();
  }

  /// Label of the nearest source at the closest finite node among the corners of the cell of `x`.
  int nearest_source_at(const Eigen::Vector3d& x) const
  {
    const Eigen::Vector3d c = grid.to_index(x);
    int best = -1;
    double best_gap = std::numeric_limits<double>::infinity();
    const int i = std::clamp(int(std::floor(c.x())), 0, grid.nx() - 2);
    const int j = std::clamp(int(std::floor(c.y())), 0, grid.ny() - 2);
    const int k = std::clamp(int(std::floor(c.z())), 0, grid.nz() - 2);
    for(int corner = 0; corner < 8; ++corner)
    {
      const int a = i + (corner & 1), b = j + ((corner >> 1) & 1), e = k + ((corner >> 2) & 1);
      const std::size_t n = grid.index(a, b, e);
      const double gap = (Eigen::Vector3d(a, b, e) - c).squaredNorm();
      if(std::isfinite(distance[n]) && gap < best_gap) { best_gap = gap; best = nearest_source[n]; }
    }
    return best;
  }
};

/// \ingroup PkgIsophoticMetricContinuousRef
/// Solver of `(grad d)^T M^{-1} grad d = 1` on the active nodes of a `Grid_3` (a narrow band around
/// a surface, or the whole grid).
///
/// Default (`Fast_sweeping_options::adaptive_stencil`): at every node, Selling's reduction of the
/// inverse metric `D = M^{-1}` gives six integer offsets `v_m` and weights `rho_m >= 0` with
/// `D = sum rho_m v_m v_m^T`; the upwind scheme `sum rho_m max(0, d - d(x -+ v_m))^2 = 1` is
/// monotone and consistent whatever the anisotropy, and causal, so it is solved in one pass in
/// increasing order (fast marching, `sweeps = 1`).  With `second_order`, a difference uses the next
/// node along the offset too where the values decrease monotonically towards it; with
/// `factor_point_sources`, the cone of each point source is factored out near it.  On the border of a
/// narrow band, where an offset's neighbour is inactive and no upwind difference remains along it,
/// and near the grid's border, where an offset leaves the grid on both sides (strong anisotropy:
/// the offsets reach many cells), the node also takes the semi-Lagrangian update of the fixed fan
/// (26 neighbours with `stencil_radius = 2`) and keeps the smaller value.  (An offset leaving the
/// grid on one side only is an outflow boundary, as usual.)  Every active node next to a reached
/// one is thus reached; `converged` is false otherwise.
///
/// Accuracy (constant metric with eigenvalues (1, 1, kappa), rotated, point source, normalised
/// L-infinity error, tested): below 0.65 % for kappa from 1e2 to 1e6 on a 21^3 grid, 0.03 % at
/// kappa = 1e8 on 41^3, which is the limit of accuracy at that size: the Selling offsets grow with
/// kappa (9 cells at 1e6, 29 at 1e8, 56 at 1e10, 97 at 1e12), and once they no longer fit in the
/// grid the fan does most updates and the error grows to several percent (11 % at 1e12 on 41^3).  Metrics are accepted up to condition numbers of about 1e15 (see
/// `Fast_sweeping_3()`), but the input matrix itself only determines its soft directions to a
/// relative kappa * 1e-16.
///
/// Otherwise: fast sweeping (8 Gauss-Seidel orderings) of the exact Hopf-Lax update on a fixed fan
/// of triangles around the node: the octahedron of the 6 axis neighbours (`stencil_radius = 1`)
/// or the 48 triangles of the 26-neighbour cube (`stencil_radius = 2`).  For each
/// triangle, the linear interpolant of the neighbour values whose gradient has unit dual norm
/// `|g|_{M^{-1}} = 1` is accepted when its characteristic `-M^{-1} g` crosses the triangle;
/// otherwise its edges (2D formula) and vertices are tried.  Monotone, first order; slower, less
/// accurate for strong anisotropy, about as accurate on mildly anisotropic narrow bands.
class Fast_sweeping_3
{
public:
  /// \param grid the grid
  /// \param active `active[grid.index(i,j,k)] != 0` for the nodes where the equation is solved
  /// \param metric symmetric positive definite matrix per node (only active nodes are read)
  /// \param options scheme (Selling fast marching or fast sweeping), initialisation and stopping settings
  /// \throws Invalid_parameter_error on size mismatch, an invalid option, no active node, or a
  ///         metric at an active node that is not symmetric positive definite (decided by a Cholesky
  ///         factorisation; accepted up to condition numbers of about 1e15; the message names the node)
  Fast_sweeping_3(const Grid_3& grid, std::vector<char> active, std::vector<Eigen::Matrix3d> metric,
                  const Fast_sweeping_options& options = Fast_sweeping_options())
    : grid_(grid), active_(std::move(active)), options_(options)
  {
    if(active_.size() != grid_.size() || metric.size() != grid_.size())
      throw Invalid_parameter_error("Fast_sweeping_3: active mask and metric must have one entry per grid node ("
                                    + std::to_string(grid_.size()) + ")");
    internal::check_fast_sweeping_options(options_, "Fast_sweeping_3");
    if(std::none_of(active_.begin(), active_.end(), [](char a) { return a != 0; }))
      throw Invalid_parameter_error("Fast_sweeping_3: no active node: mark the nodes where the equation is solved");
    metric_.resize(grid_.size());
    if(options_.adaptive_stencil) selling_.resize(grid_.size());
    else inverse_.resize(grid_.size()); // the Selling scheme inverts on the fly where it uses the fan
    const double h2 = grid_.h() * grid_.h();
    long previous = -1;
    for(int k = 0; k < grid_.nz(); ++k)
      for(int j = 0; j < grid_.ny(); ++j)
        for(int i = 0; i < grid_.nx(); ++i)
        {
          const std::size_t n = grid_.index(i, j, k);
          if(!active_[n]) continue;
          const char* defect = internal::metric_defect(metric[n]);
          if(defect)
          {
            std::ostringstream node;
            node << "node (" << i << "," << j << "," << k << "), x = (" << grid_.node(i, j, k).transpose() << "),";
            throw Invalid_parameter_error(internal::metric_error_message("Fast_sweeping_3", node.str(), defect, metric[n]));
          }
          // Work in index units: offsets are integer vectors.
          const Eigen::Matrix3d M = 0.5 * h2 * (metric[n] + metric[n].transpose());
          metric_[n] = M;
          if(options_.adaptive_stencil)
          {
            // Piecewise constant fields are common: reuse the previous node's reduction.
            if(previous < 0 || metric[std::size_t(previous)] != metric[n])
              selling_[n] = internal::selling_decomposition(internal::metric_inverse(M));
            else
              selling_[n] = selling_[std::size_t(previous)];
            const int r = 2 * selling_[n].reach;
            selling_[n].interior = i >= r && j >= r && k >= r && i < grid_.nx() - r && j < grid_.ny() - r && k < grid_.nz() - r;
            previous = long(n);
          }
          else
            inverse_[n] = internal::metric_inverse(M);
        }
    build_stencil();
    if(options_.adaptive_stencil) build_reverse_stencils();
  }

  const Grid_3& grid() const { return grid_; }
  const std::vector<char>& active() const { return active_; }
  /// Metric at an active node, in world units.
  Eigen::Matrix3d metric(std::size_t n) const { return metric_[n] / (grid_.h() * grid_.h()); }

  /// Adds a point source at `x` (in the band: within one cell of an active node); returns its label.  Active nodes within
  /// `source_initialization_radius` cells get the exact distance of the metric frozen at the
  /// nearest active node and the node.
  /// \throws Invalid_source_error if `x` is not finite, outside the grid, or no active node lies
  ///         within the initialisation radius
  int add_point_source(const Eigen::Vector3d& x)
  {
    if(!grid_.contains(x) || nearest_active(x) < 0)
    {
      std::ostringstream os;
      os << "Fast_sweeping_3: point source " << next_label_ << " at (" << x.transpose()
         << ") is outside the grid or away from the narrow band";
      throw Invalid_source_error(os.str());
    }
    point_sources_.push_back({x, next_label_});
    factors_.resize(std::size_t(next_label_) + 1);
    factors_.back() = {Source_factor{grid_.to_index(x), metric_[std::size_t(nearest_active(x))]}, true};
    return next_label_++;
  }

  /// Adds a set source: every active node with `mask[n] != 0`; returns the label of the set.
  /// \throws Invalid_source_error if the mask has the wrong size or selects no active node
  template <typename Mask>
  int add_node_sources(const Mask& mask)
  {
    if(std::size_t(mask.size()) != grid_.size())
      throw Invalid_source_error("Fast_sweeping_3: source mask of size " + std::to_string(mask.size())
                                 + " for a grid of " + std::to_string(grid_.size()) + " nodes");
    std::vector<std::size_t> nodes;
    for(std::size_t n = 0; n < grid_.size(); ++n)
      if(mask[n] && active_[n]) nodes.push_back(n);
    if(nodes.empty())
      throw Invalid_source_error("Fast_sweeping_3: the source set (label " + std::to_string(next_label_)
                                 + ") selects no active node");
    node_sources_.push_back({std::move(nodes), next_label_});
    return next_label_++;
  }

  /// Runs the sweeps.
  /// \throws Invalid_source_error if no source was added
  Distance_field_3 solve() const
  {
    if(point_sources_.empty() && node_sources_.empty())
      throw Invalid_source_error("Fast_sweeping_3: no source");
    Distance_field_3 field;
    field.grid = grid_;
    field.distance.assign(grid_.size(), std::numeric_limits<double>::infinity());
    field.nearest_source.assign(grid_.size(), -1);
    initialise_sources(field);
    if(options_.adaptive_stencil)
    {
      selling_march(field);
      field.sweeps = 1;
      field.converged = true;
    }
    else
      for(int sweep = 0; sweep < options_.max_sweeps; ++sweep)
      {
        const int order = sweep % 8;
        const bool changed = sweep_once(field, order & 1, order & 2, order & 4);
        field.sweeps = sweep + 1;
        if(!changed) { field.converged = true; break; }
      }
    // The fan's update gives a finite value to every node next to a reached one: a node left at
    // +inf there means the scheme stopped early, whatever the stopping test said.
    field.converged = field.converged && !has_stranded_node(field);
    return field;
  }

private:
  struct Point_source { Eigen::Vector3d x; int label; };
  struct Node_source { std::vector<std::size_t> nodes; int label; };
  using Offset = std::array<int, 3>;
  struct Face { int v[3]; Eigen::Matrix3d inverse_transpose, inverse; };

  long nearest_active(const Eigen::Vector3d& x) const
  {
    // Only the corners of the cell of x and their neighbours: a source must lie in the band.
    const Eigen::Vector3d c = grid_.to_index(x);
    const int r = 1;
    long best = -1;
    double best_gap = std::numeric_limits<double>::infinity();
    for(int k = std::max(0, int(std::floor(c.z())) - r + 1); k <= std::min(grid_.nz() - 1, int(std::floor(c.z())) + r); ++k)
      for(int j = std::max(0, int(std::floor(c.y())) - r + 1); j <= std::min(grid_.ny() - 1, int(std::floor(c.y())) + r); ++j)
        for(int i = std::max(0, int(std::floor(c.x())) - r + 1); i <= std::min(grid_.nx() - 1, int(std::floor(c.x())) + r); ++i)
        {
          const std::size_t n = grid_.index(i, j, k);
          const double gap = (Eigen::Vector3d(i, j, k) - c).squaredNorm();
          if(active_[n] && gap < best_gap) { best_gap = gap; best = long(n); }
        }
    return best;
  }

  void build_stencil()
  {
    std::vector<std::array<Offset, 3>> triangles;
    if(options_.stencil_radius == 1)
    {
      for(int sx : {-1, 1})
        for(int sy : {-1, 1})
          for(int sz : {-1, 1})
            triangles.push_back({Offset{sx, 0, 0}, Offset{0, sy, 0}, Offset{0, 0, sz}});
    }
    else
    {
      // Each face of the cube [-1,1]^3: fan of 8 triangles around its centre.
      for(int axis = 0; axis < 3; ++axis)
        for(int side : {-1, 1})
        {
          const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
          const int ring[8][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
          auto point = [&](int p, int q) { Offset o{0, 0, 0}; o[axis] = side; o[a1] = p; o[a2] = q; return o; };
          for(int r = 0; r < 8; ++r)
            triangles.push_back({point(0, 0), point(ring[r][0], ring[r][1]), point(ring[(r + 1) % 8][0], ring[(r + 1) % 8][1])});
        }
    }
    std::map<Offset, int> vertex_index;
    auto vertex = [&](const Offset& o) {
      auto it = vertex_index.find(o);
      if(it != vertex_index.end()) return it->second;
      offsets_.push_back(o);
      return vertex_index[o] = int(offsets_.size()) - 1;
    };
    std::map<std::pair<int, int>, int> edge_index;
    for(const auto& t : triangles)
    {
      Face f;
      Eigen::Matrix3d E;
      for(int c = 0; c < 3; ++c)
      {
        f.v[c] = vertex(t[c]);
        E.col(c) = Eigen::Vector3d(t[c][0], t[c][1], t[c][2]);
      }
      f.inverse = E.inverse();
      f.inverse_transpose = f.inverse.transpose();
      faces_.push_back(f);
      for(int c = 0; c < 3; ++c)
      {
        const int a = std::min(f.v[c], f.v[(c + 1) % 3]), b = std::max(f.v[c], f.v[(c + 1) % 3]);
        if(edge_index.emplace(std::make_pair(a, b), int(edges_.size())).second) edges_.push_back({a, b});
      }
    }
    // The simplices of each vertex: when a neighbour is accepted, only those get a new candidate.
    vertex_edges_.assign(offsets_.size(), {});
    vertex_faces_.assign(offsets_.size(), {});
    for(std::size_t e = 0; e < edges_.size(); ++e)
      for(int v : edges_[e]) vertex_edges_[std::size_t(v)].push_back(int(e));
    for(std::size_t f = 0; f < faces_.size(); ++f)
      for(int v : faces_[f].v) vertex_faces_[std::size_t(v)].push_back(int(f));
    vertex_star_.assign(offsets_.size(), {});
    for(std::size_t v = 0; v < offsets_.size(); ++v)
    {
      std::vector<int>& star = vertex_star_[v];
      for(int f : vertex_faces_[v]) star.insert(star.end(), faces_[std::size_t(f)].v, faces_[std::size_t(f)].v + 3);
      for(int e : vertex_edges_[v]) star.insert(star.end(), edges_[std::size_t(e)].begin(), edges_[std::size_t(e)].end());
      std::sort(star.begin(), star.end());
      star.erase(std::unique(star.begin(), star.end()), star.end());
    }
    all_edges_.resize(edges_.size());
    all_faces_.resize(faces_.size());
    for(std::size_t e = 0; e < edges_.size(); ++e) all_edges_[e] = int(e);
    for(std::size_t f = 0; f < faces_.size(); ++f) all_faces_[f] = int(f);
    fan_vertex_at_.fill(-1);
    for(std::size_t v = 0; v < offsets_.size(); ++v)
      fan_vertex_at_[std::size_t((offsets_[v][0] + 1) + 3 * (offsets_[v][1] + 1) + 9 * (offsets_[v][2] + 1))] = int(v);
  }

  void initialise_sources(Distance_field_3& field) const
  {
    for(const Node_source& s : node_sources_)
      for(std::size_t n : s.nodes) { field.distance[n] = 0.; field.nearest_source[n] = s.label; }
    // The zone of a point source: the active nodes within `source_zone()` cells that are connected
    // to the source's nearest active node through active nodes of the zone (26-neighbours), so
    // that the cone does not jump across a gap of the band (two sheets of a thin part).
    const int r = source_zone();
    std::vector<std::size_t> queue;
    std::vector<char> seen(grid_.size(), 0);
    for(const Point_source& s : point_sources_)
    {
      const Eigen::Vector3d c = grid_.to_index(s.x);
      const std::size_t start = std::size_t(nearest_active(s.x));
      const Eigen::Matrix3d& Ms = metric_[start];
      const int lo[3] = {int(std::ceil(c.x())) - r, int(std::ceil(c.y())) - r, int(std::ceil(c.z())) - r};
      const int hi[3] = {int(std::floor(c.x())) + r, int(std::floor(c.y())) + r, int(std::floor(c.z())) + r};
      queue.assign(1, start);
      seen[start] = 1;
      for(std::size_t q = 0; q < queue.size(); ++q)
      {
        const std::size_t n = queue[q];
        const Eigen::Vector3d x = node_index(n);
        const Eigen::Vector3d delta = x - c; // index units, like metric_
        const double d = std::sqrt(delta.dot(0.5 * (Ms + metric_[n]) * delta));
        if(d < field.distance[n]) { field.distance[n] = d; field.nearest_source[n] = s.label; }
        for(int dz = -1; dz <= 1; ++dz)
          for(int dy = -1; dy <= 1; ++dy)
            for(int dx = -1; dx <= 1; ++dx)
            {
              const int a = int(x.x()) + dx, b = int(x.y()) + dy, e = int(x.z()) + dz;
              if(a < std::max(0, lo[0]) || b < std::max(0, lo[1]) || e < std::max(0, lo[2]) || a > std::min(grid_.nx() - 1, hi[0])
                 || b > std::min(grid_.ny() - 1, hi[1]) || e > std::min(grid_.nz() - 1, hi[2]))
                continue;
              const std::size_t z = grid_.index(a, b, e);
              if(active_[z] && !seen[z]) { seen[z] = 1; queue.push_back(z); }
            }
      }
      for(std::size_t n : queue) seen[n] = 0;
    }
  }

  // Nodes whose Selling stencil contains each node (compressed rows): the nodes to update when
  // that node is accepted.  The stencils are symmetric (+-v), but vary from node to node.
  void build_reverse_stencils()
  {
    const int nx = grid_.nx(), ny = grid_.ny(), nz = grid_.nz();
    auto in_grid = [&](int a, int b, int c) {
      return unsigned(a) < unsigned(nx) && unsigned(b) < unsigned(ny) && unsigned(c) < unsigned(nz);
    };
    auto active_at = [&](int a, int b, int c) { return in_grid(a, b, c) && active_[grid_.index(a, b, c)]; };
    // Nodes that also take the fan's update (see selling_march): on the border of the band (some
    // neighbour of the Selling stencil is in the grid but inactive), and near the grid's border
    // where some offset leaves the grid on both sides.  Under strong anisotropy the offsets reach
    // far (9 cells at eigenvalues 1, 1, 1e6), such an offset can never contribute, and nodes all of
    // whose offsets are such were never updated, nor the nodes that depend only on them.
    border_.assign(grid_.size(), 0);
    for(int k = 0; k < nz; ++k)
      for(int j = 0; j < ny; ++j)
        for(int i = 0; i < nx; ++i)
        {
          const std::size_t n = grid_.index(i, j, k);
          if(!active_[n]) continue;
          const internal::Selling_decomposition_3& s = selling_[n];
          bool band_border = false, leaves = false;
          for(int m = 0; m < 6; ++m)
          {
            if(!(s.weight[m] > 0.)) continue;
            int outside = 0;
            for(int sign : {-1, 1})
            {
              const int a = i + sign * s.offset[m][0], b = j + sign * s.offset[m][1], c = k + sign * s.offset[m][2];
              if(in_grid(a, b, c) && !active_[grid_.index(a, b, c)]) band_border = true;
              if(!in_grid(a, b, c)) ++outside;
            }
            leaves = leaves || outside == 2;
          }
          border_[n] = band_border || leaves;
        }
    reverse_start_.assign(grid_.size() + 1, 0);
    for(int pass = 0; pass < 2; ++pass)
    {
      std::vector<std::uint32_t> fill;
      if(pass == 1)
      {
        for(std::size_t n = 0; n < grid_.size(); ++n) reverse_start_[n + 1] += reverse_start_[n];
        reverse_.resize(reverse_start_.back());
        fill.assign(reverse_start_.begin(), reverse_start_.end() - 1);
      }
      for(int k = 0; k < nz; ++k)
        for(int j = 0; j < ny; ++j)
          for(int i = 0; i < nx; ++i)
          {
            const std::size_t n = grid_.index(i, j, k);
            if(!active_[n]) continue;
            auto depends_on = [&](int a, int b, int c) {
              if(!active_at(a, b, c)) return;
              const std::size_t x = grid_.index(a, b, c);
              if(pass == 0) ++reverse_start_[x + 1];
              else reverse_[fill[x]++] = std::uint32_t(n);
            };
            const internal::Selling_decomposition_3& s = selling_[n];
            for(int m = 0; m < 6; ++m)
              if(s.weight[m] > 0.)
                for(int sign : {-1, 1})
                  depends_on(i + sign * s.offset[m][0], j + sign * s.offset[m][1], k + sign * s.offset[m][2]);
            if(border_[n]) // may be updated by the fan (see selling_march)
              for(const Offset& o : offsets_) depends_on(i + o[0], j + o[1], k + o[2]);
          }
    }
  }

  // Upwind update of node n from the accepted nodes only:
  //   sum_m rho_m max(0, d - d(x -+ v_m))^2 = 1,
  // second order ((3 d - 4 d(x-v) + d(x-2v)) / 2 for the difference) where the next node along
  // the upwind direction is accepted and the values decrease monotonically towards it.
  // `blind` is set if no value was found, or if some offset has a neighbour outside the band (or
  // both outside the grid) and no upwind difference: the missing one may have been upwind (the
  // caller then also tries the fan).
  double selling_value(const Distance_field_3& field, const std::vector<char>& accepted, std::size_t n,
                       int& from, bool& blind) const
  {
    const int nx = grid_.nx(), ny = grid_.ny();
    const std::ptrdiff_t sy = nx, sz = std::ptrdiff_t(nx) * ny;
    const internal::Selling_decomposition_3& s = selling_[n];
    const double* d = field.distance.data();
    const bool second_order = options_.second_order;
    double a[6], w[6];
    bool missing[6];
    std::size_t origin[6];
    int i = 0, j = 0, k = 0;
    if(!s.interior)
    {
      i = int(n % std::size_t(nx));
      j = int((n / std::size_t(nx)) % std::size_t(ny));
      k = int(n / std::size_t(sz));
    }
    auto inside = [&](int ox, int oy, int oz) {
      return s.interior || (unsigned(i + ox) < unsigned(grid_.nx()) && unsigned(j + oy) < unsigned(grid_.ny())
                            && unsigned(k + oz) < unsigned(grid_.nz()));
    };
    for(int m = 0; m < 6; ++m)
    {
      a[m] = std::numeric_limits<double>::infinity();
      w[m] = s.weight[m];
      missing[m] = false;
      const int ox = s.offset[m][0], oy = s.offset[m][1], oz = s.offset[m][2];
      const std::ptrdiff_t shift = ox + sy * oy + sz * oz;
      // The upwind side: the smaller (factored) first-order neighbour value.
      int upwind = 0;
      const Source_factor* factor = nullptr;
      for(int sign = -1; sign <= 1; sign += 2)
      {
        if(!inside(sign * ox, sign * oy, sign * oz))
        {
          // Outside the grid: an outflow boundary, unless the other side is outside too (the
          // offset then cannot contribute at all).
          if(!inside(-sign * ox, -sign * oy, -sign * oz)) missing[m] = true;
          continue;
        }
        const std::size_t z = std::size_t(std::ptrdiff_t(n) + sign * shift);
        if(!active_[z]) missing[m] = true;
        if(!accepted[z]) continue;
        const Source_factor* f = factor_for(field, z, n);
        const double value = d[z] + (f ? f->correction(node_index(n), -sign * Eigen::Vector3d(ox, oy, oz), false) : 0.);
        if(!(value < a[m])) continue;
        a[m] = value;
        origin[m] = z;
        upwind = sign;
        factor = f;
      }
      if(upwind == 0 || !second_order || !inside(2 * upwind * ox, 2 * upwind * oy, 2 * upwind * oz)) continue;
      const std::size_t z = origin[m], z2 = std::size_t(std::ptrdiff_t(n) + 2 * upwind * shift);
      if(accepted[z2] && d[z2] <= d[z])
      {
        a[m] = (4. * d[z] - d[z2]) / 3.
               + (factor ? factor->correction(node_index(n), -upwind * Eigen::Vector3d(ox, oy, oz), true) : 0.);
        w[m] = 2.25 * s.weight[m];
      }
    }
    int dominant = 0;
    const double t = internal::selling_update(a, w, dominant);
    from = std::isfinite(a[dominant]) ? int(origin[dominant]) : -1;
    blind = false;
    for(int m = 0; m < 6; ++m) blind = blind || (missing[m] && s.weight[m] > 0. && !(a[m] < t));
    blind = blind || !(t < std::numeric_limits<double>::infinity());
    return t;
  }

  // Factorisation of a point source's singularity: near the source, d = d0 + u with d0 the distance
  // of the metric frozen at the source (the cone the initialisation uses).  The upwind differences
  // of d are taken as differences of u plus the exact derivative of d0 along the offset, which is
  // the same as shifting the neighbour value by `correction()`: the differences of the cone, which
  // are not smooth at the source, then carry no discretisation error.
  struct Source_factor
  {
    Eigen::Vector3d centre; // index units
    Eigen::Matrix3d M;      // index units
    double d0(const Eigen::Vector3d& x) const { return std::sqrt((x - centre).dot(M * (x - centre))); }
    // Shift of the neighbour value for the first-order difference d(x) - d(x - step), or of
    // (4 d(x - step) - d(x - 2 step)) / 3 for the second-order one.
    double correction(const Eigen::Vector3d& x, const Eigen::Vector3d& step, bool second_order) const
    {
      const double r = d0(x);
      const double slope = r > 0. ? (M * (x - centre)).dot(step) / r : 0.; // d0's derivative along step
      if(!second_order) return r - d0(x - step) - slope;
      return (3. * r - 4. * d0(x - step) + d0(x - 2. * step)) / 3. - 2. / 3. * slope;
    }
  };

  Eigen::Vector3d node_index(std::size_t n) const
  {
    const std::size_t nx = std::size_t(grid_.nx()), ny = std::size_t(grid_.ny());
    return Eigen::Vector3d(double(n % nx), double((n / nx) % ny), double(n / (nx * ny)));
  }

  // The factor of the point source that labels the neighbour z, if node n is within
  // `factor_radius()` cells of it.
  const Source_factor* factor_for(const Distance_field_3& field, std::size_t z, std::size_t n) const
  {
    if(!options_.factor_point_sources) return nullptr;
    const int l = field.nearest_source[z];
    if(l < 0 || std::size_t(l) >= factors_.size() || !factors_[l].second) return nullptr;
    const Source_factor& f = factors_[l].first;
    return (node_index(n) - f.centre).squaredNorm() <= factor_radius() * factor_radius() ? &f : nullptr;
  }

  // Radius (cells) of the factored zone: the discretisation error of the cone decays like the
  // squared ratio of the cell size to the distance to the source; beyond a few initialisation
  // radii the metric has drifted from the source's and the factor no longer helps.
  double factor_radius() const { return 4. * source_zone(); }

  // Chebyshev radius (cells) of the initialised zone around a point source, clamped to the grid's
  // size (a larger zone covers the same nodes, and the index sums stay small).
  int source_zone() const
  { return std::clamp(options_.source_initialization_radius, 1, std::max({grid_.nx(), grid_.ny(), grid_.nz()})); }

  // True if an active node is at +inf while one of its fan neighbours is reached.
  bool has_stranded_node(const Distance_field_3& field) const
  {
    for(int k = 0; k < grid_.nz(); ++k)
      for(int j = 0; j < grid_.ny(); ++j)
        for(int i = 0; i < grid_.nx(); ++i)
        {
          const std::size_t n = grid_.index(i, j, k);
          if(!active_[n] || std::isfinite(field.distance[n])) continue;
          for(const Offset& o : offsets_)
          {
            const int a = i + o[0], b = j + o[1], c = k + o[2];
            if(unsigned(a) < unsigned(grid_.nx()) && unsigned(b) < unsigned(grid_.ny()) && unsigned(c) < unsigned(grid_.nz())
               && std::isfinite(field.distance[grid_.index(a, b, c)]))
              return true;
          }
        }
    return false;
  }

  // Values and labels of the accepted fan neighbours of node n (+inf elsewhere).
  // Only the vertices listed in `vertices` are filled.
  void fan_neighbours(const Distance_field_3& field, const std::vector<char>& accepted, std::size_t n,
                      const std::vector<int>& vertices, std::vector<double>& nd, std::vector<int>& nl) const
  {
    const int nx = grid_.nx(), ny = grid_.ny(), nz = grid_.nz();
    const int i = int(n % std::size_t(nx)), j = int((n / std::size_t(nx)) % std::size_t(ny)), k = int(n / (std::size_t(nx) * ny));
    for(int v : vertices)
    {
      const int a = i + offsets_[v][0], b = j + offsets_[v][1], c = k + offsets_[v][2];
      nd[v] = std::numeric_limits<double>::infinity();
      if(unsigned(a) >= unsigned(nx) || unsigned(b) >= unsigned(ny) || unsigned(c) >= unsigned(nz)) continue;
      const std::size_t x = grid_.index(a, b, c);
      if(!accepted[x]) continue;
      nd[v] = field.distance[x];
      nl[v] = field.nearest_source[x];
    }
  }

  // True if the offset (ox, oy, oz) is +- an offset of positive weight of node n's Selling stencil.
  bool in_selling_stencil(std::size_t n, int ox, int oy, int oz) const
  {
    const internal::Selling_decomposition_3& s = selling_[n];
    for(int m = 0; m < 6; ++m)
      if(s.weight[m] > 0.)
        for(int sign : {-1, 1})
          if(sign * s.offset[m][0] == ox && sign * s.offset[m][1] == oy && sign * s.offset[m][2] == oz) return true;
    return false;
  }

  // Fast marching (Dijkstra order) of the Selling scheme: causal, so one pass suffices.
  void selling_march(Distance_field_3& field) const
  {
    using Entry = std::pair<double, std::uint32_t>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> heap;
    std::vector<char> accepted(grid_.size(), 0);
    double* d = field.distance.data();
    int* label = field.nearest_source.data();
    std::vector<double> nd(offsets_.size());
    std::vector<int> nl(offsets_.size());
    // Border nodes: the fan's update over the accepted neighbours, brought up to date only when
    // it is used (when a neighbour is accepted, only the fan's simplices that contain it are new:
    // `pending` holds those neighbours, one bit per fan vertex).
    std::vector<double> fan_value(grid_.size(), std::numeric_limits<double>::infinity());
    std::vector<int> fan_label(grid_.size(), -1);
    std::vector<std::uint32_t> pending(grid_.size(), 0);
    // Whether the last Selling value of a node was blind (see selling_value; none is, before any).
    std::vector<char> blind(border_.begin(), border_.end());
    for(std::size_t n = 0; n < grid_.size(); ++n)
      if(std::isfinite(d[n])) heap.push({d[n], std::uint32_t(n)});
    while(!heap.empty())
    {
      const auto [value, x] = heap.top();
      heap.pop();
      if(accepted[x] || value > d[x]) continue; // stale entry
      accepted[x] = 1;
      const Eigen::Vector3d xi = node_index(x);
      for(std::uint32_t r = reverse_start_[x]; r < reverse_start_[x + 1]; ++r)
      {
        const std::uint32_t y = reverse_[r];
        if(accepted[y]) continue;
        double best = d[y];
        int best_label = label[y];
        // Only a neighbour of the Selling stencil changes the Selling value (border nodes also
        // depend on their fan neighbours).
        bool in_stencil = true;
        if(border_[y])
        {
          const Eigen::Vector3d o = xi - node_index(y);
          const int ox = int(o.x()), oy = int(o.y()), oz = int(o.z());
          const int v = (std::abs(ox) <= 1 && std::abs(oy) <= 1 && std::abs(oz) <= 1)
                          ? fan_vertex_at_[std::size_t((ox + 1) + 3 * (oy + 1) + 9 * (oz + 1))] : -1;
          if(v >= 0) pending[y] |= std::uint32_t(1) << v;
          in_stencil = in_selling_stencil(y, ox, oy, oz);
        }
        if(in_stencil)
        {
          int from = -1;
          bool blind_now = false;
          const double t = selling_value(field, accepted, y, from, blind_now);
          if(t < best) { best = t; best_label = from >= 0 ? label[from] : label[y]; }
          blind[y] = blind_now;
        }
        // Border of the band or of the grid: an offset whose neighbour is missing contributes
        // nothing, and a node whose offsets all leave the grid (strong anisotropy: they reach far)
        // would never be updated.  The fan's semi-Lagrangian update always has candidates: keep
        // the better of the two values.
        if(blind[y])
        {
          for(int v = 0; pending[y] != 0; ++v)
            if(pending[y] & (std::uint32_t(1) << v))
            {
              fan_neighbours(field, accepted, y, vertex_star_[std::size_t(v)], nd, nl);
              fan_update(y, nd.data(), nl.data(), fan_value[y], fan_label[y], v);
              pending[y] &= ~(std::uint32_t(1) << v);
            }
          if(fan_value[y] < best) { best = fan_value[y]; best_label = fan_label[y]; }
        }
        if(best < d[y]) { d[y] = best; label[y] = best_label; heap.push({best, y}); }
      }
    }
  }

  // Exact Hopf-Lax update of node n over the fixed fan (vertices, edges, faces), from the
  // neighbour values `nd` (+inf where unavailable) and labels `nl`; lowers `best` and sets `best_label`.
  // With `vertex >= 0`, only the candidates of the fan's simplices that contain that vertex.
  void fan_update(std::size_t n, const double* nd, const int* nl, double& best, int& best_label, int vertex = -1) const
  {
    const Eigen::Matrix3d& M = metric_[n];
    auto form = [&](const Offset& a, const Offset& b) {
      const Eigen::Vector3d va(a[0], a[1], a[2]), vb(b[0], b[1], b[2]);
      return va.dot(M * vb);
    };
    for(int v = 0; v < int(offsets_.size()); ++v)
      if((vertex < 0 || v == vertex) && nd[v] < best)
      {
        const double value = nd[v] + std::sqrt(form(offsets_[v], offsets_[v]));
        if(value < best) { best = value; best_label = nl[v]; }
      }
    for(int edge : vertex < 0 ? all_edges_ : vertex_edges_[std::size_t(vertex)])
    {
      const std::array<int, 2>& e = edges_[std::size_t(edge)];
      const double d0 = nd[e[0]], d1 = nd[e[1]];
      if(!(std::min(d0, d1) < best) || !std::isfinite(d0) || !std::isfinite(d1)) continue;
      const Offset& p = offsets_[e[0]];
      const Offset q{offsets_[e[1]][0] - p[0], offsets_[e[1]][1] - p[1], offsets_[e[1]][2] - p[2]};
      const double value = internal::segment_update(d0, d1, form(q, q), form(p, q), form(p, p));
      if(value < best) { best = value; best_label = d0 <= d1 ? nl[e[0]] : nl[e[1]]; }
    }
    Eigen::Matrix3d W;
    bool have_inverse = false;
    for(int face : vertex < 0 ? all_faces_ : vertex_faces_[std::size_t(vertex)])
    {
      const Face& f = faces_[std::size_t(face)];
      const double d0 = nd[f.v[0]], d1 = nd[f.v[1]], d2 = nd[f.v[2]];
      if(!(std::min({d0, d1, d2}) < best) || !std::isfinite(d0) || !std::isfinite(d1) || !std::isfinite(d2))
        continue;
      if(!have_inverse)
      {
        // The Selling scheme keeps no inverse: its decomposition is one, D = sum rho v v'.
        W = inverse_.empty() ? selling_[n].matrix() : inverse_[n];
        have_inverse = true;
      }
      // Gradient of the plane through the neighbour values and (x, t): g = a - t b.
      const Eigen::Vector3d a = f.inverse_transpose * Eigen::Vector3d(d0, d1, d2);
      const Eigen::Vector3d b = f.inverse_transpose * Eigen::Vector3d::Ones();
      const Eigen::Vector3d Wb = W * b;
      const double bb = b.dot(Wb), ab = a.dot(Wb), aa = a.dot(W * a);
      const double disc = ab * ab - bb * (aa - 1.);
      if(!(disc >= 0.)) continue;
      const double t = (ab + std::sqrt(disc)) / bb;
      if(!(t < best)) continue;
      // Accept if the characteristic -W g enters the triangle (positive barycentric weights).
      const Eigen::Vector3d lambda = -(f.inverse * (W * (a - t * b)));
      if(lambda.minCoeff() < 0.) continue;
      best = t;
      best_label = (d0 <= d1 && d0 <= d2) ? nl[f.v[0]] : (d1 <= d2 ? nl[f.v[1]] : nl[f.v[2]]);
    }
  }

  bool sweep_once(Distance_field_3& field, bool reverse_x, bool reverse_y, bool reverse_z) const
  {
    const int nx = grid_.nx(), ny = grid_.ny(), nz = grid_.nz();
    const int V = int(offsets_.size());
    const double inf = std::numeric_limits<double>::infinity();
    double* d = field.distance.data();
    int* label = field.nearest_source.data();
    std::vector<double> nd(V);
    std::vector<int> nl(V);
    std::vector<std::ptrdiff_t> shift(V);
    for(int v = 0; v < V; ++v)
      shift[v] = offsets_[v][0] + std::ptrdiff_t(nx) * (offsets_[v][1] + std::ptrdiff_t(ny) * offsets_[v][2]);
    bool changed = false;

    for(int kk = 0; kk < nz; ++kk)
    {
      const int k = reverse_z ? nz - 1 - kk : kk;
      for(int jj = 0; jj < ny; ++jj)
      {
        const int j = reverse_y ? ny - 1 - jj : jj;
        for(int ii = 0; ii < nx; ++ii)
        {
          const int i = reverse_x ? nx - 1 - ii : ii;
          const std::size_t n = grid_.index(i, j, k);
          if(!active_[n]) continue;
          const double old = d[n];
          if(old == 0.) continue;
          double best = old;
          const bool interior = i > 0 && j > 0 && k > 0 && i < nx - 1 && j < ny - 1 && k < nz - 1;
          bool any = false;
          for(int v = 0; v < V; ++v)
          {
            if(interior || (unsigned(i + offsets_[v][0]) < unsigned(nx) && unsigned(j + offsets_[v][1]) < unsigned(ny)
                            && unsigned(k + offsets_[v][2]) < unsigned(nz)))
            {
              nd[v] = d[n + shift[v]]; // +inf for inactive nodes
              nl[v] = label[n + shift[v]];
              any = any || nd[v] < best;
            }
            else
              nd[v] = inf;
          }
          if(!any) continue;
          int best_label = label[n];
          fan_update(n, nd.data(), nl.data(), best, best_label);
          if(best < old)
          {
            d[n] = best;
            label[n] = best_label;
            if(!(old - best <= options_.tolerance * best)) changed = true;
          }
        }
      }
    }
    return changed;
  }

  Grid_3 grid_;
  std::vector<char> active_;
  Fast_sweeping_options options_;
  std::vector<Eigen::Matrix3d> metric_, inverse_; // in index units (h^2 M and its inverse)
  std::vector<internal::Selling_decomposition_3> selling_; // of the inverse metric, in index units
  std::vector<char> border_; // Selling scheme: some neighbour of the node's stencil is missing
  std::vector<std::pair<Source_factor, bool>> factors_; // per label: point sources only
  std::vector<std::uint32_t> reverse_start_, reverse_;       // reverse stencils (compressed rows)
  std::vector<Offset> offsets_;
  std::vector<std::array<int, 2>> edges_;
  std::vector<Face> faces_;
  std::vector<std::vector<int>> vertex_edges_, vertex_faces_; // per fan vertex, the simplices containing it
  std::vector<std::vector<int>> vertex_star_;                  // per fan vertex, the vertices of its simplices
  std::vector<int> all_edges_, all_faces_;                     // 0, 1, 2, ...
  std::array<int, 27> fan_vertex_at_;                          // fan vertex of an offset in [-1,1]^3, or -1
  std::vector<Point_source> point_sources_;
  std::vector<Node_source> node_sources_;
  int next_label_ = 0;
};

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_CONTINUOUS_FAST_SWEEPING_3_H
