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
//
// Mappings given back are kept for reuse (up to 64 MB, see Page_cache; define
// CGAL_ISOPHOTIC_METRIC_KEPT_MEMORY_MB to another number of megabytes, 0 to keep none): a loop of
// one-shot calls on one mesh allocates the same sizes every time, and a kept mapping is faulted in
// already. Arrays
// from 64 kB up (Huge_page_vector) are mapped, kept and reused the same way, in 4 kB pages, so that
// this does not depend on how malloc gives memory back (seen: the same one-shot dilation faulted in
// 9 MB of fresh heap per call from Python and 2.5 MB from a C++ loop).
#ifndef CGAL_ISOPHOTIC_METRIC_GEODESICS_INTERNAL_HUGE_PAGE_CHUNK_H
#define CGAL_ISOPHOTIC_METRIC_GEODESICS_INTERNAL_HUGE_PAGE_CHUNK_H

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <new>
#include <type_traits>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif
#if defined(_MSC_VER)
#include <malloc.h>
#endif

#ifndef CGAL_ISOPHOTIC_METRIC_KEPT_MEMORY_MB
#define CGAL_ISOPHOTIC_METRIC_KEPT_MEMORY_MB 64
#endif

namespace CGAL {
namespace Isophotic_metric {
namespace internal {

constexpr std::size_t huge_page_bytes = std::size_t(1) << 21;

inline std::size_t round_up_to_huge_pages(std::size_t bytes)
{
  return (bytes + huge_page_bytes - 1) / huge_page_bytes * huge_page_bytes;
}

constexpr std::size_t small_page_bytes = std::size_t(1) << 12;

inline std::size_t round_up_to_small_pages(std::size_t bytes)
{
  return (bytes + small_page_bytes - 1) / small_page_bytes * small_page_bytes;
}

/// A new mapping of `size` bytes (a multiple of the page size), aligned to 2 MB and advised for
/// huge pages when `huge` (then `size` is a multiple of 2 MB).
inline void* map_pages(std::size_t size, bool huge, bool advise)
{
#if defined(__linux__)
  if(!huge)
  {
    void* p = mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if(p == MAP_FAILED)
      throw std::bad_alloc();
    return p;
  }
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
  void* p = _aligned_malloc(size, huge ? huge_page_bytes : small_page_bytes);
  if(p == nullptr)
    throw std::bad_alloc();
  return p;
#else
  (void)advise;
  void* p = std::aligned_alloc(huge ? huge_page_bytes : small_page_bytes, size);
  if(p == nullptr)
    throw std::bad_alloc();
  return p;
#endif
}

inline void unmap_pages(void* p, std::size_t size)
{
#if defined(__linux__)
  munmap(p, size);
#elif defined(_MSC_VER)
  (void)size;
  _aligned_free(p);
#else
  (void)size;
  std::free(p);
#endif
}

/// Mappings given back, kept for the next request of the same size and kind (one process-wide
/// list, guarded by a mutex: a mapping is taken or kept once per array, not per element).
/// At most `capacity` bytes are kept (the newest mappings, what a repeated call needs first). A
/// request that finds no mapping of its size first gives back kept mappings, oldest first:
/// - when it takes these arrays beyond the most they ever had in use at once, until the memory
///   mapped (in use and kept) is within that most: the peak of a single run is what it would be
///   without reuse (its set-up's temporaries go back as its propagation grows);
/// - otherwise (a call repeated, below the peak of an earlier one) until the memory mapped is
///   within 1.5 times that most. (Within the most itself, a repeated call's kept temporaries would
///   be given back as its later arrays grow, and the next call would fault them in again: seen on
///   a loop of one-shot dilations.)
class Page_cache
{
public:
  static constexpr std::size_t capacity = std::size_t(CGAL_ISOPHOTIC_METRIC_KEPT_MEMORY_MB) << 20;

  static Page_cache& instance()
  {
    static Page_cache* cache = new Page_cache; // never destroyed: arrays of static objects may come back after exit
    return *cache;
  }

  /// A mapping of `size` bytes of this kind, kept or new.
  void* take(std::size_t size, bool huge, bool advise)
  {
    std::vector<Block> released;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      in_use_ += size;
      const bool beyond_most = in_use_ > most_in_use_;
      most_in_use_ = (std::max)(most_in_use_, in_use_);
      for(std::size_t i = blocks_.size(); i-- > 0;)
        if(blocks_[i].size == size && blocks_[i].huge == huge && blocks_[i].advised == advise)
        {
          void* p = blocks_[i].pointer;
          kept_bytes_ -= size;
          blocks_.erase(blocks_.begin() + std::ptrdiff_t(i));
          return p;
        }
      // (in use and kept within `allowed`; in_use_ <= most_in_use_ <= allowed)
      const std::size_t allowed = most_in_use_ + (beyond_most ? 0 : slack());
      take_out_oldest_beyond(allowed - in_use_, released);
    }
    for(const Block& b : released) // (system calls outside the lock)
      unmap_pages(b.pointer, b.size);
    try
    {
      return map_pages(size, huge, advise);
    }
    catch(...)
    {
      std::lock_guard<std::mutex> lock(mutex_);
      in_use_ -= size;
      throw;
    }
  }

