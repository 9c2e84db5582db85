// A whole-pipeline result (meshVolume) seen as the boundary mesher's (meshSurface), so that
// the checks written for the boundary mesh (the fuzzer's, FuzzSurfaceCheck.h, and the core
// tests', Testing/Core/MeshChecks.h) apply to it. Here because the fuzz build sees only this
// directory and Filters/Core.
#pragma once

#include "Mesher.h"
#include "VolumeMesher.h"

#include <cstdint>

namespace tetmesher
{

// Its points beyond the input's are counted as Steiner points (the checks require none on
// the surface).
inline MesherResult asMesherResult(const VolumeMeshResult& v, std::int32_t inputPoints)
{
  MesherResult r;
  r.ok = v.ok;
  r.error = v.error;
  r.points = v.points;
  r.tets = v.tets;
  r.regionIds = v.regionIds;
  r.boundaryFaceTet = v.boundaryFaceTet;
  r.regionCount = v.regionCount;
  r.steinerPoints = static_cast<int>(v.points.size() / 3) - inputPoints;
  return r;
}

} // namespace tetmesher
