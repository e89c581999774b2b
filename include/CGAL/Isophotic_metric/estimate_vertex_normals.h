// Vertex normals robust to noise at a given scale, for the lift of scanned meshes: a rolling-guidance
// bilateral filter of the face normals (Wang, Fu, Zhang, Liu, Tai, "Rolling guidance normal filter for
// geometric processing", ACM TOG 34(6), 2015; the bilateral normal filter of Zheng et al. 2011 with a
// guidance that starts from the Gaussian-smoothed normals and, near sharp edges, from the most
// consistent patches of Zhang et al. 2015, chosen per face), rounds of vertex updates on a private copy of
// the positions each followed by the filter again (Sun et al. 2007), then Max's vertex weights.
#ifndef CGAL_ISOPHOTIC_METRIC_ESTIMATE_VERTEX_NORMALS_H
#define CGAL_ISOPHOTIC_METRIC_ESTIMATE_VERTEX_NORMALS_H

#include <CGAL/Isophotic_metric/exceptions.h>
#include <CGAL/Isophotic_metric/Named_function_parameters.h>
#include <CGAL/Isophotic_metric/validate_triangle_mesh.h>
#include <CGAL/Isophotic_metric/internal/for_each_index.h>
#include <CGAL/Isophotic_metric/internal/sphere_exact_vertex_normals.h>

#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/tags.h>

#include <boost/graph/graph_traits.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {
namespace internal {

inline std::array<double, 3> normalized(const std::array<double, 3>& v)
{
  const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if(!(length > 0.))
    return {0., 0., 0.};
  return {v[0] / length, v[1] / length, v[2] / length};
}

inline double squared_distance_3(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  const std::array<double, 3> d = difference(a, b);
  return d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
}

// The squared distance of two unit vectors `degrees` apart.
inline double squared_chord(double degrees)
{
  return 2. - 2. * std::cos(degrees * std::acos(-1.) / 180.);
}

// The faces of the edge-connected region around each face whose centroids lie within a radius of
// the face's centroid, visited by a breadth-first walk (so a filter never reaches across a thin
// wall or a gap, as a search in space would), in the order of the walk (the order of the filter's
// sums). Every pass of the filter reads the discs again; they are walked from an array of face
// neighbours into one reusable buffer, at every read or once for the discs that Face_discs keeps: kept
// lists of all radii cost hundreds of faces per face (a quarter of a gigabyte on a 52k-face mesh,
// growing with the square of rho), while a walk costs about as much as the pass that reads it.
// Face_disc_graph holds what all walks read (the neighbours, centroids, areas); a Face_disc_walker holds
// the buffers of one walk at a time, so each thread walks with its own walker.
class Face_disc_graph
{
public:
  // `faces` are the faces of `tm` in the order of the other arrays (their index in the filter); they are
  // triangles (the filter runs on validated meshes).
  template <typename TriangleMesh>
  Face_disc_graph(const TriangleMesh& tm,
                  const std::vector<typename boost::graph_traits<TriangleMesh>::face_descriptor>& faces,
                  const std::vector<std::array<double, 3>>& centroids, const std::vector<double>& area)
    : centroids_(centroids), area_(area), neighbours_(faces.size())
  {
    auto index = get(CGAL::dynamic_face_property_t<std::uint32_t>(), tm);
    for(std::size_t i = 0; i < faces.size(); ++i)
      put(index, faces[i], std::uint32_t(i));
    for(std::size_t i = 0; i < faces.size(); ++i)
    {
      int k = 0;
      for(const auto h : CGAL::halfedges_around_face(halfedge(faces[i], tm), tm))
      {
        const auto g = face(opposite(h, tm), tm);
        neighbours_[i][k++] = g == boost::graph_traits<TriangleMesh>::null_face() ? no_face : get(index, g);
      }
    }
  }

  std::size_t number_of_faces() const { return neighbours_.size(); }

private:
  friend class Face_disc_walker;
  static constexpr std::uint32_t no_face = std::uint32_t(-1);
  const std::vector<std::array<double, 3>>& centroids_;
  const std::vector<double>& area_;
  std::vector<std::array<std::uint32_t, 3>> neighbours_; // across the three edges of each triangle
};

// The buffers of one walk at a time over a Face_disc_graph (one walker per thread).
class Face_disc_walker
{
public:
  explicit Face_disc_walker(const Face_disc_graph& graph) : graph_(&graph), stamp_(graph.number_of_faces(), 0) {}

  // The faces of the disc of radius `radius` around face i, in the order of the walk (face i first),
  // valid until the next walk.
  const std::vector<std::uint32_t>& faces_within(std::size_t i, double radius)
  {
    const double squared_radius = radius * radius;
    if(++generation_ == 0) // the stamps wrapped around: none is current
    {
      std::fill(stamp_.begin(), stamp_.end(), 0u);
      generation_ = 1;
    }
    queue_.clear();
    squared_distance_.clear();
    queue_.push_back(std::uint32_t(i));
    squared_distance_.push_back(0.);
    stamp_[i] = generation_;
    for(std::size_t next = 0; next < queue_.size(); ++next)
      for(const std::uint32_t k : graph_->neighbours_[queue_[next]])
      {
        if(k == Face_disc_graph::no_face || stamp_[k] == generation_)
          continue;
        stamp_[k] = generation_;
        const double squared_distance = squared_distance_3(graph_->centroids_[i], graph_->centroids_[k]);
        if(squared_distance <= squared_radius)
        {
          queue_.push_back(k);
          squared_distance_.push_back(squared_distance);
        }
      }
    return queue_;
  }

