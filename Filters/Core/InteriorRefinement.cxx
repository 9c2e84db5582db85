#include "InteriorRefinement.h"

#include "BoundarySizeCeiling.h"
#include "BoundarySizeFloor.h"
#include "Delaunay.h"
#include "EdgeGraph.h"
#include "EpochHashTable.h"
#include "HilbertSort.h"
#include "HugePages.h"
#include "MedianSplit.h"
#include "MemoryBudget.h"
#include "MeshTopology.h"
#include "ParallelPair.h"
#include "RadixSort.h"
#include "TriangleDistance.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numeric>
#include <unordered_map>

namespace tetmesher
{

namespace
{

double distance(const double* a, const double* b)
{
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

std::uint64_t edgeKey(VertexId a, VertexId b)
{
  if (a > b)
    std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
    static_cast<std::uint32_t>(b);
}

bool faceIsConstrained(const TetMesh& mesh, TetId t, int f)
{
  if (mesh.isConstrained(t, f))
    return true;
  const FaceRef n = mesh.neighbor(t, f);
  return n == kNoNeighbor || mesh.isConstrained(faceTet(n), faceIndex(n));
}

// Calls visit(t, f) once per constrained face (boundary, interfaces): an interface face from
// the side of its smaller tet id.
template<typename Visit>
void forEachConstrainedFace(const TetMesh& mesh, Visit&& visit)
{
  for (TetId t = 0; t < mesh.tetCapacity(); ++t)
  {
    if (mesh.isDeleted(t))
      continue;
    for (int f = 0; f < 4; ++f)
    {
      if (!faceIsConstrained(mesh, t, f))
        continue;
      const FaceRef n = mesh.neighbor(t, f);
      if (n != kNoNeighbor && faceTet(n) < t)
        continue; // listed from its other side
      visit(t, f);
    }
  }
}

bool tetHas(const TetMesh& mesh, TetId t, VertexId v)
{
  const VertexId* tv = &mesh.tets[4 * static_cast<std::size_t>(t)];
  return tv[0] == v || tv[1] == v || tv[2] == v || tv[3] == v;
}

// Vertices bucketed by size class: class L holds sizes in [base 2^L, base 2^(L+1)) (class 0
// also the smaller ones), each class in a hash grid of cells 2 ratio base 2^L wide. A query
// scans, per class, the cells within the largest distance at which a vertex of the class can
// be rejected against it (from the largest size the class was given: sizes only ever go down
// during refinement), so it looks at ~2-3 cells per axis and ~1 vertex per cell. (Cells as
// wide as the largest radius of the class, 3x3x3 per query, made a query test ~250 vertices
// through a linked list: 10% of a 160k-tet run.) The answer does not depend on the cell size.
// A class whose cells over the box [origin, top] are few (at most kDenseCellsPerVertex per
// expected vertex, or kMinDenseCells) keeps them in a plain array instead of the hash grid:
// an interior query reads 8 cells of its class, twice in the halves (the shared grid and the
// side's own), and with hash tables alone the queries were 7% of fandisk at h/2's samples (4%
// with the arrays).
// Cells outside the box are clamped to its border cells, which only adds vertices to test.
class ProximityGrid
{
public:
  // expectedVertices: room reserved (not touched) for the vertices to come. [origin, top]:
  // the box where vertices are expected (others are accepted too). cellArrays: false for
  // hash grids only.
  ProximityGrid(double base,
    double ratio,
    const double* origin,
    const double* top,
    std::size_t expectedVertices,
    bool cellArrays)
    : base_(base)
    , ratio_(ratio)
    , maxDenseCells_(cellArrays ? std::max<double>(kMinDenseCells,
                                    kDenseCellsPerVertex * static_cast<double>(expectedVertices))
                                : 0.0)
  {
    for (int k = 0; k < 3; ++k)
    {
      origin_[k] = origin[k];
      top_[k] = std::max(top[k], origin[k]);
    }
    nodes_.reserve(expectedVertices);
  }

  void insert(VertexId v, const double* p, double h)
  {
    const int level = levelOf(h);
    while (static_cast<int>(levels_.size()) <= level)
    {
      Level l;
      l.cell = 2 * ratio_ * base_ * std::ldexp(1.0, static_cast<int>(levels_.size()));
      double cells = 1;
      for (int a = 0; a < 3; ++a)
      {
        l.dims[a] = index(l, top_[a], a) + 1;
        cells *= static_cast<double>(l.dims[a]);
      }
      if (cells <= maxDenseCells_)
        l.dense.assign(static_cast<std::size_t>(cells), -1);
      levels_.push_back(std::move(l));
    }
    Level& l = levels_[level];
    l.maxSize = std::max(l.maxSize, h);
    const std::int64_t cell[3] = { index(l, p[0], 0), index(l, p[1], 1), index(l, p[2], 2) };
    for (int a = 0; a < 3; ++a)
    {
      l.occupiedLo[a] = std::min(l.occupiedLo[a], cell[a]);
      l.occupiedHi[a] = std::max(l.occupiedHi[a], cell[a]);
    }
    const auto node = static_cast<std::int32_t>(nodes_.size());
    if (!l.dense.empty())
    {
      std::int32_t& head = l.dense[denseSlot(l, cell[0], cell[1], cell[2])];
      nodes_.push_back({ { p[0], p[1], p[2] }, v, head, level });
      head = node;
      return;
    }
    const std::uint64_t blockKey = cellKey(block(cell[0]), block(cell[1]), block(cell[2]));
    const std::uint64_t bit = std::uint64_t(1) << cellInBlock(cell[0], cell[1], cell[2]);
    if (std::uint64_t* occupied = l.blocks.find(blockKey))
      *occupied |= bit;
    else
      l.blocks.insert(blockKey, bit);
    const std::uint64_t key = cellKey(cell[0], cell[1], cell[2]);
    std::int32_t next = -1;
    if (std::int32_t* head = l.head.find(key))
    {
      next = *head;
      *head = node;
    }
    else
      l.head.insert(key, node);
    nodes_.push_back({ { p[0], p[1], p[2] }, v, next, level });
  }

  // Is some vertex q with d(p,q) * (1/h + 1/h_q) / 2 < ratio?
  bool hasNear(const double* p, double h, const std::vector<double>& sizes) const
  {
    for (const Level& l : levels_)
    {
      // d < 2 ratio / (1/h + 1/h_q) <= radius, with slack for rounding.
      const double radius = 2 * ratio_ / (1 / h + 1 / l.maxSize) * (1 + 1e-6);
      std::int64_t c0[3], c1[3];
      double cells = 1;
      for (int a = 0; a < 3; ++a)
      {
        const double slack = 4 * std::numeric_limits<double>::epsilon() *
          (std::fabs(p[a]) + std::fabs(origin_[a]) + radius);
        // Only the cells where the class has vertices: classes of other sizes than the
        // neighbourhood's (a femur's fine levels, far from a coarse query) are skipped.
        c0[a] = std::max(index(l, p[a] - radius - slack, a), l.occupiedLo[a]);
        c1[a] = std::min(index(l, p[a] + radius + slack, a), l.occupiedHi[a]);
        cells *= c1[a] < c0[a] ? 0.0 : static_cast<double>(c1[a] - c0[a] + 1);
      }
      if (cells == 0)
        continue;
      if (!(cells <= 4096)) // a query far larger than the class (or NaN): scan the class
      {
        const std::int32_t level = static_cast<std::int32_t>(&l - levels_.data());
        for (const Node& n : nodes_)
          if (n.level == level && isNear(p, h, n, sizes))
            return true;
        continue;
      }
      if (!l.dense.empty())
      {
        const std::int64_t i0 = clampCell(l, c0[0], 0), i1 = clampCell(l, c1[0], 0);
        const std::int64_t j0 = clampCell(l, c0[1], 1), j1 = clampCell(l, c1[1], 1);
        const std::int64_t k0 = clampCell(l, c0[2], 2), k1 = clampCell(l, c1[2], 2);
        for (std::int64_t i = i0; i <= i1; ++i)
          for (std::int64_t j = j0; j <= j1; ++j)
          {
            // i and j are clamped already: the row's first cell without clamping again.
            const std::int32_t* row = &l.dense[denseIndex(l, i, j, 0)];
            for (std::int64_t k = k0; k <= k1; ++k)
              for (std::int32_t n = row[k]; n >= 0; n = nodes_[n].next)
                if (isNear(p, h, nodes_[n], sizes))
                  return true;
          }
        continue;
      }
      // Most classes have no vertex near p (femur.off: 88 cell probes per query, 12 vertices
      // found): the blocks of 4x4x4 cells (1 or 2 per axis here) rule them out first, and
      // their masks of occupied cells leave only those to look up (each look-up in a large
      // table is a cache miss: the probes of empty cells were 12% of bunny00's run).
      const std::int64_t b0[3] = { block(c0[0]), block(c0[1]), block(c0[2]) };
      const std::int64_t nb[3] = {
        block(c1[0]) - b0[0] + 1, block(c1[1]) - b0[1] + 1, block(c1[2]) - b0[2] + 1
      };
      constexpr std::int64_t kMaxMasks = 64;
      if (nb[0] * nb[1] * nb[2] > kMaxMasks)
      {
        // A query far larger than the cells (rare): every cell of the range, unless no block
        // of it holds a vertex.
        bool occupied = false;
        for (std::int64_t i = b0[0]; i < b0[0] + nb[0] && !occupied; ++i)
          for (std::int64_t j = b0[1]; j < b0[1] + nb[1] && !occupied; ++j)
            for (std::int64_t k = b0[2]; k < b0[2] + nb[2] && !occupied; ++k)
              occupied = l.blocks.find(cellKey(i, j, k)) != nullptr;
        if (!occupied)
          continue;
        for (std::int64_t i = c0[0]; i <= c1[0]; ++i)
          for (std::int64_t j = c0[1]; j <= c1[1]; ++j)
            for (std::int64_t k = c0[2]; k <= c1[2]; ++k)
              if (cellHasNear(l, i, j, k, p, h, sizes))
                return true;
        continue;
      }
      std::uint64_t masks[kMaxMasks];
      std::uint64_t any = 0;
      for (std::int64_t i = 0; i < nb[0]; ++i)
        for (std::int64_t j = 0; j < nb[1]; ++j)
          for (std::int64_t k = 0; k < nb[2]; ++k)
          {
            const std::uint64_t* mask = l.blocks.find(cellKey(b0[0] + i, b0[1] + j, b0[2] + k));
            any |= masks[(i * nb[1] + j) * nb[2] + k] = mask ? *mask : 0;
          }
      if (!any)
        continue;
      for (std::int64_t i = c0[0]; i <= c1[0]; ++i)
        for (std::int64_t j = c0[1]; j <= c1[1]; ++j)
          for (std::int64_t k = c0[2]; k <= c1[2]; ++k)
          {
            const std::uint64_t mask =
              masks[((block(i) - b0[0]) * nb[1] + block(j) - b0[1]) * nb[2] + block(k) - b0[2]];
            if (((mask >> cellInBlock(i, j, k)) & 1u) && cellHasNear(l, i, j, k, p, h, sizes))
              return true;
          }
    }
    return false;
  }

private:
  struct Level
  {
    double cell = 0;
    double maxSize = 0; // largest size given to a vertex of the class
    // The cells over [origin, top] per axis, and each one's latest node (-1: none) when the
    // class keeps them in an array; else (empty) the hash tables below.
    std::int64_t dims[3] = { 0, 0, 0 };
    std::vector<std::int32_t> dense;
    EpochHashTable<std::uint64_t, std::int32_t, MixHash64> head; // a cell's latest node
    // Blocks of 4x4x4 cells holding a vertex: the mask of their cells that do.
    EpochHashTable<std::uint64_t, std::uint64_t, MixHash64> blocks;
    // The box of the cells holding the class's vertices (empty: lo > hi).
    std::int64_t occupiedLo[3] = { std::numeric_limits<std::int64_t>::max(),
      std::numeric_limits<std::int64_t>::max(),
      std::numeric_limits<std::int64_t>::max() };
    std::int64_t occupiedHi[3] = { std::numeric_limits<std::int64_t>::min(),
      std::numeric_limits<std::int64_t>::min(),
      std::numeric_limits<std::int64_t>::min() };
  };
  struct Node
  {
    double p[3];
    VertexId vertex;
    std::int32_t next; // the next node of the same cell, -1 at the end
    std::int32_t level;
  };

  // Is a vertex of hash cell (i, j, k) of level l near p?
  bool cellHasNear(const Level& l,
    std::int64_t i,
    std::int64_t j,
    std::int64_t k,
    const double* p,
    double h,
    const std::vector<double>& sizes) const
  {
    const std::int32_t* head = l.head.find(cellKey(i, j, k));
    if (!head)
      return false;
    for (std::int32_t n = *head; n >= 0; n = nodes_[n].next)
      if (isNear(p, h, nodes_[n], sizes))
        return true;
    return false;
  }

  bool isNear(const double* p, double h, const Node& n, const std::vector<double>& sizes) const
  {
    const double d = distance(p, n.p);
    return d * 0.5 * (1 / h + 1 / sizes[n.vertex]) < ratio_;
  }

  int levelOf(double h) const
  {
    if (!(h > base_))
      return 0;
    return std::min(60, std::max(0, static_cast<int>(std::floor(std::log2(h / base_)))));
  }

  std::int64_t index(const Level& l, double x, int a) const
  {
    const double c = std::floor((x - origin_[a]) / l.cell);
    return static_cast<std::int64_t>(std::max(-1e6, std::min(1e6, c)));
  }
  static std::uint64_t cellKey(std::int64_t i, std::int64_t j, std::int64_t k)
  {
    auto part = [](std::int64_t x)
    { return static_cast<std::uint64_t>(x + (1 << 20)) & ((1u << 21) - 1); };
    return (part(i) << 42) | (part(j) << 21) | part(k);
  }
  // A cell index of the array: clamped to the box's cells (monotone, so a range of cells
  // clamped holds every vertex of the range).
  static std::int64_t clampCell(const Level& l, std::int64_t c, int a)
  {
    return std::min(std::max(c, std::int64_t(0)), l.dims[a] - 1);
  }
  // The array index of cell (i, j, k), which must be within the box's cells.
  static std::size_t denseIndex(const Level& l, std::int64_t i, std::int64_t j, std::int64_t k)
  {
    return static_cast<std::size_t>((i * l.dims[1] + j) * l.dims[2] + k);
  }
  static std::size_t denseSlot(const Level& l, std::int64_t i, std::int64_t j, std::int64_t k)
  {
    return denseIndex(l, clampCell(l, i, 0), clampCell(l, j, 1), clampCell(l, k, 2));
  }
  // The block of 4 cells (per axis) that holds cell c (floor division: c may be negative).
  static std::int64_t block(std::int64_t c) { return c >= 0 ? c / 4 : -((3 - c) / 4); }
  // The bit of cell (i, j, k) in its block's mask of occupied cells.
  static int cellInBlock(std::int64_t i, std::int64_t j, std::int64_t k)
  {
    return static_cast<int>(
      ((i - 4 * block(i)) * 16 + (j - 4 * block(j)) * 4 + (k - 4 * block(k))));
  }

  static constexpr double kMinDenseCells = 1 << 18;
  static constexpr double kDenseCellsPerVertex = 2;
  double base_;
  double ratio_;
  double maxDenseCells_;
  double origin_[3];
  double top_[3];
  std::vector<Level> levels_;
  std::vector<Node> nodes_;
};

// The constrained faces (boundary, interfaces) in a hash grid, for the distance from a
// candidate point to the nearest one. They never change during refinement (no point goes on
// them, no cavity crosses them), so the grid is built once.
class FaceGrid
{
public:
  FaceGrid(const TetMesh& mesh, double cell, const double* origin)
    : cell_(cell)
  {
    for (int k = 0; k < 3; ++k)
      origin_[k] = origin[k];
    forEachConstrainedFace(mesh,
      [&](TetId t, int f)
      {
        const std::int32_t id = static_cast<std::int32_t>(corners_.size() / 3);
        double lo[3], hi[3];
        for (int k = 0; k < 3; ++k)
        {
          const VertexId v = mesh.vertex(t, kFaceVertices[f][k]);
          corners_.push_back(v);
          for (int a = 0; a < 3; ++a)
          {
            lo[a] = k == 0 ? mesh.point(v)[a] : std::min(lo[a], mesh.point(v)[a]);
            hi[a] = k == 0 ? mesh.point(v)[a] : std::max(hi[a], mesh.point(v)[a]);
          }
        }
        boxes_.insert(boxes_.end(), { lo[0], lo[1], lo[2], hi[0], hi[1], hi[2] });
        std::int64_t c0[3], c1[3];
        if (cellRange(lo, hi, 0, c0, c1) > kMaxCellsPerFace)
        {
          large_.push_back(id);
          return;
        }
        for (std::int64_t i = c0[0]; i <= c1[0]; ++i)
          for (std::int64_t j = c0[1]; j <= c1[1]; ++j)
            for (std::int64_t k = c0[2]; k <= c1[2]; ++k)
              entries_.push_back({ key(i, j, k), id });
      });
    // The faces of each cell side by side (pushed in face order, which the sort keeps), and
    // where each cell's run starts.
    sortPushedPairs(entries_);
    for (std::size_t e = 0; e < entries_.size(); ++e)
      if (e == 0 || entries_[e].first != entries_[e - 1].first)
        cellStart_.insert(entries_[e].first, static_cast<std::uint32_t>(e));
  }

  // Is a constrained face closer to p than limit?
  bool near(const TetMesh& mesh, const double* p, double limit) const
  {
    auto faceIsNear = [&](std::int32_t id)
    {
      // Bounding box first: most faces of a cell are farther than the limit.
      const double* box = &boxes_[6 * static_cast<std::size_t>(id)];
      for (int a = 0; a < 3; ++a)
        if (p[a] < box[a] - limit || p[a] > box[3 + a] + limit)
          return false;
      const VertexId* v = &corners_[3 * static_cast<std::size_t>(id)];
      return geometry::pointTriangleDistanceSquared(
               p, mesh.point(v[0]), mesh.point(v[1]), mesh.point(v[2])) < limit * limit;
    };
    for (std::int32_t id : large_)
      if (faceIsNear(id))
        return true;
    std::int64_t c0[3], c1[3];
    const std::int32_t faceCount = static_cast<std::int32_t>(corners_.size() / 3);
    if (cellRange(p, p, limit, c0, c1) > faceCount)
    {
      // Wider than the surface is fine (h ~ the model's size, or far beyond it): scan.
      for (std::int32_t id = 0; id < faceCount; ++id)
        if (faceIsNear(id))
          return true;
      return false;
    }
    for (std::int64_t i = c0[0]; i <= c1[0]; ++i)
      for (std::int64_t j = c0[1]; j <= c1[1]; ++j)
        for (std::int64_t k = c0[2]; k <= c1[2]; ++k)
        {
          const std::uint64_t cell = key(i, j, k);
          const std::uint32_t* start = cellStart_.find(cell);
          if (!start)
            continue;
          for (std::size_t e = *start; e < entries_.size() && entries_[e].first == cell; ++e)
            if (faceIsNear(entries_[e].second))
              return true;
        }
    return false;
  }

private:
  // A face spanning more cells than this (one much larger than the cell size, which is from
  // the median h: a spike of a fuzzed surface reached 1e6 cells per axis) is kept in a list
  // that every query scans, so that neither building nor querying depends on its extent.
  static constexpr double kMaxCellsPerFace = 512;

  // The cells of the box [lo - margin, hi + margin], and how many there are.
  double cellRange(const double* lo,
    const double* hi,
    double margin,
    std::int64_t* c0,
    std::int64_t* c1) const
  {
    double count = 1;
    for (int a = 0; a < 3; ++a)
    {
      c0[a] = index(lo[a] - margin, a);
      c1[a] = index(hi[a] + margin, a);
      count *= static_cast<double>(c1[a] - c0[a] + 1);
    }
    return count;
  }
  std::int64_t index(double x, int a) const
  {
    const double c = std::floor((x - origin_[a]) / cell_);
    return static_cast<std::int64_t>(std::max(-1e6, std::min(1e6, c)));
  }
  static std::uint64_t key(std::int64_t i, std::int64_t j, std::int64_t k)
  {
    auto part = [](std::int64_t x)
    { return static_cast<std::uint64_t>(x + (1 << 20)) & ((1u << 21) - 1); };
    return (part(i) << 42) | (part(j) << 21) | part(k);
  }

  double cell_;
  double origin_[3];
  std::vector<VertexId> corners_;
  std::vector<double> boxes_;                                   // per face: min x y z, max x y z
  std::vector<std::pair<std::uint64_t, std::int32_t>> entries_; // (cell, face), by cell
  EpochHashTable<std::uint64_t, std::uint32_t, MixHash64> cellStart_; // a cell's first entry
  std::vector<std::int32_t> large_; // faces over kMaxCellsPerFace cells
};

// The constrained faces and, at their vertices, the surface's own size: the mean length of the
// constrained edges there, graded like h (a vertex next to a small feature gets less). Sizes
// of vertices on no constrained face are the largest double.
struct SurfaceSizes
{
  std::vector<std::int32_t> corners; // 3 per face
  std::vector<double> vertexSize;

  // Face id's size: the smallest at its corners.
  double faceSize(std::size_t id) const
  {
    return std::min({ vertexSize[static_cast<std::size_t>(corners[3 * id])],
      vertexSize[static_cast<std::size_t>(corners[3 * id + 1])],
      vertexSize[static_cast<std::size_t>(corners[3 * id + 2])] });
  }
};

SurfaceSizes surfaceSizes(const TetMesh& mesh,
  VertexId vertexCount,
  const EdgeGraph& graph,
  double gradation)
{
  SurfaceSizes out;
  std::vector<double> edgeSum(static_cast<std::size_t>(vertexCount), 0.0);
  std::vector<int> edgeCount(static_cast<std::size_t>(vertexCount), 0);
  forEachConstrainedFace(mesh,
    [&](TetId t, int f)
    {
      for (int k = 0; k < 3; ++k)
      {
        const VertexId v = mesh.vertex(t, kFaceVertices[f][k]);
        const VertexId w = mesh.vertex(t, kFaceVertices[f][(k + 1) % 3]);
        out.corners.push_back(v);
        const double l = distance(mesh.point(v), mesh.point(w));
        edgeSum[v] += l;
        edgeSum[w] += l;
        edgeCount[v] += 1;
        edgeCount[w] += 1;
      }
    });
  out.vertexSize.assign(static_cast<std::size_t>(vertexCount), std::numeric_limits<double>::max());
  for (VertexId v = 0; v < vertexCount; ++v)
    if (edgeCount[v] > 0)
      out.vertexSize[v] = edgeSum[v] / edgeCount[v];
  limitGradation(mesh.coords.data(),
    vertexCount,
    graph.offsets.data(),
    graph.targets.data(),
    gradation,
    out.vertexSize.data());
  return out;
}

// The floor under the sizes next to boundary faces larger than h (BoundarySizeFloor.h): a
// face's size is the smallest surface size at its vertices, less (matched - 1) times the
// smallest wanted size h_F there (a face whose edges the field already accepts adds nothing),
// at most maxRatio h_F. Empty when off.
BoundarySizeFloor makeBoundarySizeFloor(const TetMesh& mesh,
  const SurfaceSizes& surface,
  const std::vector<double>& h,
  double gradation,
  double slopeFactor,
  double maxRatio,
  double matched)
{
  if (!(gradation > 1) || !(maxRatio > 1) || !(slopeFactor > 0) || surface.corners.empty())
    return {};
  std::vector<double> faceSize, faceBase;
  for (std::size_t id = 0; id < surface.corners.size() / 3; ++id)
  {
    const double size = surface.faceSize(id);
    double base = std::numeric_limits<double>::max();
    for (int k = 0; k < 3; ++k)
      base = std::min(base, h[surface.corners[3 * id + k]]);
    faceSize.push_back(std::min(size - (matched - 1) * base, maxRatio * base));
    faceBase.push_back(base);
  }
  // A slope of at most the gradation's: limitGradation never lowers what the floor sets.
  return BoundarySizeFloor(mesh.coords.data(),
    surface.corners,
    faceSize,
    faceBase,
    std::min(slopeFactor, 1.0) * (gradation - 1));
}

// The ceiling over the sizes next to boundary faces smaller than h (BoundarySizeCeiling.h): a
// face's size is `ratio` times the smallest surface size at its vertices, growing at the
// gradation's rate. Empty when off.
BoundarySizeCeiling makeBoundarySizeCeiling(const TetMesh& mesh,
  const SurfaceSizes& surface,
  double gradation,
  double ratio)
{
  if (!(gradation > 1) || !(ratio > 0) || surface.corners.empty())
    return {};
  std::vector<double> faceSize;
  for (std::size_t id = 0; id < surface.corners.size() / 3; ++id)
  {
    faceSize.push_back(ratio * surface.faceSize(id));
  }
  return BoundarySizeCeiling(mesh.coords.data(), surface.corners, faceSize, gradation - 1);
}

struct Candidate
{
  std::uint64_t order; // (length class descending, Hilbert index)
  VertexId a, b;
  TetId tet;
};

} // namespace

RefinementResult refineInterior(RegionMesh& regionMesh,
  std::vector<double>& vertexSize,
  const RefinementOptions& options,
  const std::function<double(const double*)>& background,
  const std::function<bool(double)>& progress)
{
  const auto startTime = std::chrono::steady_clock::now();
  RefinementResult result;
  auto finish = [&](bool ok, std::string error)
  {
    result.ok = ok;
    result.error = std::move(error);
    result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - startTime).count();
    return result;
  };
  TetMesh& mesh = regionMesh.mesh;
  std::vector<std::int32_t>& region = regionMesh.region;
  if (region.size() < static_cast<std::size_t>(mesh.tetCapacity()))
    return finish(false, "refineInterior: the region array is shorter than the tet array");
  if (!(options.maxEdgeRatio > 0))
    return finish(false, "refineInterior: maxEdgeRatio must be positive");
  if (!(options.size.scale > 0) || !std::isfinite(options.size.scale))
    return finish(false, "refineInterior: the size scale must be positive");
  const SizeFieldOptions& sizeOptions = options.size;
  const VertexId initialCount = mesh.vertexCount();

