#include "SurfaceQualityBound.h"

#include "TetQuality.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace tetmesher
{

double triangleQualityBound(const double* a, const double* b, const double* c)
{
  double u[3], v[3], w[3];
  for (int k = 0; k < 3; ++k)
  {
    u[k] = b[k] - a[k];
    v[k] = c[k] - a[k];
    w[k] = c[k] - b[k];
  }
  const double cross[3] = {
    u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]
  };
  const double twiceArea =
    std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]);
  auto squared = [](const double* x) { return x[0] * x[0] + x[1] * x[1] + x[2] * x[2]; };
  const double longest = std::max({ squared(u), squared(v), squared(w) });
  if (!(longest > 0) || !std::isfinite(longest) || !std::isfinite(twiceArea))
    return 0;
  return kQualityScale * 0.5 * twiceArea / longest;
}

SurfaceQualityBound surfaceQualityBound(const double* points,
  const std::int32_t* triangles,
  std::int32_t triangleCount)
{
  SurfaceQualityBound result;
  for (std::int32_t t = 0; t < triangleCount; ++t)
  {
    const std::int32_t* v = triangles + 3 * static_cast<std::size_t>(t);
    const double bound = triangleQualityBound(points + 3 * static_cast<std::size_t>(v[0]),
      points + 3 * static_cast<std::size_t>(v[1]),
      points + 3 * static_cast<std::size_t>(v[2]));
    if (bound < result.bound)
    {
      result.bound = bound;
      result.triangle = t;
    }
  }
  return result;
}

} // namespace tetmesher
