// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Exact polyhedral geodesic distances by window propagation (the windows of Mitchell-Mount-
// Papadimitriou as described by Surazhsky et al. 2005, filtered by vertex distances as in Xin &
// Wang's ICH 2009, propagated an edge at a time as in Qin et al.'s VTP 2016), extended with
// line-wave windows for region sources and with an archive of windows for point queries and paths.
//
// A window lives on a halfedge h and describes straight geodesics that cross the edge of h into
// face(h). In the frame of h (source(h) at (0,0), target(h) at (L,0), face(h) on the positive side)
// a window covers the interval [b0,b1] of the edge and carries either
//  - a point wave: distance(x) = sigma + |x - S| with the unfolded source S below the edge, or
//  - a line wave:  distance(x) = sigma + <x, n>  with a unit direction n pointing into the face
//    (the distance to a straight piece of a region's boundary).
// The windows waiting on an edge are propagated across its face together, when the front reaches
// the smallest distance among them. When a window is made, the parts of it where a real path is
// shorter by more than a rounding tolerance are cut: a path through an endpoint of its edge or,
// for a child, through the third corner of the face it has just crossed when that corner is a
// saddle or on the boundary (a straight segment in that face; vertex distances are lengths of
// real paths; one endpoint of a child's edge is the apex just reached). The third corner matters
// on scans (a fifth to a third fewer windows: obtuse faces, many saddles). Without stored
// windows, the windows of one block of a batch are also compared pairwise before they cross their
// face (cut_overlapping_windows: 16-30 % fewer windows on scans). A window that has
// crossed its face is forgotten (or archived), so memory follows the wavefront. Per window, the work is one unfolding and a few square roots; what a
// face contributes (apex, frames of its other edges) is computed once per batch. The window carrying a shortest path is
// never cut, so the result is exact up to rounding.
//
// Queries (with stored windows). The distance at a point of face f is the least value among the
// candidates of f: its corners (vertex distance plus the straight segment), the point sources in
// f, and the windows archived on its three halfedges whose interval the point's ray crosses.
// for_each_candidate_in_face enumerates them in one place; the point value and the exact minimum
// along a segment (each candidate minimised in closed form) are two small visitors of it. The
// archive files each propagated window on its halfedge, most of them as a 2-byte link to their
// parent, to be rebuilt from it when a query needs them (archive_window); paths are traced back through the
// origins of what realises each point (trace_back).
//
// Robustness. Lengths are in units of a power of two near the median edge (the mesh's
// length_unit(): exact conversion at the interface, numbers near 1 inside, whatever the model's
// units), and faces are unfolded with stable formulas (Intrinsic_triangle_mesh::unfold_apex), so
// needles and caps lose nothing beyond what their rounded lengths carry. After the queue has run
// out, one pass over the vertices reached looks for an edge uv with d(u) + l(uv) < d(v) (none on a
// mesh without ill-conditioned faces); such vertices go back to the queue and pass their values on
// along edges as Dijkstra does: whatever rounding cut, distances stay at most the edge-graph
// distance and reach every connected vertex. A vertex lying on its opposite edge (a collapsed
// corner) emits across the whole edge, its rays no longer told apart by where they cross it, and
// a window whose source lies on its edge reaches the whole of both edges of the face it crosses.
#ifndef CGAL_ISOPHOTIC_METRIC_GEODESICS_INTERNAL_WINDOW_PROPAGATION_H
#define CGAL_ISOPHOTIC_METRIC_GEODESICS_INTERNAL_WINDOW_PROPAGATION_H

#include <CGAL/Isophotic_metric/exceptions.h>
#include <CGAL/Isophotic_metric/Geodesics/internal/Huge_page_chunk.h>
#include <CGAL/Isophotic_metric/Geodesics/internal/Intrinsic_triangle_mesh.h>
#include <CGAL/Isophotic_metric/Geodesics/internal/Phase_barrier.h>
#include <CGAL/Isophotic_metric/Geodesics/internal/Radix_heap.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <functional>
#include <iterator>
#include <limits>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

// Marks the functions whose arithmetic a stored window's rebuild repeats (the face's frame, where
// a window splits at the apex, the child): compiled once, so the propagation and the rebuilds run
// the same instructions. Inlined into two callers, the compiler may fuse a multiply and an add in
// one copy and not in the other (with FMA, e.g. -march=native), and a rebuilt window would differ
// from the one propagated in its last bits.
#if defined(__GNUC__) && !defined(__clang__)
#define CGAL_ISOPHOTIC_METRIC_ONE_COPY __attribute__((noinline, noclone))
#elif defined(__GNUC__) || defined(__clang__)
#define CGAL_ISOPHOTIC_METRIC_ONE_COPY __attribute__((noinline))
#elif defined(_MSC_VER)
#define CGAL_ISOPHOTIC_METRIC_ONE_COPY __declspec(noinline)
#else
#define CGAL_ISOPHOTIC_METRIC_ONE_COPY
#endif

namespace CGAL {
namespace Isophotic_metric {
namespace internal {

/// A point of the surface: a face and barycentric coordinates over its local corners 0,1,2.
struct Surface_point
{
  std::uint32_t face;
  std::array<double, 3> barycentric;
};

class Window_propagation
{
public:
  typedef Intrinsic_triangle_mesh Mesh;
  static constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
  static constexpr double infinity = std::numeric_limits<double>::infinity();

  /// Where the value of a vertex or a window comes from; used to trace paths back.
  enum Origin : std::uint8_t
  {
    FROM_SOURCE,  // the vertex is a source vertex / a vertex of a source region
    FROM_POINT,   // straight segment to a point source in one of the vertex's faces
    FROM_WINDOW,  // vertex: reached straight through a stored window
    FROM_VERTEX,  // vertex: along an edge from another vertex; window: emitted by a pseudo-source vertex
    FROM_PARENT,  // window: produced by propagating its parent window through a face
    FROM_REGION   // window: line wave starting on a region's boundary edge
  };

  struct Window
  {
    double b0, b1;         // interval on the edge, in length units from source(halfedge)
    double sx, sy;         // point wave: unfolded source; line wave: unit direction
    double sigma;          // point wave: distance at the source; line wave: value at the frame origin
    std::uint32_t halfedge;
    std::uint32_t parent;  // vertex or source index, or the parent's reference, depending on `origin`
    std::uint32_t label;   // index of the source this window's geodesics start from
    std::uint32_t archived = none; // with stored windows: its archive entry once propagated
    bool is_line;
    Origin origin;
    std::uint8_t generation = 0; // with stored windows: windows since the last one archived in full
  };

  /// A window archived in full: 48 bytes. Its halfedge is that of its run (see archive_window);
  /// its origin and kind share a word with its label.
  struct Archived_window
  {
    double b0, b1, sx, sy, sigma;
    std::uint32_t parent;
    std::uint32_t label_and_kind; // label in the low label_bits bits, then the origin (3 bits), line wave (top bit)
  };
  /// The place of the archived windows of one batch of a halfedge (see archive_window).
  struct Archive_run
  {
    std::uint32_t full_begin, link_begin; // where its records start in full_records_ and link_records_
    std::uint32_t full_local, link_local; // the halfedge's numbers of its first records
    std::uint16_t full_count, link_count;
    std::uint32_t previous; // the halfedge's run before this one
  };
  static constexpr int label_bits = 28;
  static constexpr std::uint32_t max_sources = std::uint32_t(1) << label_bits;

  /// Kinds of the sources added since the last clear().
  struct Source
  {
    enum Kind : std::uint8_t { VERTEX, POINT, REGION } kind;
    std::uint32_t vertex;
    Surface_point point;
  };

  explicit Window_propagation(const Mesh& mesh) : mesh_(mesh), unit_(mesh.length_unit()) { clear(); }

  /// Keep every propagated window, for point queries and path trace-back (more memory), one in
  /// `full_record_every` of each line of descent in full and the others as a link to their parent
  /// (1: all in full, what the rebuilt ones are tested against). Clears the sources.
  static constexpr int default_full_record_every = 16;
  void set_keep_windows(bool keep, std::uint8_t full_record_every = default_full_record_every)
  {
    if(keep && propagation_threads_ > 0)
      throw Error("a propagation on threads keeps no windows: set_propagation_threads(0) first");
    keep_windows_ = keep;
    full_record_every_ = std::max<std::uint8_t>(full_record_every, 1);
    clear();
  }
  bool keeps_windows() const { return keep_windows_; }

  /// 0: the serial propagation. n >= 1: the propagation in bands (see run_in_bands) on n threads,
  /// whose results depend on its partitions (band_partitions_for_threads), not on which thread ran
  /// what. Needs windows not kept. Clears the sources.
  void set_propagation_threads(unsigned n)
  {
    if(n > 0 && keep_windows_)
      throw Error("a propagation on threads keeps no windows: set_keep_windows(false) first");
    propagation_threads_ = n;
    const std::uint32_t partitions = n > 0 ? band_partitions_for_threads(n) : 0;
    band_partitions_ = std::vector<Band_partition>(partitions);
    if(n > 0 && patches_dealt_to_ != partitions)
      make_band_patches(partitions);
    if(n > 0 && !band_blocks_)
      band_blocks_ = std::make_unique<Band_block_store>();
    for(Band_partition& part : band_partitions_)
      part.front.pool.blocks.store = band_blocks_.get();
    clear();
  }
  unsigned propagation_threads() const { return propagation_threads_; }
  std::uint8_t full_record_every() const { return full_record_every_; }

  /// Forgets the sources and results. Costs what the last propagation touched, not the mesh size
  /// (many small bounded propagations, e.g. one disc per face, stay cheap).
  void clear()
  {
    const std::size_t nv = mesh_.number_of_vertices();
    if(distance_.size() != nv)
    {
      distance_.assign(nv, infinity);
      emitted_at_.assign(nv, infinity);
      vertex_label_.assign(nv, none);
      vertex_parent_.assign(nv, none);
      incoming_corner_.assign(nv, none);
      incoming_angle_.assign(nv, 0.0);
      vertex_origin_.assign(nv, FROM_SOURCE);
      edge_.assign(mesh_.number_of_corners(), Edge_state());
    }
    for(std::uint32_t v : front_.touched_vertices)
    {
      distance_[v] = emitted_at_[v] = infinity;
      vertex_label_[v] = vertex_parent_[v] = incoming_corner_[v] = none;
      incoming_angle_[v] = 0;
      vertex_origin_[v] = FROM_SOURCE;
    }
    for(std::uint32_t h : front_.touched_edges)
      edge_[h] = Edge_state();
    front_.clear();
    for(Band_partition& part : band_partitions_)
      part.clear(); // (what they touched went to front_ when their run ended)
    if(band_blocks_)
      band_blocks_->clear();
    for(std::uint32_t f : region_faces_)
      in_region_[f] = none;
    region_faces_.clear();
    full_records_.clear();
    link_records_.clear();
    runs_.clear();
    runs_by_halfedge_.clear();
    first_run_of_halfedge_.clear();
    archived_windows_ = 0;
    sources_.clear();
    point_sources_in_face_.clear();
    propagated_ = false;
    max_distance_ = infinity;
  }

  const std::vector<Source>& sources() const { return sources_; }
  std::size_t windows_created() const
  {
    return sum_over_fronts([](const auto& front) { return front.windows_created; });
  }
  std::size_t windows_propagated() const
  {
    return sum_over_fronts([](const auto& front) { return front.windows_propagated; });
  }
  std::size_t stored_windows() const
  {
    return sum_over_fronts([](const auto& front) { return front.pending_windows; }) + archived_windows_;
  }

  // ---------------------------------------------------------------- sources

  std::uint32_t add_vertex_source(std::uint32_t v)
  {
    const std::uint32_t label = new_source({Source::VERTEX, v, {0, {0, 0, 0}}});
    seed_vertex(v, label);
    return label;
  }

  /// A point given by barycentric coordinates in a face (validated by the caller).
  std::uint32_t add_point_source(const Surface_point& p)
  {
    const std::uint32_t label = new_source({Source::POINT, none, p});
    // A point at a corner is that vertex.
    for(int c = 0; c < 3; ++c)
      if(p.barycentric[c] >= 1.0 - 1e-14)
      {
        sources_[label].vertex = mesh_.source(3 * p.face + c);
        seed_vertex(sources_[label].vertex, label);
        return label;
      }
    // A point on an edge (by its barycentric coordinate, never by a rounded position) is also a
    // point of the face across that edge, and that edge needs no window of the point.
    unsigned seeded_across = 0; // bit k: the face across halfedge 3 * p.face + k holds the point
    for(int c = 0; c < 3; ++c)
      if(p.barycentric[c] <= 1e-14 && mesh_.opposite(3 * p.face + (c + 1) % 3) != Mesh::no_halfedge)
        seeded_across |= 1u << ((c + 1) % 3); // the edge not incident to corner c
    seed_point(p, label, seeded_across);
    for(int k = 0; k < 3; ++k)
      if(seeded_across & (1u << k))
      {
        const std::uint32_t h = 3 * p.face + k, o = mesh_.opposite(h);
        Surface_point q{Mesh::face(o), {0, 0, 0}};
        q.barycentric[o % 3] = p.barycentric[(h + 1) % 3]; // source(o) = target(h)
        q.barycentric[(o + 1) % 3] = p.barycentric[h % 3];
        seed_point(q, label, 1u << (o % 3));
      }
    return label;
  }

  /// The union of closed faces `faces` (indices) as one source: distance 0 on it.
  std::uint32_t add_region_source(const std::vector<std::uint32_t>& faces)
  {
    const std::uint32_t label = new_source({Source::REGION, none, {0, {0, 0, 0}}});
    if(in_region_.empty())
      in_region_.assign(mesh_.number_of_faces(), none);
    for(std::uint32_t f : faces)
    {
      in_region_[f] = label;
      region_faces_.push_back(f);
    }
    for(std::uint32_t f : faces)
      for(std::uint32_t h = 3 * f; h < 3 * f + 3; ++h)
      {
        seed_vertex(mesh_.source(h), label);
        // Line wave into the neighbour across every boundary edge of the region.
        const std::uint32_t o = mesh_.opposite(h);
        if(o == Mesh::no_halfedge || in_region_[Mesh::face(o)] != none)
          continue;
        Window w;
        w.b0 = 0;
        w.b1 = mesh_.length(o);
        w.sx = 0;
        w.sy = 1;
        w.sigma = 0;
        w.is_line = true;
        w.halfedge = o;
        w.parent = label;
        w.label = label;
        w.origin = FROM_REGION;
        push_window(w);
      }
    return label;
  }