  // The faces [first, last) of a disc around face i kept from an earlier walk, as faces_within() gives
  // them.
  const std::vector<std::uint32_t>& faces_kept(std::size_t i, const std::uint32_t* first, const std::uint32_t* last)
  {
    queue_.assign(first, last);
    squared_distance_.resize(queue_.size());
    for(std::size_t k = 0; k < queue_.size(); ++k)
      squared_distance_[k] = squared_distance_3(graph_->centroids_[i], graph_->centroids_[queue_[k]]);
    return queue_;
  }

  // The spatial weights area_j exp(-d^2 / 2 s^2) of the faces j of the disc last walked, d the distance
  // of the centroids, s `spatial_scale`; valid until the next call.
  const std::vector<double>& spatial_weights(double spatial_scale)
  {
    const double spatial = -0.5 / (spatial_scale * spatial_scale);
    weight_.resize(queue_.size());
    for(std::size_t k = 0; k < queue_.size(); ++k)
      weight_[k] = graph_->area_[queue_[k]] * std::exp(spatial * squared_distance_[k]);
    return weight_;
  }

private:
  const Face_disc_graph* graph_;
  std::vector<unsigned> stamp_;
  unsigned generation_ = 0;
  std::vector<std::uint32_t> queue_;
  std::vector<double> squared_distance_; // of the centroids to face i's, for the faces in queue_
  std::vector<double> weight_;
};

// Grain of the loops over faces (for_each_index): a face's disc is a few hundred faces, a short task.
constexpr std::size_t faces_per_task = 256;

// The discs of one radius, and the spatial scale of their weights, walked at every read or, after
// keep(), walked once and kept as lists of faces (4 bytes per face of each disc). A read walks with the
// walker it is given, so threads reading with their own walkers do not share a buffer.
class Face_discs
{
public:
  Face_discs(const Face_disc_graph& graph, double radius, double spatial_scale = 0.)
    : graph_(&graph), radius_(radius), spatial_scale_(spatial_scale)
  {}

  // Walks every disc once and keeps it: in blocks of consecutive faces, each allocated to its size once
  // walked (no list copied as it grows), the blocks walked in parallel with CGAL::Parallel_tag.
  template <class ConcurrencyTag>
  void keep()
  {
    const std::size_t n = graph_->number_of_faces();
    end_.assign(n, 0);
    blocks_.assign((n + faces_per_block - 1) / faces_per_block, {});
    struct Block_walker
    {
      Face_disc_walker walker;
      std::vector<std::uint32_t> block;
    };
    for_each_index<ConcurrencyTag>(blocks_.size(), 1, [&] { return Block_walker{Face_disc_walker(*graph_), {}}; },
                                   [&](Block_walker& local, std::size_t b) {
      local.block.clear();
      for(std::size_t i = b * faces_per_block; i < std::min((b + 1) * faces_per_block, n); ++i)
      {
        const std::vector<std::uint32_t>& disc = local.walker.faces_within(i, radius_);
        local.block.insert(local.block.end(), disc.begin(), disc.end());
        end_[i] = std::uint32_t(local.block.size());
      }
      blocks_[b].assign(local.block.begin(), local.block.end());
    });
  }

