// Hilbert keys of Skilling's transpose algorithm (J. Skilling, "Programming the Hilbert
// curve", AIP Conf. Proc. 707, 2004), computed level by level from a state table instead of
// by his per-level bit operations on whole words: the same keys (the test compares them with
// the transpose algorithm itself) for about a sixth of the instructions.
#include "HilbertSort.h"

#include "HugePages.h"
#include "ParallelPair.h"
#include "RadixSort.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace tetmesher
{

namespace
{
// Moves bit b of x (b < 21) to bit 3b.
inline std::uint64_t spreadBits(std::uint32_t x)
{
  std::uint64_t v = x & 0x1FFFFFu;
  v = (v | (v << 32)) & 0x001F00000000FFFFULL;
  v = (v | (v << 16)) & 0x001F0000FF0000FFULL;
  v = (v | (v << 8)) & 0x100F00F00F00F00FULL;
  v = (v | (v << 4)) & 0x10C30C30C30C30C3ULL;
  v = (v | (v << 2)) & 0x1249249249249249ULL;
  return v;
}

// Skilling's algorithm, from the coarsest level down, reflects or swaps the *lower* bits of
// the axes by the bits of each level; then Gray-codes each level's three bits and flips every
// level by the parity of the Gray-coded axis-2 bits above it. So a level's key digit depends
// on its own three bits and on a state: the signed permutation of the axes that the levels
// above applied (axis j now holds original axis perm[j], complemented when flip bit j is
// set: 6 x 8) and that parity (x 2), 96 states. kHilbertLevels[8 * state + octant] is
// 8 * (next state) + digit, octant and digit as x y z bits from the most significant.
constexpr int kHilbertStates = 96;
constexpr std::array<std::array<int, 3>, 6> kAxisPermutations = {
  { { 0, 1, 2 }, { 0, 2, 1 }, { 1, 0, 2 }, { 1, 2, 0 }, { 2, 0, 1 }, { 2, 1, 0 } }
};

constexpr std::array<std::uint16_t, 8 * kHilbertStates> makeHilbertLevels()
{
  std::array<std::uint16_t, 8 * kHilbertStates> table{};
  for (int state = 0; state < kHilbertStates; ++state)
    for (int octant = 0; octant < 8; ++octant)
    {
      const int parity = state & 1;
      int flip[3] = { (state >> 1) & 1, (state >> 2) & 1, (state >> 3) & 1 };
      int perm[3] = { kAxisPermutations[static_cast<std::size_t>(state >> 4)][0],
        kAxisPermutations[static_cast<std::size_t>(state >> 4)][1],
        kAxisPermutations[static_cast<std::size_t>(state >> 4)][2] };
      const int original[3] = { (octant >> 2) & 1, (octant >> 1) & 1, octant & 1 };
      int bit[3] = { 0, 0, 0 }; // this level's bits of the axes as the levels above left them
      for (int j = 0; j < 3; ++j)
        bit[j] = original[perm[j]] ^ flip[j];
      const int gray0 = bit[0], gray1 = bit[1] ^ gray0, gray2 = bit[2] ^ gray1;
      const int digit = ((gray0 ^ parity) << 2) | ((gray1 ^ parity) << 1) | (gray2 ^ parity);
      // This level's operations on the lower bits, axis by axis: a set bit reflects axis 0,
      // a clear one swaps axes 0 and i.
      for (int i = 0; i < 3; ++i)
        if (bit[i])
          flip[0] ^= 1;
        else
        {
          const int p = perm[0], f = flip[0];
          perm[0] = perm[i];
          flip[0] = flip[i];
          perm[i] = p;
          flip[i] = f;
        }
      int permIndex = 0;
      while (kAxisPermutations[static_cast<std::size_t>(permIndex)][0] != perm[0] ||
        kAxisPermutations[static_cast<std::size_t>(permIndex)][1] != perm[1])
        ++permIndex;
      const int next =
        (((permIndex << 3) | (flip[2] << 2) | (flip[1] << 1) | flip[0]) << 1) | (parity ^ gray2);
      table[static_cast<std::size_t>(8 * state + octant)] =
        static_cast<std::uint16_t>(8 * next + digit);
    }
  return table;
}

constexpr std::array<std::uint16_t, 8 * kHilbertStates> kHilbertLevels = makeHilbertLevels();

// Inlined where `bits` is a constant, so that the level loop unrolls.
inline std::uint64_t hilbertKey(std::uint32_t x, std::uint32_t y, std::uint32_t z, int bits)
{
  const std::uint32_t used = (1u << bits) - 1;
  // Bit b of x, y, z at bits 3b + 2, 3b + 1, 3b: each level's octant in three bits.
  const std::uint64_t octants =
    (spreadBits(x & used) << 2) | (spreadBits(y & used) << 1) | spreadBits(z & used);
  std::uint64_t key = 0;
  unsigned state8 = 0; // 8 * state; the start is the identity with parity 0
#pragma GCC unroll 21
  for (int level = bits - 1; level >= 0; --level)
  {
    const unsigned entry =
      kHilbertLevels[state8 | static_cast<unsigned>((octants >> (3 * level)) & 7u)];
    key = (key << 3) | (entry & 7u);
    state8 = entry & ~7u;
  }
  return key;
}
} // namespace

std::uint64_t hilbertIndex(std::uint32_t x, std::uint32_t y, std::uint32_t z, int bits)
{
  return hilbertKey(x, y, z, bits);
}

namespace
{

struct Box
{
  double lo[3], scale;
};

// The grid over `count` points stored contiguously (xyz each).
Box boundingGrid(const double* xyz, std::size_t count, int bits)
{
  Box box;
  double hi[3];
  for (int k = 0; k < 3; ++k)
  {
    box.lo[k] = std::numeric_limits<double>::max();
    hi[k] = std::numeric_limits<double>::lowest();
  }
  for (std::size_t i = 0; i < count; ++i)
    for (int k = 0; k < 3; ++k)
    {
      const double c = xyz[3 * i + k];
      box.lo[k] = std::min(box.lo[k], c);
      hi[k] = std::max(hi[k], c);
    }
  double extent = 0;
  for (int k = 0; k < 3; ++k)
    extent = std::max(extent, hi[k] - box.lo[k]);
  // One scale for the three axes keeps the curve's cells cubic.
  const double cells = std::ldexp(1.0, bits) - 1.0;
  box.scale = extent > 0 ? cells / extent : 0.0;
  return box;
}

// SplitMix64: a tiny, well-mixed generator whose output is the same on every platform
// (std::shuffle's algorithm is implementation-defined, so we shuffle ourselves).
struct SplitMix64
{
  std::uint64_t state;
  std::uint64_t next()
  {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
};

struct Keyed
{
  std::uint64_t key;
  VertexId id;
};

} // namespace

void hilbertSort(const double* coords, VertexId* first, VertexId* last, bool twoThreads)
{
  // 16 levels (2^48 cells) separate any realistic point count; fewer levels, faster keys.
  constexpr int kBits = 16;
  if (last - first < 2)
    return;
  const std::size_t count = static_cast<std::size_t>(last - first);
  // One gather of the coordinates (the ids come shuffled, so every read is a cache miss),
  // then the box and the keys read the copy in order.
  std::vector<double> gathered;
  gathered.reserve(3 * count);
  adviseHugePages(gathered);
  gathered.resize(3 * count);
  constexpr std::size_t kMinHalves = 65536;
  forHalves(count,
    twoThreads,
    kMinHalves,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t i = begin; i < end; ++i)
        for (int k = 0; k < 3; ++k)
          gathered[3 * i + k] = coords[3 * static_cast<std::size_t>(first[i]) + k];
    });
  const Box box = boundingGrid(gathered.data(), count, kBits);

  std::vector<Keyed> keyed, scratch;
  keyed.reserve(count);
  adviseHugePages(keyed);
  keyed.resize(count);
  const double maxCell = std::ldexp(1.0, kBits) - 1.0;
  forHalves(count,
    twoThreads,
    kMinHalves,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t i = begin; i < end; ++i)
      {
        std::uint32_t g[3];
        for (int k = 0; k < 3; ++k)
        {
          const double c = (gathered[3 * i + k] - box.lo[k]) * box.scale;
          g[k] = static_cast<std::uint32_t>(std::min(c, maxCell));
        }
        keyed[i] = { hilbertKey(g[0], g[1], g[2], kBits), first[i] };
      }
    });
  const auto byKeyThenId = [](const Keyed& a, const Keyed& b)
  { return a.key < b.key || (a.key == b.key && a.id < b.id); };
  if (count < 1024)
    std::sort(keyed.begin(), keyed.end(), byKeyThenId);
  else
  {
    radixSortByKey(
      keyed, scratch, [](const Keyed& k) { return k.key; }, 3 * kBits, twoThreads);
    // Equal keys (duplicate or nearly coincident points) are ordered by id, as the
    // comparison sort would: find the runs and sort each.
    for (std::size_t i = 0; i + 1 < count;)
    {
      std::size_t j = i + 1;
      while (j < count && keyed[j].key == keyed[i].key)
        ++j;
      if (j - i > 1)
        std::sort(keyed.begin() + static_cast<std::ptrdiff_t>(i),
          keyed.begin() + static_cast<std::ptrdiff_t>(j),
          byKeyThenId);
      i = j;
    }
  }
  for (std::size_t i = 0; i < count; ++i)
    first[i] = keyed[i].id;
}

