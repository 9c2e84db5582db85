#include "SurfaceDiagnosis.h"

#include "Predicates.h"
#include "RadixSort.h"
#include "TriangleIntersection.h"
#include "UnusedPoints.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

namespace tetmesher
{

using predicates::orient2d;
using predicates::orient3d;

namespace
{

constexpr int kKindCount = static_cast<int>(SurfaceDefect::UnusedPointLeftOut) + 1;

// Order in which kinds are listed (records and summary).
constexpr SurfaceDefect kReportOrder[kKindCount] = { SurfaceDefect::Empty,
  SurfaceDefect::InvalidPointId,
  SurfaceDefect::NonFiniteCoordinate,
  SurfaceDefect::CoordinateOutOfRange,
  SurfaceDefect::OutlyingPoint,
  SurfaceDefect::DuplicatePoint,
  SurfaceDefect::DegenerateTriangle,
  SurfaceDefect::DuplicateTriangle,
  SurfaceDefect::OpenEdge,
  SurfaceDefect::NonManifoldEdge,
  SurfaceDefect::InconsistentOrientation,
  SurfaceDefect::SelfIntersection,
  SurfaceDefect::UnusedPoint,
  SurfaceDefect::UnusedPointLeftOut };

// Per-triangle state bits.
enum : std::uint8_t
{
  kBadIds = 1u << 0,     // an id out of range
  kRepeatedId = 1u << 1, // two equal ids
  kNonFinite = 1u << 2,  // uses a non-finite point
  kCollinear = 1u << 3,  // exactly zero area
  kDuplicate = 1u << 4,  // not the first triangle on its three ids
};
constexpr std::uint8_t kNoTopology = kBadIds | kRepeatedId | kDuplicate;
constexpr std::uint8_t kNoGeometry = kNoTopology | kNonFinite | kCollinear;

class UnionFind
{
public:
  explicit UnionFind(std::size_t n)
    : Parent(n)
  {
    std::iota(Parent.begin(), Parent.end(), 0);
  }
  std::size_t find(std::size_t x)
  {
    while (Parent[x] != x)
    {
      Parent[x] = Parent[Parent[x]];
      x = Parent[x];
    }
    return x;
  }
  void unite(std::size_t a, std::size_t b)
  {
    a = find(a);
    b = find(b);
    if (a != b)
      Parent[std::max(a, b)] = std::min(a, b);
  }

private:
  std::vector<std::size_t> Parent;
};

// One use of an undirected edge lo<hi by a triangle; forward when the triangle goes lo->hi.
struct EdgeUse
{
  std::int32_t lo, hi, tri;
  bool forward;
  std::int32_t opposite; // the triangle's third vertex
};

class Diagnoser
{
public:
  Diagnoser(const double* points,
    std::int32_t pointCount,
    const std::int32_t* triangles,
    std::int32_t triangleCount,
    const DiagnosisOptions& options)
    : Points(points)
    , PointCount(pointCount)
    , Tris(triangles)
    , TriCount(triangleCount)
    , Options(options)
  {
  }

  SurfaceDiagnosis run()
  {
    if (PointCount <= 0 || TriCount <= 0 || Points == nullptr || Tris == nullptr)
    {
      add(SurfaceDefect::Empty, {}, {});
      return finish();
    }
    State.assign(static_cast<std::size_t>(TriCount), 0);
    checkIds();
    checkPoints();
    checkTriangles();
    checkProportions();
    checkEdges();
    if (Options.checkSelfIntersections)
      checkIntersections();
    checkUnused();
    return finish();
  }

private:
  const double* pt(std::int32_t i) const { return Points + 3 * static_cast<std::size_t>(i); }
  const std::int32_t* tri(std::int32_t t) const { return Tris + 3 * static_cast<std::size_t>(t); }

  bool full(SurfaceDefect kind)
  {
    auto& list = Records[static_cast<int>(kind)];
    if (Options.maxRecordsPerKind != 0 && list.size() >= Options.maxRecordsPerKind)
    {
      Truncated = true;
      return true;
    }
    return false;
  }