  // Constrained edges (edges of boundary / interface faces), a tet per vertex.
  std::vector<char> onConstraint(static_cast<std::size_t>(initialCount), 0);
  EpochHashTable<std::uint64_t, std::uint8_t, MixHash64> constrainedEdges;
  std::vector<TetId> vertexTet(static_cast<std::size_t>(initialCount), -1);
  // The domain's boundary faces (on one tet only) at each initial vertex: a star that meets
  // fewer is one of several, the domain pinched at the vertex (see starRoundRatio).
  std::vector<std::int32_t> boundaryFacesAt(static_cast<std::size_t>(initialCount), 0);
  for (TetId t = 0; t < mesh.tetCapacity(); ++t)
  {
    if (mesh.isDeleted(t))
      continue;
    for (int i = 0; i < 4; ++i)
      vertexTet[mesh.vertex(t, i)] = t;
    for (int f = 0; f < 4; ++f)
    {
      if (mesh.neighbor(t, f) == kNoNeighbor)
        for (int k = 0; k < 3; ++k)
          ++boundaryFacesAt[static_cast<std::size_t>(mesh.vertex(t, kFaceVertices[f][k]))];
      if (!faceIsConstrained(mesh, t, f))
        continue;
      VertexId fv[3];
      for (int k = 0; k < 3; ++k)
      {
        fv[k] = mesh.vertex(t, kFaceVertices[f][k]);
        onConstraint[fv[k]] = 1;
      }
      for (int k = 0; k < 3; ++k)
        constrainedEdges.insert(edgeKey(fv[k], fv[(k + 1) % 3]));
    }
  }