  /// Gives back a mapping from take(): kept, or unmapped when the list would exceed its capacity.
  void give_back(void* p, std::size_t size, bool huge, bool advise)
  {
    std::vector<Block> released;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      in_use_ -= size;
      if(size > capacity)
        released.push_back({p, size, huge, advise});
      else
      {
        blocks_.push_back({p, size, huge, advise});
        kept_bytes_ += size;
      }
      take_out_oldest_beyond(capacity, released);
    }
    for(const Block& b : released)
      unmap_pages(b.pointer, b.size);
  }

  /// Bytes kept for reuse.
  std::size_t kept_bytes() const
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return kept_bytes_;
  }

private:
  std::size_t slack() const { return (std::min)(capacity, most_in_use_ / 2); }

  struct Block
  {
    void* pointer;
    std::size_t size;
    bool huge, advised;
  };

  // Moves the oldest kept mappings to `released` (to be unmapped outside the lock) until at most
  // `kept_limit` bytes are kept.
  void take_out_oldest_beyond(std::size_t kept_limit, std::vector<Block>& released)
  {
    std::size_t n = 0;
    while(n < blocks_.size() && kept_bytes_ > kept_limit)
      kept_bytes_ -= blocks_[n++].size;
    released.insert(released.end(), blocks_.begin(), blocks_.begin() + std::ptrdiff_t(n));
    blocks_.erase(blocks_.begin(), blocks_.begin() + std::ptrdiff_t(n));
  }

  mutable std::mutex mutex_;
  std::vector<Block> blocks_; // oldest first
  std::size_t kept_bytes_ = 0;
  std::size_t in_use_ = 0, most_in_use_ = 0; // bytes taken and not given back, and the most of it
};

/// At least `bytes` bytes, aligned to 2 MB, advised for huge pages unless `advise` is false (memory
/// written once, where waiting for the kernel to make huge pages may cost more than the faults it
/// saves); give back with `free_huge_pages(p, bytes, advise)`. On Linux the memory is mapped for
/// itself, not taken from `malloc`: advice given to `malloc`'s heap would stay with the heap after
/// the memory is freed and slow other code's allocations (seen: CGAL's exact shortest paths, run
/// after the engine in one process, took 3x as long).
inline void* allocate_huge_pages(std::size_t bytes, bool advise = true)
{
  return Page_cache::instance().take(round_up_to_huge_pages(bytes), true, advise);
}

inline void free_huge_pages(void* p, std::size_t bytes, bool advise = true)
{
  Page_cache::instance().give_back(p, round_up_to_huge_pages(bytes), true, advise);
}

struct Huge_page_deleter
{
  std::size_t bytes = 0;
  bool advised = true;
  void operator()(void* p) const { free_huge_pages(p, bytes, advised); }
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
                            Huge_page_deleter{count * sizeof(T), advise_huge_pages});
}

/// `std::allocator`, except that arrays of 2 MB or more come from `allocate_huge_pages`, and arrays
/// from 64 kB up are mapped for themselves in 4 kB pages (both kept for reuse when freed).
template <class T>
struct Huge_page_allocator
{
  using value_type = T;
  Huge_page_allocator() = default;
  template <class U>
  Huge_page_allocator(const Huge_page_allocator<U>&) {}

#if defined(__SANITIZE_ADDRESS__)
  // (the address sanitizer checks malloc's memory only: arrays below 2 MB stay there)
  static constexpr std::size_t mapped_from_bytes = huge_page_bytes;
#else
  static constexpr std::size_t mapped_from_bytes = std::size_t(1) << 16;
#endif
  static bool is_large(std::size_t n) { return n * sizeof(T) >= huge_page_bytes; }
  static bool is_mapped(std::size_t n) { return n * sizeof(T) >= mapped_from_bytes; }
  T* allocate(std::size_t n)
  {
    if(is_large(n))
      return static_cast<T*>(allocate_huge_pages(n * sizeof(T)));
    if(is_mapped(n))
      return static_cast<T*>(Page_cache::instance().take(round_up_to_small_pages(n * sizeof(T)), false, false));
    return std::allocator<T>().allocate(n);
  }
  void deallocate(T* p, std::size_t n)
  {
    if(is_large(n))
      free_huge_pages(p, n * sizeof(T));
    else if(is_mapped(n))
      Page_cache::instance().give_back(p, round_up_to_small_pages(n * sizeof(T)), false, false);
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