  void add(SurfaceDefect kind,
    std::vector<std::int32_t> pointIds,
    std::vector<std::int32_t> triangleIds)
  {
    if (full(kind))
      return;
    Records[static_cast<int>(kind)].push_back(
      { kind, std::move(pointIds), std::move(triangleIds) });
  }

  SurfaceDiagnosis finish()
  {
    SurfaceDiagnosis result;
    result.truncated = Truncated;
    for (SurfaceDefect kind : kReportOrder)
    {
      auto& list = Records[static_cast<int>(kind)];
      result.defects.insert(result.defects.end(),
        std::make_move_iterator(list.begin()),
        std::make_move_iterator(list.end()));
    }
    return result;
  }

  void checkIds()
  {
    for (std::int32_t t = 0; t < TriCount; ++t)
    {
      const std::int32_t* v = tri(t);
      bool bad = false;
      for (int k = 0; k < 3; ++k)
        bad = bad || v[k] < 0 || v[k] >= PointCount;
      if (bad)
      {
        State[t] |= kBadIds;
        add(SurfaceDefect::InvalidPointId, { v[0], v[1], v[2] }, { t });
      }
    }
  }

  void checkPoints()
  {
    Finite.assign(static_cast<std::size_t>(PointCount), true);
    std::vector<std::int32_t> order;
    order.reserve(static_cast<std::size_t>(PointCount));
    for (std::int32_t i = 0; i < PointCount; ++i)
    {
      const double* p = pt(i);
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      {
        Finite[i] = false;
        add(SurfaceDefect::NonFiniteCoordinate, { i }, {});
      }
      else if (!predicates::inExactRange(p[0]) || !predicates::inExactRange(p[1]) ||
        !predicates::inExactRange(p[2]))
      {
        // Not decidable exactly: kept out of the geometric checks like a non-finite point.
        Finite[i] = false;
        add(SurfaceDefect::CoordinateOutOfRange, { i }, {});
      }
      else
        order.push_back(i);
    }
    LeftOut.assign(static_cast<std::size_t>(PointCount), 0);
    for (const LeftOutPoint& p : unusedPointsLeftOut(Points, PointCount, Tris, TriCount))
      LeftOut[static_cast<std::size_t>(p.point)] = 1;
    // Exactly equal coordinates (-0 == +0). Canonical id: the smallest id of the group.
    Canonical.resize(static_cast<std::size_t>(PointCount));
    std::iota(Canonical.begin(), Canonical.end(), 0);
    auto less = [this](std::int32_t a, std::int32_t b)
    {
      const double* p = pt(a);
      const double* q = pt(b);
      for (int k = 0; k < 3; ++k)
      {
        if (p[k] < q[k])
          return true;
        if (q[k] < p[k])
          return false;
      }
      return a < b;
    };
    std::sort(order.begin(), order.end(), less);
    auto equal = [this](std::int32_t a, std::int32_t b)
    {
      const double* p = pt(a);
      const double* q = pt(b);
      return p[0] == q[0] && p[1] == q[1] && p[2] == q[2];
    };
    for (std::size_t i = 0; i < order.size();)
    {
      std::size_t j = i + 1;
      while (j < order.size() && equal(order[i], order[j]))
        ++j;
      // Unused points that the mesh leaves out do not count (one point and its unused
      // copies are no defect).
      const auto kept = std::count_if(order.begin() + i,
        order.begin() + j,
        [&](std::int32_t id) { return !LeftOut[static_cast<std::size_t>(id)]; });
      if (kept > 1)
      {
        std::vector<std::int32_t> group(order.begin() + i, order.begin() + j);
        for (std::int32_t id : group)
          Canonical[id] = group.front();
        add(SurfaceDefect::DuplicatePoint, std::move(group), {});
      }
      i = j;
    }
  }

