// Least-significant-digit radix sort of records by an unsigned 64-bit key.
#pragma once

#include "HugePages.h"

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
template<typename T, typename KeyOf>
void radixSortByKey(std::vector<T>& items, std::vector<T>& scratch, KeyOf keyOf, int keyBits)
{
  constexpr int kDigitBits = 12;
  constexpr std::size_t kBuckets = std::size_t(1) << kDigitBits;
  scratch.reserve(items.size());
  adviseHugePages(scratch); // first written here, front to back
  scratch.resize(items.size());
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
