// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Memory in huge pages for the engine's large arrays. Filling an array costs a page fault per 4 kB
// page first touched; on virtual machines a fault costs microseconds: a third of a large dilation's
// time (its window archive) and a fifth of a one-shot distance computation (its per-mesh arrays and
// pending windows) went to them. Arrays of 2 MB or more are therefore aligned to 2 MB, rounded up to
// whole 2 MB pages and, on Linux, mapped on their own and advised for transparent huge pages: one
// fault per 2 MB. The advice may be ignored (huge pages disabled, none free): the memory then works
// as ordinary memory. Define CGAL_ISOPHOTIC_METRIC_NO_HUGE_PAGES to give no advice (where the
// kernel's compaction for huge pages is unwelcome, say).
#ifndef CGAL_ISOPHOTIC_METRIC_GEODESICS_INTERNAL_HUGE_PAGE_CHUNK_H
#define CGAL_ISOPHOTIC_METRIC_GEODESICS_INTERNAL_HUGE_PAGE_CHUNK_H

#include <cstddef>
#include <cstdint>
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

inline std::size_t round_up_to_huge_pages(std::size_t bytes)
{
  return (bytes + huge_page_bytes - 1) / huge_page_bytes * huge_page_bytes;
}

/// At least `bytes` bytes, aligned to 2 MB, advised for huge pages unless `advise` is false (memory
/// written once, where waiting for the kernel to make huge pages may cost more than the faults it
/// saves); give back with `free_huge_pages(p, bytes)`. On Linux the
/// memory is mapped for itself, not taken from `malloc`: advice given to `malloc`'s heap would stay
/// with the heap after the memory is freed and slow other code's allocations (seen: CGAL's exact
/// shortest paths, run after the engine in one process, took 3x as long).
inline void* allocate_huge_pages(std::size_t bytes, bool advise = true)
{
  const std::size_t size = round_up_to_huge_pages(bytes);
#if defined(__linux__)
  // Map 2 MB more than needed and unmap the unaligned head and the tail.
  void* raw = mmap(nullptr, size + huge_page_bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if(raw == MAP_FAILED)
    throw std::bad_alloc();
  const std::uintptr_t first = reinterpret_cast<std::uintptr_t>(raw);
  const std::uintptr_t aligned = (first + huge_page_bytes - 1) & ~std::uintptr_t(huge_page_bytes - 1);
  const std::size_t head = aligned - first, tail = huge_page_bytes - head;
  if(head != 0)
    munmap(raw, head);
  if(tail != 0)
    munmap(reinterpret_cast<void*>(aligned + size), tail);
  void* p = reinterpret_cast<void*>(aligned);
#if defined(MADV_HUGEPAGE) && !defined(CGAL_ISOPHOTIC_METRIC_NO_HUGE_PAGES)
  if(advise)
    madvise(p, size, MADV_HUGEPAGE);
#else
  (void)advise;
#endif
  return p;
#elif defined(_MSC_VER)
  (void)advise;
  void* p = _aligned_malloc(size, huge_page_bytes);
  if(p == nullptr)
    throw std::bad_alloc();
  return p;
#else
  (void)advise;
  void* p = std::aligned_alloc(huge_page_bytes, size);
  if(p == nullptr)
    throw std::bad_alloc();
  return p;
#endif
}

inline void free_huge_pages(void* p, std::size_t bytes)
{
#if defined(__linux__)
  munmap(p, round_up_to_huge_pages(bytes));
#elif defined(_MSC_VER)
  (void)bytes;
  _aligned_free(p);
#else
  (void)bytes;
  std::free(p);
#endif
}

struct Huge_page_deleter
{
  std::size_t bytes = 0;
  void operator()(void* p) const { free_huge_pages(p, bytes); }
};

/// Uninitialised storage for `count` objects of `T`, which are never destroyed (hence trivially
/// destructible); a chunk should be a multiple of 2 MB, or the rest of its last page is wasted.
template <class T>
using Huge_page_chunk = std::unique_ptr<T, Huge_page_deleter>;

template <class T>
Huge_page_chunk<T> allocate_huge_page_chunk(std::size_t count, bool advise_huge_pages = true)
{
  static_assert(std::is_trivially_destructible<T>::value, "chunk objects are never destroyed");
  return Huge_page_chunk<T>(static_cast<T*>(allocate_huge_pages(count * sizeof(T), advise_huge_pages)),
                            Huge_page_deleter{count * sizeof(T)});
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
      free_huge_pages(p, n * sizeof(T));
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

#endif // CGAL_ISOPHOTIC_METRIC_GEODESICS_INTERNAL_HUGE_PAGE_CHUNK_H