  // ------------------------------------------------------------ propagation

  /// Runs the propagation up to `max_distance`. `progress(front_distance)` is called now and then
  /// and may return false to cancel (Cancelled_error is thrown).
  void propagate(double max_distance, const std::function<bool(double)>& progress = {})
  {
    max_distance_ = max_distance / unit_;
    std::size_t steps = 0, next_report = windows_propagated() + progress_interval;
    do
      if(band_partitions_.empty())
        run_queue(progress, steps, next_report);
      else
        run_in_bands(progress, next_report);
    while(repair_along_edges());
    index_runs();
    propagated_ = true;
  }

  double max_distance() const { return max_distance_ * unit_; }

  // The safety net of ill-conditioned faces: where rounding cut every window into a region, a
  // vertex may be left above a neighbour's value plus their edge (or at +inf). One pass over the
  // vertices reached finds them (nothing, on a mesh without such faces); each one found goes back
  // to the queue, whose vertex events pass values on along edges as Dijkstra does. Distances are
  // then never above the edge-graph distance, and finite wherever a source is connected.
  bool repair_along_edges()
  {
    bool repaired = false;
    for(std::size_t k = 0; k < front_.touched_vertices.size(); ++k)
    {
      const std::uint32_t v = front_.touched_vertices[k];
      const double d = distance_[v];
      if(!(d <= max_distance_))
        continue;
      for(const std::uint32_t* c = mesh_.corners_begin(v); c != mesh_.corners_end(v); ++c)
        for(const std::uint32_t h : {*c, Mesh::prev(*c)})
        {
          const std::uint32_t u = h == *c ? mesh_.target(h) : mesh_.source(h);
          const double through = d + mesh_.length(h);
          if(through < distance_[u] * (1 - 1e-12)) // (not for the rounding of exact values)
          {
            // The queue would raise the events below its last key to it: the edge paths would
            // then leave in any order, not the shortest first as in Dijkstra's algorithm.
            if(!repaired)
              front_.queue.lower_floor();
            update_vertex(u, through, vertex_label_[v], FROM_VERTEX, v);
            front_.queue.push({through, u, Queue_entry::VERTEX});
            repaired = true;
          }
        }
    }
    return repaired;
  }

  void run_queue(const std::function<bool(double)>& progress, std::size_t& steps, std::size_t& next_report)
  {
    const bool bounded = max_distance_ < infinity;
    Queue& queue = front_.queue;
    const Immediate_effects effects{*this};
    while(!queue.empty())
    {
      // (min_key, not top: a peek at a key beyond the bound must not raise the keys that
      // repair_along_edges pushes afterwards)
      if(bounded && queue.min_key() > max_distance_)
        break;
      const Queue_entry e = queue.top();
      queue.pop();
      // (every 2^16 windows, or queue events on a mesh where few windows are needed)
      if(progress && (front_.windows_propagated >= next_report || (++steps & 0xFFFF) == 0))
      {
        next_report = front_.windows_propagated + progress_interval;
        if(!progress(e.key * unit_))
          throw Cancelled_error("geodesic propagation cancelled by its visitor at distance " + std::to_string(e.key * unit_));
      }
      // A vertex emits at its distance, not at the key: the queue raises a key below the last one
      // removed to it, and a vertex improved below that, its event raised, looked stale and emitted
      // nothing (a saddle reached just below the key of the vertex 3e-10 away that had just emitted: the
      // distances behind it were 1.5e-5 too long). An event whose vertex improved since is not
      // stale either: the vertex emits at its distance once, at the first of its events.
      if(e.kind == Queue_entry::VERTEX)
        emit_from_vertex(e.index, distance_[e.index], effects);
      else
        process_edge(e.index, effects);
    }
  }

  /// Distance of a vertex, +infinity when unreachable or beyond the distance bound.
  double vertex_distance(std::uint32_t v) const
  {
    return distance_[v] <= max_distance_ ? distance_[v] * unit_ : infinity;
  }
  std::uint32_t vertex_label(std::uint32_t v) const { return distance_[v] <= max_distance_ ? vertex_label_[v] : none; }

  /// Distance and label at a surface point. Requires stored windows.
  struct Point_value
  {
    double distance = infinity;
    std::uint32_t label = none;
    // what realises the value, for trace-back
    enum Kind { NOTHING, IN_REGION, POINT_SOURCE, VERTEX, WINDOW } kind = NOTHING;
    std::uint32_t index = none; // point source position / vertex / window's archive entry
    Surface_point at{0, {0, 0, 0}}; // the query point, in the face where `index` was found
    std::uint32_t halfedge = none; // of the window
  };

  Point_value point_value(const Surface_point& p) const
  {
    Point_value best;
    evaluate_in_face(p, best);
    // A point on an edge: the face across may hold the realising window.
    for(int c = 0; c < 3; ++c)
      if(p.barycentric[c] <= 1e-14)
      {
        const std::uint32_t h = 3 * p.face + (c + 1) % 3;
        if(mesh_.opposite(h) != Mesh::no_halfedge)
          evaluate_in_face(across_edge(p, h), best);
      }
    return in_caller_units(best);
  }

  /// Minimum of the distance over the segment from `p0` to `p1`, two points of one face, exact (each
  /// candidate's distance along the segment is convex or linear on the part of the segment it
  /// covers, so its minimum is found in closed form); `t` receives where, as a fraction of the way
  /// from `p0` to `p1`. Requires stored windows.
  Point_value segment_minimum(const Surface_point& p0, const Surface_point& p1, double& t) const
  {
    Point_value best;
    t = 0;
    segment_minimum_in_face(p0, p1, best, t);
    // A segment on an edge: the face across may hold the realising windows (as for point_value).
    for(int c = 0; c < 3; ++c)
      if(p0.barycentric[c] <= 1e-14 && p1.barycentric[c] <= 1e-14)
      {
        const std::uint32_t h = 3 * p0.face + (c + 1) % 3;
        if(mesh_.opposite(h) != Mesh::no_halfedge)
          segment_minimum_in_face(across_edge(p0, h), across_edge(p1, h), best, t);
      }
    return in_caller_units(best);
  }

  /// Writes the shortest path from `p` back to its nearest source as surface points, `p` first.
  /// Consecutive points share a face. Requires stored windows. Returns false when unreachable.
  ///
  /// The path is walked back through what realises each point: a vertex (its origin), or a window
  /// (the path crosses its edge towards the window's source, then goes on with the window's parent).
  /// Where the parent, rebuilt with the final vertex distances, lost that part, and behind a vertex
  /// reached through a window, the path goes on through whatever realises the point in the face
  /// across (a part of a shortest path is a shortest path).
  bool trace_back(const Surface_point& p, std::vector<Surface_point>& path) const
  {
    path.clear();
    const Point_value start = point_value(p);
    if(start.kind == Point_value::NOTHING)
      return false;
    path.push_back(p);
    std::vector<Window> chain; // the window the path crosses last, after the ancestors rebuilt with it
    Trace_state state = step_to(start, path, chain);
    const std::size_t max_steps = 4 * (mesh_.number_of_faces() + mesh_.number_of_vertices()) + 16;
    for(std::size_t step = 0; step < max_steps && state.kind != Trace_state::AT_SOURCE; ++step)
      state = state.kind == Trace_state::AT_VERTEX ? step_back_from_vertex(state.index, path, chain)
                                                   : step_back_across_window(path, chain);
    if(state.kind == Trace_state::AT_SOURCE)
      return true;
    throw Error(std::string("geodesic path trace-back did not terminate: the stored windows are inconsistent, as faces of "
                            "nearly no area side by side (caps, needles, collapsed corners) can make them; ") +
                scan_repair_hint);
  }

  /// The surface point of a vertex, in one of its faces.
  Surface_point vertex_point(std::uint32_t v) const
  {
    const std::uint32_t h = *mesh_.corners_begin(v);
    Surface_point p{Mesh::face(h), {0, 0, 0}};
    p.barycentric[h % 3] = 1;
    return p;
  }

  /// Point at distance t along halfedge h from its source.
  Surface_point point_on_halfedge(std::uint32_t h, double t) const
  {
    const double s = std::clamp(t / mesh_.length(h), 0.0, 1.0);
    Surface_point p{Mesh::face(h), {0, 0, 0}};
    p.barycentric[h % 3] = 1 - s;
    p.barycentric[(h + 1) % 3] = s;
    return p;
  }

private:
  struct Queue_entry
  {
    double key;
    std::uint32_t index;
    enum Kind : std::uint8_t { EDGE, VERTEX } kind;
  };
  typedef Radix_heap<Queue_entry> Queue;

  struct Walked_corner
  {
    std::uint32_t halfedge;
    double start, angle;
  };

  // The windows waiting on the halfedges to cross their faces, in small blocks from one pool
  // (freed blocks are reused): no allocation per edge, and memory follows the wavefront.
  struct Window_block
  {
    static constexpr std::uint32_t capacity = 4;
    std::array<Window, capacity> windows;
    std::uint32_t count = 0;
    std::uint32_t next = none; // next block of the same halfedge
  };
  // Asks for a block's memory ahead of its use (see Window_pool::prefetch).
  static void prefetch_block(const Window_block& block)
  {
#if defined(__GNUC__) || defined(__clang__)
    const char* p = reinterpret_cast<const char*>(&block);
    for(std::size_t offset = 0; offset < sizeof(Window_block); offset += 64)
      __builtin_prefetch(p + offset);
#else
    (void)block;
#endif
  }
  // One pool of blocks; blocks are addressed by index, so the pool may grow while a chain is
  // walked. The free blocks are a stack of their indices, not a list through the blocks: taking
  // one then reads no block (in a band, the block taken was freed long before and is no longer in
  // the cache: that read was a fifth of the time of a band's second phase).
  struct Window_pool
  {
    Huge_page_vector<Window_block> blocks;
    std::vector<std::uint32_t> free_blocks;

    std::uint32_t allocate()
    {
      std::uint32_t b;
      if(!free_blocks.empty())
      {
        b = free_blocks.back();
        free_blocks.pop_back();
      }
      else
      {
        b = static_cast<std::uint32_t>(blocks.size());
        blocks.emplace_back();
      }
      blocks[b].count = 0;
      return b;
    }
    void release(std::uint32_t b) { free_blocks.push_back(b); }
    // Asks for a block's memory ahead of its use. The windows of an edge are read long after they
    // were written (when the front reaches the edge), from blocks scattered in the pool: walking the
    // chain without this waited for memory at every block (measured: 1.5x the time at 207k faces,
    // 1.7x at 829k).
    void prefetch(std::uint32_t b) const { prefetch_block(blocks[b]); }
    void clear()
    {
      blocks.clear();
      free_blocks.clear();
    }
  };
  // The blocks of a run in bands: one store the partitions share, in chunks that never move, so
  // that a block one partition's events fill is linked onto its edge, read and freed by another
  // partition (see Band_effects::window) while the others' pools grow.
  struct Band_block_store
  {
    static constexpr unsigned chunk_bits = 8; // 256 blocks (70 kB) a chunk
    static constexpr std::uint32_t chunk_size = std::uint32_t(1) << chunk_bits;
    static constexpr std::size_t max_chunks = std::size_t(1) << 20; // 2^28 blocks: beyond any memory
    // (calloc: the table's pages cost memory only once used)
    Window_block** chunks = static_cast<Window_block**>(std::calloc(max_chunks, sizeof(Window_block*)));
    std::atomic<std::size_t> chunks_used{0};
    std::size_t chunks_made = 0; // (chunks_used is reset by clear(); its chunks are kept and reused)

    Band_block_store()
    {
      if(!chunks)
        throw std::bad_alloc();
    }
    Band_block_store(const Band_block_store&) = delete;
    Band_block_store& operator=(const Band_block_store&) = delete;
    ~Band_block_store()
    {
      for(std::size_t k = 0; k < std::max(chunks_made, chunks_used.load()); ++k)
        delete[] chunks[k];
      std::free(chunks);
    }
    Window_block& operator[](std::uint32_t b) const { return chunks[b >> chunk_bits][b & (chunk_size - 1)]; }
    // The index of the first block of a chunk no partition has taken yet.
    std::uint32_t take_chunk()
    {
      const std::size_t k = chunks_used.fetch_add(1, std::memory_order_relaxed);
      if(k >= max_chunks)
        throw Error("the propagation on threads ran out of room for its windows: use propagation_threads(0)");
      if(!chunks[k])
        chunks[k] = new Window_block[chunk_size];
      return static_cast<std::uint32_t>(k << chunk_bits);
    }
    void clear()
    {
      chunks_made = std::max(chunks_made, chunks_used.load());
      chunks_used = 0;
    }
  };
  // A partition's pool in a run in bands: its free blocks (from any partition: it frees the blocks
  // of the windows its edges propagate) and the unused rest of its last chunk of the store.
  struct Band_pool
  {
    struct Blocks
    {
      Band_block_store* store = nullptr;
      Window_block& operator[](std::uint32_t b) const { return (*store)[b]; }
    } blocks;
    std::vector<std::uint32_t> free_blocks;
    std::uint32_t next_new = 0, end_new = 0;

    std::uint32_t allocate()
    {
      std::uint32_t b;
      if(!free_blocks.empty())
      {
        b = free_blocks.back();
        free_blocks.pop_back();
      }
      else
      {
        if(next_new == end_new)
        {
          next_new = blocks.store->take_chunk();
          end_new = next_new + Band_block_store::chunk_size;
        }
        b = next_new++;
      }
      blocks[b].count = 0;
      return b;
    }
    void release(std::uint32_t b) { free_blocks.push_back(b); }
    void prefetch(std::uint32_t b) const { prefetch_block(blocks[b]); }
    void clear()
    {
      free_blocks.clear();
      next_new = end_new = 0;
    }
  };
  // What the events of a queue change besides the vertex and edge states: the queue, the pool of
  // the windows waiting on its edges, what it touched (for clear()) and its counts. The serial run
  // has one (Front); a run in bands one per partition (Band_front, see Band_partition).
  template <class Pool>
  struct Front_of
  {
    Queue queue;
    Pool pool;
    std::vector<std::uint32_t> touched_vertices, touched_edges;
    std::size_t pending_windows = 0; // in the edge lists
    std::size_t windows_created = 0, windows_propagated = 0;
    std::vector<Walked_corner> corner_walk; // scratch of emit_from_vertex

