#include "BoundarySizeCeiling.h"

#include "TriangleDistance.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tetmesher
{

namespace
{
constexpr std::int32_t kLeafFaces = 4;
constexpr double kMaxCells = 1 << 18;

// x rounded down to a float (FLT_MAX above it): a lower bound of x in half the bytes.
float floatBelow(double x)
{
  if (!(x < std::numeric_limits<float>::max()))
    return x != x ? 0.0f : std::numeric_limits<float>::max();
  if (x < -static_cast<double>(std::numeric_limits<float>::max()))
    return -std::numeric_limits<float>::infinity();
  float f = static_cast<float>(x);
  if (static_cast<double>(f) > x)
    f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}

// Distance between two boxes (min x, y, z, max x, y, z); for a box a containing x, never more
// than pointBoxDistance(x, b) in floating point: each step is monotone in the corners.
double boxBoxDistance(const double* a, const double* b)
{
  double d2 = 0;
  for (int k = 0; k < 3; ++k)
  {
    const double d = std::max({ b[k] - a[3 + k], a[k] - b[3 + k], 0.0 });
    d2 += d * d;
  }
  return std::sqrt(d2);
}

} // namespace

BoundarySizeCeiling::BoundarySizeCeiling(const double* points,
  const std::vector<std::int32_t>& faceCorners,
  const std::vector<double>& faceSize,
  double slope)
  : slope_(slope)
{
  if (!(slope > 0) || !std::isfinite(slope))
    return;
  // Reserved: grown by doubling, the faces' copies (128 bytes each) showed as 1% of fandisk's
  // sized run, in reallocation and the first touch of each larger block.
  faces_.reserve(faceSize.size());
  for (std::size_t id = 0; id < faceSize.size(); ++id)
  {
    Face f;
    f.size = faceSize[id];
    if (!(f.size > 0) || !std::isfinite(f.size))
      continue;
    geometry::gatherTriangle(points, &faceCorners[3 * id], f.corner, f.box);
    bool finite = true;
    for (double c : f.corner)
      finite = finite && std::isfinite(c);
    if (finite)
      faces_.push_back(f);
  }
  if (!faces_.empty())
  {
    nodes_.reserve(2 * faces_.size() / kLeafFaces + 2);
    build(0, static_cast<std::int32_t>(faces_.size()));
    // Cells twice the median face size (femur.off's lattice candidates 0.69 -> 0.53 s at 1x,
    // 0.57 s at 2x, but fandisk.off's 0.075 -> 0.083 s at 1x, 0.066 s at 2x: small cells cost
    // more bounds to compute than they save), at most 4 kMaxCells over the faces' box (wider
    // cells where that is exceeded: a flat domain). None when the box is not finite.
    std::vector<double> sizes;
    for (const Face& f : faces_)
      sizes.push_back(f.size);
    std::nth_element(sizes.begin(), sizes.begin() + sizes.size() / 2, sizes.end());
    const double* box = nodes_[0].box;
    double extent[3], volume = 1;
    for (int a = 0; a < 3; ++a)
    {
      extent[a] = std::max(box[3 + a] - box[a], 1e-300);
      volume *= extent[a];
    }
    cellSize_ = std::max(2 * sizes[sizes.size() / 2], std::cbrt(volume / kMaxCells));
    auto cellCount = [&]()
    {
      double cells = 1;
      for (int a = 0; a < 3; ++a)
        cells *= std::floor(extent[a] / cellSize_) + 1;
      return cells;
    };
    if (!std::isfinite(cellSize_) || !(cellSize_ > 0) || !std::isfinite(volume))
      return;
    while (!(cellCount() <= 4 * kMaxCells))
      cellSize_ *= 2;
    for (int a = 0; a < 3; ++a)
    {
      cellOrigin_[a] = box[a];
      cellDims_[a] = static_cast<std::int32_t>(std::floor(extent[a] / cellSize_) + 1);
    }
    cells_ = CellLists(static_cast<std::size_t>(cellCount()));
  }
}

BoundarySizeCeiling::CellLists::CellLists(std::size_t n)
  : slots(new std::atomic<CellList*>[n])
  , count(n)
{
  for (std::size_t c = 0; c < n; ++c)
    slots[c].store(nullptr, std::memory_order_relaxed);
}

BoundarySizeCeiling::CellLists& BoundarySizeCeiling::CellLists::operator=(
  CellLists&& other) noexcept
{
  if (this != &other)
  {
    release();
    slots = std::move(other.slots);
    count = other.count;
    other.count = 0;
  }
  return *this;
}

BoundarySizeCeiling::CellLists::~CellLists()
{
  release();
}

void BoundarySizeCeiling::CellLists::release()
{
  for (std::size_t c = 0; slots && c < count; ++c)
    delete slots[c].load(std::memory_order_relaxed);
  slots.reset();
  count = 0;
}

const BoundarySizeCeiling::CellList& BoundarySizeCeiling::cellList(std::size_t cell,
  const double* cellBox,
  double atMost) const
{
  std::atomic<CellList*>& slot = cells_.slots[cell];
  CellList* known = slot.load(std::memory_order_acquire);
  if (known && atMost <= known->limit)
    return *known;
  // Faces whose bound is not below `cap` cannot answer this query (nor one with an atMost up
  // to cap); the slack spares remaking the list for the next, slightly larger, atMost.
  const double cap = 1.25 * atMost;
  // An upper bound of the ceiling anywhere in the cell: its value at the centre plus slope
  // times the half diagonal, widened for rounding by a relative 1e-9 and by the rounding of the
  // centre's and the corners' coordinates (far from the origin, ulps can exceed 1e-9 of a
  // small cell). Measured from cap: a value at the centre not below it makes upper above cap.
  double centre[3], magnitude = 0;
  for (int a = 0; a < 3; ++a)
  {
    centre[a] = 0.5 * (cellBox[a] + cellBox[3 + a]);
    magnitude = std::max({ magnitude, std::fabs(cellBox[a]), std::fabs(cellBox[3 + a]) });
  }
  const double atCentre = search(
    cap,
    [&](const double* box) { return geometry::pointBoxDistance(centre, box); },
    [&](const Face& f, double best) { return faceValue(f, centre, best); });
  const double halfDiagonal =
    0.5 * std::sqrt(3.0) * cellSize_ + 8 * std::numeric_limits<double>::epsilon() * magnitude;
  const double upper = (atCentre + slope_ * halfDiagonal) * (1 + 1e-9);
  // Below upper (when atCentre < cap), every face that can give the ceiling in the cell:
  // complete for any atMost. Else the faces below cap, complete for atMost up to cap.
  const bool complete = atCentre < cap && upper <= cap;
  const double bound = complete ? upper : cap;
  // Gathered in a scratch list, then copied at its size (lists grown by doubling held twice
  // their entries: femur.off's peak RSS 82 -> 93 MB with double bounds, now 86 MB).
  thread_local std::vector<CellEntry> entries;
  entries.clear();
  // The tree search with its bound held at `bound` (not finite: every face) visits every face
  // whose lower bound over the cell is below it.
  search(
    std::isfinite(bound) ? bound : std::numeric_limits<double>::infinity(),
    [&](const double* box) { return boxBoxDistance(cellBox, box); },
    [&](const Face& f, double b)
    {
      const double lower = f.size + slope_ * boxBoxDistance(cellBox, f.box);
      if (lower < b)
        entries.push_back({ floatBelow(lower), static_cast<std::int32_t>(&f - faces_.data()) });
      return b;
    });
  std::sort(entries.begin(),
    entries.end(),
    [](const CellEntry& x, const CellEntry& y)
    { return x.lower != y.lower ? x.lower < y.lower : x.face < y.face; });
  auto list = std::make_unique<CellList>();
  list->entries.assign(entries.begin(), entries.end());
  list->limit = complete || !std::isfinite(bound) ? std::numeric_limits<double>::infinity() : cap;
  for (;;)
  {
    list->replaced.reset(known);
    if (slot.compare_exchange_strong(
          known, list.get(), std::memory_order_acq_rel, std::memory_order_acquire))
      return *list.release();
    // Another thread published first (`known` is now its list, owned by the slot).
    list->replaced.release();
    if (atMost <= known->limit)
      return *known;
  }
}

double BoundarySizeCeiling::faceValue(const Face& f, const double* p, double bound) const
{
  if (!(f.size + slope_ * geometry::pointBoxDistance(p, f.box) < bound))
    return bound;
  const double d =
    std::sqrt(geometry::pointTriangleDistanceSquared(p, f.corner, f.corner + 3, f.corner + 6));
  return std::min(bound, f.size + slope_ * d);
}

template<typename BoxDistance, typename FaceValue>
double BoundarySizeCeiling::search(double best,
  const BoxDistance& boxDistance,
  const FaceValue& faceValue) const
{
  std::int32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0)
  {
    const Node& node = nodes_[static_cast<std::size_t>(stack[--top])];
    if (!(node.minSize + slope_ * boxDistance(node.box) < best))
      continue;
    if (node.count > 0)
    {
      for (std::int32_t i = node.first; i < node.first + node.count; ++i)
        best = faceValue(faces_[static_cast<std::size_t>(i)], best);
      continue;
    }
    // The nearer child last on the stack, so it is visited first and tightens the bound.
    const Node& l = nodes_[static_cast<std::size_t>(node.left)];
    const Node& r = nodes_[static_cast<std::size_t>(node.right)];
    const bool leftNearer = boxDistance(l.box) <= boxDistance(r.box);
    if (top + 2 > 128)
      continue; // deeper than any balanced tree of 2^31 faces; cannot happen
    stack[top++] = leftNearer ? node.right : node.left;
    stack[top++] = leftNearer ? node.left : node.right;
  }
  return best;
}

