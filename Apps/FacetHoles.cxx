#include "FacetHoles.h"

#include "PolygonTriangulation.h"
#include "Predicates.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace tetmesher
{
namespace cli
{
namespace
{

using Polygon = std::vector<std::int64_t>;

// The joined polygon has the outer corners and, per inner polygon, its corners and 2 for the
// slit; beyond the ear clipper's bound it would be fanned (overlapping triangles), so such a
// facet is refused. That bound also keeps the quadratic searches below small.
constexpr std::size_t kMaxJoinedCorners = static_cast<std::size_t>(kMaxEarClippedCorners);

struct Plane
{
  const std::vector<double>& points;
  int drop; // the axis orient2d drops
  int i, j; // the two it keeps, in its cyclic order

  const double* at(std::int64_t id) const { return &points[3 * static_cast<std::size_t>(id)]; }
  int orient(const double* a, const double* b, const double* c) const
  {
    return predicates::orient2d(a, b, c, drop);
  }
  // p on the closed segment ab, a, b and p collinear.
  bool within(const double* a, const double* b, const double* p) const
  {
    return std::min(a[i], b[i]) <= p[i] && p[i] <= std::max(a[i], b[i]) &&
      std::min(a[j], b[j]) <= p[j] && p[j] <= std::max(a[j], b[j]);
  }
  bool same(const double* a, const double* b) const { return a[i] == b[i] && a[j] == b[j]; }
  // +1 inside, -1 outside, 0 on the boundary (even-odd crossings of the ray towards +i).
  int locate(const double* p, const Polygon& polygon) const
  {
    bool inside = false;
    for (std::size_t k = 0; k < polygon.size(); ++k)
    {
      const double* a = at(polygon[k]);
      const double* b = at(polygon[(k + 1) % polygon.size()]);
      const int o = orient(a, b, p);
      if (o == 0 && within(a, b, p))
        return 0;
      const bool aAbove = a[j] > p[j], bAbove = b[j] > p[j];
      if (aAbove != bAbove && (bAbove ? o > 0 : o < 0))
        inside = !inside;
    }
    return inside ? 1 : -1;
  }
  // +1 counter-clockwise in (i, j), -1 clockwise, 0 degenerate: the turn at the lowest corner,
  // which is convex.
  int orientation(const Polygon& polygon) const
  {
    std::size_t low = 0;
    for (std::size_t k = 1; k < polygon.size(); ++k)
    {
      const double *p = at(polygon[k]), *q = at(polygon[low]);
      if (p[i] < q[i] || (p[i] == q[i] && p[j] < q[j]))
        low = k;
    }
    const std::size_t n = polygon.size();
    return orient(at(polygon[(low + n - 1) % n]), at(polygon[low]), at(polygon[(low + 1) % n]));
  }
  // True when the segments mv and ab share a point other than an end they share.
  bool blocks(const double* m, const double* v, const double* a, const double* b) const
  {
    const bool aEnd = same(a, m) || same(a, v), bEnd = same(b, m) || same(b, v);
    if (aEnd && bEnd)
      return false; // the same segment's ends (or a slit walked the other way)
    const int o1 = orient(m, v, a), o2 = orient(m, v, b);
    const int o3 = orient(a, b, m), o4 = orient(a, b, v);
    if (!aEnd && o1 == 0 && within(m, v, a))
      return true;
    if (!bEnd && o2 == 0 && within(m, v, b))
      return true;
    if (aEnd || bEnd)
      return false; // touching at the shared end only, the other end off the segment
    if ((o3 == 0 && within(a, b, m)) || (o4 == 0 && within(a, b, v)))
      return true;
    return o1 * o2 < 0 && o3 * o4 < 0;
  }
  // The closed segments ab and cd share a point.
  bool meet(const double* a, const double* b, const double* c, const double* d) const
  {
    const int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a),
              o4 = orient(c, d, b);
    if (o1 * o2 < 0 && o3 * o4 < 0)
      return true;
    return (o1 == 0 && within(a, b, c)) || (o2 == 0 && within(a, b, d)) ||
      (o3 == 0 && within(c, d, a)) || (o4 == 0 && within(c, d, b));
  }
  // m strictly inside the angle p-v-n of a counter-clockwise polygon.
  bool inCone(const double* p, const double* v, const double* n, const double* m) const
  {
    if (orient(p, v, n) >= 0)
      return orient(p, v, m) > 0 && orient(v, n, m) > 0;
    return !(orient(p, v, m) <= 0 && orient(v, n, m) <= 0);
  }
};

// The polygon of largest area (Newell normal): the outer one of a facet whose polygons nest.
std::size_t LargestPolygon(const std::vector<double>& points, const std::vector<Polygon>& polygons)
{
  std::size_t largestIndex = 0;
  double largest = -1;
  for (std::size_t p = 0; p < polygons.size(); ++p)
  {
    // Held by value: a pointer into the temporary's array would dangle (ASan caught it).
    const PolygonNormal newell = polygonNormal(
      points.data(), polygons[p].data(), static_cast<std::int64_t>(polygons[p].size()));
    const double area = std::hypot(newell.normal[0], newell.normal[1], newell.normal[2]);
    if (area > largest)
    {
      largest = area;
      largestIndex = p;
    }
  }
  return largestIndex;
}

// The plane that drops the largest component of the polygon's normal (as the ear clipper's).
Plane PlaneOf(const std::vector<double>& points, const Polygon& polygon)
{
  const int drop =
    polygonNormal(points.data(), polygon.data(), static_cast<std::int64_t>(polygon.size()))
      .dominantAxis;
  return Plane{ points, drop, (drop + 1) % 3, (drop + 2) % 3 };
}

// Joins `hole` (clockwise) to `outer` (counter-clockwise) by a slit from the hole's corner of
// largest i to the nearest outer corner it sees, checked exactly against every edge of the
// outer polygon and of the holes still apart. False when none is found.
bool JoinHole(const Plane& plane,
  Polygon& outer,
  const Polygon& hole,
  const std::vector<const Polygon*>& others)
{
  std::size_t mi = 0;
  for (std::size_t k = 1; k < hole.size(); ++k)
  {
    const double *p = plane.at(hole[k]), *q = plane.at(hole[mi]);
    if (p[plane.i] > q[plane.i] || (p[plane.i] == q[plane.i] && p[plane.j] > q[plane.j]))
      mi = k;
  }
  const double* m = plane.at(hole[mi]);
  std::vector<std::size_t> order(outer.size());
  std::iota(order.begin(), order.end(), 0);
  auto distance2 = [&](std::size_t k)
  {
    const double* v = plane.at(outer[k]);
    const double di = v[plane.i] - m[plane.i], dj = v[plane.j] - m[plane.j];
    return di * di + dj * dj;
  };
  std::stable_sort(order.begin(),
    order.end(),
    [&](std::size_t a, std::size_t b) { return distance2(a) < distance2(b); });
  auto clear = [&](const double* v, const Polygon& polygon)
  {
    for (std::size_t k = 0; k < polygon.size(); ++k)
      if (plane.blocks(m, v, plane.at(polygon[k]), plane.at(polygon[(k + 1) % polygon.size()])))
        return false;
    return true;
  };
  const std::size_t n = outer.size();
  for (std::size_t k : order)
  {
    const double* v = plane.at(outer[k]);
    if (plane.same(v, m) ||
      !plane.inCone(plane.at(outer[(k + n - 1) % n]), v, plane.at(outer[(k + 1) % n]), m) ||
      !clear(v, outer) || !clear(v, hole))
      continue;
    if (!std::all_of(
          others.begin(), others.end(), [&](const Polygon* other) { return clear(v, *other); }))
      continue;
    Polygon joined(outer.begin(), outer.begin() + static_cast<std::ptrdiff_t>(k) + 1);
    for (std::size_t s = 0; s <= hole.size(); ++s)
      joined.push_back(hole[(mi + s) % hole.size()]); // round the hole, back to its corner
    joined.insert(joined.end(), outer.begin() + static_cast<std::ptrdiff_t>(k), outer.end());
    outer.swap(joined);
    return true;
  }
  return false;
}

} // namespace

bool PolygonsNested(const std::vector<double>& points, const std::vector<Polygon>& polygons)
{
  if (polygons.size() < 2)
    return false;
  const Plane plane = PlaneOf(points, polygons[LargestPolygon(points, polygons)]);
  // Each polygon's box in the plane: a corner outside a polygon's box is not inside it (a
  // facet may hold thousands of polygons side by side).
  std::vector<std::array<double, 4>> boxes;
  for (const Polygon& polygon : polygons)
  {
    std::array<double, 4> box{ INFINITY, INFINITY, -INFINITY, -INFINITY };
    for (std::int64_t id : polygon)
    {
      const double* x = plane.at(id);
      box = { std::min(box[0], x[plane.i]),
        std::min(box[1], x[plane.j]),
        std::max(box[2], x[plane.i]),
        std::max(box[3], x[plane.j]) };
    }
    boxes.push_back(box);
  }
  for (std::size_t p = 0; p < polygons.size(); ++p)
    for (std::size_t q = 0; q < polygons.size(); ++q)
    {
      if (p == q)
        continue;
      const auto& box = boxes[q];
      for (std::int64_t id : polygons[p])
      {
        const double* x = plane.at(id);
        if (box[0] < x[plane.i] && x[plane.i] < box[2] && box[1] < x[plane.j] &&
          x[plane.j] < box[3] && plane.locate(x, polygons[q]) > 0)
          return true;
      }
    }
  return false;
}

std::vector<Polygon> FacetWithoutHoles(const std::vector<double>& points,
  const std::vector<Polygon>& polygons,
  const std::vector<std::array<double, 3>>& holes,
  std::string& error)
{
  error.clear();
  std::size_t corners = 0;
  for (std::size_t p = 0; p < polygons.size(); ++p)
  {
    corners += polygons[p].size() + 2;
    for (std::size_t k = 0; k < polygons[p].size(); ++k)
    {
      const double* a = &points[3 * static_cast<std::size_t>(polygons[p][k])];
      const double* b =
        &points[3 * static_cast<std::size_t>(polygons[p][(k + 1) % polygons[p].size()])];
      if (a[0] == b[0] && a[1] == b[1] && a[2] == b[2])
      {
        error = "polygon " + std::to_string(p + 1) + " repeats a corner";
        return {};
      }
    }
  }
  if (corners > kMaxJoinedCorners + 2)
  {
    error = "more than " + std::to_string(kMaxJoinedCorners) +
      " corners once its polygons are joined (the ear clipper's bound)";
    return {};
  }
  const std::size_t outerIndex = LargestPolygon(points, polygons);
  const Plane plane = PlaneOf(points, polygons[outerIndex]);
  const Polygon& outer = polygons[outerIndex];
  const int outerTurn = plane.orientation(outer);
  if (outerTurn == 0)
  {
    error = "its largest polygon has no area in its plane";
    return {};
  }
  // Every other polygon strictly inside the outer one, and none inside another.
  std::vector<std::size_t> inner;
  for (std::size_t p = 0; p < polygons.size(); ++p)
  {
    if (p == outerIndex)
      continue;
    for (std::int64_t id : polygons[p])
      if (plane.locate(plane.at(id), outer) <= 0)
      {
        error = "polygon " + std::to_string(p + 1) + " is not inside polygon " +
          std::to_string(outerIndex + 1) +
          " (a facet with holes or nested polygons is one polygon around others)";
        return {};
      }
    if (plane.orientation(polygons[p]) == 0)
    {
      error = "polygon " + std::to_string(p + 1) + " has no area in the facet's plane";
      return {};
    }
    inner.push_back(p);
  }
  for (std::size_t p : inner)
    for (std::size_t q : inner)
      if (p != q && plane.locate(plane.at(polygons[p][0]), polygons[q]) >= 0)
      {
        error = "polygon " + std::to_string(p + 1) + " lies inside polygon " +
          std::to_string(q + 1) + " (polygons nested two deep are not supported)";
        return {};
      }
  // No two polygons share a point (the vertex tests above miss crossing edges).
  for (std::size_t p = 0; p < polygons.size(); ++p)
    for (std::size_t q = p + 1; q < polygons.size(); ++q)
      for (std::size_t k = 0; k < polygons[p].size(); ++k)
        for (std::size_t l = 0; l < polygons[q].size(); ++l)
        {
          const Polygon &a = polygons[p], &b = polygons[q];
          if (plane.meet(plane.at(a[k]),
                plane.at(a[(k + 1) % a.size()]),
                plane.at(b[l]),
                plane.at(b[(l + 1) % b.size()])))
          {
            error = "polygons " + std::to_string(p + 1) + " and " + std::to_string(q + 1) +
              " cross or touch";
            return {};
          }
        }
  // Each hole point removes the inner polygon it lies in, or the part around the inner ones.
  std::vector<char> removed(polygons.size(), 0);
  bool ringRemoved = false;
  for (std::size_t h = 0; h < holes.size(); ++h)
  {
    const double* x = holes[h].data();
    const int whereOuter = plane.locate(x, outer);
    std::size_t in = polygons.size();
    bool onBoundary = whereOuter == 0;
    for (std::size_t p : inner)
    {
      const int where = plane.locate(x, polygons[p]);
      onBoundary = onBoundary || where == 0;
      if (where > 0)
        in = p;
    }
    if (onBoundary || whereOuter < 0)
    {
      error = "hole " + std::to_string(h + 1) + " lies " +
        (onBoundary ? "on one of its polygons" : "outside its polygons");
      return {};
    }
    if (in < polygons.size())
      removed[in] = 1;
    else
      ringRemoved = true;
  }
  // Kept inner polygons turn as the outer one: the facet's parts share its orientation.
  std::vector<Polygon> kept;
  for (std::size_t p : inner)
    if (!removed[p])
    {
      kept.push_back(polygons[p]);
      if (plane.orientation(kept.back()) != outerTurn)
        std::reverse(kept.back().begin(), kept.back().end());
    }
  if (ringRemoved)
  {
    if (kept.empty())
      error = "its hole points leave nothing of it";
    return kept;
  }
  // The ring: the outer polygon counter-clockwise, each inner one clockwise, joined in turn.
  Polygon ring = outer;
  if (outerTurn < 0)
    std::reverse(ring.begin(), ring.end());
  std::vector<Polygon> apart;
  for (std::size_t p : inner)
  {
    apart.push_back(polygons[p]);
    if (plane.orientation(apart.back()) > 0)
      std::reverse(apart.back().begin(), apart.back().end());
  }
  // A hole may see no corner of the ring until another one is joined (one inside a C-shaped
  // one): passes over the holes left, until all are joined or a pass joins none.
  std::vector<char> joined(apart.size(), 0);
  for (std::size_t left = apart.size(); left > 0;)
  {
    const std::size_t before = left;
    for (std::size_t h = 0; h < apart.size(); ++h)
    {
      if (joined[h])
        continue;
      std::vector<const Polygon*> others;
      for (std::size_t k = 0; k < apart.size(); ++k)
        if (k != h && !joined[k])
          others.push_back(&apart[k]);
      if (JoinHole(plane, ring, apart[h], others))
      {
        joined[h] = 1;
        --left;
      }
    }
    if (left == before)
    {
      const std::size_t h =
        static_cast<std::size_t>(std::find(joined.begin(), joined.end(), 0) - joined.begin());
      error = "no slit joins polygon " + std::to_string(inner[h] + 1) + " to the polygon around it";
      return {};
    }
  }
  if (outerTurn < 0)
    std::reverse(ring.begin(), ring.end());
  kept.insert(kept.begin(), ring);
  return kept;
}

} // namespace cli
} // namespace tetmesher