  // Points of usable triangles farther (per axis) from the median point than kMaxProportion
  // times the shortest edge. O(n): medians by nth_element.
  void checkProportions()
  {
    std::vector<char> used(static_cast<std::size_t>(PointCount), 0);
    double shortest = std::numeric_limits<double>::infinity();
    for (std::int32_t t = 0; t < TriCount; ++t)
    {
      if (State[t] & (kNoTopology | kNonFinite))
        continue;
      const std::int32_t* v = tri(t);
      for (int e = 0; e < 3; ++e)
      {
        used[v[e]] = 1;
        const double* p = pt(v[e]);
        const double* q = pt(v[(e + 1) % 3]);
        const double length =
          std::max({ std::abs(p[0] - q[0]), std::abs(p[1] - q[1]), std::abs(p[2] - q[2]) });
        if (length > 0)
          shortest = std::min(shortest, length);
      }
    }
    if (!(shortest < std::numeric_limits<double>::infinity()))
      return;
    std::vector<std::int32_t> ids;
    for (std::int32_t i = 0; i < PointCount; ++i)
    {
      if (used[i])
        ids.push_back(i);
    }
    double median[3];
    std::vector<double> values(ids.size());
    for (int k = 0; k < 3; ++k)
    {
      for (std::size_t i = 0; i < ids.size(); ++i)
        values[i] = pt(ids[i])[k];
      std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
      median[k] = values[values.size() / 2];
    }
    const double limit = kMaxProportion * shortest;
    for (std::int32_t i : ids)
    {
      const double* p = pt(i);
      if (std::abs(p[0] - median[0]) > limit || std::abs(p[1] - median[1]) > limit ||
        std::abs(p[2] - median[2]) > limit)
        add(SurfaceDefect::OutlyingPoint, { i }, {});
    }
  }

  void checkTriangles()
  {
    std::vector<std::pair<std::array<std::int32_t, 3>, std::int32_t>> keys;
    keys.reserve(static_cast<std::size_t>(TriCount));
    for (std::int32_t t = 0; t < TriCount; ++t)
    {
      if (State[t] & kBadIds)
        continue;
      const std::int32_t* v = tri(t);
      if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0])
      {
        State[t] |= kRepeatedId;
        add(SurfaceDefect::DegenerateTriangle, { v[0], v[1], v[2] }, { t });
        continue;
      }
      if (!Finite[v[0]] || !Finite[v[1]] || !Finite[v[2]])
        State[t] |= kNonFinite;
      else if (isTriangleDegenerate(pt(v[0]), pt(v[1]), pt(v[2])))
      {
        State[t] |= kCollinear;
        add(SurfaceDefect::DegenerateTriangle, { v[0], v[1], v[2] }, { t });
      }
      std::array<std::int32_t, 3> key = { v[0], v[1], v[2] };
      std::sort(key.begin(), key.end());
      keys.push_back({ key, t });
    }
    std::sort(keys.begin(), keys.end());
    for (std::size_t i = 0; i < keys.size();)
    {
      std::size_t j = i + 1;
      while (j < keys.size() && keys[j].first == keys[i].first)
        ++j;
      if (j - i > 1)
      {
        std::vector<std::int32_t> group;
        for (std::size_t k = i; k < j; ++k)
        {
          group.push_back(keys[k].second);
          if (k > i)
            State[keys[k].second] |= kDuplicate;
        }
        const auto& key = keys[i].first;
        add(SurfaceDefect::DuplicateTriangle, { key[0], key[1], key[2] }, std::move(group));
      }
      i = j;
    }
  }

  // Front side of triangle t is node 2t (the side its right-hand normal points to), back 2t+1.
  static std::size_t front(std::int32_t t) { return 2 * static_cast<std::size_t>(t); }
  static std::size_t back(std::int32_t t) { return 2 * static_cast<std::size_t>(t) + 1; }

