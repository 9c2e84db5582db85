#include "Regions.h"

#include <algorithm>
#include <set>

namespace tetmesher
{

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
  std::vector<std::int32_t> regionOf(componentCount, -1);
  for (std::int32_t c = 0; c < componentCount; ++c)
  {
    bool hole = options.enclosedShellsAreHoles && depth[c] >= 2 && depth[c] % 2 == 0;
    if (depth[c] != 0 && !hole)
      regionOf[c] = result.regionCount++;
  }
  result.tetRegion.assign(capacity, -1);
  for (TetId t = 0; t < capacity; ++t)
  {
    if (component[t] >= 0)
      result.tetRegion[t] = regionOf[component[t]];
  }
  return result;
}

} // namespace tetmesher
