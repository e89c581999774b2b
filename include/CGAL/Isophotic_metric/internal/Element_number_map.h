// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Numbers attached to the elements of a mesh during the set-up (their index in the package's
// numbering, a flag), without a dynamic property where the mesh's own indices serve.
#ifndef CGAL_ISOPHOTIC_METRIC_INTERNAL_ELEMENT_NUMBER_MAP_H
#define CGAL_ISOPHOTIC_METRIC_INTERNAL_ELEMENT_NUMBER_MAP_H

#include <CGAL/Isophotic_metric/Geodesics/internal/Huge_page_chunk.h>

#include <CGAL/Dynamic_property_map.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>

#include <boost/graph/graph_traits.hpp>
#include <boost/property_map/property_map.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {
namespace internal {

/// A writable map from the elements of a mesh (`Descriptor`: its vertex, halfedge or face
/// descriptor, `DynamicTag` the matching `CGAL::dynamic_*_property_t<std::uint32_t>`) to 32-bit
/// numbers. Where the descriptor converts to an index (Surface_mesh), a vector indexed by it, sized
/// for the number of elements and grown on `put` when an index is beyond (no dynamic property to
/// create and fill); `get` of an element never `put` then gives `no_number`. Otherwise, a dynamic
/// property map.
template <class TriangleMesh, class Descriptor, class DynamicTag>
class Element_number_map
{
  static constexpr bool by_own_index = std::is_convertible<Descriptor, std::size_t>::value;
  typedef typename boost::property_map<TriangleMesh, DynamicTag>::const_type Dynamic_map;
  typedef std::conditional_t<by_own_index, Huge_page_vector<std::uint32_t>, Dynamic_map> Storage;

public:
  static constexpr std::uint32_t no_number = (std::numeric_limits<std::uint32_t>::max)();

  explicit Element_number_map(const TriangleMesh& tm) : storage_(make_storage(tm)) {}

  friend void put(Element_number_map& m, const Descriptor& d, std::uint32_t value)
  {
    if constexpr(by_own_index)
    {
      const std::size_t i = static_cast<std::size_t>(d);
      if(i >= m.storage_.size())
        m.storage_.resize((std::max)(i + 1, 2 * m.storage_.size()), no_number);
      m.storage_[i] = value;
    }
    else
      put(m.storage_, d, value);
  }

  friend std::uint32_t get(const Element_number_map& m, const Descriptor& d)
  {
    if constexpr(by_own_index)
    {
      const std::size_t i = static_cast<std::size_t>(d);
      return i < m.storage_.size() ? m.storage_[i] : no_number;
    }
    else
      return get(m.storage_, d);
  }

private:
  static Storage make_storage(const TriangleMesh& tm)
  {
    if constexpr(by_own_index)
      return Storage(number_of_elements(tm), no_number);
    else
      return get(DynamicTag(), tm);
  }

  // (the indices of a mesh without removed elements run up to this number)
  static std::size_t number_of_elements(const TriangleMesh& tm)
  {
    typedef boost::graph_traits<TriangleMesh> GT;
    if constexpr(std::is_same<Descriptor, typename GT::vertex_descriptor>::value)
      return static_cast<std::size_t>(num_vertices(tm));
    else if constexpr(std::is_same<Descriptor, typename GT::halfedge_descriptor>::value)
      return static_cast<std::size_t>(num_halfedges(tm));
    else
      return static_cast<std::size_t>(num_faces(tm));
  }

  Storage storage_;
};

template <class TriangleMesh>
using Vertex_number_map = Element_number_map<TriangleMesh, typename boost::graph_traits<TriangleMesh>::vertex_descriptor,
                                             CGAL::dynamic_vertex_property_t<std::uint32_t>>;
template <class TriangleMesh>
using Halfedge_number_map = Element_number_map<TriangleMesh, typename boost::graph_traits<TriangleMesh>::halfedge_descriptor,
                                               CGAL::dynamic_halfedge_property_t<std::uint32_t>>;
template <class TriangleMesh>
using Face_number_map = Element_number_map<TriangleMesh, typename boost::graph_traits<TriangleMesh>::face_descriptor,
                                           CGAL::dynamic_face_property_t<std::uint32_t>>;

} // namespace internal
} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_INTERNAL_ELEMENT_NUMBER_MAP_H
