// The command line program's operator new and delete: blocks of 1 MiB and more (the mesh's
// arrays, the optimiser's per-tet tables, the output buffers) go on transparent huge pages.
//
// Why: every such array is first written front to back, and on 4 KiB pages each first touch
// is a page fault. On this project's virtual machines a fault costs ~10 us: cube.vtp at
// h = 0.0303 (262k tets) took 33k faults and 0.3 s of system time in a 1.5 s run. glibc can
// do this itself (GLIBC_TUNABLES=glibc.malloc.hugetlb=1: 5k faults, 1.1 s), but only when
// set before the process starts, and re-executing costs ~14 ms, more than a small mesh.
//
// How: big blocks are carved from one reserved range of address space (PROT_NONE, nothing
// committed) by a bump pointer, made writable and advised MADV_HUGEPAGE; freeing one gives
// its pages back and leaves its addresses unused. A pointer is big iff it lies in the range,
// which delete tests without reading any header. Everything else is malloc and free, as in
// the default operators. Not in sanitizer builds (their runtimes provide these operators).
// The library (vtkTetMesher in ParaView, Python) keeps the host's allocator.
//
// The small blocks (malloc's heap) go on huge pages too: the heap grows by at least 32 MiB
// at a time (M_TOP_PAD) and every growth is advised MADV_HUGEPAGE, as glibc's own
// glibc.malloc.hugetlb=1 does. The meshes' many small vectors (grids, per-vertex lists,
// workspaces) faulted in their 4 KiB pages one by one: cube.vtp at h = 0.0711, a 0.11 s run,
// took 2.8k faults, torus.vtp at h = 0.0638 4.2k; with the heap on huge pages 0.3-0.7k.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>

#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer)
#define TETMESHER_NO_LARGE_ALLOCATIONS
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define TETMESHER_NO_LARGE_ALLOCATIONS
#endif

#if defined(__linux__) && !defined(TETMESHER_NO_LARGE_ALLOCATIONS)
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

