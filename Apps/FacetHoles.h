// A TetGen .poly facet with hole points, or with polygons inside a polygon: an outer polygon,
// polygons inside it (one level), and points that name the parts to leave out. What is kept becomes
// polygons that the ear clipper (PolygonTriangulation.h) can cut: each inner polygon without a hole
// point as it is, and the part between the outer polygon and the inner ones, unless a hole point
// lies there, as one polygon joined to each inner polygon by a slit (walked twice, once each way),
// which the ear clipper handles. Inside/outside and the slits are decided with exact 2D
// orientations in the plane that drops the largest component of the outer polygon's normal.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tetmesher
{
namespace cli
{

// points: 3 doubles per point; polygons: point ids (3 or more each); holes: the facet's hole
// points. Returns the polygons to keep (the outer one's orientation), or throws nothing and
// sets `error` (what is wrong, for the reader's message) when the facet is not of that form:
// no polygon holding all the others, polygons nested two deep, a hole point outside the facet
// or on one of its polygons, or no slit found.
std::vector<std::vector<std::int64_t>> FacetWithoutHoles(const std::vector<double>& points,
  const std::vector<std::vector<std::int64_t>>& polygons,
  const std::vector<std::array<double, 3>>& holes,
  std::string& error);

// True when a corner of one polygon lies strictly inside another (decided exactly, in the
// plane of the largest): the facet is one polygon around others, which FacetWithoutHoles cuts
// (with no hole points: the part around the inner polygons and each inner polygon, as TetGen
// keeps a facet's polygons without holes as constraints inside it), not polygons side by side.
bool PolygonsNested(const std::vector<double>& points,
  const std::vector<std::vector<std::int64_t>>& polygons);

} // namespace cli
} // namespace tetmesher