  // See Face_disc_walker::faces_within() and spatial_weights(); `walker` walks the graph of these discs.
  const std::vector<std::uint32_t>& faces(Face_disc_walker& walker, std::size_t i) const
  {
    if(blocks_.empty())
      return walker.faces_within(i, radius_);
    const std::vector<std::uint32_t>& block = blocks_[i / faces_per_block];
    return walker.faces_kept(i, block.data() + (i % faces_per_block == 0 ? 0 : end_[i - 1]), block.data() + end_[i]);
  }
  const std::vector<double>& spatial_weights(Face_disc_walker& walker) const
  {
    return walker.spatial_weights(spatial_scale_);
  }
  const Face_disc_graph& graph() const { return *graph_; }

private:
  static constexpr std::size_t faces_per_block = 1024;
  const Face_disc_graph* graph_;
  double radius_, spatial_scale_;
  std::vector<std::vector<std::uint32_t>> blocks_; // the kept lists
  std::vector<std::uint32_t> end_;                 // the disc of face i ends at end_[i] in its block
};

// The guidance of the patch filter (after Zhang, Deng, Zhang, Bouaziz, Liu, "Guided mesh normal
// filtering", Computer Graphics Forum 34(7), 2015): every face takes the mean raw normal of the most
// consistent patch that contains it, among the `discs` (radius rho / 2) around the faces near it.
// Consistency is the spread 1 - |m|^2 of the unit normals around their area-weighted mean m (zero
// when they all agree). A face beside a sharp edge lies in discs that straddle the edge and in discs
// that lie mostly on either side; the straddling ones spread more and lose, so its guidance is the
// normal of one side, where a Gaussian guidance would mix the two sides.
// Which side is left to the noise by the spread alone: the face is at the rim of the discs of both
// sides, and their spreads differ by the noise only. So when a disc of the other side (mean more
// than 30 degrees from the most consistent one) is nearly as consistent (spread within 1.5 times),
// the face takes that side if its own raw normal is clearly closer to it: the face's own tilt tells
// in which plane it lies. "Clearly" keeps the noise of single faces out of the smooth regions, where
// two discs can differ by more than 30 degrees along a narrow fillet.
template <class ConcurrencyTag>
std::vector<std::array<double, 3>> consistent_patch_guidance(const Face_discs& discs,
                                                                    const std::vector<std::array<double, 3>>& raw,
                                                                    const std::vector<double>& area)
{
  const double other_side = 2. - std::sqrt(3.); // the squared chord of 30 degrees, 2 - 2 cos 30
  const double nearly_as_consistent = 1.5;
  const double clearly_closer = 0.5; // a difference of squared chords (0.5: the squared chord of 41 degrees)
  const auto walker = [&] { return Face_disc_walker(discs.graph()); };
  std::vector<std::array<double, 3>> mean(raw.size());
  std::vector<double> spread(raw.size());
  for_each_index<ConcurrencyTag>(raw.size(), faces_per_task, walker, [&](Face_disc_walker& local, std::size_t i) {
    std::array<double, 3> sum = {0., 0., 0.};
    double total = 0.;
    for(const std::uint32_t j : discs.faces(local, i))
    {
      for(int k = 0; k < 3; ++k)
        sum[k] += area[j] * raw[j][k];
      total += area[j];
    }
    mean[i] = total > 0. ? std::array<double, 3>{sum[0] / total, sum[1] / total, sum[2] / total} : raw[i];
    spread[i] = 1. - (mean[i][0] * mean[i][0] + mean[i][1] * mean[i][1] + mean[i][2] * mean[i][2]);
  });
  std::vector<std::array<double, 3>> guidance(raw.size());
  for_each_index<ConcurrencyTag>(raw.size(), faces_per_task, walker, [&](Face_disc_walker& local, std::size_t i) {
    const std::vector<std::uint32_t>& disc = discs.faces(local, i);
    std::size_t most_consistent = i;
    for(const std::uint32_t j : disc)
      if(spread[j] < spread[most_consistent])
        most_consistent = j;
    const std::array<double, 3> side = normalized(mean[most_consistent]);
    std::size_t best_other = raw.size(); // the most consistent disc of the other side, if any
    for(const std::uint32_t j : disc)
      if(squared_distance_3(normalized(mean[j]), side) > other_side &&
         (best_other == raw.size() || spread[j] < spread[best_other]))
        best_other = j;
    guidance[i] = side;
    if(best_other != raw.size() && spread[best_other] <= nearly_as_consistent * spread[most_consistent])
    {
      const std::array<double, 3> other = normalized(mean[best_other]);
      if(squared_distance_3(other, raw[i]) + clearly_closer < squared_distance_3(side, raw[i]))
        guidance[i] = other;
    }
  });
  return guidance;
}

// The faces within their `reach_discs` (4 rho) of a sharp edge, for the guidance chosen per face: a face
// is beside a sharp edge when a face of its `beside_discs` (rho / 2) has a normal more than 35 degrees
// away. The normals are those of the filter with the Gaussian guidance and the flat range, whose noise
// is a few degrees and whose sharp edges turn within a face or two; a fillet of radius r turns by
// (rho / 2) / r within that radius, about 20 degrees for r = 1.4 rho (box_fillet_r4 at the suggested scale).
template <class ConcurrencyTag>
std::vector<char> faces_near_sharp_edges(const Face_discs& beside_discs, const Face_discs& reach_discs,
                                         const std::vector<std::array<double, 3>>& normals)
{
  const double sharp_turn = squared_chord(35.);
  const auto walker = [&] { return Face_disc_walker(beside_discs.graph()); };
  std::vector<char> beside(normals.size(), 0), near(normals.size(), 0);
  for_each_index<ConcurrencyTag>(normals.size(), faces_per_task, walker, [&](Face_disc_walker& local, std::size_t i) {
    for(const std::uint32_t j : beside_discs.faces(local, i))
      if(squared_distance_3(normals[i], normals[j]) > sharp_turn)
        beside[i] = 1;
  });
  for_each_index<ConcurrencyTag>(normals.size(), faces_per_task, walker, [&](Face_disc_walker& local, std::size_t i) {
    for(const std::uint32_t j : reach_discs.faces(local, i))
      if(beside[j])
        near[i] = 1;
  });
  return near;
}

// Whether face i lies on an evenly curved region (a fillet) at the scale `s` of the spatial weights
// `weights` of its disc `disc` (radius 2 s): at least 30 % of the spatial weight of the disc has normals
// between 8 and 50 degrees away, turned by the curvature; on a plane they agree within a few degrees,
// beside a sharp edge they lie on one side or the other. The refinement passes leave these faces alone:
// a range of 3 degrees finds no agreeing neighbour on a fillet and would fall back to the face's own
// raw normal.
inline bool on_curved_region(std::size_t i, const std::vector<std::uint32_t>& disc, const std::vector<double>& weights,
                             const std::vector<std::array<double, 3>>& normals)
{
  const double least_turn = squared_chord(8.), most_turn = squared_chord(50.);
  double total = 0., turned = 0.;
  for(std::size_t k = 0; k < disc.size(); ++k)
  {
    const double chord = squared_distance_3(normals[i], normals[disc[k]]);
    total += weights[k];
    if(chord > least_turn && chord < most_turn)
      turned += weights[k];
  }
  return turned >= 0.3 * total;
}

} // namespace internal