    void clear()
    {
      queue.clear();
      pool.clear();
      touched_vertices.clear();
      touched_edges.clear();
      pending_windows = windows_created = windows_propagated = 0;
    }
  };
  typedef Front_of<Window_pool> Front;
  typedef Front_of<Band_pool> Band_front;

  // The propagation in bands (see run_in_bands): the state of one partition and what its events
  // do to each partition, in the order they did it.
  struct Vertex_event
  {
    double key;      // (may be raised by its queue: the distance is kept apart)
    double distance;
    std::uint32_t vertex;
  };
  struct Vertex_change
  {
    double distance, angle;
    std::uint32_t vertex, label, parent, corner;
    Origin origin;
    bool always_queued;
  };
  // The windows one partition's events of a band made for one halfedge, in blocks of the store
  // (first_block the newest, as on an edge), to be linked onto the halfedge in phase 2.
  struct Staged_chain
  {
    double key; // the smallest key of its windows
    std::uint32_t halfedge, first_block, last_block, count;
  };
  // Where a partition's staged chain of a halfedge is, for the band whose number is `band`.
  struct Staged_slot
  {
    std::uint32_t halfedge, band = 0, index;
  };
  struct Band_outbox
  {
    std::vector<Vertex_change> vertices;
    std::vector<Staged_chain> windows;
  };
  // Partitions of a run in bands: 8 a thread, a power of two from 16 to 64 (the masks of senders
  // and outboxes have 64 bits). Each partition costs a visit of its queues and outboxes in every
  // band, cold in the cache: 16 partitions have 15 % fewer L1 misses than 64 (bunny00 refined,
  // isophotic, one thread; benchmark/README.md); more threads need more partitions to share the work.
  static constexpr std::uint32_t max_band_partitions = 64;
  static std::uint32_t band_partitions_for_threads(unsigned n)
  {
    std::uint32_t partitions = 16;
    while(partitions < max_band_partitions && partitions < 8 * std::uint64_t(n))
      partitions *= 2;
    return partitions;
  }
  struct Band_partition
  {
    Band_front front; // front.queue: the events of its edges
    Radix_heap<Vertex_event> vertex_queue;
    std::vector<Staged_slot> staged_slots; // open addressing by halfedge (a power of two of them)
    std::uint32_t staged_count = 0, staged_band = 0; // chains staged in its phase 1 number staged_band
    std::array<Band_outbox, max_band_partitions> outbox;  // by receiving partition
    std::uint64_t outbox_used = 0;                        // bit q: outbox[q] written in this band
    std::atomic<std::uint64_t> senders{0};                // bit p: partition p wrote to it in this band
    double smallest_key = infinity;                       // of its two queues

    void clear()
    {
      front.clear();
      vertex_queue.clear();
      for(Band_outbox& box : outbox) // (not empty after a failure in a band)
      {
        box.vertices.clear();
        box.windows.clear();
      }
      outbox_used = 0;
      senders = 0;
      smallest_key = infinity;
      staged_count = 0;
    }
  };
  static constexpr std::size_t progress_interval = std::size_t(1) << 16; // windows between reports
  // Below this height over its opposite edge (relative to that edge), a vertex emits across the
  // edge as if it lay on it (emit_in_corner): the rays' crossings are then known to 1e-10 or better.
  static constexpr double flat_corner_height = 1e-6;

  struct Located_point_source
  {
    std::uint32_t label;
    Surface_point point;
  };

  // A query's result, its distance converted from the engine's unit (nothing beyond the bound).
  Point_value in_caller_units(Point_value best) const
  {
    if(best.distance > max_distance_)
      return Point_value();
    best.distance *= unit_;
    return best;
  }

  std::uint32_t new_source(const Source& s)
  {
    if(propagated_)
      throw Error("sources must be added before propagation; call clear() to start a new source set");
    if(sources_.size() == max_sources - 1)
      throw Invalid_source_error("too many sources: at most " + std::to_string(max_sources - 1) + " per propagation");
    sources_.push_back(s);
    return static_cast<std::uint32_t>(sources_.size() - 1);
  }

  void seed_vertex(std::uint32_t v, std::uint32_t label)
  {
    if(distance_[v] <= 0 && vertex_origin_[v] == FROM_SOURCE)
      return; // already a source (first source wins ties)
    touch_vertex(front_, v);
    distance_[v] = 0;
    vertex_label_[v] = label;
    vertex_origin_[v] = FROM_SOURCE;
    vertex_parent_[v] = label;
    front_.queue.push({0.0, v, Queue_entry::VERTEX});
  }

  // `seeded_across`: bit k set where the face across halfedge 3 * p.face + k holds the point too.
  void seed_point(const Surface_point& p, std::uint32_t label, unsigned seeded_across)
  {
    const std::uint32_t id = static_cast<std::uint32_t>(point_sources_in_face_.size());
    point_sources_in_face_.push_back({label, p});
    const std::uint32_t f = p.face;
    for(std::uint32_t h = 3 * f; h < 3 * f + 3; ++h)
    {
      const std::array<Vec2, 3> corners = mesh_.corner_positions(h);
      const Vec2 s = position(corners, p.barycentric);
      // corner source(h) is at the origin of this frame
      const double d = norm(s);
      update_vertex(mesh_.source(h), d, label, FROM_POINT, id);
      const std::uint32_t o = mesh_.opposite(h);
      // Every edge with a neighbour gets the point's window unless the face across holds the point
      // itself and the point is on the edge in this frame (above it, the window is redundant but
      // harmless, and kept). Whether the point lies on an edge is decided once, from its barycentric
      // coordinates, for both faces: its rounded height s.y is no test (in a cap whose height
      // rounds to 0 it is 0 above the long edge for a point on a short one, and no window crossed
      // the long edge: 29 % too long behind it). A point barely above an edge still sends its
      // window across it: in a needle every point is within rounding of the two long edges, and a
      // cut-off on the height (1e-12 of the edge) left such a point only its short edge (5.6 %).
      if(o == Mesh::no_halfedge || ((seeded_across >> (h - 3 * f)) & 1u && !(s.y > 0)))
        continue;
      Window w;
      w.b0 = 0;
      w.b1 = mesh_.length(h);
      // frame of o: origin target(h), x reversed, y reversed
      w.sx = w.b1 - s.x;
      w.sy = -std::max(s.y, 0.0); // the source on the edge where rounding puts it below
      w.sigma = 0;
      w.is_line = false;
      w.halfedge = o;
      w.parent = id;
      w.label = label;
      w.origin = FROM_POINT;
      push_window(w);
    }
  }

  // Position of the point with barycentric coordinates `b`, given the corners of its face in some frame.
  static Vec2 position(const std::array<Vec2, 3>& corners, const std::array<double, 3>& b)
  {
    return b[0] * corners[0] + b[1] * corners[1] + b[2] * corners[2];
  }

  // ---------------------------------------------------------- window helpers

  // (A line wave's value, the distance to its region's boundary line, is never below 0: rounded
  // through faces unfolded from their lengths it can fall below it, and a vertex of the region
  // reached at -5e-13 stopped being a source and emitted no windows: 2e-3 too long behind it.)
  static double value_at(const Window& w, Vec2 x)
  {
    return w.is_line ? std::max(0.0, w.sigma + x.x * w.sx + x.y * w.sy) : w.sigma + length_of(x.x - w.sx, x.y - w.sy);
  }
  static double edge_value(const Window& w, double t) { return value_at(w, {t, 0}); }

  static double min_value(const Window& w)
  {
    if(w.is_line)
      return std::max(0.0, w.sigma + std::min(w.sx * w.b0, w.sx * w.b1));
    const double dx = std::max({0.0, w.b0 - w.sx, w.sx - w.b1});
    return w.sigma + length_of(dx, w.sy);
  }

  // Parameter on the edge (y = 0) where the geodesic of `w` reaching x (on the face side) crosses.
  static double edge_crossing(const Window& w, Vec2 x)
  {
    if(w.is_line)
      return x.x - x.y * w.sx / w.sy;
    const double denom = x.y - w.sy;
    if(denom <= 0)
      return x.x;
    return x.x + (w.sx - x.x) * x.y / denom;
  }

  // The rounding tolerance on where a ray of `w` crosses its edge (of length L), in the apex test of
  // the propagation. It grows with the unfolded source's distance: on a ray through a flat vertex
  // the windows of its two sides meet within 1e-12 of each other, and an apex on that ray fell
  // between them with a slack of 1e-12 L (5e-12 out of both, 0.5 % too long behind it, on a damaged
  // cube-meshed whose source lay 12 edges away along a line of vertices).
  static double crossing_slack(const Window& w, double L) { return 1e-12 * (L + std::abs(w.sx) + std::abs(w.sy)); }

  // The same tolerance in the queries, wider (and so never missing a vertex reached in the apex test
  // when a path is traced back): two windows of one source that meet on one ray were unfolded
  // through different faces, and across a needle their ends came 1.3e-10 apart on an edge of 5e-6
  // (source 11.6 away): a point between them fell to a corner, 5e-8 too long. A window taken up to
  // 1e-9 of the distance beyond its end gives the length of a path that misses the surface by as
  // little, shorter than a real one by its square at most.
  static double query_slack(const Window& w, double L) { return 1e-9 * (L + std::abs(w.sx) + std::abs(w.sy)); }

  // Where the ray of `w` through the apex of its face crosses its edge: where the window splits.
  static CGAL_ISOPHOTIC_METRIC_ONE_COPY double apex_crossing(const Window& w, Vec2 apex) { return edge_crossing(w, apex); }

  // Puts a new window on its halfedge, to wait for the front at its smallest value `key`.
  void push_window(const Window& w) { push_window(front_, w, min_value(w)); }
  template <class F>
  void push_window(F& front, const Window& w, double key)
  {
    Edge_state& edge = edge_[w.halfedge];
    if(!edge.touched)
    {
      edge.touched = true;
      front.touched_edges.push_back(w.halfedge);
    }
    append_to_edge(front, w);
    ++front.windows_created;
    schedule_edge(front, w.halfedge, key);
  }

  template <class F>
  void append_to_edge(F& front, const Window& w)
  {
    Edge_state& edge = edge_[w.halfedge];
    auto& pool = front.pool;
    if(edge.first_block == none || pool.blocks[edge.first_block].count == Window_block::capacity)
    {
      const std::uint32_t b = pool.allocate();
      pool.blocks[b].next = edge.first_block;
      edge.first_block = b;
    }
    Window_block& block = pool.blocks[edge.first_block];
    block.windows[block.count++] = w;
    ++front.pending_windows;
  }

  // Makes sure the pending windows of halfedge h are propagated once the front reaches `key`.
  template <class F>
  void schedule_edge(F& front, std::uint32_t h, double key)
  {
    if(key < edge_[h].scheduled_at)
    {
      edge_[h].scheduled_at = key;
      front.queue.push({key, h, Queue_entry::EDGE});
    }
  }

  // Remembers that a vertex's state left its initial value (for clear()).
  template <class F>
  void touch_vertex(F& front, std::uint32_t v)
  {
    if(distance_[v] == infinity)
      front.touched_vertices.push_back(v);
  }

  void update_vertex(std::uint32_t v, double d, std::uint32_t label, Origin origin, std::uint32_t parent,
                     std::uint32_t corner = none, double angle = 0)
  {
    if(improve_vertex(front_, v, d, label, origin, parent, corner, angle) && mesh_.is_pseudo_source_candidate(v))
      front_.queue.push({d, v, Queue_entry::VERTEX});
  }

  // Sets the state of vertex v if d is below its distance; true if it did.
  template <class F>
  bool improve_vertex(F& front, std::uint32_t v, double d, std::uint32_t label, Origin origin, std::uint32_t parent,
                      std::uint32_t corner, double angle)
  {
    if(!(d < distance_[v]))
      return false;
    touch_vertex(front, v);
    distance_[v] = d;
    vertex_label_[v] = label;
    vertex_origin_[v] = origin;
    vertex_parent_[v] = parent;
    incoming_corner_[v] = corner;
    incoming_angle_[v] = angle;
    return true;
  }

  // Where the effects of an event go in the serial run: into the state at once, seen by the next
  // window of the same event. (A run in bands collects them instead: Band_effects.)
  struct Immediate_effects
  {
    Window_propagation& engine;

    Front& front() const { return engine.front_; }
    void vertex(std::uint32_t v, double d, std::uint32_t label, Origin origin, std::uint32_t parent,
                std::uint32_t corner = none, double angle = 0) const
    {
      engine.update_vertex(v, d, label, origin, parent, corner, angle);
    }
    // u reached along an edge from v; `always_queued`: its event is queued even if u bends no geodesic
    void along_edge(std::uint32_t u, double d, std::uint32_t label, std::uint32_t v, bool always_queued) const
    {
      engine.update_vertex(u, d, label, FROM_VERTEX, v);
      if(always_queued && !engine.mesh_.is_pseudo_source_candidate(u))
        engine.front_.queue.push({d, u, Queue_entry::VERTEX});
    }
    void window(const Window& w, double key) const { engine.push_window(engine.front_, w, key); }
  };

  // ------------------------------------------------------- propagation in bands
  //
  // The front advances in bands: the edge events within one length unit of the smallest key of
  // all queues and the vertex events within 1/32 of it (a vertex's value must be final, or nearly,
  // when it emits). The halfedges and vertices fall into partitions (8 a thread, 16 to 64), each
  // with its queues and its pool of windows. A band has two phases, with a barrier after each:
  //  1. each partition runs its events of the band against the vertex distances as the band
  //     found them, and writes what they change elsewhere into one outbox per receiving
  //     partition: the vertex values, and for each halfedge a chain of blocks holding the new
  //     windows (written there once, in blocks of a store all partitions share);
  //  2. each partition applies the outboxes addressed to it, those of partition 0 first, each in
  //     the order it was written (a chain is linked in front of its halfedge's windows, not
  //     copied), then finds its smallest key.
  // Both phases read and write only the state of the partitions a thread owns (besides reading
  // the frozen distances), and phase 2 applies everything in an order the state fixes: the results
  // (distances, labels, windows) are those of one thread on the same partitions, whatever the
  // number of threads (band_partitions_for_threads). They can differ from the serial run's where
  // two values tie exactly (which label wins) and in the windows made (a window trimmed against a
  // vertex value of the band, not the one the serial order would have reached by then; the
  // distances are exact either way). Thread t owns the partitions t, t + n, t + 2n, ...; the
  // halfedges of a patch of about 256 faces (see make_band_patches) and the vertices whose first
  // corner is in it share a partition, and the patches go round the partitions, so each thread has
  // a share of every part of the front.
  std::uint32_t partition_of_halfedge(std::uint32_t h) const { return face_partition_[Mesh::face(h)]; }
  std::uint32_t partition_of_vertex(std::uint32_t v) const { return vertex_partition_[v]; }