  void checkEdges()
  {
    std::vector<EdgeUse> uses;
    uses.reserve(3 * static_cast<std::size_t>(TriCount));
    for (std::int32_t t = 0; t < TriCount; ++t)
    {
      if (State[t] & kNoTopology)
        continue;
      const std::int32_t* v = tri(t);
      for (int k = 0; k < 3; ++k)
      {
        const std::int32_t a = v[k], b = v[(k + 1) % 3], c = v[(k + 2) % 3];
        uses.push_back({ std::min(a, b), std::max(a, b), t, a < b, c });
      }
    }
    // By (lo, hi, tri): the uses were pushed in triangle order, and the radix sort is stable.
    {
      auto keyOf = [](const EdgeUse& u)
      {
        return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(u.lo)) << 32) |
          static_cast<std::uint32_t>(u.hi);
      };
      std::vector<EdgeUse> scratch;
      radixSortByKey(uses, scratch, keyOf, keyBitsOf(uses, keyOf));
    }

    // Sides of triangles joined through the space around each edge: a triangle whose two sides
    // end up in one class has the same region on both sides and bounds nothing.
    UnionFind sides(2 * static_cast<std::size_t>(TriCount));
    std::vector<std::pair<std::size_t, std::size_t>> junctions; // edges with 3+ triangles
    for (std::size_t i = 0; i < uses.size();)
    {
      std::size_t j = i + 1;
      while (j < uses.size() && uses[j].lo == uses[i].lo && uses[j].hi == uses[i].hi)
        ++j;
      const EdgeUse& e = uses[i];
      const std::size_t n = j - i;
      if (n == 1)
      {
        if (!Options.innerFacets)
          add(SurfaceDefect::OpenEdge, { e.lo, e.hi }, { e.tri });
        sides.unite(front(e.tri), back(e.tri));
      }
      else if (n == 2)
      {
        const EdgeUse& f = uses[i + 1];
        if (e.forward == f.forward)
        {
          add(SurfaceDefect::InconsistentOrientation, { e.lo, e.hi }, { e.tri, f.tri });
          sides.unite(front(e.tri), back(f.tri));
          sides.unite(back(e.tri), front(f.tri));
        }
        else
        {
          sides.unite(front(e.tri), front(f.tri));
          sides.unite(back(e.tri), back(f.tri));
        }
      }
      else
      {
        junctions.push_back({ i, j });
        joinAroundEdge(uses.data() + i, n, sides);
      }
      i = j;
    }

    for (const auto& range : junctions)
    {
      bool dangling = false;
      std::vector<std::int32_t> tris;
      for (std::size_t k = range.first; k < range.second; ++k)
      {
        const std::int32_t t = uses[k].tri;
        tris.push_back(t);
        dangling = dangling || sides.find(front(t)) == sides.find(back(t));
      }
      if (dangling && !Options.innerFacets)
        add(SurfaceDefect::NonManifoldEdge,
          { uses[range.first].lo, uses[range.first].hi },
          std::move(tris));
    }
  }

  // Sorts the n >= 3 triangles around edge (lo,hi) by angle (exactly) and joins the sides that
  // face each other across each wedge between consecutive triangles.
  void joinAroundEdge(const EdgeUse* e, std::size_t n, UnionFind& sides)
  {
    for (std::size_t k = 0; k < n; ++k)
    {
      if (State[e[k].tri] & kNoGeometry)
        return; // angles undecidable; the triangle's own defect is reported
    }
    std::vector<const double*> w(n);
    for (std::size_t k = 0; k < n; ++k)
      w[k] = pt(e[k].opposite);
    const std::vector<std::size_t> ring = sortAroundEdge(pt(e[0].lo), pt(e[0].hi), w);
    // A triangle traversing the edge lo->hi has its normal pointing counterclockwise.
    for (std::size_t k = 0; k < n; ++k)
    {
      const EdgeUse& a = e[ring[k]];
      const EdgeUse& b = e[ring[(k + 1) % n]];
      const std::size_t aCcw = a.forward ? front(a.tri) : back(a.tri);
      const std::size_t bCw = b.forward ? back(b.tri) : front(b.tri);
      sides.unite(aCcw, bCw);
    }
  }

  void checkIntersections()
  {
    // Candidate triangles and their boxes.
    std::vector<std::int32_t> cand;
    for (std::int32_t t = 0; t < TriCount; ++t)
    {
      if (!(State[t] & kNoGeometry))
        cand.push_back(t);
    }
    if (cand.size() < 2)
      return;
    const std::size_t m = cand.size();
    std::vector<double> box(6 * m);
    double lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL };
    double hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
    double meanExtent = 0;
    for (std::size_t i = 0; i < m; ++i)
    {
      const std::int32_t* v = tri(cand[i]);
      double* b = &box[6 * i];
      double ext = 0;
      for (int k = 0; k < 3; ++k)
      {
        b[k] = std::min({ pt(v[0])[k], pt(v[1])[k], pt(v[2])[k] });
        b[3 + k] = std::max({ pt(v[0])[k], pt(v[1])[k], pt(v[2])[k] });
        lo[k] = std::min(lo[k], b[k]);
        hi[k] = std::max(hi[k], b[3 + k]);
        ext = std::max(ext, b[3 + k] - b[k]);
      }
      meanExtent += ext / static_cast<double>(m);
    }
    // Cell size: about one mean triangle, bounded so that indices fit 21 bits per axis.
    double cell = meanExtent;
    for (int k = 0; k < 3; ++k)
      cell = std::max(cell, (hi[k] - lo[k]) / double(1 << 20));
    if (!(cell > 0) || !std::isfinite(cell))
      cell = 1;
    std::vector<std::uint32_t> range(6 * m);
    // Triangles whose box covers many cells (a few big faces among many small ones) stay out
    // of the grid and are tested against every box; when there are too many of them, the
    // cells grow instead.
    constexpr std::uint64_t kLargeCells = 64;
    const std::size_t maxLarge = 64 + m / 256;
    std::vector<std::uint32_t> large;
    std::uint64_t entryCount = 0;
    for (;;)
    {
      large.clear();
      entryCount = 0;
      for (std::size_t i = 0; i < m; ++i)
      {
        std::uint32_t* r = &range[6 * i];
        std::uint64_t cells = 1;
        for (int k = 0; k < 3; ++k)
        {
          r[k] = cellIndex(box[6 * i + k] - lo[k], cell);
          r[3 + k] = cellIndex(box[6 * i + 3 + k] - lo[k], cell);
          cells *= r[3 + k] - r[k] + 1;
        }
        if (cells > kLargeCells)
          large.push_back(static_cast<std::uint32_t>(i));
        else
          entryCount += cells;
      }
      if (large.size() <= maxLarge)
        break;
      cell *= 2;
    }
    std::vector<std::pair<std::uint64_t, std::uint32_t>> entries;
    entries.reserve(entryCount);
    std::vector<bool> isLarge(m, false);
    for (std::uint32_t i : large)
      isLarge[i] = true;
    // Cells numbered densely (x, then y, then z) over the cells in use: short keys, fewer
    // radix passes.
    std::uint64_t cellsY = 1, cellsZ = 1;
    for (std::size_t i = 0; i < m; ++i)
      if (!isLarge[i])
      {
        cellsY = std::max<std::uint64_t>(cellsY, range[6 * i + 4] + 1);
        cellsZ = std::max<std::uint64_t>(cellsZ, range[6 * i + 5] + 1);
      }
    auto key = [cellsY, cellsZ](std::uint32_t x, std::uint32_t y, std::uint32_t z)
    { return (x * cellsY + y) * cellsZ + z; };
    for (std::size_t i = 0; i < m; ++i)
    {
      if (isLarge[i])
        continue;
      const std::uint32_t* r = &range[6 * i];
      for (std::uint32_t x = r[0]; x <= r[3]; ++x)
        for (std::uint32_t y = r[1]; y <= r[4]; ++y)
          for (std::uint32_t z = r[2]; z <= r[5]; ++z)
            entries.push_back({ key(x, y, z), static_cast<std::uint32_t>(i) });
    }
    sortPushedPairs(entries);

    std::vector<std::pair<std::int32_t, std::int32_t>> found;
    const std::size_t limit = Options.maxRecordsPerKind;
    auto boxesOverlap = [&](std::uint32_t i, std::uint32_t j)
    {
      const double* bi = &box[6 * i];
      const double* bj = &box[6 * j];
      return !(bi[3] < bj[0] || bj[3] < bi[0] || bi[4] < bj[1] || bj[4] < bi[1] || bi[5] < bj[2] ||
        bj[5] < bi[2]);
    };
    auto test = [&](std::uint32_t i, std::uint32_t j)
    {
      if (intersect(cand[i], cand[j]))
        found.push_back({ std::min(cand[i], cand[j]), std::max(cand[i], cand[j]) });
      return limit != 0 && found.size() > limit;
    };
    bool stop = false;
    // Large triangles against every other box (each large pair once).
    for (std::uint32_t i : large)
    {
      for (std::uint32_t j = 0; j < m && !stop; ++j)
      {
        if (j == i || (isLarge[j] && j < i) || !boxesOverlap(i, j))
          continue;
        stop = test(i, j);
      }
    }
    // Per cell, its triangles' boxes and first cells copied side by side: the pairs then read
    // them from a few cache lines instead of two scattered loads per pair.
    struct CellEntry
    {
      std::uint32_t triangle;
      std::uint32_t firstCell[3];
      double box[6];
    };
    std::vector<CellEntry> cellEntries;
    for (std::size_t s = 0; s < entries.size() && !stop;)
    {
      std::size_t e = s + 1;
      while (e < entries.size() && entries[e].first == entries[s].first)
        ++e;
      cellEntries.clear();
      for (std::size_t a = s; a < e; ++a)
      {
        const std::uint32_t i = entries[a].second;
        CellEntry entry;
        entry.triangle = i;
        std::copy(&range[6 * i], &range[6 * i] + 3, entry.firstCell);
        std::copy(&box[6 * i], &box[6 * i] + 6, entry.box);
        cellEntries.push_back(entry);
      }
      for (std::size_t a = 0; a < cellEntries.size() && !stop; ++a)
      {
        const CellEntry& x = cellEntries[a];
        for (std::size_t b = a + 1; b < cellEntries.size() && !stop; ++b)
        {
          const CellEntry& y = cellEntries[b];
          if (x.box[3] < y.box[0] || y.box[3] < x.box[0] || x.box[4] < y.box[1] ||
            y.box[4] < x.box[1] || x.box[5] < y.box[2] || y.box[5] < x.box[2])
            continue;
          // Test each pair once: in the first cell both boxes cover.
          if (key(std::max(x.firstCell[0], y.firstCell[0]),
                std::max(x.firstCell[1], y.firstCell[1]),
                std::max(x.firstCell[2], y.firstCell[2])) != entries[s].first)
            continue;
          stop = test(x.triangle, y.triangle);
        }
      }
      s = e;
    }
    std::sort(found.begin(), found.end());
    for (const auto& pr : found)
    {
      const std::int32_t* v = tri(pr.first);
      const std::int32_t* w = tri(pr.second);
      add(SurfaceDefect::SelfIntersection,
        { v[0], v[1], v[2], w[0], w[1], w[2] },
        { pr.first, pr.second });
    }
  }

  // Cell index of an offset from the grid origin; monotone in x, so overlapping boxes always
  // share a cell.
  static std::uint32_t cellIndex(double x, double cell)
  {
    const double f = std::floor(x / cell);
    return static_cast<std::uint32_t>(std::min(std::max(f, 0.0), double((1 << 21) - 1)));
  }

  bool intersect(std::int32_t s, std::int32_t t) const
  {
    const std::int32_t* a = tri(s);
    const std::int32_t* b = tri(t);
    const std::int32_t ca[3] = { Canonical[a[0]], Canonical[a[1]], Canonical[a[2]] };
    const std::int32_t cb[3] = { Canonical[b[0]], Canonical[b[1]], Canonical[b[2]] };
    std::array<std::int32_t, 3> ka = { ca[0], ca[1], ca[2] }, kb = { cb[0], cb[1], cb[2] };
    std::sort(ka.begin(), ka.end());
    std::sort(kb.begin(), kb.end());
    if (ka == kb)
      return true; // coincident triangles on different (but coincident) points
    const double* p[3] = { pt(a[0]), pt(a[1]), pt(a[2]) };
    const double* q[3] = { pt(b[0]), pt(b[1]), pt(b[2]) };
    return trianglesIntersectImproperly(p, ca, q, cb);
  }

  void checkUnused()
  {
    std::vector<bool> used(static_cast<std::size_t>(PointCount), false);
    for (std::int32_t t = 0; t < TriCount; ++t)
    {
      if (State[t] & kBadIds)
        continue;
      for (int k = 0; k < 3; ++k)
        used[tri(t)[k]] = true;
    }
    for (std::int32_t i = 0; i < PointCount; ++i)
    {
      if (!used[i])
        add(LeftOut[static_cast<std::size_t>(i)] ? SurfaceDefect::UnusedPointLeftOut
                                                 : SurfaceDefect::UnusedPoint,
          { i },
          {});
    }
  }

  const double* Points;
  std::int32_t PointCount;
  const std::int32_t* Tris;
  std::int32_t TriCount;
  DiagnosisOptions Options;
  std::vector<std::uint8_t> State;
  std::vector<char> LeftOut; // unused points the mesh leaves out (UnusedPoints.h)
  std::vector<bool> Finite;
  std::vector<std::int32_t> Canonical;
  std::vector<DefectRecord> Records[kKindCount];
  bool Truncated = false;
};

