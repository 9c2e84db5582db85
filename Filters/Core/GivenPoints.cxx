#include "GivenPoints.h"

#include "Delaunay.h"
#include "MeshTopology.h"
#include "Predicates.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <sstream>

namespace tetmesher
{
namespace
{

// Tets to start walks from, by a grid over the mesh's box. A walk from the last point's tet
// stops at the boundary where the domain is not convex (a knot, a ring) and locatePoint then
// reads every tet: 10k random points inside knot1.off took 4.7 s. Each cell keeps the last
// tet whose centroid fell in it (about 8 tets per cell), and each insertion notes a tet of its
// new vertex; a seed swallowed since is skipped (a slot reused elsewhere only makes its walk
// longer). Deterministic: the same points give the same seeds.
class WalkSeeds
{
public:
  explicit WalkSeeds(const TetMesh& mesh)
  {
    double hi[3];
    for (int a = 0; a < 3; ++a)
    {
      lo_[a] = std::numeric_limits<double>::max();
      hi[a] = -std::numeric_limits<double>::max();
    }
    for (VertexId v = 0; v < mesh.vertexCount(); ++v)
      for (int a = 0; a < 3; ++a)
      {
        lo_[a] = std::min(lo_[a], mesh.point(v)[a]);
        hi[a] = std::max(hi[a], mesh.point(v)[a]);
      }
    const double cells = std::max(1.0, static_cast<double>(mesh.liveTetCount()) / 8);
    const double extent = std::max({ hi[0] - lo_[0], hi[1] - lo_[1], hi[2] - lo_[2] });
    std::size_t total = 1;
    for (int a = 0; a < 3; ++a)
    {
      // Cells of about equal sides, cbrt(cells) along the longest extent at most.
      const double share = extent > 0 ? (hi[a] - lo_[a]) / extent : 0;
      dims_[a] =
        static_cast<std::int64_t>(std::clamp(std::ceil(share * std::cbrt(cells)), 1.0, 1024.0));
      width_[a] = (hi[a] - lo_[a]) / static_cast<double>(dims_[a]);
      total *= static_cast<std::size_t>(dims_[a]);
    }
    seeds_.assign(total, -1);
    for (TetId t = 0; t < mesh.tetCapacity(); ++t)
    {
      if (mesh.isDeleted(t))
        continue;
      double centroid[3] = { 0, 0, 0 };
      for (int i = 0; i < 4; ++i)
        for (int a = 0; a < 3; ++a)
          centroid[a] += 0.25 * mesh.point(mesh.vertex(t, i))[a];
      note(centroid, t);
    }
  }

  // A live tet near p (in p's cell or one next to it), or -1.
  TetId near(const TetMesh& mesh, const double* p) const
  {
    std::int64_t c[3];
    cellOf(p, c);
    for (std::int64_t di = 0; di < 27; ++di)
    {
      // Offsets 0, -1, +1 per axis: p's own cell first.
      const std::int64_t d[3] = {
        (di / 9 + 1) % 3 - 1, (di / 3 % 3 + 1) % 3 - 1, (di % 3 + 1) % 3 - 1
      };
      std::int64_t q[3];
      bool inside = true;
      for (int a = 0; a < 3; ++a)
      {
        q[a] = c[a] + d[a];
        inside = inside && q[a] >= 0 && q[a] < dims_[a];
      }
      if (!inside)
        continue;
      const TetId t = seeds_[index(q)];
      if (t >= 0 && t < mesh.tetCapacity() && !mesh.isDeleted(t))
        return t;
    }
    return -1;
  }

