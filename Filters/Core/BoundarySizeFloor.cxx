#include "BoundarySizeFloor.h"

#include "ParallelPair.h"
#include "TriangleDistance.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tetmesher
{

namespace
{
// A face whose reach's box spans more cells than this (a face far larger than the median
// reach, e.g. a spike of a fuzzed surface) is read by every query instead, so that neither
// building nor querying depends on its extent. Within it, a face is listed only in the cells
// its reach actually meets: long thin CAD triangles cross many cells (couplingdown at 0.4 of
// its edge sizes: 243 of 3714 faces were read by every query with a listing by boxes).
constexpr double kMaxCellsPerFace = 1 << 14;
// From this many faces on, the listing and the sorting run in two halves side by side (fandisk
// at h = 0.0103: 0.12 s on one thread, most of the refinement's setup).
constexpr std::size_t kMinFacesForHalves = 2048;
} // namespace

BoundarySizeFloor::BoundarySizeFloor(const double* points,
  const std::vector<std::int32_t>& faceCorners,
  const std::vector<double>& faceSize,
  const std::vector<double>& faceBase,
  double slope)
  : slope_(slope)
{
  if (!(slope > 0) || !std::isfinite(slope))
    return;
  std::vector<double> reaches;
  faces_.reserve(faceSize.size());
  reaches.reserve(faceSize.size());
  for (std::size_t id = 0; id < faceSize.size(); ++id)
  {
    const double s = faceSize[id], base = faceBase[id];
    if (!(s > base) || !std::isfinite(s) || !(base > 0))
      continue;
    Face f;
    f.size = s;
    f.reach = (s - base) / slope;
    geometry::gatherTriangle(points, &faceCorners[3 * id], f.corner, f.box);
    const double* a = f.corner;
    const double u[3] = { a[3] - a[0], a[4] - a[1], a[5] - a[2] };
    const double v[3] = { a[6] - a[0], a[7] - a[1], a[8] - a[2] };
    const double n[3] = {
      u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]
    };
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; ++k)
      f.normal[k] = length > 0 && std::isfinite(length) ? n[k] / length : 0.0;
    f.offset = f.normal[0] * a[0] + f.normal[1] * a[1] + f.normal[2] * a[2];
    bool finite = std::isfinite(f.offset);
    for (double b : f.box)
      finite = finite && std::isfinite(b);
    if (!finite)
      continue;
    faces_.push_back(f);
    reaches.push_back(f.reach);
  }
  if (faces_.empty())
    return;
  // Cells as wide as the median reach: a face is listed in a few cells per axis.
  std::nth_element(reaches.begin(), reaches.begin() + reaches.size() / 2, reaches.end());
  cell_ = reaches[reaches.size() / 2];
  for (int a = 0; a < 3; ++a)
  {
    origin_[a] = std::numeric_limits<double>::max();
    for (const Face& f : faces_)
      origin_[a] = std::min(origin_[a], f.box[a] - f.reach);
  }
  // (cell key, entry) pairs in face order (each half of the faces lists its own, the first
  // half's first), then bucketed by cell (a counting sort over the cells' dense indices) and
  // each cell's list sorted: the same whether the halves ran on one thread or two.
  struct Listing
  {
    std::uint64_t key;
    Entry entry;
  };
  const bool twoThreads = wantTwoThreads(0) && faces_.size() >= kMinFacesForHalves;
  const std::size_t middleFace = faces_.size() / 2;
  std::vector<Listing> halfListings[2];
  std::vector<std::int32_t> halfLarge[2];
  splitAt(twoThreads,
    middleFace,
    faces_.size(),
    [&](int half, std::size_t firstFace, std::size_t lastFace)
    {
      std::vector<Listing>& listings = halfListings[half];
      // Reserved, not touched (no memory until written): 40-50 cells per face on the corpus.
      listings.reserve(64 * (lastFace - firstFace));
      for (std::size_t id = firstFace; id < lastFace; ++id)
      {
        const Face& f = faces_[id];
        double lo[3], hi[3];
        for (int a = 0; a < 3; ++a)
        {
          lo[a] = f.box[a] - f.reach;
          hi[a] = f.box[3 + a] + f.reach;
        }
        std::int64_t c0[3], c1[3];
        double count = 1;
        bool inRange = cellOf(lo, c0) && cellOf(hi, c1);
        for (int a = 0; a < 3 && inRange; ++a)
          count *= static_cast<double>(c1[a] - c0[a] + 1);
        if (!inRange || count > kMaxCellsPerFace)
        {
          halfLarge[half].push_back(static_cast<std::int32_t>(id));
          continue;
        }
        const double halfDiagonal = 0.5 * std::sqrt(3.0) * cell_;
        for (std::int64_t i = c0[0]; i <= c1[0]; ++i)
          for (std::int64_t j = c0[1]; j <= c1[1]; ++j)
            for (std::int64_t k = c0[2]; k <= c1[2]; ++k)
            {
              // The face's floor over the cell is at most its size less the slope times a lower
              // bound of the distance from the cell to the face: the distance between the cell
              // and the face's box, and the distance from the cell's centre to the face (or its
              // plane, cheaper, first) less the cell's half diagonal.
              const std::int64_t c[3] = { i, j, k };
              double gap2 = 0, centre[3];
              for (int a = 0; a < 3; ++a)
              {
                const double cellLo = origin_[a] + static_cast<double>(c[a]) * cell_;
                centre[a] = cellLo + 0.5 * cell_;
                const double d =
                  std::max({ cellLo - f.box[3 + a], f.box[a] - (cellLo + cell_), 0.0 });
                gap2 += d * d;
              }
              const double plane = std::fabs(f.normal[0] * centre[0] + f.normal[1] * centre[1] +
                                     f.normal[2] * centre[2] - f.offset) -
                halfDiagonal;
              double gap = std::max(std::sqrt(gap2), plane);
              if (gap < f.reach)
                gap = std::max(gap,
                  std::sqrt(geometry::pointTriangleDistanceSquared(
                    centre, f.corner, f.corner + 3, f.corner + 6)) -
                    halfDiagonal);
              // Beyond the reach the face adds nothing to the cell. The bound is only used to
              // stop early, so it is widened by a relative 1e-9 for rounding rather than proven.
              if (!(gap < f.reach))
                continue;
              const double bound = f.size - slope_ * std::max(gap, 0.0) * (1 - 1e-9);
              listings.push_back({ key(i, j, k), { bound, static_cast<std::int32_t>(id) } });
            }
      }
    });
  large_ = std::move(halfLarge[0]);
  large_.insert(large_.end(), halfLarge[1].begin(), halfLarge[1].end());
  // The two halves' listings are read in turn, as if end to end, rather than joined: copying
  // them took a third of the construction (fandisk at h = 0.0103: 15 MB written anew).
  // Each listing's key is overwritten by its cell's dense index.
  std::int32_t cellCount = 0;
  for (std::vector<Listing>& listings : halfListings)
  {
    for (Listing& listing : listings)
    {
      if (const std::int32_t* known = cellIndex_.find(listing.key))
        listing.key = static_cast<std::uint64_t>(*known);
      else
      {
        cellIndex_.insert(listing.key, cellCount);
        listing.key = static_cast<std::uint64_t>(cellCount++);
      }
    }
  }
  cellStart_.assign(static_cast<std::size_t>(cellCount) + 1, 0);
  for (const std::vector<Listing>& listings : halfListings)
    for (const Listing& listing : listings)
      ++cellStart_[listing.key + 1];
  for (std::size_t c = 0; c < static_cast<std::size_t>(cellCount); ++c)
    cellStart_[c + 1] += cellStart_[c];
  entries_.resize(cellStart_.back());
  std::vector<std::size_t> fill(cellStart_.begin(), cellStart_.end() - 1);
  for (std::vector<Listing>& listings : halfListings)
  {
    for (const Listing& listing : listings)
      entries_[fill[listing.key]++] = listing.entry;
    std::vector<Listing>().swap(listings);
  }
  const std::size_t cells = static_cast<std::size_t>(cellCount);
  splitAt(twoThreads,
    cells / 2,
    cells,
    [&](int, std::size_t firstCell, std::size_t lastCell)
    {
      for (std::size_t c = firstCell; c < lastCell; ++c)
        std::sort(entries_.begin() + static_cast<std::ptrdiff_t>(cellStart_[c]),
          entries_.begin() + static_cast<std::ptrdiff_t>(cellStart_[c + 1]),
          [](const Entry& x, const Entry& y)
          { return x.bound != y.bound ? x.bound > y.bound : x.face < y.face; });
    });
}