namespace internal {

// The raw unit normal (zero for a zero-area face, which then carries no weight), the area and the centroid
// of every face, from the positions of its corners (`corners`: three indices into `positions` per face,
// in the order source(h), target(h), target(next(h)) of its halfedge h).
inline void face_geometry(const std::vector<std::array<double, 3>>& positions,
                          const std::vector<std::array<std::uint32_t, 3>>& corners,
                          std::vector<std::array<double, 3>>& raw, std::vector<std::array<double, 3>>& centroid,
                          std::vector<double>& area)
{
  raw.resize(corners.size());
  centroid.resize(corners.size());
  area.resize(corners.size());
  for(std::size_t i = 0; i < corners.size(); ++i)
  {
    const std::array<double, 3>& a = positions[corners[i][0]];
    const std::array<double, 3>& b = positions[corners[i][1]];
    const std::array<double, 3>& c = positions[corners[i][2]];
    const std::array<double, 3> u = internal::difference(b, a), v = internal::difference(c, a);
    const std::array<double, 3> cross = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    raw[i] = internal::normalized(cross);
    area[i] = 0.5 * std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]);
    centroid[i] = {(a[0] + b[0] + c[0]) / 3., (a[1] + b[1] + c[1]) / 3., (a[2] + b[2] + c[2]) / 3.};
  }
}

// One step of the least-squares vertex update of Sun, Rosin, Martin, Langbein ("Fast and effective
// feature-preserving mesh denoising", IEEE TVCG 13(5), 2007): every vertex moves towards the planes of its
// faces, x_v += (1 / |F(v)|) sum_{f in F(v)} n_f (n_f . (c_f - x_v)), n_f the filtered normal, c_f the
// face's `centroid` in `positions`. It moves the positions that the next filter reads so that its raw
// normals carry less noise; every vertex is moved from the given positions (from its own faces, in the
// order of their index), so the threads give the same result. (One step a round, measured on the figure
// of merit, benchmark/README.md, section "Vertex updates between the filter passes": more steps move the
// vertices beside sharp edges after the faces whose normal took the wrong side, and anchor_dense and
// l_bracket leak more with each step.)
// `faces_of` / `first_face`: the faces of vertex v are faces_of[first_face[v], first_face[v + 1]).
template <class ConcurrencyTag>
void update_vertices(std::vector<std::array<double, 3>>& positions, const std::vector<std::array<double, 3>>& centroid,
                     const std::vector<std::uint32_t>& faces_of, const std::vector<std::size_t>& first_face,
                     const std::vector<std::array<double, 3>>& normals)
{
  std::vector<std::array<double, 3>> next(positions.size());
  for_each_index<ConcurrencyTag>(positions.size(), 1024, [] { return 0; }, [&](int&, std::size_t v) {
    const std::array<double, 3>& x = positions[v];
    std::array<double, 3> move = {0., 0., 0.};
    for(std::size_t k = first_face[v]; k < first_face[v + 1]; ++k)
    {
      const std::array<double, 3>& n = normals[faces_of[k]];
      const std::array<double, 3> d = internal::difference(centroid[faces_of[k]], x);
      const double along = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
      for(int c = 0; c < 3; ++c)
        move[c] += along * n[c];
    }
    const std::size_t count = first_face[v + 1] - first_face[v];
    next[v] = x;
    if(count > 0)
      for(int c = 0; c < 3; ++c)
        next[v][c] += move[c] / double(count);
  });
  positions.swap(next);
}

constexpr unsigned max_vertex_updates = 10;

// The rounds of vertex updates (named parameter number_of_vertex_updates), each followed by the filter
// again on the moved positions: one by default with the guidance chosen per face; none with
// use_patch_guidance, whose normals stay those of before.
template <typename NamedParameters>
unsigned number_of_vertex_updates(const NamedParameters& np)
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  constexpr int default_updates =
    parameters::is_default_parameter<NamedParameters, internal_np::use_patch_guidance_t>::value ? 1 : 0;
  const double updates =
    double(choose_parameter(get_parameter(np, internal_np::number_of_vertex_updates), default_updates));
  if(!(updates >= 0. && updates <= double(max_vertex_updates) && updates == std::floor(updates)))
    throw Invalid_parameter_error(message("number_of_vertex_updates is ", updates, "; it must be an integer from 0 to ",
                                          max_vertex_updates));
  return unsigned(updates);
}

