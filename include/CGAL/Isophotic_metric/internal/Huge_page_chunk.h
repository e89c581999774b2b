// Memory in huge pages for the engine's large arrays. Filling an array costs a page fault per 4 kB
// page first touched; on virtual machines a fault costs microseconds: a third of a large dilation's
// time (its window archive) and a fifth of a one-shot distance computation (its per-mesh arrays and
// pending windows) went to them. Arrays of 2 MB or more are therefore aligned to 2 MB, rounded up to
// whole 2 MB pages and, on Linux, advised for transparent huge pages: one fault per 2 MB. The advice
// may be ignored (huge pages disabled, none free): the memory then works as ordinary memory.
#ifndef CGAL_ISOPHOTIC_METRIC_INTERNAL_HUGE_PAGE_CHUNK_H
#define CGAL_ISOPHOTIC_METRIC_INTERNAL_HUGE_PAGE_CHUNK_H

#include <cstddef>
#include <cstdlib>
#include <memory>
#include <new>
#include <type_traits>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif
#if defined(_MSC_VER)
#include <malloc.h>
#endif

namespace CGAL {
namespace Isophotic_metric {
namespace internal {

constexpr std::size_t huge_page_bytes = std::size_t(1) << 21;

/// At least `bytes` bytes, rounded up to whole 2 MB pages, aligned to 2 MB; free with `free_huge_pages`.
inline void* allocate_huge_pages(std::size_t bytes)
{
  bytes = (bytes + huge_page_bytes - 1) / huge_page_bytes * huge_page_bytes;
#if defined(_MSC_VER)
  void* p = _aligned_malloc(bytes, huge_page_bytes);
#else
  void* p = std::aligned_alloc(huge_page_bytes, bytes);
#endif
  if(p == nullptr)
    throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  madvise(p, bytes, MADV_HUGEPAGE);
#endif
  return p;
}

inline void free_huge_pages(void* p)
{
#if defined(_MSC_VER)
  _aligned_free(p);
#else
  std::free(p);
#endif
}

struct Huge_page_deleter
{
  void operator()(void* p) const { free_huge_pages(p); }
};

/// Uninitialised storage for `count` objects of `T`, which are never destroyed (hence trivially
/// destructible); a chunk should be a multiple of 2 MB, or the rest of its last page is wasted.
template <class T>
using Huge_page_chunk = std::unique_ptr<T, Huge_page_deleter>;

template <class T>
Huge_page_chunk<T> allocate_huge_page_chunk(std::size_t count)
{
  static_assert(std::is_trivially_destructible<T>::value, "chunk objects are never destroyed");
  return Huge_page_chunk<T>(static_cast<T*>(allocate_huge_pages(count * sizeof(T))));
}

/// `std::allocator`, except that arrays of 2 MB or more come from `allocate_huge_pages`.
template <class T>
struct Huge_page_allocator
{
  using value_type = T;
  Huge_page_allocator() = default;
  template <class U>
  Huge_page_allocator(const Huge_page_allocator<U>&) {}

  static bool is_large(std::size_t n) { return n * sizeof(T) >= huge_page_bytes; }
  T* allocate(std::size_t n)
  {
    return is_large(n) ? static_cast<T*>(allocate_huge_pages(n * sizeof(T))) : std::allocator<T>().allocate(n);
  }
  void deallocate(T* p, std::size_t n)
  {
    if(is_large(n))
      free_huge_pages(p);
    else
      std::allocator<T>().deallocate(p, n);
  }
  template <class U>
  bool operator==(const Huge_page_allocator<U>&) const { return true; }
  template <class U>
  bool operator!=(const Huge_page_allocator<U>&) const { return false; }
};

template <class T>
using Huge_page_vector = std::vector<T, Huge_page_allocator<T>>;

} // namespace internal
} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_INTERNAL_HUGE_PAGE_CHUNK_H
