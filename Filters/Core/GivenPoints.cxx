#include "GivenPoints.h"

#include "Delaunay.h"
#include "MeshTopology.h"
#include "Predicates.h"

#include <memory>
#include <sstream>

namespace tetmesher
{

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
  for (std::size_t i = 0; i < count; ++i)
  {
    const double* p = &xyz[3 * i];
    // The domain's tets only: the exterior and holes were removed, so a point there is found
    // in none (the walk falls back to an exhaustive search where the domain is not convex).
    const TetId container = locatePoint(tets, p, hint);
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
  }
  return "";
}

} // namespace tetmesher