namespace
{

constexpr std::size_t kHugePage = std::size_t(2) << 20;
constexpr std::size_t kLargeFrom = std::size_t(1) << 20;
// The range: virtual addresses only (1 TiB of the 128 TiB of x86-64 user space). Addresses
// are not reused, so a run may allocate 1 TiB of big blocks in all; past that, malloc.
constexpr std::size_t kRangeBytes = std::size_t(1) << 40;
// Ahead of each block: its mapped length (64 bytes keep the caller's alignment generous).
constexpr std::size_t kHeader = 64;

std::atomic<char*> rangeBase{ nullptr };
std::atomic<std::size_t> rangeUsed{ 0 };
std::atomic<bool> rangeFailed{ false };

char* range()
{
  char* base = rangeBase.load(std::memory_order_acquire);
  if (base || rangeFailed.load(std::memory_order_relaxed))
    return base;
  void* reserved = mmap(nullptr,
    kRangeBytes + kHugePage,
    PROT_NONE,
    MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE,
    -1,
    0);
  if (reserved == MAP_FAILED)
  {
    rangeFailed.store(true);
    return nullptr;
  }
  // Huge-page aligned start; the unaligned head stays reserved and unused.
  const std::uintptr_t aligned =
    (reinterpret_cast<std::uintptr_t>(reserved) + kHugePage - 1) & ~(kHugePage - 1);
  char* expected = nullptr;
  if (!rangeBase.compare_exchange_strong(expected, reinterpret_cast<char*>(aligned)))
  {
    munmap(reserved, kRangeBytes + kHugePage); // another thread won
    return expected;
  }
  return reinterpret_cast<char*>(aligned);
}

bool isLarge(const void* p)
{
  const char* base = rangeBase.load(std::memory_order_acquire);
  const char* c = static_cast<const char*>(p);
  return base && c >= base && c < base + kRangeBytes;
}

void* allocateLarge(std::size_t bytes)
{
  char* base = range();
  if (!base || bytes > kRangeBytes)
    return nullptr;
  const std::size_t length = (bytes + kHeader + kHugePage - 1) & ~(kHugePage - 1);
  const std::size_t offset = rangeUsed.fetch_add(length);
  if (offset + length > kRangeBytes)
    return nullptr;
  char* block = base + offset;
  if (mprotect(block, length, PROT_READ | PROT_WRITE) != 0)
    return nullptr;
  // Huge pages over the caller's bytes rounded to the nearest 2 MiB: a tail under 1 MiB
  // stays on 4 KiB pages, so that no block holds 1 MiB or more that it does not use.
  const std::size_t full = (kHeader + bytes + kHugePage / 2) & ~(kHugePage - 1);
  if (full > 0)
    madvise(block, full, MADV_HUGEPAGE); // advice only: without THP, 4 KiB pages
  *reinterpret_cast<std::size_t*>(block) = length;
  return block + kHeader;
}

void releaseLarge(void* p)
{
  char* block = static_cast<char*>(p) - kHeader;
  const std::size_t length = *reinterpret_cast<std::size_t*>(block);
  // Replacing the mapping drops its pages at once and returns the addresses to PROT_NONE.
  mmap(block, length, PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE | MAP_FIXED, -1, 0);
}

// malloc's heap: grown in steps of at least kHeapStep, and advised onto huge pages whenever
// the next small allocation sees the program break moved (grown, or trimmed and grown
// again: the whole heap is advised each time, which also covers a regrown part). Any thread
// may see it first; the advice is idempotent, so a race only advises twice.
constexpr std::size_t kHeapStep = std::size_t(32) << 20;
constexpr std::uintptr_t kPage = 4096;
std::atomic<std::uintptr_t> heapSeenEnd{ 0 };

std::uintptr_t heapStart()
{
  static const std::uintptr_t start = []
  {
    mallopt(M_TOP_PAD, static_cast<int>(kHeapStep));
    return (reinterpret_cast<std::uintptr_t>(sbrk(0)) + kPage - 1) & ~(kPage - 1);
  }();
  return start;
}

void adviseHeapGrowth()
{
  const std::uintptr_t end = reinterpret_cast<std::uintptr_t>(sbrk(0));
  if (end == heapSeenEnd.load(std::memory_order_relaxed))
    return;
  heapSeenEnd.store(end, std::memory_order_relaxed);
  if (end > heapStart() && end != static_cast<std::uintptr_t>(-1))
    madvise(reinterpret_cast<void*>(heapStart()), end - heapStart(), MADV_HUGEPAGE); // advice only
}

void* allocate(std::size_t bytes) noexcept
{
  if (bytes >= kLargeFrom)
    if (void* p = allocateLarge(bytes))
      return p;
  heapStart(); // the growth step is set before the first heap allocation
  void* p = std::malloc(bytes == 0 ? 1 : bytes);
  adviseHeapGrowth();
  return p;
}

void release(void* p) noexcept
{
  if (!p)
    return;
  if (isLarge(p))
    releaseLarge(p);
  else
    std::free(p);
}

void* allocateOrThrow(std::size_t bytes)
{
  for (;;)
  {
    if (void* p = allocate(bytes))
      return p;
    std::new_handler handler = std::get_new_handler();
    if (!handler)
      throw std::bad_alloc();
    handler();
  }
}

} // namespace

void* operator new(std::size_t bytes)
{
  return allocateOrThrow(bytes);
}
void* operator new[](std::size_t bytes)
{
  return allocateOrThrow(bytes);
}
void* operator new(std::size_t bytes, const std::nothrow_t&) noexcept
{
  return allocate(bytes);
}
void* operator new[](std::size_t bytes, const std::nothrow_t&) noexcept
{
  return allocate(bytes);
}
void operator delete(void* p) noexcept
{
  release(p);
}
void operator delete[](void* p) noexcept
{
  release(p);
}
void operator delete(void* p, std::size_t) noexcept
{
  release(p);
}
void operator delete[](void* p, std::size_t) noexcept
{
  release(p);
}
void operator delete(void* p, const std::nothrow_t&) noexcept
{
  release(p);
}
void operator delete[](void* p, const std::nothrow_t&) noexcept
{
  release(p);
}

#endif