// The passes of the filter on the faces `face_list` of `tm` with their raw normals, centroids and areas
// (filtered_face_normals() with the parameters read).
template <class ConcurrencyTag, typename TriangleMesh>
std::vector<std::array<double, 3>>
filter_passes(const TriangleMesh& tm, const std::vector<typename boost::graph_traits<TriangleMesh>::face_descriptor>& face_list,
              const std::vector<std::array<double, 3>>& raw, const std::vector<std::array<double, 3>>& centroid,
              const std::vector<double>& area, double scale, double range, unsigned iterations, bool automatic,
              bool patch_guidance)
{
  // Every pass averages the raw normals within 2 s (s = rho; 2 rho for the refinement passes), with the
  // spatial weight of the scale s and a range weight on the guidance: exp(-x) (Gaussian) or, where
  // `flat_range`, exp(-x^2) with x = |g_i - g_j|^2 / 2 range_i^2, a weight that stays near 1 for the turn
  // of a fillet within the window and falls faster beyond. A face that `keeps` its normal is not
  // averaged (refinement passes). The discs have three radii: rho / 2 (the patches and the sharp-edge
  // marks), 2 rho (the passes at the scale rho), 4 rho (the refinement passes at 2 rho, the marks).
  // Every loop over the faces computes each face from the arrays of the previous loop only, so they run
  // in parallel (each thread walks with its own Face_disc_walker) with the same results bit for bit.
  const internal::Face_disc_graph graph(tm, face_list, centroid, area);
  const auto walker = [&] { return internal::Face_disc_walker(graph); };
  const std::size_t grain = internal::faces_per_task;
  internal::Face_discs half_discs(graph, 0.5 * scale), discs(graph, 2. * scale, scale),
    double_discs(graph, 4. * scale, 2. * scale);
  discs.keep<ConcurrencyTag>();
  std::vector<std::array<double, 3>> guidance, next(raw.size());
  std::vector<double> range_of(raw.size(), range);
  std::vector<char> flat_range(raw.size(), 0), keeps(raw.size(), 0);
  // The filtered normal of face i from its disc and their spatial weights.
  auto filtered_normal = [&](std::size_t i, const std::vector<std::uint32_t>& disc,
                             const std::vector<double>& spatial_weights, bool refinement) {
    const double pass_range = refinement ? 0.05 : range_of[i];
    const double ranged = 0.5 / (pass_range * pass_range);
    const bool flat = flat_range[i] && !refinement;
    std::array<double, 3> sum = {0., 0., 0.};
    for(std::size_t k = 0; k < disc.size(); ++k)
    {
      const std::size_t j = disc[k];
      double weight = spatial_weights[k];
      if(!guidance.empty())
      {
        const double x = ranged * internal::squared_distance_3(guidance[i], guidance[j]);
        weight *= std::exp(flat ? -x * x : -x);
      }
      for(int c = 0; c < 3; ++c)
        sum[c] += weight * raw[j][c];
    }
    return internal::normalized(sum);
  };
  // next[i] from guidance (the previous pass) only
  auto rolling_guidance_pass = [&](const internal::Face_discs& pass_discs, bool refinement) {
    next.resize(raw.size());
    internal::for_each_index<ConcurrencyTag>(raw.size(), grain, walker, [&](internal::Face_disc_walker& local, std::size_t i) {
      if(refinement && keeps[i])
        next[i] = guidance[i];
      else
      {
        const std::vector<std::uint32_t>& disc = pass_discs.faces(local, i);
        next[i] = filtered_normal(i, disc, pass_discs.spatial_weights(local), refinement);
      }
    });
    guidance.swap(next);
  };
  // Two refinement passes over twice the radius (rolling_guidance_pass(double_discs, true)) average only
  // faces whose normals already agree within about 3 degrees. The isophotic metric scales the normals by
  // a length of the size of the part, so the residual noise of the first radius still makes a planar
  // face long to cross; these passes remove it inside flat regions and beside sharp edges without
  // averaging across the edge.

  if(!automatic)
  {
    // One guidance for all faces: the Gaussian pass (guidance empty) or the most consistent patches,
    // then rolling-guidance passes; the refinement passes with the patch guidance.
    if(patch_guidance)
      guidance = internal::consistent_patch_guidance<ConcurrencyTag>(half_discs, raw, area);
    for(unsigned pass = patch_guidance ? 1 : 0; pass <= iterations; ++pass)
      rolling_guidance_pass(discs, false);
    if(patch_guidance)
      for(int pass = 0; pass < 2; ++pass)
        rolling_guidance_pass(double_discs, true);
    return guidance;
  }

  // Chosen per face. First the Gaussian guidance with the flat range everywhere: good on fillets,
  // it rounds sharp edges a little but leaves them steep enough to be found. Then the faces within
  // 4 rho of a sharp edge start again from the patch guidance with half the range (a Gaussian weight),
  // which keeps the two sides apart; the others go on from their filtered normals. Last, the
  // refinement passes, except on the curved regions away from sharp edges.
  std::fill(flat_range.begin(), flat_range.end(), 1);
  for(unsigned pass = 0; pass <= iterations; ++pass)
    rolling_guidance_pass(discs, false);
  const std::vector<char> near_sharp_edge =
    internal::faces_near_sharp_edges<ConcurrencyTag>(half_discs, double_discs, guidance);
  const std::vector<std::array<double, 3>> patch =
    internal::consistent_patch_guidance<ConcurrencyTag>(half_discs, raw, area);
  for(std::size_t i = 0; i < raw.size(); ++i)
    if(near_sharp_edge[i])
    {
      guidance[i] = patch[i];
      range_of[i] = 0.5 * range;
      flat_range[i] = 0;
    }
  for(unsigned pass = 1; pass <= iterations; ++pass)
    rolling_guidance_pass(discs, false);
  // The first refinement pass finds the curved regions on the discs it walks (the guidance it reads).
  next.resize(raw.size());
  internal::for_each_index<ConcurrencyTag>(raw.size(), grain, walker, [&](internal::Face_disc_walker& local, std::size_t i) {
    const std::vector<std::uint32_t>& disc = double_discs.faces(local, i);
    const std::vector<double>& spatial_weights = double_discs.spatial_weights(local);
    keeps[i] = !near_sharp_edge[i] && internal::on_curved_region(i, disc, spatial_weights, guidance);
    next[i] = keeps[i] ? guidance[i] : filtered_normal(i, disc, spatial_weights, true);
  });
  guidance.swap(next);
  rolling_guidance_pass(double_discs, true);

  return guidance;
}