  // The patches: grown breadth-first across edges from the lowest face not yet taken, up to 256
  // faces, so that a patch is a disc, not a run of consecutive faces. (Faces are numbered
  // breadth-first from one face: 256 consecutive ones are a thin strip along a ring of that
  // search, across which nearly every window went to another partition, measured 84-95 % of the
  // staged chains; each then cost a staging and a link on another partition, out of the cache.)
  void make_band_patches(std::uint32_t partitions)
  {
    static constexpr std::uint8_t unset = 0xFF;
    patches_dealt_to_ = partitions;
    const std::size_t nf = mesh_.number_of_faces(), nv = mesh_.number_of_vertices();
    face_partition_.assign(nf, unset);
    std::vector<std::uint32_t> patch;
    std::uint32_t patches = 0;
    for(std::uint32_t start = 0; start < nf; ++start)
    {
      if(face_partition_[start] != unset)
        continue;
      const std::uint8_t partition = static_cast<std::uint8_t>(patches++ % partitions);
      patch.assign(1, start);
      face_partition_[start] = partition;
      for(std::size_t k = 0; k < patch.size() && patch.size() < 256; ++k)
        for(std::uint32_t i = 0; i < 3 && patch.size() < 256; ++i)
        {
          const std::uint32_t o = mesh_.opposite(3 * patch[k] + i);
          if(o != Mesh::no_halfedge && face_partition_[Mesh::face(o)] == unset)
          {
            face_partition_[Mesh::face(o)] = partition;
            patch.push_back(Mesh::face(o));
          }
        }
    }
    vertex_partition_.assign(nv, 0);
    for(std::uint32_t v = 0; v < nv; ++v)
      vertex_partition_[v] = mesh_.corners_begin(v) == mesh_.corners_end(v)
                               ? static_cast<std::uint8_t>(v % partitions)
                               : face_partition_[Mesh::face(*mesh_.corners_begin(v))];
  }

  // Where the effects of an event go in phase 1: its own partition's state (its front), or an outbox.
  struct Band_effects
  {
    Window_propagation& engine;
    Band_partition& part;
    std::uint32_t index; // of `part`

    Band_front& front() const { return part.front; }
    void vertex(std::uint32_t v, double d, std::uint32_t label, Origin origin, std::uint32_t parent,
                std::uint32_t corner = none, double angle = 0) const
    {
      if(d < engine.distance_[v]) // (distances only decrease: what loses now loses in phase 2)
        outbox(engine.partition_of_vertex(v)).vertices.push_back({d, angle, v, label, parent, corner, origin, false});
    }
    void along_edge(std::uint32_t u, double d, std::uint32_t label, std::uint32_t v, bool always_queued) const
    {
      outbox(engine.partition_of_vertex(u)).vertices.push_back({d, 0, u, label, v, none, FROM_VERTEX, always_queued});
    }
    // The window goes straight into a block of its halfedge's chain for this band, which phase 2
    // links onto the halfedge as it is: each window is written once, here.
    void window(const Window& w, double key) const
    {
      Staged_chain& chain = staged_chain(w.halfedge);
      Band_pool& pool = part.front.pool;
      if(chain.first_block == none || pool.blocks[chain.first_block].count == Window_block::capacity)
      {
        const std::uint32_t b = pool.allocate();
        pool.blocks[b].next = chain.first_block;
        chain.first_block = b;
        if(chain.last_block == none)
          chain.last_block = b;
      }
      Window_block& block = pool.blocks[chain.first_block];
      block.windows[block.count++] = w;
      ++chain.count;
      chain.key = std::min(chain.key, key);
    }
    Staged_chain& staged_chain(std::uint32_t h) const
    {
      // Most windows go to a halfedge of the partition itself, whose state only this partition
      // writes in both phases: the chain is found from the state, which phase 2 reads anyway
      // (the table's slots, spread by a hash, each missed the cache: 45 % of this function).
      if(engine.partition_of_halfedge(h) == index)
      {
        Edge_state& edge = engine.edge_[h];
        std::vector<Staged_chain>& chains = outbox(index).windows;
        if(edge.staged != none)
          return chains[edge.staged];
        if(!edge.touched) // (so that clear() resets `staged` even after a failure in the band)
        {
          edge.touched = true;
          part.front.touched_edges.push_back(h);
        }
        edge.staged = static_cast<std::uint32_t>(chains.size());
        chains.push_back({infinity, h, none, none, 0});
        return chains.back();
      }
      if(part.staged_slots.size() < 2 * std::size_t(part.staged_count + 1))
        engine.grow_staged_slots(part);
      const std::size_t mask = part.staged_slots.size() - 1;
      for(std::size_t i = slot_of_halfedge(h) & mask;; i = (i + 1) & mask)
      {
        Staged_slot& slot = part.staged_slots[i];
        if(slot.band != part.staged_band)
        {
          std::vector<Staged_chain>& chains = outbox(engine.partition_of_halfedge(h)).windows;
          slot = {h, part.staged_band, static_cast<std::uint32_t>(chains.size())};
          ++part.staged_count;
          chains.push_back({infinity, h, none, none, 0});
          return chains.back();
        }
        if(slot.halfedge == h)
          return part.outbox[engine.partition_of_halfedge(h)].windows[slot.index];
      }
    }
    Band_outbox& outbox(std::uint32_t to) const
    {
      if(!(part.outbox_used >> to & 1))
      {
        part.outbox_used |= std::uint64_t(1) << to;
        engine.band_partitions_[to].senders.fetch_or(std::uint64_t(1) << index, std::memory_order_relaxed);
      }
      return part.outbox[to];
    }
  };

  static std::size_t slot_of_halfedge(std::uint32_t h) { return std::size_t(h) * 0x9E3779B1u >> 7; }

  // Twice the slots (at least 256), the chains of the current band staged again.
  void grow_staged_slots(Band_partition& part) const
  {
    std::vector<Staged_slot> slots(std::max<std::size_t>(256, 2 * part.staged_slots.size()));
    const std::size_t mask = slots.size() - 1;
    for(const Staged_slot& slot : part.staged_slots)
      if(slot.band == part.staged_band)
      {
        std::size_t i = slot_of_halfedge(slot.halfedge) & mask;
        while(slots[i].band == part.staged_band)
          i = (i + 1) & mask;
        slots[i] = slot;
      }
    part.staged_slots.swap(slots);
  }

  // Phase 1 for one partition: its edge events below `edge_bound` and vertex events below
  // `vertex_bound` (and none beyond the distance bound).
  void run_band_events(std::uint32_t p, double edge_bound, double vertex_bound)
  {
    Band_partition& part = band_partitions_[p];
    part.outbox_used = 0;
    part.staged_count = 0;
    if(++part.staged_band == 0) // (a slot of band 0 is empty: after 2^32 bands, empty them all)
    {
      part.staged_slots.assign(part.staged_slots.size(), Staged_slot());
      part.staged_band = 1;
    }
    const Band_effects effects{*this, part, p};
    Queue& edges = part.front.queue;
    while(!edges.empty() && edges.min_key() < edge_bound && edges.min_key() <= max_distance_)
    {
      const std::uint32_t h = edges.top().index;
      edges.pop();
      process_edge(h, effects);
    }
    Radix_heap<Vertex_event>& vertices = part.vertex_queue;
    while(!vertices.empty() && vertices.min_key() < vertex_bound && vertices.min_key() <= max_distance_)
    {
      const Vertex_event e = vertices.top();
      vertices.pop();
      emit_from_vertex(e.vertex, e.distance, effects);
    }
  }

  // Phase 2 for partition q: applies what the partitions sent it, in partition order.
  void apply_band_outboxes(std::uint32_t q)
  {
    Band_partition& part = band_partitions_[q];
    for(std::uint64_t senders = part.senders.exchange(0, std::memory_order_relaxed); senders != 0; senders &= senders - 1)
    {
      Band_outbox& box = band_partitions_[lowest_bit(senders)].outbox[q];
      for(const Vertex_change& c : box.vertices)
        if(improve_vertex(part.front, c.vertex, c.distance, c.label, c.origin, c.parent, c.corner, c.angle) &&
           (c.always_queued || mesh_.is_pseudo_source_candidate(c.vertex)))
          part.vertex_queue.push({c.distance, c.distance, c.vertex});
      for(const Staged_chain& chain : box.windows)
        link_staged_chain(part.front, chain);
      box.vertices.clear();
      box.windows.clear();
    }
    part.smallest_key = std::min(part.front.queue.min_key(), part.vertex_queue.min_key());
  }

  // Puts the windows of a staged chain in front of the pending windows of its halfedge.
  void link_staged_chain(Band_front& front, const Staged_chain& chain)
  {
    Edge_state& edge = edge_[chain.halfedge];
    if(!edge.touched)
    {
      edge.touched = true;
      front.touched_edges.push_back(chain.halfedge);
    }
    edge.staged = none;
    front.pool.blocks[chain.last_block].next = edge.first_block;
    edge.first_block = chain.first_block;
    front.pending_windows += chain.count;
    front.windows_created += chain.count;
    schedule_edge(front, chain.halfedge, chain.key);
  }

  // The events and windows the serial structures hold (the sources' before the first run, the
  // repair pass's after one) go to their partitions.
  void move_front_into_partitions()
  {
    while(!front_.queue.empty())
    {
      const Queue_entry e = front_.queue.top();
      front_.queue.pop();
      if(e.kind == Queue_entry::VERTEX)
        band_partitions_[partition_of_vertex(e.index)].vertex_queue.push({e.key, distance_[e.index], e.index}); // (as in run_queue)
      else
        band_partitions_[partition_of_halfedge(e.index)].front.queue.push(e);
    }
    front_.queue.clear();
    // (only sources put windows there, before the first run: every chain is still in the serial pool)
    if(front_.pending_windows > 0)
      for(const std::uint32_t h : front_.touched_edges)
      {
        std::uint32_t block = edge_[h].first_block;
        edge_[h].first_block = none;
        for(; block != none; block = front_.pool.blocks[block].next)
          for(std::uint32_t i = 0; i < front_.pool.blocks[block].count; ++i)
            append_to_edge(band_partitions_[partition_of_halfedge(h)].front, front_.pool.blocks[block].windows[i]);
      }
    front_.pool.clear();
    front_.pending_windows = 0;
    for(Band_partition& part : band_partitions_)
      part.smallest_key = std::min(part.front.queue.min_key(), part.vertex_queue.min_key());
  }

  // The propagation in bands on propagation_threads_ threads (see above), to an empty queue or the
  // distance bound. The threads live for the whole run and meet at a barrier twice a band: no task
  // scheduler per phase (a band's phases last tens of microseconds, shorter than what a task
  // scheduler shares between threads).
  void run_in_bands(const std::function<bool(double)>& progress, std::size_t& next_report)
  {
    move_front_into_partitions();
    const unsigned threads = propagation_threads_;
    Phase_barrier barrier(threads);
    std::atomic<bool> stop{false};
    double cancelled_at = -1;
    std::exception_ptr failure;
    std::mutex failure_mutex;
    auto fail = [&] {
      std::lock_guard<std::mutex> lock(failure_mutex);
      if(!failure)
        failure = std::current_exception();
      stop = true;
    };
    // A phase's partitions: a thread runs its own (t, t + n, ...), then those of the others that
    // nobody has started, from the last one down (what a partition does does not depend on which
    // thread runs it). claims[p]: the number of the phase partition p was last taken for.
    struct alignas(64) Claim
    {
      std::atomic<std::size_t> phase{0};
    };
    const std::uint32_t partitions = static_cast<std::uint32_t>(band_partitions_.size());
    const std::unique_ptr<Claim[]> claims(new Claim[partitions]);
    auto run_phase = [&](unsigned t, std::size_t phase, const auto& run_partition) {
      auto take = [&](std::uint32_t p) {
        return claims[p].phase.load(std::memory_order_relaxed) != phase &&
               claims[p].phase.exchange(phase, std::memory_order_relaxed) != phase;
      };
      for(std::uint32_t p = t; p < partitions; p += threads)
        if(take(p))
          run_partition(p);
      for(std::uint32_t p = partitions; p-- > 0;)
        if(p % threads != t && take(p))
          run_partition(p);
    };
    // The smallest key of the partitions each thread applied in the last phase 2: after the
    // barrier each thread reads these n lines, not the partitions' (written on other cores).
    struct alignas(64) Thread_key
    {
      double smallest = infinity;
    };
    const std::unique_ptr<Thread_key[]> smallest_keys(new Thread_key[threads]);
    for(const Band_partition& part : band_partitions_)
      smallest_keys[0].smallest = std::min(smallest_keys[0].smallest, part.smallest_key);
    auto band_loop = [&](unsigned t) {
      for(std::size_t band = 0;; ++band)
      {
        double front_key = infinity; // the same on every thread: read after the barrier
        for(unsigned i = 0; i < threads; ++i)
          front_key = std::min(front_key, smallest_keys[i].smallest);
        if(front_key == infinity || front_key > max_distance_ || stop)
          return;
        try
        {
          run_phase(t, 2 * band + 1, [&](std::uint32_t p) { run_band_events(p, front_key + 1, front_key + 1.0 / 32); });
        }
        catch(...)
        {
          fail();
        }
        barrier.wait();
        try
        {
          // (the counts of windows propagated are written in phase 1 only)
          if(t == 0 && progress && (windows_propagated() >= next_report || band % 256 == 0))
          {
            next_report = windows_propagated() + progress_interval;
            if(!progress(front_key * unit_))
            {
              cancelled_at = front_key * unit_;
              stop = true;
            }
          }
          double smallest = infinity;
          run_phase(t, 2 * band + 2, [&](std::uint32_t q) {
            apply_band_outboxes(q);
            smallest = std::min(smallest, band_partitions_[q].smallest_key);
          });
          smallest_keys[t].smallest = smallest;
        }
        catch(...)
        {
          fail();
        }
        barrier.wait();
      }
    };
    run_on_threads(threads, band_loop);
    for(Band_partition& part : band_partitions_)
    {
      Band_front& front = part.front;
      front_.touched_vertices.insert(front_.touched_vertices.end(), front.touched_vertices.begin(), front.touched_vertices.end());
      front_.touched_edges.insert(front_.touched_edges.end(), front.touched_edges.begin(), front.touched_edges.end());
      front.touched_vertices.clear();
      front.touched_edges.clear();
    }
    if(failure)
      std::rethrow_exception(failure);
    if(cancelled_at >= 0)
      throw Cancelled_error("geodesic propagation cancelled by its visitor at distance " + std::to_string(cancelled_at));
  }