double BoundarySizeFloor::at(const double* p, double atLeast) const
{
  double best = std::max(atLeast, 0.0);
  if (faces_.empty())
    return best;
  for (std::int32_t id : large_)
    consider(faces_[static_cast<std::size_t>(id)], p, best);
  std::int64_t c[3];
  if (!cellOf(p, c))
    return best;
  const std::int32_t* cell = cellIndex_.find(key(c[0], c[1], c[2]));
  if (!cell)
    return best;
  const std::size_t end = cellStart_[static_cast<std::size_t>(*cell) + 1];
  for (std::size_t n = cellStart_[static_cast<std::size_t>(*cell)]; n < end; ++n)
  {
    const Entry& e = entries_[n];
    if (!(e.bound > best))
      break;
    consider(faces_[static_cast<std::size_t>(e.face)], p, best);
  }
  return best;
}

void BoundarySizeFloor::consider(const Face& f, const double* p, double& best) const
{
  // The distances to the face's box and to its plane bound the distance to the face from
  // below (the plane's less a relative 1e-9 for rounding): most faces stop here.
  const double planeDistance =
    std::fabs(f.normal[0] * p[0] + f.normal[1] * p[1] + f.normal[2] * p[2] - f.offset);
  const double lower = std::max(geometry::pointBoxDistance(p, f.box), planeDistance * (1 - 1e-9));
  if (!(f.size - slope_ * lower > best))
    return;
  const double d =
    std::sqrt(geometry::pointTriangleDistanceSquared(p, f.corner, f.corner + 3, f.corner + 6));
  // Beyond its reach a face adds nothing (its cone is under its base size there), wherever
  // the cells happen to list it.
  const double value = f.size - slope_ * d;
  if (value > f.size - slope_ * f.reach)
    best = std::max(best, value);
}

bool BoundarySizeFloor::cellOf(const double* p, std::int64_t* c) const
{
  for (int a = 0; a < 3; ++a)
  {
    const double x = std::floor((p[a] - origin_[a]) / cell_);
    // Keys hold 21 bits per index: beyond that (or NaN) the point is in no cell.
    if (!(x >= 0 && x < (1 << 20)))
      return false;
    c[a] = static_cast<std::int64_t>(x);
  }
  return true;
}

std::uint64_t BoundarySizeFloor::key(std::int64_t i, std::int64_t j, std::int64_t k)
{
  return (static_cast<std::uint64_t>(i) << 42) | (static_cast<std::uint64_t>(j) << 21) |
    static_cast<std::uint64_t>(k);
}

} // namespace tetmesher