// The filtered unit normal of every face, in the order of faces(tm): estimate_vertex_normals() before
// its vertex weights (the tests measure these normals on the faces beside sharp edges).
template <class ConcurrencyTag = CGAL::Parallel_if_available_tag, typename TriangleMesh, typename NamedParameters>
std::vector<std::array<double, 3>> filtered_face_normals(const TriangleMesh& tm, double scale,
                                                         const NamedParameters& np, bool validate_mesh)
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  using internal::message;

  typedef boost::graph_traits<TriangleMesh> Graph_traits;
  typedef typename Graph_traits::face_descriptor face_descriptor;

  if(!(std::isfinite(scale) && scale > 0.))
    throw Invalid_parameter_error(message("the normal smoothing scale is ", scale, "; it must be finite and positive"));
  const double range = CGAL::to_double(choose_parameter(get_parameter(np, internal_np::normal_range), 0.6));
  if(!(std::isfinite(range) && range > 0.))
    throw Invalid_parameter_error(message("normal_range is ", range, "; it must be finite and positive"));
  const unsigned iterations = choose_parameter(get_parameter(np, CGAL::internal_np::number_of_iterations), 5u);
  // use_patch_guidance given: one guidance for all faces; not given: chosen per face
  constexpr bool automatic = parameters::is_default_parameter<NamedParameters, internal_np::use_patch_guidance_t>::value;
  const bool patch_guidance = choose_parameter(get_parameter(np, internal_np::use_patch_guidance), false);
  const unsigned vertex_updates = number_of_vertex_updates(np);

  if(validate_mesh)
    validate_triangle_mesh(tm, np);
  const auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                                    get_const_property_map(CGAL::vertex_point, tm));

  // Per face: unit normal (zero for a zero-area face, which then carries no weight), area, centroid.
  // (This loop, and not face_geometry(), for the given positions: the same code as before the vertex
  // updates, so that the compiler's fused multiply-adds, and with them the normals, stay the same bit for bit.)
  std::vector<face_descriptor> face_list;
  std::vector<std::array<double, 3>> raw, centroid;
  std::vector<double> area;
  for(face_descriptor f : faces(tm))
  {
    const auto h = halfedge(f, tm);
    const std::array<double, 3> a = internal::to_array(get(vpm, source(h, tm)));
    const std::array<double, 3> b = internal::to_array(get(vpm, target(h, tm)));
    const std::array<double, 3> c = internal::to_array(get(vpm, target(next(h, tm), tm)));
    const std::array<double, 3> u = internal::difference(b, a), v = internal::difference(c, a);
    const std::array<double, 3> cross = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    face_list.push_back(f);
    raw.push_back(internal::normalized(cross));
    area.push_back(0.5 * std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]));
    centroid.push_back({(a[0] + b[0] + c[0]) / 3., (a[1] + b[1] + c[1]) / 3., (a[2] + b[2] + c[2]) / 3.});
  }
  std::vector<std::array<double, 3>> filtered =
    filter_passes<ConcurrencyTag>(tm, face_list, raw, centroid, area, scale, range, iterations, automatic, patch_guidance);
  if(vertex_updates == 0)
    return filtered;

  // The positions (a private copy: the vertex updates move it, never the mesh) and the corners of the faces.
  auto vertex_index = get(CGAL::dynamic_vertex_property_t<std::uint32_t>(), tm);
  std::vector<std::array<double, 3>> positions;
  for(const auto v : vertices(tm))
  {
    put(vertex_index, v, std::uint32_t(positions.size()));
    positions.push_back(internal::to_array(get(vpm, v)));
  }
  std::vector<std::array<std::uint32_t, 3>> corners;
  for(face_descriptor f : face_list)
  {
    const auto h = halfedge(f, tm);
    corners.push_back({get(vertex_index, source(h, tm)), get(vertex_index, target(h, tm)),
                       get(vertex_index, target(next(h, tm), tm))});
  }

  // Outer iterations (Sun et al. 2007; Zheng et al. 2011): move the private positions onto the planes of
  // the filtered normals, then filter the normals of the moved faces again from the start. The noise of
  // the positions, which the filter alone keeps in every raw normal it averages, is reduced at each round.
  std::vector<std::size_t> first_face(positions.size() + 1, 0);
  for(const auto& c : corners)
    for(const std::uint32_t v : c)
      ++first_face[v + 1];
  for(std::size_t v = 0; v < positions.size(); ++v)
    first_face[v + 1] += first_face[v];
  std::vector<std::uint32_t> faces_of(first_face.back());
  {
    std::vector<std::size_t> fill(first_face.begin(), first_face.end() - 1);
    for(std::size_t i = 0; i < corners.size(); ++i)
      for(const std::uint32_t v : corners[i])
        faces_of[fill[v]++] = std::uint32_t(i);
  }
  for(unsigned round = 0; round < vertex_updates; ++round)
  {
    internal::update_vertices<ConcurrencyTag>(positions, centroid, faces_of, first_face, filtered);
    internal::face_geometry(positions, corners, raw, centroid, area);
    filtered =
      filter_passes<ConcurrencyTag>(tm, face_list, raw, centroid, area, scale, range, iterations, automatic, patch_guidance);
  }
  return filtered;
}

// estimate_vertex_normals(); the lift calls it with `validate_mesh = false` on the mesh it has
// already validated, so that smoothing does not validate the mesh a second time.
template <class ConcurrencyTag = CGAL::Parallel_if_available_tag, typename TriangleMesh, typename VertexNormalMap,
          typename NamedParameters>