  // Runs f(0) here and f(1), ..., f(n - 1) on new threads, once all of them have started (a
  // thread that cannot start leaves none waiting at a barrier for it: Error).
  template <class F>
  static void run_on_threads(unsigned n, F& f)
  {
    std::mutex mutex;
    std::condition_variable started;
    enum { WAITING, GO, ABORT } state = WAITING;
    std::vector<std::thread> workers;
    auto worker = [&](unsigned t) {
      {
        std::unique_lock<std::mutex> lock(mutex);
        started.wait(lock, [&] { return state != WAITING; });
        if(state == ABORT)
          return;
      }
      f(t);
    };
    auto release = [&](decltype(state) s) {
      {
        std::lock_guard<std::mutex> lock(mutex);
        state = s;
      }
      started.notify_all();
    };
    try
    {
      for(unsigned t = 1; t < n; ++t)
        workers.emplace_back(worker, t);
    }
    catch(const std::exception& e)
    {
      release(ABORT);
      for(std::thread& w : workers)
        w.join();
      throw Error(std::string("could not start the threads of the propagation (") + e.what() +
                  "): ask for fewer threads or none");
    }
    release(GO);
    f(0);
    for(std::thread& w : workers)
      w.join();
  }

  static std::uint32_t lowest_bit(std::uint64_t x) // (x not 0)
  {
#if defined(__GNUC__)
    return static_cast<std::uint32_t>(__builtin_ctzll(x));
#else
    std::uint32_t i = 0;
    for(; !(x >> i & 1); ++i)
    {
    }
    return i;
#endif
  }

  template <class Count>
  std::size_t sum_over_fronts(Count count) const
  {
    std::size_t sum = count(front_);
    for(const Band_partition& part : band_partitions_)
      sum += count(part.front);
    return sum;
  }

  // A pseudo-source vertex sends a point wave across the opposite edges of the faces around it.
  // When the vertex was reached by a straight geodesic, only its shadow needs this: the sector of
  // directions that the straight geodesics passing on either side of it cannot reach (angle
  // sum - 2*pi for an interior saddle; beyond the straight continuation for a boundary vertex).
  template <class Effects>
  void emit_from_vertex(std::uint32_t v, double d, const Effects& effects)
  {
    if(d > distance_[v] || emitted_at_[v] <= d)
      return; // stale event, or already emitted at this distance
    emitted_at_[v] = d;
    const std::uint32_t label = vertex_label_[v];
    pass_on_along_edges(v, d, label, effects);
    // Windows leave sources and the vertices where geodesics may bend (an isolated vertex has no
    // corner: nothing leaves it).
    if(mesh_.corners_begin(v) == mesh_.corners_end(v) ||
       (!mesh_.is_pseudo_source_candidate(v) && vertex_origin_[v] != FROM_SOURCE))
      return;
    std::vector<Walked_corner>& corner_walk = effects.front().corner_walk;
    const Corner_walk walk = walk_corners_around(v, corner_walk);
    const Sectors sectors = sectors_to_emit(v, walk);
    for(const Walked_corner& corner : corner_walk)
    {
      const std::uint32_t h = corner.halfedge;
      if(!in_region_.empty() && in_region_[Mesh::face(h)] != none)
        continue;
      for(int i = 0; i < sectors.count; ++i)
      {
        const double a0 = std::max(sectors.bounds[i][0] - corner.start, 0.0);
        const double a1 = std::min(sectors.bounds[i][1] - corner.start, corner.angle);
        if(a1 > a0)
          emit_in_corner(v, d, label, h, a0, a1, corner.angle, effects);
      }
    }
  }

  // The value d of vertex v goes on along its edges (lengths of real paths). When v was itself
  // reached along an edge (repair_along_edges), a neighbour improved so goes to the queue too: edge
  // paths then continue as in Dijkstra's algorithm where windows were lost.
  template <class Effects>
  void pass_on_along_edges(std::uint32_t v, double d, std::uint32_t label, const Effects& effects)
  {
    const bool along_edges = vertex_origin_[v] == FROM_VERTEX;
    for(const std::uint32_t* c = mesh_.corners_begin(v); c != mesh_.corners_end(v); ++c)
      if(in_region_.empty() || in_region_[Mesh::face(*c)] == none)
        for(const std::uint32_t u : {mesh_.target(*c), mesh_.source(Mesh::prev(*c))})
        {
          const double through = d + mesh_.length(u == mesh_.target(*c) ? *c : Mesh::prev(*c));
          if(through < distance_[u])
            effects.along_edge(u, through, label, v, along_edges);
        }
  }

  struct Corner_walk
  {
    double total;       // angle sum of the corners walked
    double incoming_at; // angle of the direction back to the incoming geodesic's source
    bool on_boundary;
  };

  // Walks the corners around v counter-clockwise into corner_walk, from the clockwise-most one
  // on a boundary, else from the corner the incoming geodesic came through (if any).
  Corner_walk walk_corners_around(std::uint32_t v, std::vector<Walked_corner>& corner_walk) const
  {
    const std::uint32_t incoming = incoming_corner_[v];
    std::uint32_t first = incoming != none ? incoming : *mesh_.corners_begin(v);
    bool on_boundary = false;
    for(const std::uint32_t* c = mesh_.corners_begin(v); c != mesh_.corners_end(v); ++c)
      if(mesh_.opposite(*c) == Mesh::no_halfedge)
      {
        first = *c;
        on_boundary = true;
        break;
      }
    corner_walk.clear();
    double total = 0, incoming_at = 0;
    for(std::uint32_t h = first;;)
    {
      if(h == incoming)
        incoming_at = total + incoming_angle_[v];
      const double angle = mesh_.corner_angle(h);
      corner_walk.push_back({h, total, angle});
      total += angle;
      const std::uint32_t o = mesh_.opposite(Mesh::prev(h));
      if(o == Mesh::no_halfedge || o == first || corner_walk.size() > 1024 * 1024)
        break;
      h = o;
    }
    return {total, incoming_at, on_boundary};
  }

  struct Sectors
  {
    double bounds[2][2] = {}; // angle intervals of the corner walk
    int count = 0;
  };

  // The sectors of the walk around v that need v as a pseudo-source: all of them without an
  // incoming geodesic or at the end of a needle edge, else its shadow.
  Sectors sectors_to_emit(std::uint32_t v, const Corner_walk& walk) const
  {
    const double pi = 3.14159265358979323846;
    Sectors sectors;
    if(incoming_corner_[v] == none || mesh_.bends_geodesics_in_every_direction(v))
    {
      sectors.bounds[0][0] = -1;
      sectors.bounds[0][1] = walk.total + 1;
      sectors.count = 1;
    }
    else if(!walk.on_boundary)
    {
      if(walk.total > 2 * pi)
      {
        sectors.bounds[0][0] = walk.incoming_at + pi;
        sectors.bounds[0][1] = walk.incoming_at + walk.total - pi;
        sectors.bounds[1][0] = sectors.bounds[0][0] - walk.total; // the same sector seen one turn earlier
        sectors.bounds[1][1] = sectors.bounds[0][1] - walk.total;
        sectors.count = 2;
      }
    }
    else
    {
      if(walk.incoming_at + pi < walk.total)
      {
        sectors.bounds[sectors.count][0] = walk.incoming_at + pi;
        sectors.bounds[sectors.count++][1] = walk.total;
      }
      if(walk.incoming_at - pi > 0)
      {
        sectors.bounds[sectors.count][0] = 0;
        sectors.bounds[sectors.count++][1] = walk.incoming_at - pi;
      }
    }
    return sectors;
  }

  // Window across the edge opposite to corner h (at v), for the directions [a0,a1] measured
  // counter-clockwise from the edge h.
  template <class Effects>
  void emit_in_corner(std::uint32_t v, double d, std::uint32_t label, std::uint32_t h, double a0, double a1, double angle,
                      const Effects& effects) const
  {
    const std::uint32_t opposite_edge = Mesh::next(h);
    const std::uint32_t o = mesh_.opposite(opposite_edge);
    if(o == Mesh::no_halfedge || (!in_region_.empty() && in_region_[Mesh::face(o)] != none))
      return;
    const Vec2 apex = mesh_.apex(opposite_edge);
    Window w;
    const double L = mesh_.length(opposite_edge);
    w.sx = L - apex.x;
    w.sy = -apex.y;
    if(apex.y <= flat_corner_height * L)
    {
      // v lies on the opposite edge, or nearly (a corner of nearly pi, a face of nearly no area):
      // its directions go straight on into the face across, and where they cross the edge no
      // longer tells them apart (it is ill-conditioned, or the same point for all). The whole edge
      // is emitted, a window whose source lies on or just below it (real paths all the same: the
      // segment from v to the edge lies in the face). Skipping it lost every geodesic bending at
      // such a vertex (a collapsed corner: 0.3 % too long behind it).
      w.b0 = 0;
      w.b1 = L;
    }
    else
    {
      // Where the rays at angles a0 and a1 meet the opposite edge, as a fraction from target(h).
      const Vec2 B{mesh_.length(h), 0};
      const Vec2 C = mesh_.apex(h);
      auto hit = [&](double a) {
        if(a <= 0)
          return 0.0;
        if(a >= angle)
          return 1.0;
        const Vec2 u{std::cos(a), std::sin(a)};
        const double den = cross(u, C - B);
        return den != 0 ? std::clamp(cross(B, u) / den, 0.0, 1.0) : 0.0;
      };
      // o runs from source(prev(h)) (fraction 1) to target(h) (fraction 0)
      w.b0 = L * (1 - hit(a1));
      w.b1 = L * (1 - hit(a0));
      if(!(w.b1 > w.b0))
        return;
    }
    w.sigma = d;
    w.is_line = false;
    w.halfedge = o;
    w.parent = v;
    w.label = label;
    w.origin = FROM_VERTEX;
    if(trim_by_edge_vertices(w))
      effects.window(w, min_value(w));
  }

  // Trims [b0,b1] to the part where the window beats the paths through the edge's endpoints
  // (d(A) + t and d(B) + L - t). The window's value minus t is non-increasing along the edge and
  // its value plus t non-decreasing, so each vertex removes a prefix or a suffix. Returns false
  // when nothing is left.
  bool trim_by_edge_vertices(Window& w) const
  {
    double v0, v1;
    return trim_by_edge_vertices(w, mesh_.length(w.halfedge), mesh_.source(w.halfedge), mesh_.target(w.halfedge), v0, v1);
  }

  // The same, with the edge's length and end vertices given by the caller; v0 and v1 receive the
  // values at the ends of what is left (computed once for both tests).
  bool trim_by_edge_vertices(Window& w, double L, std::uint32_t source_vertex, std::uint32_t target_vertex,
                             double& v0, double& v1) const
  {
    v0 = edge_value(w, w.b0);
    v1 = edge_value(w, w.b1);
    // Only parts worse than a vertex path by more than the tolerance are cut: the window that
    // carries a shortest path is never trimmed, whatever the rounding. The rounding of a value is
    // relative to the value itself (a source far from a short edge: sigma small, values large).
    const double tol = 1e-12 * (L + std::max(v0, v1));
    const double da = distance_[source_vertex] + tol;
    const double db = distance_[target_vertex] + tol;
    if(da < infinity && v1 >= da + w.b1)
      return false;
    if(db < infinity && v0 >= db + (L - w.b0))
      return false;
    // Both ends survive one of the tests; cut where value(t) - t = d(A) and value(t) + t = d(B) + L.
    if(da < infinity && v0 >= da + w.b0)
    {
      w.b0 = std::max(w.b0, crossing_with_vertex_path(w, da, false, L));
      v0 = edge_value(w, w.b0);
    }
    if(db < infinity && v1 >= db + (L - w.b1))
    {
      w.b1 = std::min(w.b1, crossing_with_vertex_path(w, db, true, L));
      v1 = edge_value(w, w.b1);
    }
    return w.b1 > w.b0;
  }

  // The smallest value of w on [b0,b1], given its values v0 and v1 at the ends. The values are
  // convex along the edge: the minimum is at an end unless a point wave's foot lies inside.
  static double smallest_value(const Window& w, double v0, double v1)
  {
    return !w.is_line && w.sx > w.b0 && w.sx < w.b1 ? w.sigma + std::abs(w.sy) : std::min(v0, v1);
  }

  // Trims [b0,b1] by the straight paths from the corner P of the face behind the edge that is not
  // an end of it (the third vertex of the face the window has just crossed, at distance dP): the
  // segment from P to a point x of the edge lies in that face, so dP + |x - P| is the length of a
  // real path. (The ends of the edge are the other two corners: trim_by_edge_vertices.) Only
  // parts worse by more than the tolerance are cut, as there. v0 and v1, the values at the ends,
  // follow the cut. Returns false when nothing is left.
  //
  // What P cuts, {x : value(x) > dP + |x - P|}, is convex for a line wave (the inside of a
  // parabola of focus P) and for a point wave whose sigma is at most dP (beyond the branch around P
  // of a hyperbola of foci S and P): on the edge, an interval. Both ends cut: all of it is. One end
  // cut: a prefix or a suffix, whose end is bracketed (regula falsi) and taken on the cut side, so
  // only points that the path through P beats are removed. No end cut: nothing is (a
  // piece inside the edge would leave two windows; kept whole). A point wave with sigma above dP
  // (its source farther than P) is not tested: that set is not convex.
  bool trim_by_face_vertex(Window& w, Vec2 P, double dP, double L, double& v0, double& v1) const
  {
    if(!(dP < infinity) || (!w.is_line && w.sigma > dP))
      return true;
    const double d = dP + 1e-12 * (L + std::max(v0, v1));
    // value - d > |x - P| compared in squares first: most windows are not cut, and pay no root
    auto cut = [&](double t, double value) {
      const double a = value - d;
      return a > 0 && a * a > (t - P.x) * (t - P.x) + P.y * P.y;
    };
    const bool cut0 = cut(w.b0, v0), cut1 = cut(w.b1, v1);
    if(cut0 && cut1)
      return false;
    if(!(cut0 || cut1))
      return true;
    // The cut end `out` (excess > 0) and the kept end `in`; the boundary lies between them.
    auto excess = [&](double t, double value) { return value - d - length_of(t - P.x, P.y); };
    double out = cut0 ? w.b0 : w.b1, in = cut0 ? w.b1 : w.b0;
    double g_out = cut0 ? excess(w.b0, v0) : excess(w.b1, v1), g_in = cut0 ? excess(w.b1, v1) : excess(w.b0, v0);
    if(!(g_out > 0) || g_in > 0)
      return true; // (the two forms disagree only within a rounding: nothing is cut)
    // Three steps (Illinois: an end kept twice in a row has its excess halved): each moves `out`
    // or `in` towards the boundary; what they leave of the cut part stays, and is trimmed later or
    // costs a few windows (measured: 1 % more windows than with the boundary to 1e-10, 5-10 % less
    // time).
    int replaced_last = 0;
    for(int i = 0; i < 3; ++i)
    {
      const double t = out + (in - out) * (g_out / (g_out - g_in));
      const double g = excess(t, edge_value(w, t));
      if(g > 0)
      {
        out = t;
        g_out = g;
        if(replaced_last == 1)
          g_in *= 0.5;
        replaced_last = 1;
      }
      else
      {
        in = t;
        g_in = g;
        if(replaced_last == -1)
          g_out *= 0.5;
        replaced_last = -1;
      }
    }
    if(cut0)
    {
      w.b0 = out;
      v0 = edge_value(w, out);
    }
    else
    {
      w.b1 = out;
      v1 = edge_value(w, out);
    }
    return w.b1 > w.b0;
  }