// Median split on the longest axis of the faces' centres; the order is a function of the
// input alone (ties by position in the array), so the tree is deterministic.
std::int32_t BoundarySizeCeiling::build(std::int32_t first, std::int32_t count)
{
  const std::int32_t id = static_cast<std::int32_t>(nodes_.size());
  nodes_.push_back({});
  Node node;
  node.minSize = faces_[static_cast<std::size_t>(first)].size;
  std::copy(faces_[static_cast<std::size_t>(first)].box,
    faces_[static_cast<std::size_t>(first)].box + 6,
    node.box);
  double lo[3] = { 0, 0, 0 }, hi[3] = { 0, 0, 0 };
  for (std::int32_t i = first; i < first + count; ++i)
  {
    const Face& f = faces_[static_cast<std::size_t>(i)];
    node.minSize = std::min(node.minSize, f.size);
    for (int a = 0; a < 3; ++a)
    {
      node.box[a] = std::min(node.box[a], f.box[a]);
      node.box[3 + a] = std::max(node.box[3 + a], f.box[3 + a]);
      const double c = f.box[a] + f.box[3 + a];
      lo[a] = i == first ? c : std::min(lo[a], c);
      hi[a] = i == first ? c : std::max(hi[a], c);
    }
  }
  node.first = first;
  node.count = count;
  node.left = node.right = -1;
  if (count > kLeafFaces)
  {
    int axis = 0;
    for (int a = 1; a < 3; ++a)
      if (hi[a] - lo[a] > hi[axis] - lo[axis])
        axis = a;
    const std::int32_t half = count / 2;
    auto begin = faces_.begin() + first;
    std::nth_element(begin,
      begin + half,
      begin + count,
      [axis](const Face& x, const Face& y)
      {
        const double cx = x.box[axis] + x.box[3 + axis], cy = y.box[axis] + y.box[3 + axis];
        if (cx != cy)
          return cx < cy;
        return std::lexicographical_compare(x.corner, x.corner + 9, y.corner, y.corner + 9);
      });
    node.count = 0;
    node.left = build(first, half);
    node.right = build(first + half, count - half);
  }
  nodes_[static_cast<std::size_t>(id)] = node;
  return id;
}