void estimate_vertex_normals(const TriangleMesh& tm, double scale, VertexNormalMap normals,
                             const NamedParameters& np, bool validate_mesh)
{
  using parameters::choose_parameter;
  using parameters::get_parameter;

  typedef boost::graph_traits<TriangleMesh> Graph_traits;
  typedef typename Graph_traits::vertex_descriptor vertex_descriptor;
  typedef typename boost::property_traits<VertexNormalMap>::value_type Normal;

  const std::vector<std::array<double, 3>> filtered =
    filtered_face_normals<ConcurrencyTag>(tm, scale, np, validate_mesh);
  // Max's weights from the given positions (measured against the moved ones: benchmark/README.md, section
  // "Vertex updates between the filter passes").
  const auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                                    get_const_property_map(CGAL::vertex_point, tm));

  // Vertex normals: Max's weights on the filtered face normals.
  auto filtered_of = get(CGAL::dynamic_face_property_t<std::array<double, 3>>(), tm);
  std::size_t i = 0;
  for(const auto f : faces(tm))
    put(filtered_of, f, filtered[i++]);
  for(vertex_descriptor v : vertices(tm))
  {
    std::array<double, 3> n = {0., 0., 0.};
    if(halfedge(v, tm) != Graph_traits::null_halfedge())
    {
      const std::array<double, 3> p = internal::to_array(get(vpm, v));
      for(const auto h : CGAL::halfedges_around_target(halfedge(v, tm), tm))
      {
        if(is_border(h, tm))
          continue;
        const std::array<double, 3> e1 = internal::difference(internal::to_array(get(vpm, source(h, tm))), p);
        const std::array<double, 3> e2 = internal::difference(internal::to_array(get(vpm, target(next(h, tm), tm))), p);
        const std::array<double, 3> cross = {e2[1] * e1[2] - e2[2] * e1[1], e2[2] * e1[0] - e2[0] * e1[2],
                                             e2[0] * e1[1] - e2[1] * e1[0]};
        const double l1 = e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2];
        const double l2 = e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2];
        const double weight = std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]) / (l1 * l2);
        const std::array<double, 3>& nf = get(filtered_of, face(h, tm));
        for(int k = 0; k < 3; ++k)
          n[k] += weight * nf[k];
      }
      n = internal::normalized(n);
    }
    put(normals, v, Normal{n[0], n[1], n[2]});
  }
}

} // namespace internal

