// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// A monotone min-priority queue on non-negative double keys (a radix heap). Window propagation
// only ever inserts keys no smaller than the last one removed, up to rounding (a child window is
// never closer than its parent); such keys are raised to the last removed one. Entries wait in 65
// buckets by the highest bit in which their key differs from the last removed key: pushing is an
// append, and each entry is moved only a few times before it leaves, all in sequential memory,
// where a binary or 4-ary heap touches a cache line per level of a large heap. A 64-bit mask of
// the buckets above the first that hold entries finds the lowest of them in one instruction, so
// the minimum (each bucket's smallest key is kept) and the refill cost no scan of empty buckets.
#ifndef CGAL_ISOPHOTIC_METRIC_GEODESICS_INTERNAL_RADIX_HEAP_H
#define CGAL_ISOPHOTIC_METRIC_GEODESICS_INTERNAL_RADIX_HEAP_H

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {
namespace internal {

/// `T` needs a public member `double key`. Keys below the last removed key are raised to it.
template <class T>
class Radix_heap
{
public:
  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }

  void clear()
  {
    for(std::vector<T>& bucket : buckets_)
      bucket.clear();
    bucket_min_.fill(std::numeric_limits<double>::infinity());
    non_empty_ = 0;
    size_ = 0;
    last_ = 0;
    last_key_ = 0;
  }

  void push(T item)
  {
    if(!(item.key > last_key_)) // also maps NaN and negative zero to the last key
      item.key = last_key_;
    insert(item);
    ++size_;
  }

  /// Lets keys below the last removed one in again, unraised; the entries waiting keep their keys.
  /// Costs their number (for a new run of insertions that may start lower, not for every push).
  void lower_floor()
  {
    std::vector<T> waiting;
    waiting.reserve(size_);
    for(const std::vector<T>& bucket : buckets_)
      waiting.insert(waiting.end(), bucket.begin(), bucket.end());
    clear();
    for(const T& item : waiting)
      push(item);
  }

  /// The smallest key (+infinity when empty), without taking anything out: unlike top(), which
  /// makes that key the last removed one, it leaves the keys pushed afterwards as they are.
  double min_key() const
  {
    if(!buckets_[0].empty())
      return last_key_; // (what bucket 0 holds)
    if(non_empty_ == 0)
      return std::numeric_limits<double>::infinity();
    return bucket_min_[lowest_non_empty()];
  }

  /// The entry with the smallest key (not empty). Keys pushed afterwards are raised to its key.
  const T& top()
  {
    refill();
    return buckets_[0].back();
  }

  void pop()
  {
    refill();
    buckets_[0].pop_back();
    --size_;
  }

private:
  static std::array<double, 65> infinities()
  {
    std::array<double, 65> a;
    a.fill(std::numeric_limits<double>::infinity());
    return a;
  }

  // Non-negative doubles compare like their bit patterns.
  static std::uint64_t bits(double key)
  {
    std::uint64_t b;
    std::memcpy(&b, &key, sizeof b);
    return b;
  }

  int bucket_of(std::uint64_t key_bits) const
  {
    std::uint64_t x = key_bits ^ last_;
#if defined(__GNUC__)
    return x == 0 ? 0 : 64 - __builtin_clzll(x);
#else
    int n = 0;
    for(; x != 0; x >>= 1)
      ++n;
    return n;
#endif
  }

  // The lowest bucket above the first that holds entries (non_empty_ not 0): bucket i is bit i - 1.
  std::size_t lowest_non_empty() const
  {
#if defined(__GNUC__)
    return 1 + static_cast<std::size_t>(__builtin_ctzll(non_empty_));
#else
    std::size_t i = 1;
    while(!(non_empty_ >> (i - 1) & 1))
      ++i;
    return i;
#endif
  }

  // Makes bucket 0 hold the entries with the smallest key.
  void refill()
  {
    if(!buckets_[0].empty())
      return;
    const std::size_t i = lowest_non_empty();
    std::vector<T>& bucket = buckets_[i];
    const double smallest = bucket_min_[i];
    last_ = bits(smallest);
    last_key_ = smallest;
    // Every entry of bucket i now differs from the last key in a lower bit only.
    for(const T& item : bucket)
      insert(item);
    bucket.clear();
    bucket_min_[i] = std::numeric_limits<double>::infinity();
    non_empty_ &= ~(std::uint64_t(1) << (i - 1));
  }

  void insert(const T& item)
  {
    const int b = bucket_of(bits(item.key));
    buckets_[b].push_back(item);
    if(b == 0)
      return;
    non_empty_ |= std::uint64_t(1) << (b - 1);
    if(item.key < bucket_min_[b])
      bucket_min_[b] = item.key;
  }

  std::array<std::vector<T>, 65> buckets_;
  std::array<double, 65> bucket_min_ = infinities(); // the smallest key of each bucket but the first
  std::uint64_t non_empty_ = 0; // bit i - 1: bucket i (from 1) holds entries
  std::size_t size_ = 0;
  std::uint64_t last_ = 0;
  double last_key_ = 0;
};

} // namespace internal
} // namespace Isophotic_metric
} // namespace CGAL

#endif