  // Without stored windows, the windows of one block of a batch (up to four, in the order they
  // reached the edge) are compared pairwise: a point wave longer than another by more than the
  // tolerance on all of the part of the edge both cover loses that part (see cut_pair); one cut to
  // nothing is left with an empty interval. On each point of the edge both values are lengths of
  // real paths, so only what a real path beats is removed. (Not with stored windows: a window
  // rebuilt from its parent would not repeat the cut.)
  void cut_overlapping_windows(Window* windows, std::uint32_t count, double L) const
  {
    for(std::uint32_t i = 0; i + 1 < count; ++i)
    {
      Window& a = windows[i];
      for(std::uint32_t j = i + 1; j < count; ++j)
      {
        Window& b = windows[j];
        // (one test of all four conditions: most pairs do not overlap)
        if(!((b.b1 > a.b0) & (a.b1 > b.b0) & !a.is_line & !b.is_line))
          continue;
        cut_pair(a, b, L);
        if(!(a.b1 > a.b0))
          break;
      }
    }
  }

  // Point waves a and b of one halfedge (of length L): the one longer by more than the tolerance on all of
  // [lo, hi], the part of the edge both cover, loses it when it is all of its interval (it is left
  // empty) or reaches one of its ends (else it would leave two pieces: kept whole). Their
  // difference g = value_a - value_b has one critical point along the edge, where the line through
  // the two sources meets it (rays from both are parallel there): a maximum when a's source lies
  // deeper below the edge, a minimum when b's does. So the smallest value of g on [lo, hi] is at
  // lo, at hi or, in the second case, at that point; likewise for -g.
  void cut_pair(Window& a, Window& b, double L) const
  {
    const double lo = std::max(a.b0, b.b0), hi = std::min(a.b1, b.b1);
    const double a_lo = edge_value(a, lo), a_hi = edge_value(a, hi);
    const double b_lo = edge_value(b, lo), b_hi = edge_value(b, hi);
    const double tol = 1e-12 * (L + std::max(std::max(a_lo, a_hi), std::max(b_lo, b_hi)));
    const double g_lo = a_lo - b_lo, g_hi = a_hi - b_hi;
    const bool a_longer = g_lo > tol && g_hi > tol;
    if(!a_longer && !(g_lo < -tol && g_hi < -tol))
      return;
    Window& longer = a_longer ? a : b;
    const Window& shorter = a_longer ? b : a;
    if(shorter.sy < longer.sy) // the critical point is a minimum of the excess: look there too
    {
      const double x = longer.sx + (shorter.sx - longer.sx) * (longer.sy / (longer.sy - shorter.sy));
      if(x > lo && x < hi && !(edge_value(longer, x) - edge_value(shorter, x) > tol))
        return;
    }
    if(lo <= longer.b0 && hi >= longer.b1)
      longer.b1 = longer.b0;
    else if(lo <= longer.b0)
      longer.b0 = hi;
    else if(hi >= longer.b1)
      longer.b1 = lo;
  }

  // Parameter t where value(t) equals d + t (from_target = false) or d + (L - t) (from_target = true).
  static double crossing_with_vertex_path(const Window& w, double d, bool from_target, double L)
  {
    if(w.is_line)
      return from_target ? (d + L - w.sigma) / (1 + w.sx) : (w.sigma - d) / (1 - w.sx);
    // sigma + sqrt((t - a)^2 + b^2) = d + t, in mirrored coordinates for the target
    const double a = from_target ? L - w.sx : w.sx;
    const double k = d - w.sigma;
    const double den = 2 * (k + a);
    double t = den > 0 ? (a * a + w.sy * w.sy - k * k) / den : infinity;
    return from_target ? L - t : t;
  }

  // Propagates the pending windows of halfedge h across face(h) together (they share the face,
  // its apex and its vertex distances), except those beyond the distance bound.
  template <class Effects>
  void process_edge(std::uint32_t h, const Effects& effects)
  {
    auto& front = effects.front();
    auto& pool = front.pool;
    if(edge_[h].scheduled_at == infinity)
      return; // an older entry: its windows went with an earlier one
    edge_[h].scheduled_at = infinity;
    double waiting = infinity; // smallest key of the windows left pending
    bool propagated_any = false;
    const Face_frame face = face_frame(h);
    const bool bounded = max_distance_ < infinity;
    // Take the whole chain of blocks off the edge; windows beyond the bound go back onto it.
    // (Children go to the other two edges of the face, never to this one. Blocks are addressed by
    // index: the pool may grow while the chain is walked.)
    std::uint32_t block = edge_[h].first_block;
    edge_[h].first_block = none;
    while(block != none)
    {
      const std::uint32_t count = pool.blocks[block].count, next = pool.blocks[block].next;
      if(next != none)
        pool.prefetch(next); // (read while this block's windows are propagated)
      // (cut in a copy of the block: the pool itself is only read here)
      std::array<Window, Window_block::capacity> windows = pool.blocks[block].windows;
      if(!keep_windows_)
        cut_overlapping_windows(windows.data(), count, face.length);
      for(std::uint32_t i = 0; i < count; ++i)
      {
        Window w = windows[i];
        --front.pending_windows;
        if(!(w.b1 > w.b0))
          continue; // (cut to nothing by another window of the block)
        if(bounded)
        {
          const double window_key = min_value(w);
          if(window_key > max_distance_)
          {
            waiting = std::min(waiting, window_key);
            append_to_edge(front, w);
            continue;
          }
        }
        // (No test against the apex here: the windows it would drop have only children that the
        // apex, an end of both of their edges, cuts off when they are made; measured, dropping it
        // changes no window created.)
        if(keep_windows_)
          w.archived = archive_window(w);
        process_window(w, face, effects);
        propagated_any = true;
      }
      pool.release(block);
      block = next;
    }
    if(propagated_any)
    {
      // Safety net along the edges of the face (lengths of real paths), once per batch.
      const std::uint32_t vc = mesh_.source(Mesh::prev(h)), va = mesh_.source(h), vb = mesh_.target(h);
      effects.vertex(vc, distance_[va] + mesh_.length(Mesh::prev(h)), vertex_label_[va], FROM_VERTEX, va);
      effects.vertex(vc, distance_[vb] + mesh_.length(Mesh::next(h)), vertex_label_[vb], FROM_VERTEX, vb);
    }
    if(waiting < infinity)
      schedule_edge(front, h, waiting);
  }

  // What the windows of one halfedge need of its face, computed once per batch: the apex and, for
  // each of the two other edges, its frame as seen from the halfedge (origin U, unit direction e,
  // inward normal perp) and the halfedge across it, where the children wait.
  struct Child_edge
  {
    Vec2 U, e, perp;
    double length;
    std::uint32_t halfedge; // in the next face; Mesh::no_halfedge on the boundary
    std::uint32_t source_vertex, target_vertex; // of `halfedge`
    double apex_at;         // parameter of the apex along the edge (1 on A->C, 0 on C->B)
    Vec2 far;               // the third corner of the face, in the frame of `halfedge`
    std::uint32_t far_vertex; // that corner if it is a saddle or on the boundary, else none
  };
  struct Face_frame
  {
    std::uint32_t halfedge, apex_vertex;
    double length;
    Vec2 apex;
    Child_edge left, right; // A->C and C->B
  };

  CGAL_ISOPHOTIC_METRIC_ONE_COPY Face_frame face_frame(std::uint32_t h) const
  {
    Face_frame f;
    f.halfedge = h;
    f.apex_vertex = mesh_.source(Mesh::prev(h));
    f.length = mesh_.length(h);
    f.apex = mesh_.apex(h);
    auto child_edge = [&](Vec2 U, Vec2 V, std::uint32_t edge, double apex_at, Vec2 far, std::uint32_t far_vertex) {
      Child_edge c;
      c.apex_at = apex_at;
      c.source_vertex = mesh_.target(edge); // (the halfedge across runs the other way)
      c.target_vertex = mesh_.source(edge);
      c.U = U;
      c.length = mesh_.length(edge);
      // (normalised by |V - U|, not by the edge's length: for a needle's short edge, U and V
      // carry absolute rounding errors that make |V - U| differ from it by 1e-4 relative, and a
      // direction of that length shrank every child's source image by as much: 1e-4 of an edge
      // below the chord behind the needle. Its direction is then known to that angle, as the
      // needle's rounded lengths fix it; the distances of the rays crossing it do not change.)
      c.e = (1.0 / norm(V - U)) * (V - U);
      c.perp = {-c.e.y, c.e.x};
      c.halfedge = mesh_.opposite(edge);
      c.far = {dot(far - U, c.e), dot(far - U, c.perp)};
      // (tested only where the third corner bends geodesics: at other corners the test cut few
      // windows and cost more than it saved, measured on fandisk, armadillo and the scans)
      c.far_vertex = mesh_.is_pseudo_source_candidate(far_vertex) ? far_vertex : none;
      return c;
    };
    f.left = child_edge({0, 0}, f.apex, Mesh::prev(h), 1, {f.length, 0}, mesh_.target(h));
    f.right = child_edge(f.apex, {f.length, 0}, Mesh::next(h), 0, {0, 0}, mesh_.source(h));
    return f;
  }

  template <class Effects>
  void process_window(const Window& w, const Face_frame& face, const Effects& effects)
  {
    const double L = face.length;
    const Vec2 C = face.apex;
    const std::uint32_t vc = face.apex_vertex;
    ++effects.front().windows_propagated;

    // The apex: reached straight through the window when its direction crosses [b0,b1].
    const double tc = apex_crossing(w, C);
    const double slack = crossing_slack(w, L);
    const double dc = tc >= w.b0 - slack && tc <= w.b1 + slack ? value_at(w, C) : infinity;
    if(dc < distance_[vc])
    {
      // The direction back to the source, as an angle in the corner at the apex from its edge to A.
      const Vec2 back = w.is_line ? Vec2{-w.sx, -w.sy} : Vec2{w.sx - C.x, w.sy - C.y};
      const Vec2 to_a{-C.x, -C.y};
      const double angle = std::atan2(std::max(0.0, cross(to_a, back)), dot(to_a, back));
      effects.vertex(vc, dc, w.label, FROM_WINDOW, none, Mesh::prev(face.halfedge), angle);
    }

    // Children: the part of [b0,b1] left of tc crosses edge A->C, the part right of it C->B
    // (an end at tc is the ray through the apex).
    const double tsplit = std::clamp(tc, w.b0, w.b1);
    if(tsplit > w.b0)
      make_child(w, w.b0, tsplit, face.left, tc <= w.b1, effects);
    if(tsplit < w.b1)
      make_child(w, tsplit, w.b1, face.right, tc >= w.b0, effects);
  }

  // Propagates the part [t0,t1] of window w onto the edge `edge` of its face (in the frame of the
  // child halfedge, U is at the origin and the next face on the positive side). `ends_at_apex`:
  // the end of [t0,t1] nearer the apex is the ray through it.
  template <class Effects>
  void make_child(const Window& w, double t0, double t1, const Child_edge& edge, bool ends_at_apex,
                  const Effects& effects) const
  {
    Window c;
    double key;
    if(child_window(w, t0, t1, edge, ends_at_apex, c, key))
      effects.window(c, key);
  }

  // The child of make_child, trimmed by the ends of its edge and the far corner of the face
  // (`key`: its smallest value); false when nothing is left. Also what rebuilds an archived window
  // from its parent.
  CGAL_ISOPHOTIC_METRIC_ONE_COPY bool child_window(const Window& w, double t0, double t1, const Child_edge& edge, bool ends_at_apex, Window& c,
                    double& key) const
  {
    if(edge.halfedge == Mesh::no_halfedge)
      return false;
    const Vec2 U = edge.U, e = edge.e, perp = edge.perp;
    const double len = edge.length;
    const Vec2 S{w.sx, w.sy};
    // Where the geodesic through (t,0) meets the child edge: parameter along it, in [0,1].
    // (The child edge, in the parent's frame, is U + a * len * e.)
    auto hit = [&](double t) -> double {
      const Vec2 P{t, 0};
      const Vec2 D = w.is_line ? S : P - S;
      const double den = cross(D, e) * len;
      if(den == 0)
        return t <= t0 ? 0.0 : 1.0;
      const double a = cross(D, (w.is_line ? P : S) - U) / den;
      return std::clamp(a, 0.0, 1.0);
    };
    double a0 = hit(t0), a1 = hit(t1);
    // The ray through the apex meets the edge at the apex, whatever the rounding of its crossing
    // tc: for a source on or just below its edge (a collapsed corner emits so), tc rounds onto the
    // source's foot, the rays through [t0,t1] all run along the edge, and hit() sent the whole
    // child to one end of its edge, where it vanished (1 % too long behind such a corner).
    if(ends_at_apex)
      (edge.apex_at == 0 ? a0 : a1) = edge.apex_at;
    // A source on its edge (within 1e-9), its foot in [t0,t1]: its geodesics cross the edge at the
    // foot, in every direction into the face, and reach the whole of both edges across, as those of
    // a collapsed corner's own window do; hit() cannot tell where rays along the edge go (a border
    // vertex on the long edge of a cap, a needle across: 1 % too long behind it).
    const double near = 1e-9 * (std::abs(w.sx) + len);
    if(!w.is_line && w.sy >= -near && w.sx >= t0 - near && w.sx <= t1 + near)
    {
      a0 = 0;
      a1 = 1;
    }
    if(a0 > a1)
      std::swap(a0, a1);
    if(a1 - a0 <= 1e-12)
      return false;
    c.b0 = a0 * len;
    c.b1 = a1 * len;
    if(w.is_line)
    {
      c.sx = dot(S, e);
      c.sy = dot(S, perp);
      if(!(c.sy > 1e-15))
        return false;
      c.sigma = w.sigma + dot(U, S);
    }
    else
    {
      const Vec2 R = S - U;
      c.sx = dot(R, e);
      c.sy = dot(R, perp);
      if(!(c.sy < 0))
      {
        // A source on the child edge's line: the window of a collapsed corner (its source on its
        // edge) crossing a face collapsed along the same line (caps side by side). Its geodesics
        // leave the source into the face across, as those of the corner's own window do; dropping
        // it lost every path bending there (5e-5 too long behind two such caps). Above the line
        // by a rounding at most, the source is put on it.
        if(!(c.sy <= 0x1p-50 * (std::abs(R.x) + std::abs(R.y))))
          return false;
        c.sy = -0.0;
      }
      c.sigma = w.sigma;
    }
    c.is_line = w.is_line;
    c.halfedge = edge.halfedge;
    c.parent = (edge.apex_at == 0 ? right_child : 0) | w.archived; // (C->B: the right child)
    c.label = w.label;
    c.origin = FROM_PARENT;
    c.generation = static_cast<std::uint8_t>(w.generation + 1);
    double v0, v1;
    if(!trim_by_edge_vertices(c, len, edge.source_vertex, edge.target_vertex, v0, v1) ||
       (edge.far_vertex != none && !trim_by_face_vertex(c, edge.far, distance_[edge.far_vertex], len, v0, v1)))
      return false;
    key = smallest_value(c, v0, v1);
    return true;
  }