/// \ingroup PkgIsophoticMetricLift
///
/// \brief computes vertex normals of `tm` that are robust to noise at the scale `scale`, and keep
/// sharp edges sharp, for the lift of scanned meshes (named parameter `normal_smoothing_scale` of
/// `compute_lifted_embedding()`).
///
/// On a scan the normals of the triangles are noisy at the scale of a triangle, and the normal part
/// of the isophotic metric then measures the noise: a planar face becomes as long to cross as a
/// feature. This function filters the face normals with a rolling-guidance bilateral filter (Wang et
/// al. 2015): each face normal is replaced by the area-weighted average of the original normals of the
/// faces around it, with a spatial weight \f$ \exp(-d^2/2\rho^2) \f$ (`d` the distance between the
/// centroids, \f$ \rho \f$ = `scale`, faces reached across edges within \f$ 2\rho \f$) and a range weight
/// \f$ \exp(-\|g_i - g_j\|^2/2\sigma_r^2) \f$ on the difference of a guidance normal `g`. The guidance
/// starts as the Gaussian average (no range weight), which removes the noise but rounds the features,
/// and is then replaced by the result of the previous iteration: faces on either side of a sharp edge
/// stop averaging each other, so the edge becomes sharp again while the noise stays removed.
/// The guidance is chosen per face (the default): after these passes with the Gaussian first guidance
/// and a flat range weight \f$ \exp(-(\|g_i - g_j\|^2/2\sigma_r^2)^2) \f$ (near 1 for the turn of a
/// fillet within the window, falling fast beyond), the faces within \f$ 4\rho \f$ of a sharp edge (a
/// face within \f$ \rho/2 \f$ whose filtered normal is more than 35 degrees away) start again from the
/// most consistent patch around them (see `use_patch_guidance`) with the range \f$ \sigma_r/2 \f$,
/// which keeps the two sides of the edge apart; the other faces go on from their filtered normals. Two
/// refinement passes follow (see `use_patch_guidance`), except on the curved regions away from sharp
/// edges (at least 30 % of the window's weight with normals 8 to 50 degrees away), where no neighbour
/// agrees within their range. So fillets stay round and sharp edges sharp with one default.
/// With `use_patch_guidance(true)` or `use_patch_guidance(false)`, one guidance serves all faces.
/// Then, by default with the guidance chosen per face, one round of vertex updates (Sun et al. 2007,
/// the outer iteration of Zheng et al. 2011): a private copy of the vertex positions is moved once
/// towards the planes of the filtered normals of its faces, and the raw normals of the moved faces are
/// filtered again from the start (see `number_of_vertex_updates`); the mesh and its positions are not changed.
/// The vertex normal is then the sum of the filtered normals of its faces with the weights of the
/// default normal of `compute_lifted_embedding()` (Max 1999), so that in a planar region all vertex
/// normals are equal, as on a clean mesh.
///
/// `scale` is the radius of the features that are kept: a bend of radius smaller than about
/// \f$ \rho \f$ becomes a sharp edge, a bump smaller than \f$ \rho \f$ disappears. See
/// `suggested_normal_smoothing_scale()` for a scale derived from the mesh.
///
/// The cost is linear in the number of faces times the number of faces within \f$ 2\rho \f$ of one face,
/// times the number of vertex updates plus one (the filter runs once more after each round),
/// times the number of iterations plus one with `use_patch_guidance(false)`, plus eight with
/// `use_patch_guidance(true)` (its two refinement passes reach four times as many faces), and about
/// twice the number of iterations plus twelve with the guidance chosen per face. The discs of radius
/// \f$ 2\rho \f$ around the faces are walked once and kept for all passes, which costs 4 bytes for each
/// face within \f$ 2\rho \f$ of a face; the others are walked again at every pass (on CGAL's armadillo,
/// 52k faces at \f$ \rho \f$ = two mean edges: 151 faces per disc, a peak of 51 MB).
///
/// The passes run on TBB's threads with `ConcurrencyTag` = `CGAL::Parallel_tag` (what the default
/// `CGAL::Parallel_if_available_tag` is when `CGAL_LINKED_WITH_TBB` is defined), each face's normal
/// computed from the previous pass only, in the same order of the sums; with `CGAL::Sequential_tag` one
/// face after the other. The normals do not depend on it, bit for bit.
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag`, `CGAL::Parallel_tag` or `CGAL::Parallel_if_available_tag`
/// \tparam TriangleMesh a model of `FaceListGraph` and `HalfedgeListGraph`
/// \tparam VertexNormalMap a model of `WritablePropertyMap` with
///         `boost::graph_traits<TriangleMesh>::%vertex_descriptor` as key type and a vector type
///         constructible from three `double` as value type (`%Vector_3` of the kernel)
/// \tparam NamedParameters a sequence of \ref IsophoticMetricNamedParameters "Named Parameters"
///
/// \param tm the triangle mesh; see `validate_triangle_mesh()`
/// \param scale the radius \f$ \rho > 0 \f$ of the filter, a length in the units of `tm`
/// \param normals receives the unit normal of every vertex (the zero vector for an isolated vertex,
///        or for a vertex whose incident faces all have zero area)
/// \param np an optional sequence of named parameters among the ones listed below
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{vertex_point_map}
///     \cgalParamDescription{a property map associating points to the vertices of `tm`}
///     \cgalParamType{a class model of `ReadablePropertyMap` with
///                    `boost::graph_traits<TriangleMesh>::%vertex_descriptor` as key type and
///                    `%Point_3` as value type}
///     \cgalParamDefault{`boost::get(CGAL::vertex_point, tm)`}
///   \cgalParamNEnd
///   \cgalParamNBegin{number_of_iterations}
///     \cgalParamDescription{the number of rolling-guidance iterations after the first guidance}
///     \cgalParamType{unsigned int}
///     \cgalParamDefault{`5`}
///   \cgalParamNEnd
///   \cgalParamNBegin{use_patch_guidance}
///     \cgalParamDescription{if given, one guidance for all faces instead of the guidance chosen per face.
///                           `true`: the first guidance is not the Gaussian average but, for every face,
///                           the mean normal of the most consistent disc of radius \f$ \rho/2 \f$ that
///                           contains it (the disc whose normals spread least; after Zhang et al.,
///                           "Guided mesh normal filtering", 2015): beside a sharp edge that disc lies on
///                           one side, so the two sides are kept apart from the first pass on; a face right
///                           beside the edge, where discs of both sides are nearly as consistent, takes the
///                           side its own raw normal is clearly closer to.
///                           After the rolling-guidance iterations, two refinement passes over the radius
///                           \f$ 2\rho \f$ with the range 0.05 (about 3 degrees) average only faces whose
///                           normals already agree: they remove the noise that the radius \f$ \rho \f$ leaves
///                           on planes without averaging across a sharp edge (on a fillet they find no
///                           agreeing neighbour and keep much of the raw normal).
///                           `false`: the Gaussian guidance, no refinement passes (the default before the
///                           guidance chosen per face). See the manual}
///     \cgalParamType{Boolean}
///     \cgalParamDefault{not given: chosen per face}
///   \cgalParamNEnd
///   \cgalParamNBegin{number_of_vertex_updates}
///     \cgalParamDescription{the number of rounds of vertex updates after the filter. In each round a private
///                           copy of the vertex positions moves once by the least-squares update of Sun et al.
///                           ("Fast and effective feature-preserving mesh denoising", 2007),
///                           \f$ x_v \mathrel{+}= \frac{1}{|F(v)|} \sum_{f \in F(v)} n_f\,(n_f \cdot (c_f - x_v)) \f$
///                           (\f$ n_f \f$ the filtered normal, \f$ c_f \f$ the centroid of face `f`), towards the
///                           planes of the filtered normals; the raw normals, areas and centroids of the moved
///                           faces are then filtered again with the same options. The noise of the positions,
///                           which every raw normal carries into the filter, shrinks with each round; the vertex
///                           normals take Max's weights from the given positions. The mesh, and so the
///                           Euclidean part of the metric, is not changed. `0`: the filter alone}
///     \cgalParamType{unsigned int}
///     \cgalParamDefault{`1` with the guidance chosen per face, `0` with `use_patch_guidance`}
///     \cgalParamExtra{Must be an integer from 0 to 10.}
///   \cgalParamNEnd
///   \cgalParamNBegin{normal_range}
///     \cgalParamDescription{the range \f$ \sigma_r \f$ of the bilateral weight, a difference of unit
///                           normals: faces whose guidance normals differ by much more are not
///                           averaged together. With the guidance chosen per face, the range of the faces
///                           away from sharp edges; the faces near them take half of it}
///     \cgalParamType{a number}
///     \cgalParamDefault{`0.6` (an angle of about 35 degrees)}
///     \cgalParamExtra{Must be finite and positive.}
///   \cgalParamNEnd
/// \cgalNamedParamsEnd
///
/// \throws Invalid_mesh_error if `tm` fails `validate_triangle_mesh()`.
/// \throws Invalid_parameter_error if `scale` or `normal_range` is not finite and positive, or if
/// `number_of_vertex_updates` is not an integer from 0 to 10.
template <class ConcurrencyTag = CGAL::Parallel_if_available_tag, typename TriangleMesh, typename VertexNormalMap,
          typename NamedParameters = parameters::Default_named_parameters>
void estimate_vertex_normals(const TriangleMesh& tm,
                             double scale,
                             VertexNormalMap normals,
                             const NamedParameters& np = parameters::default_values())
{
  internal::estimate_vertex_normals<ConcurrencyTag>(tm, scale, normals, np, true);
}

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_ESTIMATE_VERTEX_NORMALS_H