  EdgeGraph graph;
  graph.build(mesh, wantTwoThreads(0));

  // Sizes of the initial vertices: given, else background, else the mean of known neighbours.
  std::vector<double>& h = vertexSize;
  const std::size_t given = std::min(h.size(), static_cast<std::size_t>(initialCount));
  h.resize(static_cast<std::size_t>(initialCount), 0.0);
  std::vector<char> known(static_cast<std::size_t>(initialCount), 0);
  for (std::size_t v = 0; v < given; ++v)
    known[v] = h[v] > 0 && std::isfinite(h[v]);
  for (VertexId v = 0; v < initialCount; ++v)
  {
    if (known[v] || !background)
      continue;
    const double b = background(mesh.point(v));
    if (b > 0 && std::isfinite(b))
    {
      h[v] = b;
      known[v] = 1;
    }
  }
  for (bool progressMade = true; progressMade;)
  {
    progressMade = false;
    std::vector<std::pair<VertexId, double>> assigned;
    for (VertexId v = 0; v < initialCount; ++v)
    {
      if (known[v])
        continue;
      double sum = 0, low = std::numeric_limits<double>::max(), high = 0;
      int count = 0;
      for (std::int32_t k = graph.offsets[v]; k < graph.offsets[v + 1]; ++k)
        if (known[graph.targets[k]])
        {
          const double x = h[graph.targets[k]];
          sum += x;
          low = std::min(low, x);
          high = std::max(high, x);
          ++count;
        }
      if (count)
        assigned.emplace_back(v, low == high ? low : sum / count);
    }
    for (const auto& [v, value] : assigned)
    {
      h[v] = value;
      known[v] = 1;
      progressMade = true;
    }
  }
  {
    double sum = 0;
    int count = 0;
    for (VertexId v = 0; v < initialCount; ++v)
      if (known[v])
      {
        sum += h[v];
        ++count;
      }
    if (count == 0)
      return finish(false, "refineInterior: no vertex has a size (no sizes given, no background)");
    for (VertexId v = 0; v < initialCount; ++v)
      if (!known[v])
        h[v] = sum / count; // a vertex in no tet
  }
  for (double& value : h)
    value = scaleAndClampSize(value, sizeOptions);
  // The region list's bounds (options.regionMaxSize): per tet by its region, and at each
  // initial vertex the smallest of its tets' (before gradation, which carries them on).
  constexpr double kNoCap = std::numeric_limits<double>::infinity();
  const bool regionCaps = std::any_of(
    options.regionMaxSize.begin(), options.regionMaxSize.end(), [](double b) { return b > 0; });
  auto regionCap = [&](TetId t)
  {
    const std::int32_t r = region[static_cast<std::size_t>(t)];
    if (!regionCaps || r < 0 || static_cast<std::size_t>(r) >= options.regionMaxSize.size())
      return kNoCap;
    const double b = options.regionMaxSize[static_cast<std::size_t>(r)];
    return b > 0 ? b : kNoCap;
  };
  std::vector<double> vertexCap;
  if (regionCaps)
  {
    vertexCap.assign(static_cast<std::size_t>(initialCount), kNoCap);
    for (TetId t = 0; t < mesh.tetCapacity(); ++t)
      if (!mesh.isDeleted(t))
        for (int i = 0; i < 4; ++i)
        {
          double& cap = vertexCap[static_cast<std::size_t>(mesh.vertex(t, i))];
          cap = std::min(cap, regionCap(t));
        }
    for (VertexId v = 0; v < initialCount; ++v)
      h[static_cast<std::size_t>(v)] =
        std::min(h[static_cast<std::size_t>(v)], vertexCap[static_cast<std::size_t>(v)]);
  }
  if (sizeOptions.gradation > 1)
    limitGradation(mesh.coords.data(),
      initialCount,
      graph.offsets.data(),
      graph.targets.data(),
      sizeOptions.gradation,
      h.data());

  // Estimated vertex count of a mesh with edges ~h: sqrt(2)/h^3 per unit volume (the density
  // of the face-centred cubic packing with nearest neighbours h, i.e. one vertex per 6 regular
  // tets of edge h: 6 * h^3 / (6 sqrt 2)).
  double lo[3] = { std::numeric_limits<double>::max(),
    std::numeric_limits<double>::max(),
    std::numeric_limits<double>::max() };
  double hi[3] = { -lo[0], -lo[1], -lo[2] };
  {
    double estimate = 0;
    for (TetId t = 0; t < mesh.tetCapacity(); ++t)
    {
      if (mesh.isDeleted(t))
        continue;
      const double* c[4];
      double hm = 0;
      for (int i = 0; i < 4; ++i)
      {
        c[i] = mesh.point(mesh.vertex(t, i));
        hm += 0.25 * h[mesh.vertex(t, i)];
      }
      const double u[3] = { c[0][0] - c[3][0], c[0][1] - c[3][1], c[0][2] - c[3][2] };
      const double v[3] = { c[1][0] - c[3][0], c[1][1] - c[3][1], c[1][2] - c[3][2] };
      const double w[3] = { c[2][0] - c[3][0], c[2][1] - c[3][1], c[2][2] - c[3][2] };
      const double volume =
        std::fabs(u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
          u[2] * (v[0] * w[1] - v[1] * w[0])) /
        6;
      estimate += volume * std::sqrt(2.0) / (hm * hm * hm);
    }
    result.estimatedPoints = estimate;
  }
  // Refuse, before inserting anything, a size field the machine cannot hold.
  if (std::string tooLarge = checkMemoryBudget(result.estimatedPoints, options.memoryLimitBytes);
      !tooLarge.empty())
    return finish(false, tooLarge);
  for (VertexId v = 0; v < initialCount; ++v)
    for (int k = 0; k < 3; ++k)
    {
      lo[k] = std::min(lo[k], mesh.point(v)[k]);
      hi[k] = std::max(hi[k], mesh.point(v)[k]);
    }
  const double budgetDouble = options.maxPoints >= 0
    ? static_cast<double>(options.maxPoints)
    : std::min(8.0 * result.estimatedPoints + 16.0 * initialCount + 10000.0, 1.0e9);
  const std::int64_t budget = static_cast<std::int64_t>(budgetDouble);
  if (initialCount == 0 || mesh.liveTetCount() == 0)
    return finish(true, "");
  {
    // Room for the estimated mesh up front (~6.5 tets per vertex): growing the arrays by
    // copying took ~3% of the refinement. Bounded, as the estimate may be far off.
    const double points = std::min(result.estimatedPoints, 3.0e7);
    const auto tets = static_cast<std::size_t>(mesh.tetCapacity() + 6.5 * points);
    const auto vertices = static_cast<std::size_t>(initialCount + points);
    mesh.coords.reserve(3 * vertices);
    mesh.tets.reserve(4 * tets);
    mesh.neighbors.reserve(4 * tets);
    mesh.flags.reserve(tets);
    region.reserve(tets);
    h.reserve(vertices);
    adviseHugePages(mesh.coords);
    adviseHugePages(mesh.tets);
    adviseHugePages(mesh.neighbors);
    adviseHugePages(mesh.flags);
    adviseHugePages(region);
    adviseHugePages(h);
  }

  // The floor next to faces larger than h (BoundarySizeFloor.h) and the ceiling next to faces
  // smaller than h (BoundarySizeCeiling.h) bound the sizes of the initial vertices, the sizes
  // of their edges; interpolation keeps their wanted sizes, or the boundary mesh's long tets
  // would carry the faces' sizes across the domain. Every new point's size is bounded too.
  const std::vector<double> wanted(h.begin(), h.end());
  const SurfaceSizes surface = surfaceSizes(mesh, initialCount, graph, sizeOptions.gradation);
  const BoundarySizeFloor sizeFloor = makeBoundarySizeFloor(mesh,
    surface,
    h,
    sizeOptions.gradation,
    options.floorSlope,
    options.maxFloorRatio,
    options.maxEdgeRatio);
  const BoundarySizeCeiling sizeCeiling =
    makeBoundarySizeCeiling(mesh, surface, sizeOptions.gradation, options.ceilingRatio);
  // hp raised to the floor at p and lowered to the ceiling, within the user's clamps and the
  // region's cap (the ceiling wins where both apply: the smaller feature decides).
  auto boundToSurface = [&](const double* p, double hp, double cap)
  {
    hp = std::min(hp, cap);
    if (!sizeFloor.empty())
    {
      double f = std::min(sizeFloor.at(p, hp), cap);
      if (sizeOptions.maxSize > 0)
        f = std::min(f, sizeOptions.maxSize);
      hp = std::max(hp, f);
    }
    if (!sizeCeiling.empty())
      hp = std::max(sizeCeiling.at(p, hp), std::min(hp, sizeOptions.minSize));
    return hp;
  };
  // Each vertex on its own (the floor and ceiling are read only): in two halves from 2048
  // vertices (fandisk.off at h: 6.5k surface points, 7 ms on one thread).
  splitAt(initialCount >= 2048 && wantTwoThreads(0),
    initialCount / 2,
    initialCount,
    [&](int, VertexId first, VertexId last)
    {
      for (VertexId v = first; v < last; ++v)
        h[v] = boundToSurface(
          mesh.point(v), h[v], regionCaps ? vertexCap[static_cast<std::size_t>(v)] : kNoCap);
    });
  double minH = std::numeric_limits<double>::max();
  for (VertexId v = 0; v < initialCount; ++v)
    minH = std::min({ minH, h[v], wanted[v] });
  auto interpolationSize = [&](VertexId v) { return v < initialCount ? wanted[v] : h[v]; };
  const bool checkProximity = options.minPointDistance > 0;
  ProximityGrid grid(minH,
    std::max(options.minPointDistance, 1e-3),
    lo,
    hi,
    static_cast<std::size_t>(initialCount + std::min(result.estimatedPoints, 1.0e7)),
    options.proximityCellArrays);
  if (checkProximity)
    for (VertexId v = 0; v < initialCount; ++v)
      if (vertexTet[v] >= 0)
        grid.insert(v, mesh.point(v), h[v]);
  std::unique_ptr<FaceGrid> faces;
  if (options.minBoundaryDistance > 0 || options.latticeBoundaryDistance > 0)
  {
    // Cells as wide as the query radius at the median size: a query looks at 2 or 3 cells
    // per axis.
    std::vector<double> sorted(h.begin(), h.end());
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double radius = std::max({ options.minBoundaryDistance,
      options.latticeSpacing > 0 ? options.latticeBoundaryDistance : 0.0,
      0.1 });
    faces = std::make_unique<FaceGrid>(mesh, radius * sorted[sorted.size() / 2], lo);
  }

