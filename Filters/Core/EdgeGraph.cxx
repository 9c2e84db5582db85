#include "EdgeGraph.h"

#include "ParallelPair.h"

#include <algorithm>

namespace tetmesher
{

namespace
{

constexpr int kEdges[6][2] = { { 0, 1 }, { 0, 2 }, { 0, 3 }, { 1, 2 }, { 1, 3 }, { 2, 3 } };
// Half edges go to their vertex's list in two steps: first to their block of 1024 vertices,
// where the writes are a few hundred sequential streams, then within each block (a few hundred
// kB, in cache). Written straight to their vertex, they were random writes over the whole
// arrays: 3/4 of the build (fandisk at h = 0.0103, 6.6M half edges: 0.11 s of 0.15 s).
constexpr int kBlockShift = 10;
constexpr VertexId kBlockMask = (1 << kBlockShift) - 1;
// Below this many tet slots one thread builds it all (a second one costs more than it saves).
constexpr TetId kMinTetsForHalves = 65536;

// The graph is rebuilt after each refinement round on a slightly larger mesh: a quarter more
// room than asked for, so that the next build neither copies the arrays nor faults in fresh
// pages. The contents are not kept (every build overwrites them).
template<typename T>
void resizeWithRoom(std::vector<T>& v, std::size_t n)
{
  if (v.capacity() < n)
  {
    std::vector<T> larger;
    larger.reserve(n + n / 4);
    v.swap(larger);
  }
  v.resize(n);
}

// The index in [0, n] that splits the increasing prefix sums `start` (n + 1 entries) nearest
// to half their total: the two halves of a vertex or block range get as many half edges.
std::size_t halfWay(const std::vector<std::int32_t>& start, std::size_t n)
{
  const std::int32_t middle = start[n] / 2;
  return static_cast<std::size_t>(
    std::lower_bound(start.begin(), start.begin() + static_cast<std::ptrdiff_t>(n) + 1, middle) -
    start.begin());
}

} // namespace

void EdgeGraph::build(const TetMesh& mesh, bool twoThreads)
{
  const std::size_t nv = static_cast<std::size_t>(mesh.vertexCount());
  const TetId capacity = mesh.tetCapacity();
  twoThreads = twoThreads && capacity >= kMinTetsForHalves;
  // Halves of the tets for the first two steps; of the blocks and of the vertices (by their
  // half edges) for the others.
  const TetId tetMiddle = capacity / 2;
  // fn(t, a, b) for the 6 edges (a, b) of every live tet t of [first, last), in order.
  auto forEdgesOf = [&](TetId first, TetId last, const auto& fn)
  {
    for (TetId t = first; t < last; ++t)
    {
      if (mesh.isDeleted(t))
        continue;
      for (const auto& e : kEdges)
        fn(t, mesh.vertex(t, e[0]), mesh.vertex(t, e[1]));
    }
  };

  // 1. Half edges per smaller vertex, counted by each half of the tets.
  splitAt(twoThreads,
    tetMiddle,
    capacity,
    [&](int k, TetId first, TetId last)
    {
      std::vector<std::int32_t>& count = half_[k].count;
      count.assign(nv + 1, 0);
      forEdgesOf(first,
        last,
        [&](TetId, VertexId a, VertexId b)
        { ++count[static_cast<std::size_t>(std::min(a, b)) + 1]; });
    });
  start_.assign(nv + 1, 0);
  for (std::size_t v = 0; v < nv; ++v)
    start_[v + 1] = start_[v] + half_[0].count[v + 1] + half_[1].count[v + 1];
  const std::size_t halfEdges = static_cast<std::size_t>(start_[nv]);
  resizeWithRoom(halfTarget_, halfEdges);
  resizeWithRoom(halfTet_, halfEdges);
  resizeWithRoom(lowBits_, halfEdges);

  // 2. To their blocks, in tet order: within a block, the first half's tets' edges first.
  const std::size_t blocks = (nv >> kBlockShift) + 1;
  auto blockStart = [&](std::size_t b) { return start_[std::min(nv, b << kBlockShift)]; };
  half_[0].fill.resize(blocks);
  half_[1].fill.resize(blocks);
  for (std::size_t b = 0; b < blocks; ++b)
  {
    std::int32_t firstHalf = 0;
    const std::size_t v1 = std::min(nv, (b + 1) << kBlockShift);
    for (std::size_t v = b << kBlockShift; v < v1; ++v)
      firstHalf += half_[0].count[v + 1];
    half_[0].fill[b] = blockStart(b);
    half_[1].fill[b] = blockStart(b) + firstHalf;
  }
  splitAt(twoThreads,
    tetMiddle,
    capacity,
    [&](int k, TetId first, TetId last)
    {
      std::vector<std::int32_t>& fill = half_[k].fill;
      forEdgesOf(first,
        last,
        [&](TetId t, VertexId a, VertexId b)
        {
          const VertexId lo = std::min(a, b);
          const std::int32_t at = fill[static_cast<std::size_t>(lo >> kBlockShift)]++;
          halfTarget_[static_cast<std::size_t>(at)] = std::max(a, b);
          halfTet_[static_cast<std::size_t>(at)] = t;
          lowBits_[static_cast<std::size_t>(at)] = static_cast<std::uint16_t>(lo & kBlockMask);
        });
    });

  // 3. Within each block to their vertex, keeping the order (halves of the blocks).
  std::vector<std::int32_t> blockStarts(blocks + 1);
  for (std::size_t b = 0; b <= blocks; ++b)
    blockStarts[b] = blockStart(b);
  const std::size_t blockMiddle = halfWay(blockStarts, blocks);
  splitAt(twoThreads,
    blockMiddle,
    blocks,
    [&](int k, std::size_t firstBlock, std::size_t lastBlock)
    {
      Half& me = half_[k];
      for (std::size_t b = firstBlock; b < lastBlock; ++b)
      {
        const std::int32_t first = blockStart(b), last = blockStart(b + 1);
        me.blockTarget.assign(halfTarget_.begin() + first, halfTarget_.begin() + last);
        me.blockTet.assign(halfTet_.begin() + first, halfTet_.begin() + last);
        const std::size_t v0 = b << kBlockShift;
        const std::size_t v1 = std::min(nv, v0 + (std::size_t{ 1 } << kBlockShift));
        me.vertexFill.assign(start_.begin() + static_cast<std::ptrdiff_t>(v0),
          start_.begin() + static_cast<std::ptrdiff_t>(v1));
        for (std::int32_t j = 0; j < last - first; ++j)
        {
          const std::int32_t at = me.vertexFill[lowBits_[static_cast<std::size_t>(first + j)]]++;
          halfTarget_[static_cast<std::size_t>(at)] = me.blockTarget[static_cast<std::size_t>(j)];
          halfTet_[static_cast<std::size_t>(at)] = me.blockTet[static_cast<std::size_t>(j)];
        }
      }
    });

  // 4. Unique half edges (the first of each), kept at the front of their vertex's list and
  // counted: per vertex its larger neighbours (unique_), and per half of the vertices its
  // smaller ones (incoming; the halves' stamps and counts are their own).
  const std::size_t vertexMiddle = halfWay(start_, nv);
  unique_.assign(nv, 0);
  splitAt(twoThreads,
    vertexMiddle,
    nv,
    [&](int k, std::size_t firstVertex, std::size_t lastVertex)
    {
      Half& me = half_[k];
      me.stamp.assign(nv, -1);
      me.incoming.assign(nv, 0);
      for (std::size_t a = firstVertex; a < lastVertex; ++a)
      {
        std::int32_t out = start_[a];
        for (std::int32_t j = start_[a]; j < start_[a + 1]; ++j)
        {
          const VertexId b = halfTarget_[static_cast<std::size_t>(j)];
          if (me.stamp[static_cast<std::size_t>(b)] == static_cast<VertexId>(a))
            continue;
          me.stamp[static_cast<std::size_t>(b)] = static_cast<VertexId>(a);
          halfTarget_[static_cast<std::size_t>(out)] = b;
          halfTet_[static_cast<std::size_t>(out++)] = halfTet_[static_cast<std::size_t>(j)];
          ++unique_[a];
          ++me.incoming[static_cast<std::size_t>(b)];
        }
        // Entries [out, start_[a + 1]) are duplicates: mark the end of the unique ones.
        if (out < start_[a + 1])
          halfTarget_[static_cast<std::size_t>(out)] = -1;
      }
    });

  // 5. The lists: v's smaller neighbours (those of the first half's vertices, then the
  // second's, each in increasing order), then its larger ones.
  offsets.assign(nv + 1, 0);
  for (std::size_t v = 0; v < nv; ++v)
    offsets[v + 1] = offsets[v] + half_[0].incoming[v] + half_[1].incoming[v] + unique_[v];
  resizeWithRoom(targets, static_cast<std::size_t>(offsets[nv]));
  resizeWithRoom(tetOf, targets.size());
  splitAt(twoThreads,
    vertexMiddle,
    nv,
    [&](int k, std::size_t firstVertex, std::size_t lastVertex)
    {
      Half& me = half_[k];
      me.cursor.resize(nv);
      for (std::size_t v = 0; v < nv; ++v)
        me.cursor[v] = offsets[v] + (k == 1 ? half_[0].incoming[v] : 0);
      for (std::size_t a = firstVertex; a < lastVertex; ++a)
      {
        std::int32_t own = offsets[a] + half_[0].incoming[a] + half_[1].incoming[a];
        for (std::int32_t j = start_[a];
             j < start_[a + 1] && halfTarget_[static_cast<std::size_t>(j)] >= 0;
             ++j)
        {
          const VertexId b = halfTarget_[static_cast<std::size_t>(j)];
          const TetId t = halfTet_[static_cast<std::size_t>(j)];
          const std::int32_t at = me.cursor[static_cast<std::size_t>(b)]++;
          targets[static_cast<std::size_t>(at)] = static_cast<VertexId>(a);
          tetOf[static_cast<std::size_t>(at)] = t;
          targets[static_cast<std::size_t>(own)] = b;
          tetOf[static_cast<std::size_t>(own++)] = t;
        }
      }
    });
}

} // namespace tetmesher