void appendIds(std::ostringstream& out, const std::vector<std::int32_t>& ids, const char* sep)
{
  for (std::size_t i = 0; i < ids.size(); ++i)
    out << (i ? sep : "") << ids[i];
}

} // namespace

const char* defectLabel(SurfaceDefect kind, bool plural)
{
  switch (kind)
  {
    case SurfaceDefect::NonFiniteCoordinate:
      return plural ? "points with non-finite coordinates" : "point with non-finite coordinates";
    case SurfaceDefect::DuplicatePoint:
      return plural ? "groups of coincident points" : "group of coincident points";
    case SurfaceDefect::DegenerateTriangle:
      return plural ? "degenerate (zero-area) triangles" : "degenerate (zero-area) triangle";
    case SurfaceDefect::DuplicateTriangle:
      return plural ? "duplicated triangles" : "duplicated triangle";
    case SurfaceDefect::OpenEdge:
      return plural ? "open edges" : "open edge";
    case SurfaceDefect::NonManifoldEdge:
      return plural ? "non-manifold edges" : "non-manifold edge";
    case SurfaceDefect::InconsistentOrientation:
      return plural ? "edges with inconsistently oriented triangles"
                    : "edge with inconsistently oriented triangles";
    case SurfaceDefect::SelfIntersection:
      return plural ? "intersecting triangle pairs" : "intersecting triangle pair";
    case SurfaceDefect::UnusedPoint:
      return plural ? "unused points" : "unused point";
    case SurfaceDefect::UnusedPointLeftOut:
      return plural ? "unused points left out of the mesh (on the surface, or equal to another "
                      "point)"
                    : "unused point left out of the mesh (on the surface, or equal to another "
                      "point)";
    case SurfaceDefect::Empty:
      return "empty surface (no points or no triangles)";
    case SurfaceDefect::InvalidPointId:
      return plural ? "triangles with out-of-range point ids"
                    : "triangle with out-of-range point ids";
    case SurfaceDefect::OutlyingPoint:
      return plural ? "points out of all proportion to the surface (farther from its median "
                      "point than 1e15 times its shortest edge: a corrupted coordinate?)"
                    : "point out of all proportion to the surface (farther from its median "
                      "point than 1e15 times its shortest edge: a corrupted coordinate?)";
    case SurfaceDefect::CoordinateOutOfRange:
      return plural ? "points with coordinates too large or too small to decide exactly "
                      "(magnitudes beyond 1e-40..1e50; scale the model)"
                    : "point with coordinates too large or too small to decide exactly "
                      "(magnitudes beyond 1e-40..1e50; scale the model)";
  }
  return "unknown defect";
}