double BoundarySizeCeiling::at(const double* p, double atMost) const
{
  double best = atMost;
  if (nodes_.empty())
    return best;
  if (cells_.count > 0)
  {
    std::size_t cell = 0;
    double cellBox[6];
    bool inside = true;
    for (int a = 2; a >= 0; --a)
    {
      const double x = std::floor((p[a] - cellOrigin_[a]) / cellSize_);
      const std::int32_t i = x >= 0 && x < cellDims_[a] ? static_cast<std::int32_t>(x) : -1;
      inside = inside && i >= 0;
      if (!inside)
        break;
      cellBox[a] = cellOrigin_[a] + i * cellSize_;
      cellBox[3 + a] = cellOrigin_[a] + (i + 1) * cellSize_;
      inside = cellBox[a] <= p[a] && p[a] <= cellBox[3 + a]; // rounding may put p outside
      cell = cell * static_cast<std::size_t>(cellDims_[a]) + static_cast<std::size_t>(i);
    }
    if (inside)
    {
      // A face's lower bound over the cell is at most its tree search bound at p (the box
      // distances are monotone), so the faces past the first bound not below best, and those
      // not listed (above the ceiling's upper bound over the cell, or not below the list's
      // limit, which is at least atMost), cannot go below it.
      for (const CellEntry& e : cellList(cell, cellBox, best).entries)
      {
        if (!(static_cast<double>(e.lower) < best))
          break;
        best = faceValue(faces_[static_cast<std::size_t>(e.face)], p, best);
      }
      return best;
    }
  }
  return search(
    best,
    [p](const double* box) { return geometry::pointBoxDistance(p, box); },
    [&](const Face& f, double bound) { return faceValue(f, p, bound); });
}

} // namespace tetmesher