  void note(const double* p, TetId t)
  {
    std::int64_t c[3];
    cellOf(p, c);
    seeds_[index(c)] = t;
  }

private:
  void cellOf(const double* p, std::int64_t* c) const
  {
    for (int a = 0; a < 3; ++a)
    {
      const double x = width_[a] > 0 ? std::floor((p[a] - lo_[a]) / width_[a]) : 0.0;
      c[a] = static_cast<std::int64_t>(std::clamp(x, 0.0, static_cast<double>(dims_[a] - 1)));
    }
  }
  std::size_t index(const std::int64_t* c) const
  {
    return static_cast<std::size_t>((c[0] * dims_[1] + c[1]) * dims_[2] + c[2]);
  }

  double lo_[3];
  double width_[3];
  std::int64_t dims_[3];
  std::vector<TetId> seeds_;
};

} // namespace

std::string insertGivenPoints(RegionMesh& mesh,
  const std::vector<double>& xyz,
  const std::function<std::string(VertexId)>& nameVertex)
{
  const std::size_t count = xyz.size() / 3;
  if (count == 0)
    return "";
  std::string error = predicates::coordinateRangeError(
    xyz.data(), static_cast<std::int64_t>(count), "interior point");
  if (!error.empty())
    return error;
  auto name = [&](std::size_t i)
  {
    std::ostringstream out;
    out << "interior point " << i << " (" << xyz[3 * i] << ", " << xyz[3 * i + 1] << ", "
        << xyz[3 * i + 2] << ")";
    return out.str();
  };
  TetMesh& tets = mesh.mesh;
  TetId hint = 0;
  while (hint < tets.tetCapacity() && tets.isDeleted(hint))
    ++hint;
  if (hint == tets.tetCapacity())
    return name(0) + " is outside the meshed domain (the mesh has no tetrahedra)";
  std::unique_ptr<InsertionWorkspace, InsertionWorkspaceDeleter> workspace(
    createInsertionWorkspace());
  const VertexId firstNew = tets.vertexCount();
  std::vector<TetId> star;
  std::unique_ptr<WalkSeeds> seeds; // made on the first walk that stops at the boundary
  for (std::size_t i = 0; i < count; ++i)
  {
    const double* p = &xyz[3 * i];
    // The domain's tets only: the exterior and holes were removed, so a point there is found
    // in none. A walk that stops at the boundary starts again from a tet near p (WalkSeeds),
    // then every tet is searched.
    TetId container = walkToPoint(tets, p, hint);
    if (container < 0)
    {
      if (!seeds)
        seeds = std::make_unique<WalkSeeds>(tets);
      const TetId start = seeds->near(tets, p);
      container = start >= 0 ? walkToPoint(tets, p, start) : -1;
      if (container < 0)
        container = locatePoint(tets, p, -1);
    }
    if (container < 0)
      return name(i) + " is outside the meshed domain (outside the surface, or in a hole)";
    const std::int32_t region = mesh.region[static_cast<std::size_t>(container)];
    const VertexId v = tets.addVertex(p[0], p[1], p[2]);
    const InsertResult inserted = insertVertex(tets, v, container, *workspace);
    if (inserted.status != InsertStatus::Inserted)
    {
      tets.coords.resize(3 * static_cast<std::size_t>(v));
      if (inserted.status == InsertStatus::Duplicate)
        return name(i) + " coincides with " +
          (inserted.existing >= firstNew
              ? "interior point " + std::to_string(inserted.existing - firstNew)
              : nameVertex(inserted.existing));
      if (inserted.status == InsertStatus::OnConstraint)
        return name(i) + " lies on the surface (on an input triangle or one of its edges)";
      return name(i) + " is outside the meshed domain (outside the surface, or in a hole)";
    }
    // The cavity never crosses a constrained face (the boundary, interfaces): every tet of the
    // new vertex's star lies in the container's region.
    mesh.region.resize(static_cast<std::size_t>(tets.tetCapacity()), -1);
    starOf(tets, inserted.tet, v, star);
    for (TetId u : star)
      mesh.region[static_cast<std::size_t>(u)] = region;
    hint = inserted.tet;
    if (seeds)
      seeds->note(p, inserted.tet);
  }
  return "";
}

} // namespace tetmesher