bool isWarning(SurfaceDefect kind)
{
  return kind == SurfaceDefect::UnusedPoint || kind == SurfaceDefect::UnusedPointLeftOut ||
    kind == SurfaceDefect::InconsistentOrientation;
}

SurfaceDiagnosis SurfaceDiagnosis::errors() const
{
  SurfaceDiagnosis out;
  out.truncated = truncated;
  for (const DefectRecord& r : defects)
  {
    if (!isWarning(r.kind))
      out.defects.push_back(r);
  }
  return out;
}

bool SurfaceDiagnosis::ok() const
{
  for (const DefectRecord& r : defects)
  {
    if (!isWarning(r.kind))
      return false;
  }
  return true;
}

int SurfaceDiagnosis::count(SurfaceDefect kind) const
{
  int n = 0;
  for (const DefectRecord& r : defects)
    n += r.kind == kind;
  return n;
}

std::string SurfaceDiagnosis::summary(std::size_t maxIdsPerKind) const
{
  if (defects.empty())
    return "no defects";
  std::ostringstream out;
  bool firstLine = true;
  for (SurfaceDefect kind : kReportOrder)
  {
    std::vector<const DefectRecord*> records;
    for (const DefectRecord& r : defects)
    {
      if (r.kind == kind)
        records.push_back(&r);
    }
    if (records.empty())
      continue;
    if (!firstLine)
      out << '\n';
    firstLine = false;
    if (kind == SurfaceDefect::Empty)
    {
      out << defectLabel(kind);
      continue;
    }
    out << records.size() << (truncated ? "+ " : " ") << defectLabel(kind, records.size() != 1)
        << " (";
    const std::size_t shown = std::min(records.size(), maxIdsPerKind);
    const bool more = shown < records.size();
    const bool pairs =
      kind == SurfaceDefect::SelfIntersection || kind == SurfaceDefect::DuplicateTriangle;
    if (kind != SurfaceDefect::SelfIntersection)
    {
      out << (records[0]->pointIds.size() == 1 ? "point " : "points ");
      for (std::size_t i = 0; i < shown; ++i)
      {
        out << (i ? ", " : "");
        appendIds(out, records[i]->pointIds, kind == SurfaceDefect::DuplicatePoint ? "=" : "-");
      }
      if (more)
        out << ", ...";
    }
    std::vector<std::int32_t> tris;
    bool moreTris = false;
    if (!pairs)
    {
      for (const DefectRecord* r : records)
      {
        for (std::int32_t t : r->triangleIds)
        {
          if (std::find(tris.begin(), tris.end(), t) != tris.end())
            continue;
          if (tris.size() == maxIdsPerKind)
            moreTris = true;
          else
            tris.push_back(t);
        }
        if (moreTris)
          break;
      }
    }
    if (pairs || !tris.empty())
    {
      if (kind != SurfaceDefect::SelfIntersection)
        out << "; ";
      out << "triangles ";
      if (pairs)
      {
        for (std::size_t i = 0; i < shown; ++i)
        {
          out << (i ? ", " : "");
          appendIds(
            out, records[i]->triangleIds, kind == SurfaceDefect::DuplicateTriangle ? "=" : "-");
        }
        moreTris = more;
      }
      else
        appendIds(out, tris, ", ");
      if (moreTris)
        out << ", ...";
    }
    out << ')';
  }
  return out.str();
}

SurfaceDiagnosis diagnoseSurface(const double* points,
  std::int32_t pointCount,
  const std::int32_t* triangles,
  std::int32_t triangleCount,
  const DiagnosisOptions& options)
{
  return Diagnoser(points, pointCount, triangles, triangleCount, options).run();
}

SurfaceDiagnosis diagnoseSurface(const double* points,
  std::int32_t pointCount,
  const std::int32_t* triangles,
  std::int32_t triangleCount)
{
  return diagnoseSurface(points, pointCount, triangles, triangleCount, DiagnosisOptions{});
}

} // namespace tetmesher