  auto lap = [last = std::chrono::steady_clock::now()]() mutable
  {
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - last).count();
    last = now;
    return seconds;
  };
  result.setupSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - startTime).count();

  std::unique_ptr<InsertionWorkspace, InsertionWorkspaceDeleter> workspace(
    createInsertionWorkspace());
  std::vector<Candidate> candidates;
  std::vector<TetId> star;
  const double extent = std::max({ hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-300 });
  auto hilbertKey = [&](const double* p)
  {
    std::uint32_t g[3];
    for (int k = 0; k < 3; ++k)
    {
      const double s = (p[k] - lo[k]) / extent * 65535.0;
      g[k] = static_cast<std::uint32_t>(std::max(0.0, std::min(65535.0, s)));
    }
    return hilbertIndex(g[0], g[1], g[2], 16);
  };
  // The point of ab that halves it in the metric of h, for h linear along the edge:
  // integral of 1/h from a equal on both sides <=> h(t) = sqrt(h_a h_b).
  auto splitPoint = [&](VertexId a, VertexId b, double* p)
  {
    const double sa = std::sqrt(h[a]), sb = std::sqrt(h[b]);
    // Structured input (grids) makes midpoints lattice points, hence exactly coplanar and
    // co-spherical groups that rounding turns into flat tets; a deterministic shift of the
    // split point along the edge (a hash of the edge's ends) breaks the lattice.
    std::uint64_t x = edgeKey(a, b) * 0x9E3779B97F4A7C15ULL;
    x ^= x >> 29;
    x *= 0xBF58476D1CE4E5B9ULL;
    x ^= x >> 32;
    const double s0 = sa / (sa + sb);
    // Scaled down near the ends, so that the point stays strictly inside the edge.
    const double shift = std::clamp(options.splitJitter, 0.0, 0.9) * 2 * std::min(s0, 1 - s0) *
      ((x >> 11) * (1.0 / 9007199254740992.0) - 0.5);
    const double s = s0 + shift;
    const double* pa = mesh.point(a);
    const double* pb = mesh.point(b);
    for (int k = 0; k < 3; ++k)
      p[k] = pa[k] + s * (pb[k] - pa[k]);
  };
  // A tet of edge ab: the hint, else one of a's star (found in `stars`, unmarked for a side
  // of MeshHalves).
  auto findEdgeIn =
    [&](VertexId a, VertexId b, TetId hint, std::vector<TetId>& stars, bool side) -> TetId
  {
    if (hint >= 0 && hint < mesh.tetCapacity() && !mesh.isDeleted(hint) && tetHas(mesh, hint, a) &&
      tetHas(mesh, hint, b))
      return hint;
    const TetId t = vertexTet[a];
    if (t < 0 || mesh.isDeleted(t) || !tetHas(mesh, t, a))
      return -1;
    starOf(mesh, t, a, stars, !side);
    for (TetId u : stars)
      if (tetHas(mesh, u, b))
        return u;
    return -1;
  };
  auto findEdge = [&](VertexId a, VertexId b, TetId hint)
  { return findEdgeIn(a, b, hint, star, false); };

  // h at p, a point in `container`: the background field, else the interpolation of the
  // container's vertex sizes (already scaled: clamped only).
  auto sizeAt = [&](const double* p, TetId container, double fallback)
  {
    double hp;
    if (background)
    {
      hp = background(p);
      hp = hp > 0 && std::isfinite(hp) ? scaleAndClampSize(hp, sizeOptions) : fallback;
      return boundToSurface(p, hp, regionCap(container));
    }
    const double* corners[4];
    double hc[4];
    for (int i = 0; i < 4; ++i)
    {
      const VertexId w = mesh.vertex(container, i);
      corners[i] = mesh.point(w);
      hc[i] = interpolationSize(w);
    }
    hp = interpolateSize(p, corners, hc, sizeOptions.interpolationPower);
    if (sizeOptions.minSize > 0)
      hp = std::max(hp, sizeOptions.minSize);
    if (sizeOptions.maxSize > 0)
      hp = std::min(hp, sizeOptions.maxSize);
    return boundToSurface(p, hp, regionCap(container));
  };
  // Inserts p (in `container`, of region r) with size hp unless a vertex or a constrained
  // face is too close or the kernel refuses it. Returns a tet of the new vertex, or -1.
  // Is p (size hp) too close to a vertex (of the grid, or of `own` too, a side's: see
  // HalvesPhase) or a constrained face? Counted in the counters given.
  auto tooClose = [&](const ProximityGrid* own,
                    int& nearVertex,
                    int& nearBoundary,
                    const double* p,
                    double hp,
                    double boundaryDistance)
  {
    if (checkProximity && (grid.hasNear(p, hp, h) || (own && own->hasNear(p, hp, h))))
    {
      ++nearVertex;
      return true;
    }
    if (boundaryDistance > 0 && faces->near(mesh, p, boundaryDistance * hp))
    {
      ++nearBoundary;
      return true;
    }
    return false;
  };
  auto refused = [&](const double* p, double hp, double boundaryDistance)
  {
    return tooClose(
      nullptr, result.rejectedNearVertex, result.rejectedNearBoundary, p, hp, boundaryDistance);
  };
  // Inserts p unless refused; checked = the caller has just asked `refused`.
  // After v (at p, size hp, in a tet of region r) went in through `tet`: its star's regions,
  // its vertices' tets, and v in the proximity grid `into`.
  auto noteNewVertex = [&](VertexId v,
                         TetId tet,
                         const double* p,
                         double hp,
                         std::int32_t r,
                         std::vector<TetId>& stars,
                         ProximityGrid& into)
  {
    starOf(mesh, tet, v, stars);
    for (TetId u : stars)
    {
      region[u] = r;
      for (int i = 0; i < 4; ++i)
        vertexTet[mesh.vertex(u, i)] = u;
    }
    if (checkProximity)
      into.insert(v, p, hp);
  };
  auto tryInsert = [&](const double* p,
                     TetId container,
                     double hp,
                     std::int32_t r,
                     double boundaryDistance,
                     bool checked = false) -> TetId
  {
    if (!checked && refused(p, hp, boundaryDistance))
      return -1;
    const VertexId v = mesh.addVertex(p[0], p[1], p[2]);
    const InsertResult inserted = insertVertex(mesh, v, container, *workspace);
    if (inserted.status != InsertStatus::Inserted)
    {
      mesh.coords.resize(3 * static_cast<std::size_t>(v));
      ++result.rejectedByKernel;
      return -1;
    }
    h.push_back(hp);
    region.resize(static_cast<std::size_t>(mesh.tetCapacity()), -1);
    vertexTet.resize(static_cast<std::size_t>(mesh.vertexCount()), -1);
    noteNewVertex(v, inserted.tet, p, hp, r, star, grid);
    return inserted.tet;
  };

  // Insertion in two halves of space side by side (MeshHalves, Delaunay.h), for the large
  // rounds of the lattice and of the edge splitting. The caller splits its points at the median
  // of their longest extent and keeps for the rest, inserted in order afterwards, those closer
  // to the split than the largest distance at which two new points can refuse each other
  // (ratio * the largest h a side will insert). Then neither side's proximity test depends on
  // the other's points: each tests the vertices from before (the shared grid, read only
  // meanwhile) and its own new ones (a grid of its own). Each side numbers its vertices from a
  // range of ids of its own; the ranges are closed up afterwards, and the new vertices enter
  // the shared grid in that order. Points a side postponed (its walk or cavity would reach the
  // other side's tets) go to the rest. The mesh does not depend on the number of threads.
  const std::size_t minHalvesPoints = options.halvesMinPoints > 0
    ? static_cast<std::size_t>(options.halvesMinPoints)
    : std::numeric_limits<std::size_t>::max();
  const double proximityRatio = std::max(options.minPointDistance, 1e-3);
  struct HalfState
  {
    std::vector<std::size_t> items, postponed; // the caller's indices
    VertexId firstId = 0, accepted = 0;
    TetId hint = -1;
    int nearVertex = 0, nearBoundary = 0, byKernel = 0;
    std::vector<TetId> star;
    std::unique_ptr<ProximityGrid> grid;
    std::unordered_map<std::uint64_t, std::array<double, 3>> outside; // edge splitting's
  };
  struct HalvesPhase
  {
    HalfState side[2];
    VertexId base = 0;
    std::unique_ptr<MeshHalves> halves;
    std::atomic<bool> abort{ false };
  };
  // Sizes the arrays for the sides' vertices (each side's item count) and opens the halves.
  auto beginHalves = [&](HalvesPhase& phase, int axis, double split)
  {
    phase.base = mesh.vertexCount();
    phase.side[0].firstId = phase.base;
    phase.side[1].firstId = phase.base + static_cast<VertexId>(phase.side[0].items.size());
    const std::size_t vertices =
      static_cast<std::size_t>(phase.side[1].firstId) + phase.side[1].items.size();
    mesh.coords.resize(3 * vertices);
    h.resize(vertices, 0.0);
    vertexTet.resize(vertices, -1);
    phase.halves = std::make_unique<MeshHalves>(
      mesh, axis, split, phase.side[0].items.size(), phase.side[1].items.size());
    region.resize(static_cast<std::size_t>(mesh.tetCapacity()), -1);
    if (checkProximity)
      for (int k = 0; k < 2; ++k)
      {
        // The side's half of the box, where its points are.
        double sideLo[3] = { lo[0], lo[1], lo[2] }, sideHi[3] = { hi[0], hi[1], hi[2] };
        (k == 0 ? sideHi : sideLo)[axis] = std::min(std::max(split, lo[axis]), hi[axis]);
        phase.side[k].grid = std::make_unique<ProximityGrid>(minH,
          proximityRatio,
          sideLo,
          sideHi,
          phase.side[k].items.size(),
          options.proximityCellArrays);
      }
  };
  // refused() for a side.
  auto refusedOnSide = [&](HalfState& me, const double* p, double hp, double boundaryDistance)
  { return tooClose(me.grid.get(), me.nearVertex, me.nearBoundary, p, hp, boundaryDistance); };
  // tryInsert() for a side, the proximity already tested.
  auto insertOnSide =
    [&](HalvesPhase& phase, int k, const double* p, double hp, TetId container, std::int32_t r)
    -> InsertStatus
  {
    HalfState& me = phase.side[k];
    const VertexId v = me.firstId + me.accepted;
    std::copy(p, p + 3, &mesh.coords[3 * static_cast<std::size_t>(v)]);
    h[v] = hp;
    const InsertResult inserted = phase.halves->insert(k, v, container);
    if (inserted.status == InsertStatus::Postponed)
      return inserted.status;
    if (inserted.status != InsertStatus::Inserted)
    {
      ++me.byKernel;
      return inserted.status;
    }
    ++me.accepted;
    // The star of a new vertex is the side's own: marks and writes stay on its tets.
    noteNewVertex(v, inserted.tet, p, hp, r, me.star, checkProximity ? *me.grid : grid);
    me.hint = inserted.tet;
    // Progress from the caller's thread only (a GUI's callback), counting both sides.
    if (k == 0 && (me.accepted & 1023) == 0 && progress)
    {
      const double fraction = std::min(0.99,
        (result.insertedPoints + 2.0 * me.accepted) /
          std::max(1.0, result.estimatedPoints - initialCount));
      if (!progress(fraction))
        phase.abort = true;
    }
    return InsertStatus::Inserted;
  };
  // Closes the halves: ids closed up, new vertices into the shared grid, counters; the items
  // the sides postponed are added to `rest`, which is sorted. Returns the points inserted.
  auto endHalves = [&](HalvesPhase& phase, std::vector<std::size_t>& rest)
  {
    // Side 1's tets moved down to close the gap of unused slots: their regions and the tet
    // ids held here move with them.
    const TetRelocation moved = phase.halves->finish();
    if (moved.to > moved.from)
      std::copy(region.begin() + moved.from,
        region.begin() + moved.to,
        region.begin() + (moved.from - moved.shift)); // down: forward is right
    region.resize(static_cast<std::size_t>(mesh.tetCapacity()), -1);
    if (moved.shift > 0)
    {
      for (TetId& t : vertexTet)
        t = moved.map(t);
      for (HalfState& me : phase.side)
        me.hint = moved.map(me.hint);
    }
    const VertexId gap = static_cast<VertexId>(phase.side[0].items.size()) - phase.side[0].accepted;
    const VertexId firstOne = phase.side[1].firstId;
    if (gap > 0 && phase.side[1].accepted > 0)
    {
      // Every tet's own ids: the two halves of the slots side by side.
      constexpr TetId kMinHalves = 65536;
      const TetId slots = mesh.tetCapacity();
      splitAt(slots >= kMinHalves && wantTwoThreads(0),
        slots / 2,
        slots,
        [&](int, TetId begin, TetId end)
        {
          for (TetId t = begin; t < end; ++t)
            if (!mesh.isDeleted(t))
              for (int i = 0; i < 4; ++i)
              {
                VertexId& w = mesh.tets[4 * static_cast<std::size_t>(t) + i];
                if (w >= firstOne)
                  w -= gap;
              }
        });
      for (VertexId v = firstOne; v < firstOne + phase.side[1].accepted; ++v)
      {
        std::copy(&mesh.coords[3 * static_cast<std::size_t>(v)],
          &mesh.coords[3 * static_cast<std::size_t>(v)] + 3,
          &mesh.coords[3 * static_cast<std::size_t>(v - gap)]);
        h[v - gap] = h[v];
        vertexTet[v - gap] = vertexTet[v];
      }
    }
    const VertexId inserted = phase.side[0].accepted + phase.side[1].accepted;
    const std::size_t kept = static_cast<std::size_t>(phase.base + inserted);
    mesh.coords.resize(3 * kept);
    h.resize(kept);
    vertexTet.resize(kept);
    if (checkProximity)
      for (VertexId v = phase.base; v < static_cast<VertexId>(kept); ++v)
        grid.insert(v, mesh.point(v), h[v]);
    for (const HalfState& me : phase.side)
    {
      result.rejectedNearVertex += me.nearVertex;
      result.rejectedNearBoundary += me.nearBoundary;
      result.rejectedByKernel += me.byKernel;
      rest.insert(rest.end(), me.postponed.begin(), me.postponed.end());
    }
    result.insertedPoints += inserted;
    std::sort(rest.begin(), rest.end());
    return inserted;
  };
  // Runs body(k, side k's state, item) over each side's items, side by side, until an abort.
  auto runHalves = [&](HalvesPhase& phase, const auto& body)
  {
    runPair(wantTwoThreads(0),
      [&](int k)
      {
        HalfState& me = phase.side[k];
        for (std::size_t item : me.items)
        {
          if (phase.abort.load(std::memory_order_relaxed))
            break;
          body(k, me, item);
        }
      });
  };

  if (options.latticeSpacing > 0)
  {
    // Lattice prefill: body-centred cubic points (the cube corners and centres of a grid of
    // spacing a) whose Delaunay tets are all congruent (edges a and a sqrt(3)/2, dihedral
    // angles 60 and 90 degrees) and unique (no 5 co-spherical points with an empty sphere).
    // Where h varies, levels of spacing a_L = latticeSpacing * h0 * ratio^L each fill the
    // places where h rounds to their level; the seams between levels, and the layer next to
    // the boundary, are left to the edge splitting below.
    const double ratio = std::max(options.latticeLevelRatio, 1.01);
    const double logRatio = std::log(ratio);
    // A level's spacing and origin, snapped to a dyadic grid: a/2 = m 2^e with m in
    // [2^11, 2^12] (the spacing moves by at most 1/4096 of itself) and the origin a multiple of
    // 2^e at or below lo. Every lattice coordinate is then an exact integer times 2^e, and so
    // is every difference of two of them: the degenerate (co-spherical, co-planar) tuples the
    // lattice is full of are decided by the predicates' integer stages (Predicates.cxx)
    // instead of expansion arithmetic, which took 13% of the whole run on icosphere at h/2.
    struct LevelGeometry
    {
      double a;
      double origin[3];
    };
    auto levelGeometry = [&](int level)
    {
      constexpr int kMantissaBits = 12;
      LevelGeometry g;
      g.a = options.latticeSpacing * minH * std::pow(ratio, level);
      std::copy(lo, lo + 3, g.origin);
      if (!(g.a > 0) || !std::isfinite(g.a))
        return g;
      const double unit = std::ldexp(1.0, std::ilogb(0.5 * g.a) - (kMantissaBits - 1));
      const double m = std::round(0.5 * g.a / unit);
      double snapped[3];
      for (int k = 0; k < 3; ++k)
        snapped[k] = std::floor(lo[k] / unit) * unit;
      // Left as it is where 2^e under- or overflows, or the coordinates would need more than
      // the 53 bits of a double.
      const double limit = std::ldexp(unit, 40);
      if (unit > 0 && std::isfinite(limit) && std::fabs(snapped[0]) < limit &&
        std::fabs(snapped[1]) < limit && std::fabs(snapped[2]) < limit)
      {
        g.a = 2 * m * unit;
        std::copy(snapped, snapped + 3, g.origin);
      }
      return g;
    };
    auto levelOfSize = [&](double size)
    { return static_cast<int>(std::floor(std::log(size / minH) / logRatio + 0.5)); };
    struct LatticePoint
    {
      double p[3];
      double h;
      TetId tet;
      VertexId corner[4];
    };
    std::vector<LatticePoint> points;
    // Room for twice the estimated mesh (the prefill finds more positions than go in: those
    // next to the boundary are refused): reserved, not touched, so it costs no memory, where
    // growing by doubling wrote about twice the final size into fresh pages.
    points.reserve(static_cast<std::size_t>(std::min(2.0 * result.estimatedPoints, 1.0e7)) + 1024);
    const double jitter = std::clamp(options.latticeJitter, 0.0, 0.5);
    EpochHashTable<std::uint64_t, std::uint8_t, MixHash64> taken; // lattice keys used
    // Work bounds. The key holds 19 bits per index, so a level whose indices would go beyond
    // that is left to the edge splitting (keys would collide, and far beyond, the index would
    // not even fit an integer). And the work is bounded: a tet's bounding box can hold vastly
    // more lattice positions than the size field asks for inside the tet (a fuzzed cube with a
    // vertex pulled out to 3.4e38 and h ~ 1 at the others), so past a bound on the rows and
    // positions scanned the prefill stops and the edge splitting, bounded by `budget`, does
    // the rest. Counted as scanned, not as box volumes: the boxes of a co-spherical surface's
    // boundary tets (uv_sphere.vtp) span the domain and overlap, and their volumes reached the
    // bound before the last tets, whose positions the rows' pruning mostly skips anyway.
    constexpr double kMaxLatticeIndex = 1 << 18;
    const double maxCandidates = 16.0 * static_cast<double>(budget) + 1e6;
    const TetId initialTets = mesh.tetCapacity();
    // The positions found in a range of tets, in tet order, duplicates (a position on a face
    // shared by two tets) included: they are dropped afterwards, first one kept. `peak` is the
    // most the work bound's tests saw (counter plus the box's cost), to tell whether a range
    // scanned on its own met the bound where the scan of all tets would have.
    struct LatticeScan
    {
      double candidates = 0, peak = 0;
      std::vector<LatticePoint> points;
      std::vector<std::uint64_t> keys;
    };
    // publish: where this scan's counter is shown to a scan of the later tets, which stops
    // once the two counters together pass the bound (`earlier`): its result is then not used
    // (see below), so it need not go on.
    auto scanTets = [&](TetId tBegin,
                      TetId tEnd,
                      LatticeScan& scan,
                      std::atomic<double>* publish = nullptr,
                      const std::atomic<double>* earlier = nullptr)
    {
      double& candidates = scan.candidates;
      for (TetId t = tBegin; t < tEnd && candidates <= maxCandidates &&
           (!earlier || candidates + earlier->load(std::memory_order_relaxed) <= maxCandidates);
           ++t)
      {
        if (publish)
          publish->store(candidates, std::memory_order_relaxed);
        if (mesh.isDeleted(t))
          continue;
        const double* c[4];
        double hc[4];
        double bmin[3], bmax[3];
        double hlo = std::numeric_limits<double>::max(), hhi = 0;
        for (int i = 0; i < 4; ++i)
        {
          c[i] = mesh.point(mesh.vertex(t, i));
          hc[i] = wanted[mesh.vertex(t, i)];
          // h, unlike hc, went through the floor and the ceiling.
          hlo = std::min({ hlo, hc[i], h[mesh.vertex(t, i)] });
          hhi = std::max({ hhi, hc[i], h[mesh.vertex(t, i)] });
          for (int k = 0; k < 3; ++k)
          {
            bmin[k] = i == 0 ? c[i][k] : std::min(bmin[k], c[i][k]);
            bmax[k] = i == 0 ? c[i][k] : std::max(bmax[k], c[i][k]);
          }
        }
        const double* const corners[4] = { c[0], c[1], c[2], c[3] };
        // The lattice positions of the tet's box are mostly outside the tet (boundary-mesh tets
        // are long and thin): per row (i, j), only the z-range where the tet's barycentric
        // coordinates can be >= -1e-9 is scanned, widened by a tolerance of 1e-6 and one position
        // each way; every position scanned still takes the test below, so the points are the
        // same. Off for flat tets (the coordinates' rounding grows as 1/volume) and with jitter
        // (a jittered point leaves its row).
        double extent = 0, scale = 0;
        for (int k = 0; k < 3; ++k)
        {
          extent = std::max(extent, bmax[k] - bmin[k]);
          scale = std::max({ scale, std::fabs(bmin[k]), std::fabs(bmax[k]) });
        }
        const double u[3] = { c[1][0] - c[0][0], c[1][1] - c[0][1], c[1][2] - c[0][2] };
        const double v[3] = { c[2][0] - c[0][0], c[2][1] - c[0][1], c[2][2] - c[0][2] };
        const double w[3] = { c[3][0] - c[0][0], c[3][1] - c[0][1], c[3][2] - c[0][2] };
        const double vw[3] = {
          v[1] * w[2] - v[2] * w[1], v[2] * w[0] - v[0] * w[2], v[0] * w[1] - v[1] * w[0]
        };
        const double det = u[0] * vw[0] + u[1] * vw[1] + u[2] * vw[2];
        const double volume6 = std::fabs(det);
        // The coordinates' rounding, ~1e-14 (scale + extent) extent^2 / volume6, stays below
        // 1e-8, far within the tolerance.
        const bool pruneRows = jitter == 0 && std::isfinite(volume6) &&
          volume6 > 1e-6 * (scale + extent) * extent * extent;
        // The coordinates' gradients (the rows of the inverse of [u v w], coordinate 0 the
        // rest): the same for every level and sub-lattice of the tet.
        double gradient[4][3] = {};
        // Without the rows' coordinates (flat tets: boundary slivers), the slab between the
        // plane of face 0 (corners 1, 2, 3) and corner 0 rejects most positions of the box
        // before the exact test: torus.vtp at h = 0.0638 took that test at 52k positions
        // outside such tets. Widened far beyond the exact test's margin (1e-9 of a height) and
        // the rounding: it rejects only positions outside the tet (the test's coordinates,
        // rounded with the error of a near-degenerate tet, might have taken some of them).
        double slabNormal[3] = { 0, 0, 0 }, slabLo = 0, slabHi = 0;
        bool slab = false;
        if (pruneRows)
        {
          const double wu[3] = {
            w[1] * u[2] - w[2] * u[1], w[2] * u[0] - w[0] * u[2], w[0] * u[1] - w[1] * u[0]
          };
          const double uv[3] = {
            u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]
          };
          for (int k = 0; k < 3; ++k)
          {
            gradient[1][k] = vw[k] / det;
            gradient[2][k] = wu[k] / det;
            gradient[3][k] = uv[k] / det;
            gradient[0][k] = -(gradient[1][k] + gradient[2][k] + gradient[3][k]);
          }
        }
        else
        {
          const double e1[3] = { c[2][0] - c[1][0], c[2][1] - c[1][1], c[2][2] - c[1][2] };
          const double e2[3] = { c[3][0] - c[1][0], c[3][1] - c[1][1], c[3][2] - c[1][2] };
          const double n[3] = { e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0] };
          const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
          if (length > 0 && std::isfinite(length))
          {
            for (int k = 0; k < 3; ++k)
              slabNormal[k] = n[k] / length;
            auto along = [&](const double* x)
            { return slabNormal[0] * x[0] + slabNormal[1] * x[1] + slabNormal[2] * x[2]; };
            const double face = along(c[1]), apex = along(c[0]);
            const double margin = 1e-6 * (scale + extent);
            slabLo = std::min(face, apex) - margin;
            slabHi = std::max(face, apex) + margin;
            slab = std::isfinite(slabLo) && std::isfinite(slabHi);
          }
        }
        // The barycentric coordinates are affine in the lattice indices: those of the box's
        // first position and their steps along i, j and k (the spacing times the gradients),
        // per level and sub-lattice, give every row's ends with a few multiplications instead
        // of two barycentric evaluations (torus.vtp at h = 0.0638 scans 214k rows for 12k
        // points: candidates 37 -> 34 ms). Both from the gradients: four barycentric
        // evaluations per level and sub-lattice took 3.4% more of knot1.off's instructions at
        // h = 0.0309. Rounding moves them by far less than the tolerance below (pruneRows:
        // well shaped), and every position scanned still takes the exact test.
        // The tolerance of the rows' affine coordinates, far above their rounding (~1e-8
        // here) and the exact test's margin (1e-9) below.
        constexpr double kRowTolerance = 1e-6;
        struct RowCoordinates
        {
          std::int64_t i0, j0, k0;
          double base[4], di[4], dj[4], dk[4];
          bool finite;
        };
        auto rowCoordinates =
          [&](double shift, double a, const double* origin, const std::int64_t* first)
        {
          RowCoordinates r{};
          r.i0 = first[0];
          r.j0 = first[1];
          r.k0 = first[2];
          const double p[3] = { origin[0] + (r.i0 + shift) * a,
            origin[1] + (r.j0 + shift) * a,
            origin[2] + (r.k0 + shift) * a };
          const double d[3] = { p[0] - corners[0][0], p[1] - corners[0][1], p[2] - corners[0][2] };
          r.finite = true;
          for (int c = 0; c < 4 && r.finite; ++c)
          {
            r.base[c] = (c == 0 ? 1.0 : 0.0) + gradient[c][0] * d[0] + gradient[c][1] * d[1] +
              gradient[c][2] * d[2];
            r.di[c] = a * gradient[c][0];
            r.dj[c] = a * gradient[c][1];
            r.dk[c] = a * gradient[c][2];
            r.finite = std::isfinite(r.base[c]) && std::isfinite(r.di[c]) &&
              std::isfinite(r.dj[c]) && std::isfinite(r.dk[c]);
          }
          return r;
        };
        // Positions [rowFirst, rowLast] of row (i, j) that may be in the tet; false: none.
        auto rowRange = [&](const RowCoordinates& r,
                          std::int64_t i,
                          std::int64_t j,
                          std::int64_t from,
                          std::int64_t to,
                          std::int64_t& rowFirst,
                          std::int64_t& rowLast)
        {
          constexpr double kTolerance = kRowTolerance;
          if (!r.finite)
            return true; // scan the whole row
          const double si = static_cast<double>(i - r.i0), sj = static_cast<double>(j - r.j0);
          const double s0 = static_cast<double>(from - r.k0), s1 = static_cast<double>(to - r.k0);
          // b_k is affine along the row: b_k(u) = b0 + u (b1 - b0), u in [0, 1] from `from` to
          // `to`.
          double u0 = 0, u1 = 1;
          for (int k = 0; k < 4; ++k)
          {
            const double b0 = r.base[k] + si * r.di[k] + sj * r.dj[k] + s0 * r.dk[k];
            const double b1 = r.base[k] + si * r.di[k] + sj * r.dj[k] + s1 * r.dk[k];
            const double slope = b1 - b0;
            if (slope > 0)
              u0 = std::max(u0, (-kTolerance - b0) / slope);
            else if (slope < 0)
              u1 = std::min(u1, (-kTolerance - b0) / slope);
            else if (b0 < -kTolerance)
              return false;
          }
          if (!(u0 <= u1))
            return false;
          const double span = static_cast<double>(to - from);
          rowFirst = std::max(from, from + static_cast<std::int64_t>(std::floor(u0 * span)) - 1);
          rowLast = std::min(to, from + static_cast<std::int64_t>(std::ceil(u1 * span)) + 1);
          return true;
        };
        const int levelLo = background ? 0 : levelOfSize(hlo);
        const int levelHi = background ? 0 : levelOfSize(hhi);
        for (int level = levelLo; level <= levelHi; ++level)
        {
          const LevelGeometry geometry = levelGeometry(level);
          const double a = geometry.a;
          const double* const origin = geometry.origin;
          for (int sub = 0; sub < 2; ++sub)
          {
            const double shift = sub ? 0.5 : 0.0;
            double from[3], to[3];
            double count[3];
            bool keyable = true;
            for (int k = 0; k < 3; ++k)
            {
              from[k] = std::ceil((bmin[k] - origin[k]) / a - shift);
              to[k] = std::floor((bmax[k] - origin[k]) / a - shift);
              keyable = keyable && to[k] < kMaxLatticeIndex; // false for NaN too
              count[k] = std::max(to[k] - from[k] + 1, 0.0);
            }
            if (!keyable)
              continue;
            // The least this box costs: its rows when they are pruned, else all its positions.
            const double rows = count[0] * count[1];
            scan.peak = std::max(scan.peak, candidates + (pruneRows ? rows : rows * count[2]));
            if (candidates + (pruneRows ? rows : rows * count[2]) > maxCandidates)
            {
              candidates = maxCandidates + 1;
              break;
            }
            // Only now, in range (from >= -1, as bmin >= lo), convert to integers.
            std::int64_t first[3], last[3];
            for (int k = 0; k < 3; ++k)
            {
              first[k] = static_cast<std::int64_t>(from[k]);
              last[k] = static_cast<std::int64_t>(to[k]);
            }
            const RowCoordinates rowCoords =
              pruneRows ? rowCoordinates(shift, a, origin, first) : RowCoordinates{};
            for (std::int64_t i = first[0]; i <= last[0] && candidates <= maxCandidates; ++i)
              for (std::int64_t j = first[1]; j <= last[1]; ++j)
              {
                std::int64_t kFirst = first[2], kLast = last[2];
                candidates += 1;
                if (pruneRows && !rowRange(rowCoords, i, j, first[2], last[2], kFirst, kLast))
                  continue;
                candidates += static_cast<double>(std::max<std::int64_t>(kLast - kFirst + 1, 0));
                // The row's affine coordinates (as rowRange has them) reject the positions
                // farther outside than its tolerance before the exact test: the row's ends
                // are widened by one position each way, and most of those are outside
                // (fandisk.off at h: 334k positions tested, 55k inside).
                const bool affine = pruneRows && rowCoords.finite;
                double rowBase[4] = { 0, 0, 0, 0 };
                if (affine)
                  for (int c = 0; c < 4; ++c)
                    rowBase[c] = rowCoords.base[c] +
                      static_cast<double>(i - rowCoords.i0) * rowCoords.di[c] +
                      static_cast<double>(j - rowCoords.j0) * rowCoords.dj[c];
                for (std::int64_t k = kFirst; k <= kLast; ++k)
                {
                  if (affine)
                  {
                    const double sk = static_cast<double>(k - rowCoords.k0);
                    bool outside = false;
                    for (int c = 0; c < 4; ++c)
                      outside = outside || rowBase[c] + sk * rowCoords.dk[c] < -kRowTolerance;
                    if (outside)
                      continue;
                  }
                  const std::uint64_t key = (static_cast<std::uint64_t>(level & 63) << 58) |
                    (static_cast<std::uint64_t>(sub) << 57) |
                    ((static_cast<std::uint64_t>(i) & 0x7FFFF) << 38) |
                    ((static_cast<std::uint64_t>(j) & 0x7FFFF) << 19) |
                    (static_cast<std::uint64_t>(k) & 0x7FFFF);
                  // A deterministic shift of up to +-latticeJitter/2 a per coordinate, hashed from
                  // the key (see the option).
                  double p[3] = { origin[0] + (i + shift) * a,
                    origin[1] + (j + shift) * a,
                    origin[2] + (k + shift) * a };
                  if (jitter > 0)
                  {
                    std::uint64_t x = key * 0x9E3779B97F4A7C15ULL;
                    for (int d = 0; d < 3; ++d)
                    {
                      x ^= x >> 29;
                      x *= 0xBF58476D1CE4E5B9ULL;
                      x ^= x >> 32;
                      p[d] += jitter * a * ((x >> 11) * (1.0 / 9007199254740992.0) - 0.5);
                    }
                  }
                  if (slab)
                  {
                    const double along =
                      slabNormal[0] * p[0] + slabNormal[1] * p[1] + slabNormal[2] * p[2];
                    if (along < slabLo || along > slabHi)
                      continue;
                  }
                  // Closed, with a margin: a point on a face shared by two tets is found from both
                  // (the key removes the duplicate), never from neither through rounding.
                  double b[4];
                  if (!barycentricCoordinates(p, corners, b) || b[0] < -1e-9 || b[1] < -1e-9 ||
                    b[2] < -1e-9 || b[3] < -1e-9)
                    continue;
                  double hp;
                  if (background)
                  {
                    hp = background(p);
                    if (!(hp > 0) || !std::isfinite(hp))
                      continue;
                    hp = boundToSurface(p, scaleAndClampSize(hp, sizeOptions), regionCap(t));
                    // One lattice only with a background field: where it matches.
                    if (std::fabs(std::log(hp / a * options.latticeSpacing)) > 0.5 * logRatio)
                      continue;
                  }
                  else
                  {
                    hp = interpolateSizeWithCoordinates(b, hc, sizeOptions.interpolationPower);
                    if (sizeOptions.minSize > 0)
                      hp = std::max(hp, sizeOptions.minSize);
                    if (sizeOptions.maxSize > 0)
                      hp = std::min(hp, sizeOptions.maxSize);
                    hp = boundToSurface(p, hp, regionCap(t));
                    if (levelOfSize(hp) != level)
                      continue;
                  }
                  scan.keys.push_back(key);
                  scan.points.push_back({ { p[0], p[1], p[2] },
                    hp,
                    t,
                    { mesh.vertex(t, 0),
                      mesh.vertex(t, 1),
                      mesh.vertex(t, 2),
                      mesh.vertex(t, 3) } });
                }
              }
          }
        }
      }
      scan.peak = std::max(scan.peak, candidates);
    };
    // The two halves of the tets side by side. The scan of all tets stops where its counter
    // meets the work bound: inside the first half when the first half's scan met it (then
    // that scan is the result), else the second half's part is what the second half gives
    // with the counter starting at the first half's total, rescanned when that bound is met
    // (or the second half stopped early: its counter and the first's passed the bound, so it
    // is met). Which is used depends on the counters' final values only, not on timing.
    // One scan with a background field (a callback that may not be thread-safe). Halves from
    // 256 tets, not 4096: a few boundary-mesh tets span the domain, so small boundary meshes
    // scan long (torus.vtp at h = 0.0638: 3793 tets, 23-26 -> 14 ms; icosphere at h/2, 1934
    // tets: 14-19 -> 9-12 ms; 2026-12-03).
    LatticeScan all;
    constexpr TetId kMinHalves = 256;
    if (!background && initialTets >= kMinHalves)
    {
      LatticeScan half[2];
      const TetId middle = initialTets / 2;
      std::atomic<double> firstCount{ 0 };
      runPair(wantTwoThreads(0),
        [&](int k)
        {
          if (k == 0)
            scanTets(0, middle, half[0], &firstCount);
          else
            scanTets(middle, initialTets, half[1], nullptr, &firstCount);
        });
      all = std::move(half[0]);
      if (all.peak <= maxCandidates)
      {
        if (all.candidates + half[1].peak > maxCandidates)
        {
          half[1] = LatticeScan{};
          half[1].candidates = all.candidates;
          scanTets(middle, initialTets, half[1]);
        }
        all.points.insert(all.points.end(), half[1].points.begin(), half[1].points.end());
        all.keys.insert(all.keys.end(), half[1].keys.begin(), half[1].keys.end());
      }
    }
    else
      scanTets(0, initialTets, all);
    for (std::size_t i = 0; i < all.points.size(); ++i)
      if (taken.insert(all.keys[i]))
        points.push_back(all.points[i]);
    result.latticeCandidateSeconds = lap();
    // Insertion order: BRIO rounds (HilbertSort.h), not one Hilbert sweep. A sweep fills the
    // domain front by front, and a point on the front conflicts with every not yet refined tet
    // whose circumsphere reaches it: boundary-mesh tets span the domain, and where the surface
    // points are (nearly) co-spherical (uv_sphere.vtp: 9802 points on one sphere) their
    // circumspheres all are that sphere, so cavities held thousands of tets (6500 on average
    // over uv_sphere's first 8192 points) and the prefill took 200 s. Random rounds refine the
    // whole domain coarse to fine, as the edge splitting's longest-first rounds do.
    std::vector<double> latticeCoords;
    latticeCoords.reserve(3 * points.size());
    for (const LatticePoint& q : points)
      latticeCoords.insert(latticeCoords.end(), q.p, q.p + 3);
    std::vector<std::size_t> roundStarts;
    const std::vector<VertexId> insertionOrder = brioOrder(
      latticeCoords.data(), static_cast<VertexId>(points.size()), 0x5eed5eedULL, &roundStarts);
    std::vector<TetId> latticeStart(points.size(), -1); // see insertInHalves
    // The initial tets are deleted as points go in: remember their regions.
    std::vector<std::int32_t> initialRegion(region.begin(), region.begin() + initialTets);
    TetId hint = -1;
    bool stop = false, aborted = false;
    auto reportProgress = [&](double inserted)
    {
      const double fraction =
        std::min(0.99, inserted / std::max(1.0, result.estimatedPoints - initialCount));
      return !progress || progress(fraction);
    };
    // One point of insertionOrder, in order (the rounds' small ones, and what the halves left).
    auto insertInOrder = [&](std::size_t position)
    {
      const LatticePoint& q = points[static_cast<std::size_t>(insertionOrder[position])];
      if (result.insertedPoints >= budget)
      {
        result.budgetReached = true;
        stop = true;
        return;
      }
      // Walk from the last insertion (close: each round is Hilbert-sorted), else from the corners
      // of the initial tet that contained q (the segment from a corner to q lies in that tet, so
      // inside the domain even when it is not convex); the exhaustive search last.
      // The point's size is known, so the proximity tests go first: most refused lattice
      // points are refused there (fine cube: 29k next to the faces for 40k inserted), and
      // then need no walk. The same points go in: neither test depends on the container.
      if (refused(q.p, q.h, options.latticeBoundaryDistance))
        return;
      TetId container = walkToPoint(mesh, q.p, hint);
      for (int i = 0; i < 4 && container < 0; ++i)
        container = walkToPoint(mesh, q.p, vertexTet[q.corner[i]]);
      if (container < 0)
        container = locatePoint(mesh, q.p, q.tet);
      if (container < 0 || region[container] != initialRegion[q.tet])
        return;
      const TetId made =
        tryInsert(q.p, container, q.h, initialRegion[q.tet], options.latticeBoundaryDistance, true);
      if (made < 0)
        return;
      hint = made;
      ++result.insertedPoints;
      ++result.latticePoints;
      if ((result.insertedPoints & 1023) == 0 && !reportProgress(result.insertedPoints))
        stop = aborted = true;
    };

    // Large rounds go in two halves of space side by side (HalvesPhase above): `items`
    // (positions in insertionOrder, increasing), and what they leave goes to `rest`. False,
    // with `rest` to be ignored, when one side would have none.
    auto insertInHalves = [&](const std::vector<std::size_t>& items, std::vector<std::size_t>& rest)
    {
      auto pointAt = [&](std::size_t i) -> const LatticePoint&
      { return points[static_cast<std::size_t>(insertionOrder[i])]; };
      int axis = 0;
      double split = 0;
      medianSplit(
        items.size(), [&](std::size_t i) { return pointAt(items[i]).p; }, axis, split);
      double hmax = 0;
      for (std::size_t i : items)
        hmax = std::max(hmax, pointAt(i).h);
      const double margin = checkProximity ? proximityRatio * hmax * (1 + 1e-6) : 0.0;
      HalvesPhase phase;
      for (std::size_t i : items)
      {
        const double c = pointAt(i).p[axis];
        if (!(std::fabs(c - split) > margin))
          rest.push_back(i);
        else
          phase.side[c < split ? 0 : 1].items.push_back(i);
      }
      // Each side starts from the tet holding its first point: that tet has a vertex of the
      // side (the point is strictly inside the side's half), so it is never the other's alone.
      for (HalfState& me : phase.side)
      {
        if (me.items.empty())
          return false;
        const LatticePoint& q = pointAt(me.items[0]);
        me.hint = walkToPoint(mesh, q.p, hint);
        for (int i = 0; i < 4 && me.hint < 0; ++i)
          me.hint = walkToPoint(mesh, q.p, vertexTet[q.corner[i]]);
        if (me.hint < 0)
          me.hint = locatePoint(mesh, q.p, q.tet);
        if (me.hint < 0)
          return false;
      }
      beginHalves(phase, axis, split);
      // A second start for each point's walk, for when the walk from the side's last point
      // meets the domain's boundary (a non-convex domain: on bunny00 that left 546k of 792k
      // points of the last round to the sequence after the halves): a tet at a corner of the
      // boundary-mesh tet that held the point, a corner of the point's side, chosen now (a
      // tet with a vertex of the side is changed by that side alone).
      for (int k = 0; k < 2; ++k)
        for (std::size_t item : phase.side[k].items)
        {
          const LatticePoint& q = pointAt(item);
          TetId& start = latticeStart[static_cast<std::size_t>(insertionOrder[item])];
          start = -1;
          for (int i = 0; i < 4 && start < 0; ++i)
            if (phase.halves->owns(k, q.corner[i]))
              start = vertexTet[q.corner[i]];
        }
      runHalves(phase,
        [&](int k, HalfState& me, std::size_t item)
        {
          const LatticePoint& q = pointAt(item);
          if (refusedOnSide(me, q.p, q.h, options.latticeBoundaryDistance))
            return;
          TetId container = phase.halves->locate(k, q.p, me.hint);
          const TetId start = latticeStart[static_cast<std::size_t>(insertionOrder[item])];
          if (container == -1 && start >= 0)
            container = phase.halves->locate(k, q.p, start);
          if (container < 0)
          {
            me.postponed.push_back(item);
            return;
          }
          if (region[container] != initialRegion[q.tet])
            return;
          if (insertOnSide(phase, k, q.p, q.h, container, initialRegion[q.tet]) ==
            InsertStatus::Postponed)
            me.postponed.push_back(item);
        });
      const VertexId inserted = endHalves(phase, rest);
      result.latticePoints += inserted;
      result.latticeHalvesPoints += inserted;
      hint = phase.side[1].hint;
      if (phase.abort)
        stop = aborted = true;
      return true;
    };

    // A large round in halves, then what it left (next to the split, postponed) in halves
    // again, across the first split when it is still large (as the kernel's BRIO rounds),
    // then the rest in order. "Large" is a quarter as many points the second time: a rest of
    // ~3000 (icosphere.vtp at h/2, the floor's sizes near the boundary widening the margin)
    // took as long in order as the 10k points of its halves.
    std::vector<std::size_t> items, rest, restOfRest;
    for (std::size_t r = 0; r < roundStarts.size() && !stop; ++r)
    {
      const std::size_t begin = roundStarts[r];
      const std::size_t end = r + 1 < roundStarts.size() ? roundStarts[r + 1] : points.size();
      items.resize(end - begin);
      std::iota(items.begin(), items.end(), begin);
      const bool halvesAllowed =
        result.insertedPoints + static_cast<double>(end - begin) < budget &&
        (options.latticeBoundaryDistance <= 0 || faces);
      for (int split = 0; split < 2 && !stop; ++split)
      {
        rest.clear();
        if (!(halvesAllowed &&
              items.size() >= (split == 0 ? minHalvesPoints : minHalvesPoints / 4) &&
              insertInHalves(items, rest)))
          break;
        items.swap(rest);
        result.latticeSecondSplits += split;
      }
      for (std::size_t i = 0; i < items.size() && !stop; ++i)
        insertInOrder(items[i]);
    }
    if (aborted)
      return finish(false, "refineInterior: aborted");
  }

  result.latticeInsertSeconds = lap();

  // Split points found outside the domain, per edge. An edge that lies in the boundary (the
  // other diagonal of a planar boundary quad, under a flat tet) has its split point rounded
  // outside, across a boundary face of the edge's shell. The domain never changes, so the
  // same point is outside for good: not walked to again in later rounds.
  std::unordered_map<std::uint64_t, std::array<double, 3>> outsideSplits;
  // The gradation after round 0 starts from the vertices inserted since the last one and
  // their neighbours: every other edge is an old one, already within the bound (insertion
  // only adds edges at the new vertex), so the sizes come out the same as from every vertex.
  VertexId gradedCount = 0;
  std::vector<VertexId> seeds, seedStamp;
  constexpr VertexId kMinVerticesForScanHalves = 16384;
  bool aborted = false;
  // One edge-splitting round's candidates in two halves (see HalvesPhase): a side takes the
  // edges with both ends on its side, the split point farther from the split than the margin,
  // and a size at most hmax (the margin's; a larger one is postponed).
  auto splitInHalves =
    [&](const std::vector<Candidate>& items, std::vector<std::size_t>& rest, int& insertedThisRound)
  {
    std::vector<std::array<double, 3>> at(items.size());
    for (std::size_t i = 0; i < items.size(); ++i)
      splitPoint(items[i].a, items[i].b, at[i].data());
    int axis = 0;
    double split = 0;
    medianSplit(
      items.size(), [&](std::size_t i) { return at[i].data(); }, axis, split);
    double hmax = 0;
    for (double hv : h)
      hmax = std::max(hmax, hv);
    const double margin = checkProximity ? proximityRatio * hmax * (1 + 1e-6) : 0.0;
    HalvesPhase phase;
    for (std::size_t i = 0; i < items.size(); ++i)
    {
      const int sideOfA = mesh.point(items[i].a)[axis] < split ? 0 : 1;
      const int sideOfB = mesh.point(items[i].b)[axis] < split ? 0 : 1;
      if (sideOfA != sideOfB || !(std::fabs(at[i][axis] - split) > margin))
        rest.push_back(i);
      else
        phase.side[sideOfA].items.push_back(i);
    }
    if (phase.side[0].items.empty() || phase.side[1].items.empty())
      return false;
    beginHalves(phase, axis, split);
    runHalves(phase,
      [&](int k, HalfState& me, std::size_t item)
      {
        const Candidate& c = items[item];
        const TetId t = findEdgeIn(c.a, c.b, c.tet, me.star, true);
        if (t < 0)
          return; // the edge is gone: a point inserted this round took its place
        const double* p = at[item].data();
        const std::uint64_t key = edgeKey(c.a, c.b);
        const auto shared = outsideSplits.find(key);
        if (shared != outsideSplits.end() && std::equal(p, p + 3, shared->second.begin()))
          return;
        const auto own = me.outside.find(key);
        if (own != me.outside.end() && std::equal(p, p + 3, own->second.begin()))
          return;
        const TetId container = phase.halves->locate(k, p, t);
        if (container == -1)
        {
          me.outside[key] = { p[0], p[1], p[2] };
          return;
        }
        if (container < 0)
        {
          me.postponed.push_back(item);
          return;
        }
        if (region[container] != region[t])
          return;
        const double hp = sizeAt(p, container, 0.5 * (h[c.a] + h[c.b]));
        if (!(hp <= hmax))
        {
          me.postponed.push_back(item);
          return;
        }
        if (refusedOnSide(me, p, hp, options.minBoundaryDistance))
          return;
        if (insertOnSide(phase, k, p, hp, container, region[t]) == InsertStatus::Postponed)
          me.postponed.push_back(item);
      });
    const VertexId inserted = endHalves(phase, rest);
    insertedThisRound += inserted;
    result.splitHalvesPoints += inserted;
    for (const HalfState& me : phase.side)
      for (const auto& [key, p] : me.outside)
        outsideSplits[key] = p;
    if (phase.abort)
      aborted = true;
    return true;
  };
  // Edge (a, b), a < b, as a candidate if it is too long and not constrained; tet: a tet of
  // the edge (the smallest id, as the graph lists it).
  auto considerEdge = [&](VertexId a, VertexId b, TetId tet, std::vector<Candidate>& out)
  {
    if (a < initialCount && b < initialCount && onConstraint[a] && onConstraint[b] &&
      constrainedEdges.find(edgeKey(a, b)))
      return;
    const double length = distance(mesh.point(a), mesh.point(b)) * 0.5 * (1 / h[a] + 1 / h[b]);
    if (!(length > options.maxEdgeRatio))
      return;
    double p[3];
    splitPoint(a, b, p);
    const std::uint64_t lengthClass =
      static_cast<std::uint64_t>(std::min(15.0, std::log2(length / options.maxEdgeRatio)));
    out.push_back({ ((15 - lengthClass) << 48) | hilbertKey(p), a, b, tet });
  };

  // Rounds from stars (RefinementOptions::starRoundRatio). An edge too long at a round's
  // start is one of the last round's candidates that is still there (lengths and sizes of old
  // vertices do not change but by the gradation), or has an end inserted since (insertion only
  // adds edges at the new vertex), or one whose size the gradation has just lowered: the stars
  // of those vertices and the last candidates give the same edges as the graph.
  std::vector<Candidate> previous; // the last round's candidates
  VertexId scannedCount = 0;       // the vertices at the last round's start
  bool starsFailed = false;        // a star could not be listed: the graph from then on
  std::vector<std::pair<VertexId, TetId>> starEdges; // (neighbour, smallest tet of the edge)
  std::vector<std::int32_t> starFirst, starSize;
  std::vector<std::uint32_t> starStamp;
  std::uint32_t starEpoch = 0;
  std::vector<TetId> walked;
  // The neighbours of v with their smallest tet, listed once per round; false when v's tet is
  // not known or its star misses some of its boundary faces.
  // v's whole star in `walked`; false when v's tet is not known or the star misses some of
  // v's boundary faces (it is one of several).
  auto walkWholeStar = [&](VertexId v) -> bool
  {
    const std::size_t i = static_cast<std::size_t>(v);
    const TetId t = vertexTet[i];
    if (t < 0 || t >= mesh.tetCapacity() || mesh.isDeleted(t) || !tetHas(mesh, t, v))
      return false;
    starOf(mesh, t, v, walked);
    if (v >= initialCount)
      return true; // an inserted point: inside, its star a whole ball
    std::int32_t boundaryFaces = 0;
    for (TetId u : walked)
      for (int k = 0; k < 4; ++k)
        boundaryFaces += mesh.vertex(u, k) != v && mesh.neighbor(u, k) == kNoNeighbor;
    return boundaryFaces == boundaryFacesAt[i];
  };
  auto listStar = [&](VertexId v) -> bool
  {
    const std::size_t i = static_cast<std::size_t>(v);
    if (starStamp[i] == starEpoch)
      return true;
    if (!walkWholeStar(v))
      return false;
    const std::int32_t first = static_cast<std::int32_t>(starEdges.size());
    for (TetId u : walked)
      for (int k = 0; k < 4; ++k)
      {
        const VertexId w = mesh.vertex(u, k);
        if (w == v)
          continue;
        auto known = std::find_if(starEdges.begin() + first,
          starEdges.end(),
          [w](const std::pair<VertexId, TetId>& e) { return e.first == w; });
        if (known == starEdges.end())
          starEdges.emplace_back(w, u);
        else
          known->second = std::min(known->second, u);
      }
    starStamp[i] = starEpoch;
    starFirst[i] = first;
    starSize[i] = static_cast<std::int32_t>(starEdges.size()) - first;
    return true;
  };
  // The gradation and the candidates of a round from stars; false (sizes unchanged, no
  // candidates) when a star could not be listed.
  std::vector<VertexId> lowered, changedVertices;
  std::vector<std::uint32_t> changedStamp;
  auto roundFromStars = [&](VertexId count) -> bool
  {
    ++starEpoch;
    starEdges.clear();
    starStamp.resize(static_cast<std::size_t>(count), 0);
    starFirst.resize(static_cast<std::size_t>(count));
    starSize.resize(static_cast<std::size_t>(count));
    changedStamp.resize(static_cast<std::size_t>(count), 0);
    changedVertices.clear();
    auto markChanged = [&](VertexId v)
    {
      if (changedStamp[static_cast<std::size_t>(v)] != starEpoch)
      {
        changedStamp[static_cast<std::size_t>(v)] = starEpoch;
        changedVertices.push_back(v);
      }
    };
    for (VertexId v = scannedCount; v < count; ++v)
      markChanged(v);
    if (sizeOptions.gradation > 1)
    {
      // The graph's rounds seed the vertices since the last gradation and their neighbours;
      // here the new vertices alone, which limitGradationFrom first lowers from their
      // neighbours: an old neighbour (its edges to old vertices within the bound) can lower
      // only them. The same sizes. Their stars are those the candidates need.
      seeds.clear();
      for (VertexId v = gradedCount; v < count; ++v)
        seeds.push_back(v);
      const std::int64_t graded = limitGradationFrom(
        mesh.coords.data(),
        count,
        sizeOptions.gradation,
        h.data(),
        seeds,
        [&](VertexId v, std::vector<VertexId>& list)
        {
          if (!listStar(v))
            return false;
          list.clear();
          for (std::int32_t k = 0; k < starSize[v]; ++k)
            list.push_back(starEdges[static_cast<std::size_t>(starFirst[v] + k)].first);
          return true;
        },
        lowered);
      if (graded < 0)
        return false;
      gradedCount = count;
      for (VertexId v : lowered)
        markChanged(v);
    }
    candidates.clear();
    for (VertexId v : changedVertices)
    {
      if (!listStar(v))
      {
        candidates.clear();
        return false; // the sizes stay graded: the graph's round grades nothing more
      }
      for (std::int32_t k = 0; k < starSize[v]; ++k)
      {
        const auto [w, tet] = starEdges[static_cast<std::size_t>(starFirst[v] + k)];
        // Once per edge: from its smaller end when both ends changed.
        if (changedStamp[static_cast<std::size_t>(w)] == starEpoch && w < v)
          continue;
        considerEdge(std::min(v, w), std::max(v, w), tet, candidates);
      }
    }
    for (const Candidate& c : previous)
    {
      if (changedStamp[static_cast<std::size_t>(c.a)] == starEpoch ||
        changedStamp[static_cast<std::size_t>(c.b)] == starEpoch)
        continue; // listed above if still there
      // The smallest tet of a's star with b, if any (most of these edges were split): not
      // listed, as most of these stars are read for this one edge.
      if (!walkWholeStar(c.a))
      {
        candidates.clear();
        return false; // as above
      }
      TetId smallest = -1;
      for (TetId u : walked)
        if (tetHas(mesh, u, c.b) && (smallest < 0 || u < smallest))
          smallest = u;
      if (smallest >= 0)
        considerEdge(c.a, c.b, smallest, candidates);
    }
    return true;
  };

  for (int round = 0; round < options.maxRounds; ++round)
  {
    const VertexId roundCount = mesh.vertexCount();
    bool fromStars = false;
    if (round > 0 && !starsFailed && options.starRoundRatio > 0 &&
      options.starRoundRatio *
          static_cast<double>(
            previous.size() + 2 * static_cast<std::size_t>(roundCount - scannedCount)) <
        static_cast<double>(mesh.liveTetCount()))
    {
      // A failure leaves no candidates, and the sizes as they were or graded: the graph's
      // round below then does the rest, to the same sizes.
      fromStars = roundFromStars(roundCount);
      starsFailed = !fromStars;
      result.starRounds += fromStars ? 1 : 0;
      result.starsRefused = starsFailed;
    }
    if (!fromStars && (round > 0 || result.latticePoints > 0))
      graph.build(mesh, wantTwoThreads(0));
    if (!fromStars && sizeOptions.gradation > 1)
    {
      const VertexId count = mesh.vertexCount();
      seeds.clear();
      if (round > 0)
      {
        seedStamp.resize(static_cast<std::size_t>(count), -1);
        for (VertexId v = gradedCount; v < count; ++v)
        {
          seedStamp[v] = v;
          seeds.push_back(v);
        }
        for (VertexId v = gradedCount; v < count; ++v)
          for (std::int32_t k = graph.offsets[v]; k < graph.offsets[v + 1]; ++k)
          {
            const VertexId w = graph.targets[k];
            if (w < gradedCount && seedStamp[w] != count)
            {
              seedStamp[w] = count;
              seeds.push_back(w);
            }
          }
      }
      limitGradation(mesh.coords.data(),
        count,
        graph.offsets.data(),
        graph.targets.data(),
        sizeOptions.gradation,
        h.data(),
        round > 0 ? seeds.data() : nullptr,
        static_cast<std::int32_t>(seeds.size()));
      gradedCount = count;
    }
    // The edges too long, from each half of the vertices (by their edges) side by side on
    // large meshes; in vertex order, then sorted: the same on one thread or two.
    const VertexId nv = fromStars ? 0 : mesh.vertexCount();
    const bool scanHalves = nv >= kMinVerticesForScanHalves;
    const VertexId middle = scanHalves
      ? static_cast<VertexId>(std::lower_bound(graph.offsets.begin(),
                                graph.offsets.end(),
                                graph.offsets[static_cast<std::size_t>(nv)] / 2) -
          graph.offsets.begin())
      : nv;
    std::vector<Candidate> secondHalf;
    if (!fromStars)
      candidates.clear();
    splitAt(scanHalves && wantTwoThreads(0),
      middle,
      nv,
      [&](int half, VertexId first, VertexId last)
      {
        std::vector<Candidate>& out = half == 0 ? candidates : secondHalf;
        for (VertexId a = first; a < last; ++a)
        {
          for (std::int32_t k = graph.offsets[a]; k < graph.offsets[a + 1]; ++k)
          {
            const VertexId b = graph.targets[k];
            if (b > a)
              considerEdge(a, b, graph.tetOf[k], out);
          }
        }
      });
    candidates.insert(candidates.end(), secondHalf.begin(), secondHalf.end());
    if (candidates.empty())
      break;
    result.rounds = round + 1;
    std::sort(candidates.begin(),
      candidates.end(),
      [](const Candidate& x, const Candidate& y)
      { return x.order != y.order ? x.order < y.order : (x.a != y.a ? x.a < y.a : x.b < y.b); });
    previous = candidates;
    scannedCount = roundCount;
    int insertedThisRound = 0;
    // Large rounds: in two halves of space first (HalvesPhase above), for the candidates
    // whose edge has both ends on one side; the others, and what the sides postponed, in
    // order afterwards. Not with a background field: a callback that may not be thread-safe.
    std::vector<std::size_t> rest;
    if (!(candidates.size() >= minHalvesPoints && !background &&
          result.insertedPoints + static_cast<double>(candidates.size()) < budget &&
          (options.minBoundaryDistance <= 0 || faces) &&
          splitInHalves(candidates, rest, insertedThisRound)))
    {
      rest.resize(candidates.size());
      for (std::size_t i = 0; i < rest.size(); ++i)
        rest[i] = i;
    }
    if (aborted)
      return finish(false, "refineInterior: aborted");
    for (std::size_t index : rest)
    {
      const Candidate& c = candidates[index];
      if (result.insertedPoints >= budget)
      {
        result.budgetReached = true;
        break;
      }
      const TetId t = findEdge(c.a, c.b, c.tet);
      if (t < 0)
        continue; // the edge is gone: a point inserted this round took its place
      double p[3];
      splitPoint(c.a, c.b, p);
      const auto outside = outsideSplits.find(edgeKey(c.a, c.b));
      if (outside != outsideSplits.end() && std::equal(p, p + 3, outside->second.begin()))
        continue;
      // The point is within rounding of edge (a,b), so the walk from a tet of the edge ends
      // in the edge's shell, or on the hull right next to it: then the point is outside the
      // domain. (locatePoint's scan of every tet after such a walk found no tet for any of the
      // 78 such split points of torus.vtp at h = 0.064, and took a third of the refinement.)
      const TetId container = walkToPoint(mesh, p, t);
      if (container < 0)
      {
        outsideSplits[edgeKey(c.a, c.b)] = { p[0], p[1], p[2] };
        continue;
      }
      if (region[container] != region[t])
        continue;
      const double hp = sizeAt(p, container, 0.5 * (h[c.a] + h[c.b]));
      if (tryInsert(p, container, hp, region[t], options.minBoundaryDistance) < 0)
        continue;
      ++result.insertedPoints;
      ++insertedThisRound;
      if (progress && (result.insertedPoints & 1023) == 0)
      {
        const double fraction = std::min(
          0.99, result.insertedPoints / std::max(1.0, result.estimatedPoints - initialCount));
        if (!progress(fraction))
          return finish(false, "refineInterior: aborted");
      }
    }
    // Late in the refinement, a round that splits under 10% of its long edges leaves what its
    // successor would find nearly unchanged: the rest were refused (too close to a vertex or
    // the boundary) and stay so, and the next round (a graph rebuild and the same refusals)
    // splits under 1% (fandisk.off at h = 0.0103: 8138 of 47448 long edges, 1374 of 21723,
    // then 116 of 16780 points for 0.09 s, 4% of the run). Late: the round also adds under 1%
    // of the points so far (early rounds on a coarse mesh split few edges and open the way for
    // many).
    const std::size_t few = static_cast<std::size_t>(insertedThisRound);
    if (insertedThisRound == 0 || result.budgetReached ||
      (10 * few < candidates.size() && 100 * few < static_cast<std::size_t>(result.insertedPoints)))
      break;
  }
  result.splitSeconds = lap();
  if (progress && !progress(1.0))
    return finish(false, "refineInterior: aborted");
  return finish(true, "");
}

} // namespace tetmesher