std::vector<VertexId> brioOrder(const double* coords,
  VertexId n,
  std::uint64_t seed,
  std::vector<std::size_t>* roundStarts,
  bool twoThreads)
{
  std::vector<VertexId> order;
  order.reserve(static_cast<std::size_t>(n));
  adviseHugePages(order);
  order.resize(static_cast<std::size_t>(n));
  for (VertexId i = 0; i < n; ++i)
    order[static_cast<std::size_t>(i)] = i;
  SplitMix64 rng{ seed };
  for (std::size_t i = order.size(); i > 1; --i)
  {
    const std::size_t j = static_cast<std::size_t>(rng.next() % i);
    std::swap(order[i - 1], order[j]);
  }
  // Rounds from the end: the last round holds 7/8 of the remaining points, and so on, until
  // a small first round (Multiscale sorting, as CGAL's spatial_sort does).
  constexpr double kRatio = 0.125;
  constexpr std::size_t kMinRound = 64;
  std::size_t end = order.size();
  while (end > 0)
  {
    std::size_t begin = end <= kMinRound ? 0 : static_cast<std::size_t>(end * kRatio);
    hilbertSort(coords, order.data() + begin, order.data() + end, twoThreads);
    if (roundStarts)
      roundStarts->push_back(begin);
    end = begin;
  }
  if (roundStarts)
    std::reverse(roundStarts->begin(), roundStarts->end());
  return order;
}

} // namespace tetmesher
