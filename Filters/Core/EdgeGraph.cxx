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

// The chunks' scratch: a quarter more room than asked for, so that the next chunks (of about
// as many half edges) fit without a copy or fresh pages. The contents are not kept.
template<typename Vector>
void resizeWithRoom(Vector& v, std::size_t n)
{
  if (v.capacity() < n)
  {
    Vector larger;
    larger.reserve(n + n / 4);
    v.swap(larger);
  }
  v.resize(n);
}

template<typename Vector>
void release(Vector& v)
{
  Vector().swap(v);
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
  // The lists are rebuilt from scratch: the last build's go now, so that they and the sorting
  // scratch are never held at once (the scratch goes before the lists are made).
  release(targets);
  release(tetOf);
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
  // splitAt over [first, last) (splitAt's ranges start at 0).
  auto splitRange = [&](std::size_t first, std::size_t middle, std::size_t last, const auto& body)
  {
    splitAt(twoThreads,
      middle - first,
      last - first,
      [&](int k, std::size_t begin, std::size_t end) { body(k, first + begin, first + end); });
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

  // Steps 2-4 per chunk of whole blocks of vertices, each chunk's half edges at most
  // chunkHalfEdges (unless one block has more), so that the scratch arrays hold one chunk: all
  // of them at once were 70 MB of fandisk at h = 0.0103 (6.8M half edges), the refinement's
  // peak. The unique edges of each chunk go to uniqueTarget / uniqueTet, vertex by vertex.
  const std::size_t blocks = (nv >> kBlockShift) + 1;
  auto blockStart = [&](std::size_t b) { return start_[std::min(nv, b << kBlockShift)]; };
  half_[0].fill.resize(blocks);
  half_[1].fill.resize(blocks);
  half_[0].stamp.assign(nv, -1);
  half_[1].stamp.assign(nv, -1);
  unique_.assign(nv, 0);
  // A chunk's half edges, and their smaller vertex within its block.
  // Not zeroed on resize: step 2 writes every slot of a chunk before anything reads it, and
  // the two threads then first touch (page faults) the parts they fill.
  FlatArray<VertexId> halfTarget;
  FlatArray<TetId> halfTet;
  FlatArray<std::uint16_t> lowBits;
  // Every vertex's unique larger neighbours and their tets, from uniqueStart[v].
  std::vector<std::int32_t> uniqueStart(nv + 1, 0);
  std::vector<VertexId> uniqueTarget;
  std::vector<TetId> uniqueTet;
  const std::size_t halfEdges = static_cast<std::size_t>(start_[nv]);
  const std::size_t chunks = std::max<std::size_t>(maxChunks, 1);
  const std::size_t chunkLimit =
    std::max<std::size_t>({ chunkHalfEdges, (halfEdges + chunks - 1) / chunks, 1 });
  for (std::size_t firstBlock = 0; firstBlock < blocks;)
  {
    std::size_t lastBlock = firstBlock + 1;
    while (lastBlock < blocks &&
      static_cast<std::size_t>(blockStart(lastBlock + 1) - blockStart(firstBlock)) <= chunkLimit)
      ++lastBlock;
    const std::size_t v0 = std::min(nv, firstBlock << kBlockShift);
    const std::size_t v1 = std::min(nv, lastBlock << kBlockShift);
    const std::int32_t base = blockStart(firstBlock);
    const std::size_t chunkEdges = static_cast<std::size_t>(blockStart(lastBlock) - base);
    resizeWithRoom(halfTarget, chunkEdges);
    resizeWithRoom(halfTet, chunkEdges);
    resizeWithRoom(lowBits, chunkEdges);

    // 2. The chunk's half edges to their blocks, in tet order: within a block, the first
    // half's tets' edges first.
    for (std::size_t b = firstBlock; b < lastBlock; ++b)
    {
      std::int32_t firstHalf = 0;
      const std::size_t end = std::min(nv, (b + 1) << kBlockShift);
      for (std::size_t v = b << kBlockShift; v < end; ++v)
        firstHalf += half_[0].count[v + 1];
      half_[0].fill[b] = blockStart(b) - base;
      half_[1].fill[b] = blockStart(b) - base + firstHalf;
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
            if (static_cast<std::size_t>(lo) < v0 || static_cast<std::size_t>(lo) >= v1)
              return;
            const std::int32_t at = fill[static_cast<std::size_t>(lo >> kBlockShift)]++;
            halfTarget[static_cast<std::size_t>(at)] = std::max(a, b);
            halfTet[static_cast<std::size_t>(at)] = t;
            lowBits[static_cast<std::size_t>(at)] = static_cast<std::uint16_t>(lo & kBlockMask);
          });
      });

    // 3. Within each block to their vertex, keeping the order (halves of the blocks).
    std::vector<std::int32_t> blockStarts(lastBlock - firstBlock + 1);
    for (std::size_t b = firstBlock; b <= lastBlock; ++b)
      blockStarts[b - firstBlock] = blockStart(b) - base;
    const std::size_t blockMiddle = firstBlock + halfWay(blockStarts, lastBlock - firstBlock);
    splitRange(firstBlock,
      blockMiddle,
      lastBlock,
      [&](int k, std::size_t fromBlock, std::size_t toBlock)
      {
        Half& me = half_[k];
        for (std::size_t b = fromBlock; b < toBlock; ++b)
        {
          const std::int32_t first = blockStart(b) - base, last = blockStart(b + 1) - base;
          me.blockTarget.assign(halfTarget.begin() + first, halfTarget.begin() + last);
          me.blockTet.assign(halfTet.begin() + first, halfTet.begin() + last);
          const std::size_t w0 = b << kBlockShift;
          const std::size_t w1 = std::min(nv, w0 + (std::size_t{ 1 } << kBlockShift));
          me.vertexFill.resize(w1 - w0);
          for (std::size_t v = w0; v < w1; ++v)
            me.vertexFill[v - w0] = start_[v] - base;
          for (std::int32_t j = 0; j < last - first; ++j)
          {
            const std::int32_t at = me.vertexFill[lowBits[static_cast<std::size_t>(first + j)]]++;
            halfTarget[static_cast<std::size_t>(at)] = me.blockTarget[static_cast<std::size_t>(j)];
            halfTet[static_cast<std::size_t>(at)] = me.blockTet[static_cast<std::size_t>(j)];
          }
        }
      });

    // 4. Unique half edges (the first of each) to the front of their vertex's list, counted
    // (halves of the chunk's vertices, by their half edges; each half its own stamps).
    const std::size_t vertexMiddle =
      static_cast<std::size_t>(std::lower_bound(start_.begin() + static_cast<std::ptrdiff_t>(v0),
                                 start_.begin() + static_cast<std::ptrdiff_t>(v1),
                                 base + static_cast<std::int32_t>(chunkEdges / 2)) -
        start_.begin());
    splitRange(v0,
      vertexMiddle,
      v1,
      [&](int k, std::size_t firstVertex, std::size_t lastVertex)
      {
        std::vector<VertexId>& stamp = half_[k].stamp;
        for (std::size_t a = firstVertex; a < lastVertex; ++a)
        {
          std::int32_t out = start_[a] - base;
          for (std::int32_t j = start_[a] - base; j < start_[a + 1] - base; ++j)
          {
            const VertexId b = halfTarget[static_cast<std::size_t>(j)];
            if (stamp[static_cast<std::size_t>(b)] == static_cast<VertexId>(a))
              continue;
            stamp[static_cast<std::size_t>(b)] = static_cast<VertexId>(a);
            halfTarget[static_cast<std::size_t>(out)] = b;
            halfTet[static_cast<std::size_t>(out++)] = halfTet[static_cast<std::size_t>(j)];
            ++unique_[a];
          }
        }
      });
    for (std::size_t a = v0; a < v1; ++a)
      uniqueStart[a + 1] = uniqueStart[a] + unique_[a];
    uniqueTarget.resize(static_cast<std::size_t>(uniqueStart[v1]));
    uniqueTet.resize(uniqueTarget.size());
    splitRange(v0,
      vertexMiddle,
      v1,
      [&](int, std::size_t firstVertex, std::size_t lastVertex)
      {
        for (std::size_t a = firstVertex; a < lastVertex; ++a)
        {
          const std::size_t from = static_cast<std::size_t>(start_[a] - base);
          std::copy_n(halfTarget.begin() + static_cast<std::ptrdiff_t>(from),
            unique_[a],
            uniqueTarget.begin() + uniqueStart[a]);
          std::copy_n(halfTet.begin() + static_cast<std::ptrdiff_t>(from),
            unique_[a],
            uniqueTet.begin() + uniqueStart[a]);
        }
      });
    firstBlock = lastBlock;
  }

  release(halfTarget); // before the lists are made
  release(halfTet);
  release(lowBits);

  // 5. The lists: v's smaller neighbours (those of the first half's vertices, then the
  // second's, each in increasing order), then its larger ones. Per half of the vertices, the
  // count of its edges into each vertex (incoming), then the lists.
  const std::size_t vertexMiddle = halfWay(start_, nv);
  splitAt(twoThreads,
    vertexMiddle,
    nv,
    [&](int k, std::size_t firstVertex, std::size_t lastVertex)
    {
      std::vector<std::int32_t>& incoming = half_[k].incoming;
      incoming.assign(nv, 0);
      for (std::int32_t j = uniqueStart[firstVertex]; j < uniqueStart[lastVertex]; ++j)
        ++incoming[static_cast<std::size_t>(uniqueTarget[static_cast<std::size_t>(j)])];
    });
  offsets.assign(nv + 1, 0);
  for (std::size_t v = 0; v < nv; ++v)
    offsets[v + 1] = offsets[v] + half_[0].incoming[v] + half_[1].incoming[v] + unique_[v];
  targets.resize(static_cast<std::size_t>(offsets[nv]));
  tetOf.resize(targets.size());
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
        for (std::int32_t j = uniqueStart[a]; j < uniqueStart[a + 1]; ++j)
        {
          const VertexId b = uniqueTarget[static_cast<std::size_t>(j)];
          const TetId t = uniqueTet[static_cast<std::size_t>(j)];
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
