// Least-significant-digit radix sort of records by an unsigned 64-bit key.
#pragma once

#include "HugePages.h"
#include "ParallelPair.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tetmesher
{

// Sorts `items` by keyOf(item) on its low `keyBits` bits, 12 bits per pass (4096 counters,
// which stay in L1). Stable: equal keys keep their order, so records pushed in increasing
// order of a second field come out as a comparison sort on (key, that field) would give,
// several times faster on the 10^5-10^6 records of the mesher's sorts.
// twoThreads: each pass counts and scatters the two halves of the records on two threads,
// the second half's records of a digit placed after the first half's: the same result.
template<typename T, typename KeyOf>
void radixSortByKey(std::vector<T>& items,
  std::vector<T>& scratch,
  KeyOf keyOf,
  int keyBits,
  bool twoThreads = false)
{
  constexpr int kDigitBits = 12;
  constexpr std::size_t kBuckets = std::size_t(1) << kDigitBits;
  scratch.reserve(items.size());
  adviseHugePages(scratch); // first written here, front to back
  scratch.resize(items.size());
  constexpr std::size_t kMinHalves = std::size_t(1) << 17;
  if (twoThreads && items.size() >= kMinHalves)
  {
    const std::size_t middle = items.size() / 2;
    std::vector<std::size_t> count[2] = { std::vector<std::size_t>(kBuckets),
      std::vector<std::size_t>(kBuckets) };
    for (int shift = 0; shift < keyBits; shift += kDigitBits)
    {
      const auto range = [&](int k, const T*& begin, const T*& end)
      {
        begin = items.data() + (k == 0 ? 0 : middle);
        end = items.data() + (k == 0 ? middle : items.size());
      };
      runPair(true,
        [&](int k)
        {
          const T *begin, *end;
          range(k, begin, end);
          std::fill(count[k].begin(), count[k].end(), 0);
          for (const T* item = begin; item != end; ++item)
            ++count[k][(keyOf(*item) >> shift) & (kBuckets - 1)];
        });
      std::size_t offset = 0;
      for (std::size_t b = 0; b < kBuckets; ++b)
        for (int k = 0; k < 2; ++k)
        {
          const std::size_t n = count[k][b];
          count[k][b] = offset;
          offset += n;
        }
      runPair(true,
        [&](int k)
        {
          const T *begin, *end;
          range(k, begin, end);
          std::size_t* position = count[k].data();
          for (const T* item = begin; item != end; ++item)
            scratch[position[(keyOf(*item) >> shift) & (kBuckets - 1)]++] = *item;
        });
      items.swap(scratch);
    }
    return;
  }
  std::vector<std::size_t> count(kBuckets);
  for (int shift = 0; shift < keyBits; shift += kDigitBits)
  {
    std::fill(count.begin(), count.end(), 0);
    for (const T& item : items)
      ++count[(keyOf(item) >> shift) & (kBuckets - 1)];
    std::size_t offset = 0;
    for (std::size_t& c : count)
    {
      const std::size_t n = c;
      c = offset;
      offset += n;
    }
    for (const T& item : items)
      scratch[count[(keyOf(item) >> shift) & (kBuckets - 1)]++] = item;
    items.swap(scratch);
  }
}

// The number of significant bits of the largest key (0 for none or all zero).
template<typename T, typename KeyOf>
int keyBitsOf(const std::vector<T>& items, KeyOf keyOf)
{
  std::uint64_t all = 0;
  for (const T& item : items)
    all |= keyOf(item);
  int bits = 0;
  while (bits < 64 && (all >> bits) != 0)
    ++bits;
  return bits;
}

// Sorts (key, value) pairs as std::sort would, given that values increase among equal keys
// on input (pushed in value order).
template<typename Value>
void sortPushedPairs(std::vector<std::pair<std::uint64_t, Value>>& items)
{
  auto keyOf = [](const std::pair<std::uint64_t, Value>& p) { return p.first; };
  if (items.size() < 512)
  {
    std::sort(items.begin(), items.end());
    return;
  }
  std::vector<std::pair<std::uint64_t, Value>> scratch;
  radixSortByKey(items, scratch, keyOf, keyBitsOf(items, keyOf));
}

} // namespace tetmesher
