// A min-heap with four children per node: half the depth of a binary heap, and the four children
// of a node share a cache line or two, which matters when the heap outgrows the caches.
#ifndef CGAL_ISOPHOTIC_METRIC_INTERNAL_QUATERNARY_HEAP_H
#define CGAL_ISOPHOTIC_METRIC_INTERNAL_QUATERNARY_HEAP_H

#include <cstddef>
#include <utility>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {
namespace internal {

/// `T` needs a public member `key` ordered by `<`.
template <class T>
class Quaternary_heap
{
public:
  bool empty() const { return items_.empty(); }
  std::size_t size() const { return items_.size(); }
  const T& top() const { return items_.front(); }
  void clear() { items_.clear(); }

  void push(const T& item)
  {
    std::size_t i = items_.size();
    items_.push_back(item);
    while(i > 0)
    {
      const std::size_t parent = (i - 1) / 4;
      if(!(item.key < items_[parent].key))
        break;
      items_[i] = items_[parent];
      i = parent;
    }
    items_[i] = item;
  }

  void pop()
  {
    const T last = items_.back();
    items_.pop_back();
    const std::size_t n = items_.size();
    if(n == 0)
      return;
    std::size_t i = 0;
    while(true)
    {
      const std::size_t first = 4 * i + 1;
      if(first >= n)
        break;
      std::size_t best = first;
      const std::size_t end = first + 4 < n ? first + 4 : n;
      for(std::size_t c = first + 1; c < end; ++c)
        if(items_[c].key < items_[best].key)
          best = c;
      if(!(items_[best].key < last.key))
        break;
      items_[i] = items_[best];
      i = best;
    }
    items_[i] = last;
  }

private:
  std::vector<T> items_;
};

} // namespace internal
} // namespace Isophotic_metric
} // namespace CGAL

#endif
