// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Named parameters of the package, chaining with CGAL's own in one expression:
//   IM::parameters::vertex_point_map(vpm).isophotic_weight(0.8).euclidean_weight(0.2)
// The result IS-A CGAL::Named_function_parameters, so CGAL functions accept it and ignore the tags
// they do not know (PMP::compute_vertex_normals, ...); where a CGAL overload set needs the exact
// CGAL type, pass parameters::cgal_np(np).
// CGAL 5.5.1 has no hook for out-of-tree parameters; this wrapper adds one without touching CGAL.
#ifndef CGAL_ISOPHOTIC_METRIC_NAMED_FUNCTION_PARAMETERS_H
#define CGAL_ISOPHOTIC_METRIC_NAMED_FUNCTION_PARAMETERS_H

#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>

namespace CGAL {
namespace Isophotic_metric {

// Our tags live in our namespace: no clash with current or future CGAL tags.
namespace internal_np {
#define CGAL_add_named_parameter(X, Y, Z) enum X { Y };
#include <CGAL/Isophotic_metric/internal/parameters_interface.h>
#undef CGAL_add_named_parameter
} // namespace internal_np

/// \ingroup PkgIsophoticMetricRef
/// A CGAL named-parameter pack that also offers the package's own parameters.
template <typename T, typename Tag, typename Base = CGAL::internal_np::No_property>
struct Named_function_parameters : CGAL::Named_function_parameters<T, Tag, Base>
{
  // No typedef called `base` here: CGAL's lookup uses NP::base.
  typedef CGAL::Named_function_parameters<T, Tag, Base> CGAL_np;
  typedef Named_function_parameters<T, Tag, Base> self;

  Named_function_parameters() : CGAL_np() {}
  Named_function_parameters(const T& v) : CGAL_np(v) {}
  Named_function_parameters(const T& v, const Base& b) : CGAL_np(v, b) {}

#define CGAL_add_named_parameter(X, Y, Z)                                      \
  template <typename K>                                                        \
  Named_function_parameters<K, CGAL::internal_np::X, self> Z(const K& k) const \
  { return Named_function_parameters<K, CGAL::internal_np::X, self>(k, *this); }
#include <CGAL/STL_Extension/internal/parameters_interface.h>
#undef CGAL_add_named_parameter

#define CGAL_add_named_parameter(X, Y, Z)                                                  \
  template <typename K>                                                                    \
  Named_function_parameters<K, Isophotic_metric::internal_np::X, self> Z(const K& k) const \
  { return Named_function_parameters<K, Isophotic_metric::internal_np::X, self>(k, *this); }
#include <CGAL/Isophotic_metric/internal/parameters_interface.h>
#undef CGAL_add_named_parameter
};

namespace parameters {

using CGAL::parameters::choose_parameter;
using CGAL::parameters::Default_named_parameters;
using CGAL::parameters::get_parameter;
using CGAL::parameters::get_parameter_reference;
using CGAL::parameters::is_default_parameter;

/// An empty pack: every parameter takes its default value.
inline Named_function_parameters<bool, CGAL::internal_np::all_default_t> default_values() { return {}; }

#define CGAL_add_named_parameter(X, Y, Z)                               \
  template <typename K>                                                 \
  Named_function_parameters<K, CGAL::internal_np::X> Z(const K& k)      \
  { return Named_function_parameters<K, CGAL::internal_np::X>(k); }
#include <CGAL/STL_Extension/internal/parameters_interface.h>
#undef CGAL_add_named_parameter

#define CGAL_add_named_parameter(X, Y, Z)                                         \
  template <typename K>                                                           \
  Named_function_parameters<K, Isophotic_metric::internal_np::X> Z(const K& k)    \
  { return Named_function_parameters<K, Isophotic_metric::internal_np::X>(k); }
#include <CGAL/Isophotic_metric/internal/parameters_interface.h>
#undef CGAL_add_named_parameter

/// Appends the parameters of `b` (and more) to any pack `a`, a plain CGAL pack included;
/// a lookup finds the first node with a tag, so parameters of later packs win.
template <typename A>
const A& combine(const A& a) { return a; }

template <typename A, typename T, typename Tag>
Named_function_parameters<T, Tag, A>
combine(const A& a, const CGAL::Named_function_parameters<T, Tag, CGAL::internal_np::No_property>& b)
{ return Named_function_parameters<T, Tag, A>(b.v, a); }

template <typename A, typename T, typename Tag, typename B>
auto combine(const A& a, const CGAL::Named_function_parameters<T, Tag, B>& b)
{
  auto ab = combine(a, static_cast<const B&>(b)); // rebuild the tail first
  return Named_function_parameters<T, Tag, decltype(ab)>(b.v, ab);
}

template <typename A, typename B, typename C, typename... Ds>
auto combine(const A& a, const B& b, const C& c, const Ds&... ds)
{ return combine(combine(a, b), c, ds...); }

/// Views any pack as an exact CGAL::Named_function_parameters. Pass a pack of the package to a CGAL
/// function through it: some CGAL 5.5.1 overload sets dispatch on partial specialisations of the
/// exact pack type, which do not see through inheritance (e.g. `PMP::area(tm, np)`, whose
/// face-range overload would otherwise be tried): `PMP::area(tm, IM::parameters::cgal_np(np))`.
template <typename NP>
const NP& cgal_np(const NP& np) { return np; }
template <typename T, typename Tag, typename Base>
const CGAL::Named_function_parameters<T, Tag, Base>&
cgal_np(const Named_function_parameters<T, Tag, Base>& np) { return np; }

} // namespace parameters
} // namespace Isophotic_metric

} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_NAMED_FUNCTION_PARAMETERS_H
