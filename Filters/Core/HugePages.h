// Transparent huge pages for large arrays that are written front to back once: on 4 KiB
// pages each first touch is a page fault (about a tenth of the Delaunay build's time, and on
// virtual machines ~10 us each). Only an advice: without THP nothing changes.
#pragma once

#include <cstdint>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace tetmesher
{

// Advises the whole 2 MiB pages of v's reserved storage (call after reserve, before the
// elements are written).
template<typename T, typename Allocator>
void adviseHugePages(const std::vector<T, Allocator>& v)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kHugePage = std::uintptr_t(1) << 21;
  const std::uintptr_t first = reinterpret_cast<std::uintptr_t>(v.data());
  const std::uintptr_t begin = (first + kHugePage - 1) & ~(kHugePage - 1);
  const std::uintptr_t end = (first + v.capacity() * sizeof(T)) & ~(kHugePage - 1);
  if (end > begin)
    madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
  (void)v;
#endif
}

} // namespace tetmesher
