#include "Regions.h"

#include "Delaunay.h"
#include "Predicates.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>

namespace tetmesher
{

namespace
{
constexpr std::int32_t kOnSurface = -2;

// The component of the tets containing point p (closed tets: p may lie on a face, an edge or
// a vertex of them), -1 when no tet contains it, kOnSurface when a constrained face does.
// The tets containing p are connected through their faces that contain p, so a search
// across those faces finds them all, and every constrained face that contains p.
std::int32_t componentOfPoint(const TetMesh& mesh,
  const std::vector<std::int32_t>& component,
  const double* p,
  TetId hint)
{
  const TetId start = locatePoint(mesh, p, hint);
  if (start < 0)
    return -1;
  std::vector<TetId> found{ start }, stack{ start };
  while (!stack.empty())
  {
    const TetId t = stack.back();
    stack.pop_back();
    for (int f = 0; f < 4; ++f)
    {
      const VertexId* tv = &mesh.tets[4 * static_cast<std::size_t>(t)];
      if (predicates::orient3d(mesh.point(tv[kFaceVertices[f][0]]),
            mesh.point(tv[kFaceVertices[f][1]]),
            mesh.point(tv[kFaceVertices[f][2]]),
            p) != 0)
        continue;
      if (mesh.isConstrained(t, f))
        return kOnSurface;
      const FaceRef n = mesh.neighbor(t, f);
      if (n != kNoNeighbor && std::find(found.begin(), found.end(), faceTet(n)) == found.end())
      {
        found.push_back(faceTet(n));
        stack.push_back(faceTet(n));
      }
    }
  }
  return component[start];
}
} // namespace

RegionResult classifyRegions(const TetMesh& mesh, const RegionOptions& options)
{
  const TetId capacity = mesh.tetCapacity();
  std::vector<std::int32_t> component(capacity, -1);
  std::vector<char> touchesBox;
  std::vector<std::set<std::int32_t>> adjacent;
  auto isBox = [&](VertexId v)
  { return v >= options.firstBoxVertex && v < options.firstBoxVertex + 8; };

  std::int32_t componentCount = 0;
  std::vector<TetId> stack;
  for (TetId seed = 0; seed < capacity; ++seed)
  {
    if (mesh.isDeleted(seed) || component[seed] >= 0)
      continue;
    const std::int32_t c = componentCount++;
    touchesBox.push_back(0);
    adjacent.emplace_back();
    component[seed] = c;
    stack.push_back(seed);
    while (!stack.empty())
    {
      TetId t = stack.back();
      stack.pop_back();
      for (int i = 0; i < 4; ++i)
      {
        if (isBox(mesh.vertex(t, i)))
          touchesBox[c] = 1;
      }
      for (int f = 0; f < 4; ++f)
      {
        FaceRef n = mesh.neighbor(t, f);
        if (n == kNoNeighbor || mesh.isConstrained(t, f))
          continue;
        TetId u = faceTet(n);
        if (component[u] < 0)
        {
          component[u] = c;
          stack.push_back(u);
        }
      }
    }
  }
  // Components meet across constrained faces; their depth is the BFS distance from the
  // exterior in that graph.
  for (TetId t = 0; t < capacity; ++t)
  {
    if (mesh.isDeleted(t))
      continue;
    for (int f = 0; f < 4; ++f)
    {
      FaceRef n = mesh.neighbor(t, f);
      if (n != kNoNeighbor && mesh.isConstrained(t, f) && component[faceTet(n)] != component[t])
        adjacent[component[t]].insert(component[faceTet(n)]);
    }
  }
  std::vector<int> depth(componentCount, -1);
  std::vector<std::int32_t> queue;
  for (std::int32_t c = 0; c < componentCount; ++c)
  {
    if (touchesBox[c])
    {
      depth[c] = 0;
      queue.push_back(c);
    }
  }
  for (std::size_t k = 0; k < queue.size(); ++k)
  {
    for (std::int32_t d : adjacent[queue[k]])
    {
      if (depth[d] < 0)
      {
        depth[d] = depth[queue[k]] + 1;
        queue.push_back(d);
      }
    }
  }
  RegionResult result;
  // Outside the exact range (or not finite) the walk's predicates would be wrong.
  result.error = predicates::coordinateRangeError(options.holePoints.data(),
    static_cast<std::int64_t>(options.holePoints.size() / 3),
    "hole point");
  if (!result.error.empty())
    return result;
  std::vector<std::int32_t> holeComponent(componentCount, 0); // 1 + the first hole point's index
  // Each walk starts from a live tet (the exhaustive search is the walk's fallback only).
  TetId hint = 0;
  while (hint < capacity && mesh.isDeleted(hint))
    ++hint;
  for (std::size_t i = 0; 3 * i < options.holePoints.size(); ++i)
  {
    const std::int32_t c = componentOfPoint(mesh, component, &options.holePoints[3 * i], hint);
    std::ostringstream where;
    where << "hole point " << i << " (" << options.holePoints[3 * i] << ", "
          << options.holePoints[3 * i + 1] << ", " << options.holePoints[3 * i + 2] << ")";
    if (c == kOnSurface)
      result.error = where.str() + " lies on the input surface";
    else if (c < 0 || touchesBox[c])
      result.error = where.str() + " is outside the input surface";
    if (!result.error.empty())
      return result;
    if (holeComponent[c] == 0)
      holeComponent[c] = static_cast<std::int32_t>(i) + 1;
  }
  std::vector<std::int32_t> regionOf(componentCount, kExteriorTet);
  for (std::int32_t c = 0; c < componentCount; ++c)
  {
    if (depth[c] == 0)
      continue;
    if (holeComponent[c] > 0)
      regionOf[c] = holePointTet(holeComponent[c] - 1);
    else if (options.enclosedShellsAreHoles && depth[c] >= 2 && depth[c] % 2 == 0)
      regionOf[c] = kEnclosedHoleTet;
    else
      regionOf[c] = result.regionCount++;
  }
  // Region points: where each lies, then the attributes.
  std::vector<double> regionPointXyz;
  for (std::size_t i = 0; 4 * i + 3 < options.regionPoints.size(); ++i)
    regionPointXyz.insert(regionPointXyz.end(),
      options.regionPoints.begin() + static_cast<std::ptrdiff_t>(4 * i),
      options.regionPoints.begin() + static_cast<std::ptrdiff_t>(4 * i + 3));
  result.error = predicates::coordinateRangeError(
    regionPointXyz.data(), static_cast<std::int64_t>(regionPointXyz.size() / 3), "region point");
  if (!result.error.empty())
    return result;
  if (!regionPointXyz.empty())
  {
    // Per region, 1 + the index of its first region point (0: none).
    std::vector<std::size_t> given(static_cast<std::size_t>(result.regionCount), 0);
    result.regionAttribute.assign(static_cast<std::size_t>(result.regionCount), 0.0);
    double largest = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; 3 * i < regionPointXyz.size(); ++i)
    {
      const double* x = &regionPointXyz[3 * i];
      const double attribute = options.regionPoints[4 * i + 3];
      const std::int32_t c = componentOfPoint(mesh, component, x, hint);
      std::ostringstream where;
      where << "region point " << i << " (" << x[0] << ", " << x[1] << ", " << x[2] << ")";
      const double maxSize = i < options.regionMaxSizes.size() ? options.regionMaxSizes[i] : 0.0;
      if (!std::isfinite(attribute))
        result.error = where.str() + " has a non-finite attribute";
      else if (!std::isfinite(maxSize))
        result.error = where.str() + " has a non-finite size";
      else if (c == kOnSurface)
        result.error = where.str() + " lies on the input surface";
      else if (c < 0 || touchesBox[c])
        result.error = where.str() + " is outside the input surface";
      else if (regionOf[c] < 0)
        result.error = where.str() + " lies in a hole (" +
          (regionOf[c] == kEnclosedHoleTet
              ? std::string("an enclosed shell made a hole")
              : "the region of hole point " + std::to_string(-3 - regionOf[c])) +
          ")";
      if (!result.error.empty())
      {
        result.regionAttribute.clear();
        result.regionMaxSize.clear();
        return result;
      }
      largest = std::max(largest, attribute);
      const auto r = static_cast<std::size_t>(regionOf[c]);
      if (!given[r])
      {
        given[r] = i + 1;
        result.regionAttribute[r] = attribute;
        if (maxSize > 0)
        {
          result.regionMaxSize.resize(static_cast<std::size_t>(result.regionCount), 0.0);
          result.regionMaxSize[r] = maxSize;
        }
      }
      else
      {
        const double regionSize = r < result.regionMaxSize.size() ? result.regionMaxSize[r] : 0;
        if (attribute != result.regionAttribute[r] || std::max(maxSize, 0.0) != regionSize)
          result.regionNotes += where.str() + " lies in the region of region point " +
            std::to_string(given[r] - 1) +
            ", whose attribute and size apply there: its own are not used\n";
      }
    }
    double next = largest;
    for (std::size_t r = 0; r < given.size(); ++r)
      if (!given[r])
        result.regionAttribute[r] = ++next;
  }
  result.tetRegion.assign(capacity, kExteriorTet);
  for (TetId t = 0; t < capacity; ++t)
  {
    if (component[t] >= 0)
      result.tetRegion[t] = regionOf[component[t]];
  }
  return result;
}

} // namespace tetmesher
