// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The named parameter `callback` (CGAL's own, as in its point set processing): a callable
// `bool(double advancement)` called now and then during a long computation with the advancement of
// the current step in [0, 1]; returning `false` stops the computation with a Cancelled_error.
// Calls are serialised, so a callback may be used by a parallel computation without locking.
#ifndef CGAL_ISOPHOTIC_METRIC_INTERNAL_PROGRESS_CALLBACK_H
#define CGAL_ISOPHOTIC_METRIC_INTERNAL_PROGRESS_CALLBACK_H

#include <CGAL/Isophotic_metric/Named_function_parameters.h>
#include <CGAL/Isophotic_metric/exceptions.h>

#include <algorithm>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

namespace CGAL {
namespace Isophotic_metric {
namespace internal {

class Progress_callback
{
public:
  Progress_callback() = default;

  /// The `callback` of `np`, or none.
  template <class NamedParameters>
  static Progress_callback of(const NamedParameters& np)
  {
    Progress_callback p;
    if constexpr(!parameters::is_default_parameter<NamedParameters, CGAL::internal_np::callback_t>::value)
    {
      p.callback_ = parameters::get_parameter(np, CGAL::internal_np::callback);
      p.mutex_ = std::make_shared<std::mutex>();
    }
    return p;
  }

  explicit operator bool() const { return bool(callback_); }

  /// Reports `advancement` (clamped to [0, 1]) of the step described by `what`.
  /// \throws Cancelled_error when the callback asks to stop
  void report(double advancement, const char* what) const
  {
    if(!callback_)
      return;
    bool go_on;
    {
      std::lock_guard<std::mutex> lock(*mutex_);
      go_on = callback_(std::clamp(advancement, 0.0, 1.0));
    }
    if(!go_on)
      throw Cancelled_error(std::string(what) + " cancelled by its callback at " +
                            std::to_string(int(100 * advancement)) + " %");
  }

private:
  std::function<bool(double)> callback_;
  std::shared_ptr<std::mutex> mutex_;
};

} // namespace internal
} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_INTERNAL_PROGRESS_CALLBACK_H