  // ------------------------------------------------------------ the archive

  // With stored windows, every propagated window is filed on its halfedge. Nearly all of them are
  // children of other windows (99.5 % on bunny00 and fandisk Loop x2), and a child is made from its
  // parent by a few operations on numbers the archive holds: it is filed as a 2-byte link to its
  // parent, and rebuilt when a query needs it (child_window, the same arithmetic, so the same source
  // and sigma bit for bit). Its interval is rebuilt trimmed by the vertex distances at the time of
  // the query, not of the propagation: it can only lose parts where a path through a corner of the
  // face it crossed is shorter, where it defines no distance. One window in full_record_every_ of a
  // line of descent, and every window that starts one (emitted by a vertex, a point, a region), is
  // filed in full (a 48-byte record), so a rebuild goes back through at most that many parents.
  //
  // Records are numbered per halfedge and per kind (full or link): a window's archive entry is its
  // number, with link_entry set for a link. A parent lies on one of two halfedges, known from the
  // child's (parent_halfedge), so a reference to it is its entry plus one bit (right_child); a link
  // holds it in 16 bits (local numbers below 2^14; a child of a parent numbered higher is filed in
  // full). The records of one batch of a halfedge follow each other in two pools, one for each kind:
  // a run (24 bytes) says where they start and what they are numbered, and a halfedge's runs are
  // chained, newest first; a batch of 50 windows on average (fandisk Loop x2) spends half a byte a
  // window on it. Returns the window's archive entry.
  std::uint32_t archive_window(Window& w)
  {
    Archive_run& run = current_run(w.halfedge);
    if(w.origin == FROM_PARENT && w.parent != none && w.generation < full_record_every_ &&
       (w.parent & local_mask) <= link_local_mask)
    {
      link_records_.push_back(static_cast<std::uint16_t>((w.parent >> 16 & ~link_local_mask) | (w.parent & link_local_mask)));
      ++archived_windows_;
      return link_entry | (run.link_local + run.link_count++);
    }
    w.generation = 0; // (its children count from here)
    full_records_.push_back({w.b0, w.b1, w.sx, w.sy, w.sigma, w.parent,
                             w.label | std::uint32_t(w.origin) << label_bits | std::uint32_t(w.is_line) << 31});
    ++archived_windows_;
    return run.full_local + run.full_count++;
  }

  // The run that records of halfedge h are appended to: its last one if nothing was filed since
  // (its records end the pools) and it has room, else a new one.
  Archive_run& current_run(std::uint32_t h)
  {
    Edge_state& edge = edge_[h];
    if(edge.last_run != none && edge.last_run + 1 == runs_.size())
    {
      Archive_run& last = runs_[edge.last_run];
      if(last.full_count < run_capacity && last.link_count < run_capacity)
        return last;
    }
    if(link_records_.size() >= max_pool_size || full_records_.size() >= max_pool_size)
      throw Error("more windows than the archive can number (" + std::to_string(archived_windows_) +
                  "): propagate without stored windows or up to a distance bound");
    Archive_run run;
    run.full_begin = static_cast<std::uint32_t>(full_records_.size());
    run.link_begin = static_cast<std::uint32_t>(link_records_.size());
    run.full_local = run.link_local = 0;
    if(edge.last_run != none)
    {
      const Archive_run& before = runs_[edge.last_run];
      run.full_local = before.full_local + before.full_count;
      run.link_local = before.link_local + before.link_count;
    }
    run.full_count = run.link_count = 0;
    run.previous = edge.last_run;
    edge.last_run = static_cast<std::uint32_t>(runs_.size());
    runs_.push_back(run);
    return runs_[edge.last_run];
  }

  // Lists the runs of each halfedge, oldest first, so that the run holding an entry is found by
  // bisection (archived_window). Walking a halfedge's chain from its newest run costs a step per
  // run, and a window can be its run's only record: around the apex of a spike (damaged cube, an
  // angle sum of 4.7e-5) a wave winds pi / 4.7e-5 times, 67k windows and runs on each of its
  // edges, and every rebuild of a child there walked them (a point query took minutes).
  void index_runs()
  {
    const std::uint32_t halfedges = static_cast<std::uint32_t>(edge_.size());
    first_run_of_halfedge_.assign(halfedges + 1, 0);
    runs_by_halfedge_.resize(runs_.size());
    for(std::uint32_t h = 0; h < halfedges; ++h)
    {
      std::uint32_t count = 0;
      for(std::uint32_t r = edge_[h].last_run; r != none; r = runs_[r].previous)
        ++count;
      first_run_of_halfedge_[h + 1] = first_run_of_halfedge_[h] + count;
      std::uint32_t slot = first_run_of_halfedge_[h + 1];
      for(std::uint32_t r = edge_[h].last_run; r != none; r = runs_[r].previous)
        runs_by_halfedge_[--slot] = r;
    }
  }

  // The halfedge of the parent referred to by `parent` from a child on halfedge h: the parent
  // crossed face(opposite(h)) through one of its two other edges.
  std::uint32_t parent_halfedge(std::uint32_t h, std::uint32_t parent) const
  {
    const std::uint32_t across = mesh_.opposite(h);
    return (parent & right_child) != 0 ? Mesh::prev(across) : Mesh::next(across);
  }

  // A window filed in full, as a window of halfedge h.
  static Window unpack(const Archived_window& a, std::uint32_t h)
  {
    Window w;
    w.b0 = a.b0;
    w.b1 = a.b1;
    w.sx = a.sx;
    w.sy = a.sy;
    w.sigma = a.sigma;
    w.halfedge = h;
    w.parent = a.parent;
    w.label = a.label_and_kind & (max_sources - 1);
    w.origin = Origin((a.label_and_kind >> label_bits) & 7);
    w.is_line = (a.label_and_kind >> 31) != 0;
    return w;
  }

  // The archived window of halfedge h and entry `entry` into `w`; false when its rebuilt interval
  // is empty. `ancestors`, if given, gets the windows rebuilt on the way, each before its child.
  bool archived_window(std::uint32_t h, std::uint32_t entry, Window& w, std::vector<Window>* ancestors = nullptr) const
  {
    const std::uint32_t local = entry & local_mask;
    const bool link = (entry & link_entry) != 0;
    // The last run of h whose first number of the kind is not above `local` (runs that hold
    // none of the kind share the number of the next one, which is then the one found).
    const auto first = runs_by_halfedge_.begin() + first_run_of_halfedge_[h];
    const auto last = runs_by_halfedge_.begin() + first_run_of_halfedge_[h + 1];
    const auto after = std::upper_bound(first, last, local, [&](std::uint32_t value, std::uint32_t r) {
      return value < (link ? runs_[r].link_local : runs_[r].full_local);
    });
    const Archive_run& run = runs_[*std::prev(after)];
    if(!link)
      w = unpack(full_records_[run.full_begin + (local - run.full_local)], h);
    else if(!linked_window(h, link_records_[run.link_begin + (local - run.link_local)], w, ancestors))
      return false;
    w.archived = entry;
    return true;
  }

  // The window of halfedge h filed as link `link`, rebuilt from its parent; false when empty.
  bool linked_window(std::uint32_t h, std::uint16_t link, Window& w, std::vector<Window>* ancestors = nullptr) const
  {
    const std::uint32_t parent = std::uint32_t(link & ~link_local_mask) << 16 | (link & link_local_mask);
    Window p;
    if(!archived_window(parent_halfedge(h, parent), parent & ~right_child, p, ancestors) || !rebuild_child(p, h, w))
      return false;
    if(ancestors != nullptr)
      ancestors->push_back(p);
    return true;
  }

  // The child of `parent` on halfedge h, made as process_window makes it.
  bool rebuild_child(const Window& parent, std::uint32_t h, Window& c) const
  {
    const Face_frame face = face_frame(parent.halfedge);
    const double tc = apex_crossing(parent, face.apex);
    const double tsplit = std::clamp(tc, parent.b0, parent.b1);
    double key;
    if(face.left.halfedge == h)
      return tsplit > parent.b0 && child_window(parent, parent.b0, tsplit, face.left, tc <= parent.b1, c, key);
    return tsplit < parent.b1 && child_window(parent, tsplit, parent.b1, face.right, tc >= parent.b0, c, key);
  }

  // ------------------------------------------------------------ trace-back

  // Where trace_back stands: at vertex `index`, or with the path's last point on the edge of the
  // last window of its chain, or at a source (the path is complete). The chain holds the
  // window's ancestors rebuilt with it, each before its child: the path goes on through them.
  struct Trace_state
  {
    enum Kind { AT_VERTEX, ON_WINDOW_EDGE, AT_SOURCE } kind;
    std::uint32_t index;
  };

  // Goes on from the path's last point through `best`, what realises it (found at `best.at`).
  Trace_state step_to(const Point_value& best, std::vector<Surface_point>& path, std::vector<Window>& chain) const
  {
    switch(best.kind)
    {
    case Point_value::POINT_SOURCE:
      path.push_back(point_sources_in_face_[best.index].point);
      return {Trace_state::AT_SOURCE, none};
    case Point_value::VERTEX:
      return {Trace_state::AT_VERTEX, best.index};
    case Point_value::WINDOW:
    {
      Window w;
      chain.clear();
      archived_window(best.halfedge, best.index, w, &chain); // (found by the query: not empty)
      chain.push_back(w);
      const Vec2 q = position(mesh_.corner_positions(w.halfedge), best.at.barycentric);
      path.push_back(point_on_halfedge(w.halfedge, edge_crossing(w, q)));
      return {Trace_state::ON_WINDOW_EDGE, none};
    }
    case Point_value::IN_REGION:
      return {Trace_state::AT_SOURCE, none};
    default:
      throw Error("geodesic path trace-back reached a point without a value (inconsistent propagation state)");
    }
  }

  // Appends vertex v and follows its origin.
  Trace_state step_back_from_vertex(std::uint32_t v, std::vector<Surface_point>& path, std::vector<Window>& chain) const
  {
    path.push_back(vertex_point(v));
    switch(vertex_origin_[v])
    {
    case FROM_SOURCE:
      return {Trace_state::AT_SOURCE, none};
    case FROM_POINT:
      path.push_back(point_sources_in_face_[vertex_parent_[v]].point);
      return {Trace_state::AT_SOURCE, none};
    case FROM_VERTEX:
      return {Trace_state::AT_VERTEX, vertex_parent_[v]};
    default: // FROM_WINDOW: v is the apex of the face it was reached through, from the edge opposite it
    {
      const std::uint32_t corner = incoming_corner_[v];
      Surface_point at{Mesh::face(corner), {0, 0, 0}};
      at.barycentric[corner % 3] = 1;
      Point_value best;
      Candidates_excluded excluded;
      excluded.vertex = v;
      excluded.halfedges = {corner, Mesh::prev(corner)}; // (the edges at v: their rays to v cross at v)
      // The windows first: a corner of the face whose value ties with v's may owe it to v, and
      // following it would lead back to v.
      excluded.corners = false;
      evaluate_candidates_in_face(at, best, excluded);
      if(best.kind != Point_value::WINDOW || !(best.distance <= distance_[v] * (1 + 1e-12)))
      {
        best = Point_value();
        excluded.corners = true;
        evaluate_candidates_in_face(at, best, excluded);
      }
      best.at = at;
      return step_to(best, path, chain);
    }
    }
  }

  // The last point of `path` lies on the edge of the last window of `chain`: follows its origin.
  Trace_state step_back_across_window(std::vector<Surface_point>& path, std::vector<Window>& chain) const
  {
    const Window w = chain.back();
    chain.pop_back();
    switch(w.origin)
    {
    case FROM_REGION:
      return {Trace_state::AT_SOURCE, none}; // the crossing point lies on the region's boundary edge
    case FROM_POINT:
      path.push_back(point_sources_in_face_[w.parent].point);
      return {Trace_state::AT_SOURCE, none};
    case FROM_VERTEX:
      return {Trace_state::AT_VERTEX, w.parent};
    default: // FROM_PARENT: the crossing lies on an edge of the parent's face; cross the parent's edge
    {
      const Surface_point at = across_edge(path.back(), w.halfedge);
      // (a window filed in full is the first of its chain: its parent is rebuilt with its own ancestors)
      Window parent;
      if(chain.empty() && archived_window(parent_halfedge(w.halfedge, w.parent), w.parent & ~right_child, parent, &chain))
        chain.push_back(parent);
      if(!chain.empty())
      {
        const Window& p = chain.back();
        const Vec2 q = position(mesh_.corner_positions(p.halfedge), at.barycentric);
        path.push_back(point_on_halfedge(p.halfedge, edge_crossing(p, q)));
        return {Trace_state::ON_WINDOW_EDGE, none};
      }
      // (rebuilt with the final vertex distances, the parent lost this part: a path through a
      // vertex is shorter there, found by what realises the crossing point in the face across,
      // not the windows of this edge)
      Point_value best;
      Candidates_excluded excluded;
      excluded.halfedges[0] = mesh_.opposite(w.halfedge);
      evaluate_candidates_in_face(at, best, excluded);
      best.at = at;
      return step_to(best, path, chain);
    }
    }
  }

  // Candidates a trace-back step leaves out: a corner and the windows of up to two halfedges.
  struct Candidates_excluded
  {
    std::uint32_t vertex = none;
    bool corners = true; // false: no corner at all
    std::array<std::uint32_t, 2> halfedges{{none, none}};
    bool window(const Window& w) const { return w.halfedge == halfedges[0] || w.halfedge == halfedges[1]; }
  };

  // ------------------------------------------------------------ point queries

  void evaluate_in_face(const Surface_point& p, Point_value& best) const
  {
    const double before = best.distance;
    evaluate_candidates_in_face(p, best, Candidates_excluded());
    if(best.distance < before)
      best.at = p;
  }

  // Point `p` of the edge of halfedge `h` (weight only on the two ends of h), in the face across h.
  Surface_point across_edge(const Surface_point& p, std::uint32_t h) const
  {
    const std::uint32_t o = mesh_.opposite(h);
    Surface_point q{Mesh::face(o), {0, 0, 0}};
    q.barycentric[o % 3] = p.barycentric[(h + 1) % 3];
    q.barycentric[(o + 1) % 3] = p.barycentric[h % 3];
    return q;
  }

  // A face of a source region: distance 0 everywhere.
  bool inside_region(std::uint32_t f, Point_value& best) const
  {
    if(in_region_.empty() || in_region_[f] == none)
      return false;
    best = Point_value();
    best.distance = 0;
    best.label = in_region_[f];
    best.kind = Point_value::IN_REGION;
    return true;
  }

  // Enumerates the candidates for the distance at points of face f, in a fixed order (ties keep
  // the first): for each halfedge h of f, `frame(corners)` with f unfolded in the frame of h, then
  // in the first frame only `corner(position, v)` for the corners of f and
  // `point_source(position, i)` for the point sources in f, then `window(w, entry, slack)` for each
  // window archived on h (slack: the rounding tolerance on where a ray crosses h).
  template <class Frame, class Corner, class Point_source, class Archived_window>
  void for_each_candidate_in_face(std::uint32_t f, Frame&& frame, Corner&& corner, Point_source&& point_source,
                                  Archived_window&& window) const
  {
    for(std::uint32_t h = 3 * f; h < 3 * f + 3; ++h)
    {
      const std::array<Vec2, 3> corners = mesh_.corner_positions(h);
      frame(corners);
      if(h == 3 * f)
      {
        for(int c = 0; c < 3; ++c)
          corner(corners[c], mesh_.source(3 * f + c));
        for(std::uint32_t i = 0; i < point_sources_in_face_.size(); ++i)
          if(point_sources_in_face_[i].point.face == f)
            point_source(position(corners, point_sources_in_face_[i].point.barycentric), i);
      }
      const double L = mesh_.length(h);
      for(std::uint32_t r = edge_[h].last_run; r != none; r = runs_[r].previous)
      {
        const Archive_run& run = runs_[r];
        for(std::uint32_t i = 0; i < run.full_count; ++i)
        {
          const Window w = unpack(full_records_[run.full_begin + i], h);
          window(w, run.full_local + i, query_slack(w, L));
        }
        Window w;
        for(std::uint32_t i = 0; i < run.link_count; ++i)
          if(linked_window(h, link_records_[run.link_begin + i], w))
            window(w, link_entry | (run.link_local + i), query_slack(w, L));
      }
    }
  }

  void evaluate_candidates_in_face(const Surface_point& p, Point_value& best,
                                   const Candidates_excluded& excluded) const
  {
    if(inside_region(p.face, best))
      return;
    Vec2 q{0, 0}; // p in the current frame
    for_each_candidate_in_face(
        p.face,
        [&](const std::array<Vec2, 3>& corners) { q = position(corners, p.barycentric); },
        [&](Vec2 corner, std::uint32_t v) {
          if(v == excluded.vertex || !excluded.corners)
            return;
          const double d = distance_[v] + norm(q - corner);
          if(d < best.distance)
            best = {d, vertex_label_[v], Point_value::VERTEX, v, p};
        },
        [&](Vec2 x, std::uint32_t i) {
          const double d = norm(q - x);
          if(d < best.distance)
            best = {d, point_sources_in_face_[i].label, Point_value::POINT_SOURCE, i, p};
        },
        [&](const Window& w, std::uint32_t entry, double slack) {
          if(excluded.window(w))
            return;
          const double t = edge_crossing(w, q);
          if(t < w.b0 - slack || t > w.b1 + slack)
            return;
          const double d = value_at(w, q);
          if(d < best.distance)
            best = {d, w.label, Point_value::WINDOW, entry, p, w.halfedge};
        });
  }

  // The part [lo, hi] of the segment from a to b (parameters in [0, 1]) covered by window w: the
  // points whose crossing of the edge lies in [b0 - slack, b1 + slack]; false when none. The
  // crossing is c(t) = N(t) / B(t) with N, B linear in t (B = 1 for a line wave, B > 0 for a point
  // wave, whose source must lie strictly across the edge from both ends), so each end of the
  // interval gives a linear inequality in t.
  static bool covered_part_of_segment(const Window& w, double slack, Vec2 a, Vec2 b, double& lo, double& hi)
  {
    double n0, n1, d0 = 1, d1 = 1;
    if(w.is_line)
    {
      if(w.sy == 0)
        return false;
      n0 = a.x - a.y * w.sx / w.sy;
      n1 = b.x - b.y * w.sx / w.sy;
    }
    else
    {
      d0 = a.y - w.sy;
      d1 = b.y - w.sy;
      n0 = w.sx * a.y - w.sy * a.x;
      n1 = w.sx * b.y - w.sy * b.x;
    }
    lo = 0;
    hi = 1;
    // keeps the t of [lo, hi] where g0 + (g1 - g0) t >= 0
    auto keep_non_negative = [&](double g0, double g1) {
      if(g0 >= 0 && g1 >= 0)
        return;
      if(g0 < 0 && g1 < 0)
      {
        lo = 1;
        hi = 0;
        return;
      }
      const double root = g0 / (g0 - g1);
      if(g0 < 0)
        lo = std::max(lo, root);
      else
        hi = std::min(hi, root);
    };
    keep_non_negative(n0 - (w.b0 - slack) * d0, n1 - (w.b0 - slack) * d1);
    keep_non_negative((w.b1 + slack) * d0 - n0, (w.b1 + slack) * d1 - n1);
    return lo <= hi;
  }

  // The candidates of evaluate_candidates_in_face, each minimised over the segment p0 p1 of face f.
  void segment_minimum_in_face(const Surface_point& p0, const Surface_point& p1, Point_value& best, double& t_best) const
  {
    const std::uint32_t f = p0.face;
    if(inside_region(f, best))
    {
      best.at = p0;
      t_best = 0;
      return;
    }
    auto consider = [&](double d, double t, std::uint32_t label, Point_value::Kind kind, std::uint32_t index,
                        std::uint32_t halfedge = none) {
      if(d < best.distance)
      {
        Surface_point at{f, {0, 0, 0}};
        for(int i = 0; i < 3; ++i)
          at.barycentric[i] = (1 - t) * p0.barycentric[i] + t * p1.barycentric[i];
        best = {d, label, kind, index, at, halfedge};
        t_best = t;
      }
    };
    Vec2 a{0, 0}, b{0, 0}, ab{0, 0}; // the segment in the current frame
    double ab2 = 0;
    // parameter of the point of the segment nearest to x, within [lo, hi]
    auto nearest = [&](Vec2 x, double lo, double hi) {
      return ab2 > 0 ? std::clamp(dot(x - a, ab) / ab2, lo, hi) : lo;
    };
    for_each_candidate_in_face(
        f,
        [&](const std::array<Vec2, 3>& corners) {
          a = position(corners, p0.barycentric);
          b = position(corners, p1.barycentric);
          ab = b - a;
          ab2 = dot(ab, ab);
        },
        [&](Vec2 corner, std::uint32_t v) {
          const double tc = nearest(corner, 0, 1);
          consider(distance_[v] + norm(a + tc * ab - corner), tc, vertex_label_[v], Point_value::VERTEX, v);
        },
        [&](Vec2 x, std::uint32_t i) {
          const double tc = nearest(x, 0, 1);
          consider(norm(a + tc * ab - x), tc, point_sources_in_face_[i].label, Point_value::POINT_SOURCE, i);
        },
        [&](const Window& w, std::uint32_t entry, double slack) {
          if(!w.is_line && (a.y - w.sy <= 0 || b.y - w.sy <= 0))
          {
            // degenerate (source on the edge's line): the point query's rule at the segment's ends
            // and at the point nearest to the source
            for(const double t : {0.0, 1.0, nearest({w.sx, w.sy}, 0, 1)})
            {
              const Vec2 x = a + t * ab;
              const double c = edge_crossing(w, x);
              if(c >= w.b0 - slack && c <= w.b1 + slack)
                consider(value_at(w, x), t, w.label, Point_value::WINDOW, entry, w.halfedge);
            }
            return;
          }
          double lo, hi;
          if(!covered_part_of_segment(w, slack, a, b, lo, hi))
            return;
          if(w.is_line) // linear along the segment: smallest at an end of the covered part
          {
            consider(value_at(w, a + lo * ab), lo, w.label, Point_value::WINDOW, entry, w.halfedge);
            consider(value_at(w, a + hi * ab), hi, w.label, Point_value::WINDOW, entry, w.halfedge);
          }
          else
          {
            const double tw = nearest({w.sx, w.sy}, lo, hi);
            consider(value_at(w, a + tw * ab), tw, w.label, Point_value::WINDOW, entry, w.halfedge);
          }
        });
  }

  const Mesh& mesh_;
  const double unit_; // of every length and distance inside (Intrinsic_triangle_mesh::length_unit())
  bool keep_windows_ = false;
  unsigned propagation_threads_ = 0; // see set_propagation_threads
  std::uint8_t full_record_every_ = default_full_record_every; // see set_keep_windows
  bool propagated_ = false;
  double max_distance_ = infinity;

  Huge_page_vector<double> distance_;
  Huge_page_vector<double> emitted_at_;
  Huge_page_vector<std::uint32_t> vertex_label_;
  Huge_page_vector<std::uint32_t> vertex_parent_;
  Huge_page_vector<Origin> vertex_origin_;
  Huge_page_vector<std::uint32_t> incoming_corner_; // corner through which a window reached the vertex
  Huge_page_vector<double> incoming_angle_;         // direction back to its source in that corner

  static constexpr std::uint32_t run_capacity = 0xFFFF; // records of a kind in one run
  static constexpr std::uint32_t link_entry = std::uint32_t(1) << 30; // in an entry: filed as a link
  static constexpr std::uint32_t right_child = std::uint32_t(1) << 31; // in a reference to a parent
  static constexpr std::uint32_t local_mask = link_entry - 1;           // an entry's number
  static constexpr std::uint32_t link_local_mask = 0x3FFF; // the parent's number in a link (its top bits: as above)
  static constexpr std::size_t max_pool_size = std::numeric_limits<std::uint32_t>::max() - run_capacity;
  // An array growing in chunks of 2 MB: no copy of the whole and no 2x peak as a vector's growth
  // would have. Not in huge pages: the archive is written once, and where the system compacts
  // memory to make huge pages for a process that asks for them, a large archive spent more time
  // waiting for that than its 4 kB page faults cost (fandisk Loop x2 on a busy machine: 1.8-2.2 s
  // of system time with the advice, 0.55 s without).
  template <class T>
  class Chunked_array
  {
  public:
    T& operator[](std::size_t i) { return chunks_[i / chunk_size].get()[i % chunk_size]; }
    const T& operator[](std::size_t i) const { return chunks_[i / chunk_size].get()[i % chunk_size]; }
    std::size_t size() const { return size_; }
    void push_back(const T& x)
    {
      if(size_ == chunks_.size() * chunk_size)
        chunks_.push_back(allocate_huge_page_chunk<T>(chunk_size, false));
      new(&(*this)[size_++]) T(x);
    }
    void clear()
    {
      if(chunks_.size() > 1)
        chunks_.resize(1); // the first chunk stays: small bounded propagations allocate nothing
      size_ = 0;
    }

  private:
    static constexpr std::size_t chunk_size = huge_page_bytes / sizeof(T);
    std::vector<Huge_page_chunk<T>> chunks_;
    std::size_t size_ = 0;
  };
  Chunked_array<Archived_window> full_records_;
  Chunked_array<std::uint16_t> link_records_; // the parent's reference, see archive_window
  Chunked_array<Archive_run> runs_;
  std::vector<std::uint32_t> runs_by_halfedge_;     // see index_runs
  std::vector<std::uint32_t> first_run_of_halfedge_; // per halfedge: its first place in runs_by_halfedge_
  std::size_t archived_windows_ = 0;
  struct Edge_state
  {
    double scheduled_at = infinity; // key of the queue entry that will propagate its pending windows
    std::uint32_t first_block = none; // its pending windows: a chain of blocks
    std::uint32_t last_run = none;  // with stored windows: the newest run of its archived windows
    bool touched = false;           // changed since the last clear()
    // In a run in bands: the index of the chain its own partition's phase 1 staged for it in the
    // current band, none if none (in the padding: the state stays 24 bytes).
    std::uint32_t staged = none;
  };
  Huge_page_vector<Edge_state> edge_;
  Front front_;
  std::vector<Band_partition> band_partitions_; // empty for the serial run
  std::vector<std::uint8_t> face_partition_, vertex_partition_; // (see make_band_patches)
  std::uint32_t patches_dealt_to_ = 0; // the number of partitions face_partition_ was made for
  std::unique_ptr<Band_block_store> band_blocks_; // (on the heap: the partitions' pools point to it)
  std::vector<std::uint32_t> region_faces_;

  std::vector<Source> sources_;
  std::vector<Located_point_source> point_sources_in_face_;
  Huge_page_vector<std::uint32_t> in_region_; // per face: region label or none
};

} // namespace internal
} // namespace Isophotic_metric
} // namespace CGAL

#endif
