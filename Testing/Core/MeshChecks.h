// Exact, independent checks of a MesherResult against its input surface, for the mesher's
// tests: GMP rationals decide orientation, volumes and point-on-triangle, so a test cannot
// pass by sharing a bug with the predicates under test.
#pragma once

#include "../Fuzz/PipelineAsMesherResult.h"
#include "Mesher.h"
#include "SurfaceGenerators.h"
#include "VolumeMesher.h"

#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace tetmesher
{
namespace testing
{

// 6 x signed volume of (a,b,c,d) = det[b-a; c-a; d-a], exact.
inline mpq_class det6(const double* a, const double* b, const double* c, const double* d)
{
  mpq_class u[3], v[3], w[3];
  for (int k = 0; k < 3; ++k)
  {
    u[k] = mpq_class(b[k]) - mpq_class(a[k]);
    v[k] = mpq_class(c[k]) - mpq_class(a[k]);
    w[k] = mpq_class(d[k]) - mpq_class(a[k]);
  }
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
    u[2] * (v[0] * w[1] - v[1] * w[0]);
}

// 6 x volume enclosed by outward triangles, weighted by sign[t] (+1, -1 or 0).
inline mpq_class enclosedVolume6(const Surface& s, const std::vector<int>& sign)
{
  static const double origin[3] = { 0, 0, 0 };
  mpq_class sum = 0;
  for (std::int32_t t = 0; t < s.triangleCount(); ++t)
  {
    if (sign[t] == 0)
      continue;
    const std::int32_t* v = &s.triangles[3 * t];
    mpq_class d = det6(origin, &s.points[3 * v[0]], &s.points[3 * v[1]], &s.points[3 * v[2]]);
    sum += sign[t] > 0 ? d : mpq_class(-d);
  }
  return sum;
}

// Point x on the closed triangle pqr, exactly.
inline bool onTriangleExact(const double* x, const double* p, const double* q, const double* r)
{
  for (int k = 0; k < 3; ++k)
  {
    if (x[k] < std::min({ p[k], q[k], r[k] }) || x[k] > std::max({ p[k], q[k], r[k] }))
      return false;
  }
  if (sgn(det6(p, q, r, x)) != 0)
    return false;
  // Coplanar: inside iff the three sub-triangle normals do not oppose the triangle's normal.
  mpq_class n[3], e1[3], e2[3];
  for (int k = 0; k < 3; ++k)
  {
    e1[k] = mpq_class(q[k]) - mpq_class(p[k]);
    e2[k] = mpq_class(r[k]) - mpq_class(p[k]);
  }
  n[0] = e1[1] * e2[2] - e1[2] * e2[1];
  n[1] = e1[2] * e2[0] - e1[0] * e2[2];
  n[2] = e1[0] * e2[1] - e1[1] * e2[0];
  const double* tri[3] = { p, q, r };
  for (int i = 0; i < 3; ++i)
  {
    const double* a = tri[i];
    const double* b = tri[(i + 1) % 3];
    mpq_class f[3], g[3];
    for (int k = 0; k < 3; ++k)
    {
      f[k] = mpq_class(b[k]) - mpq_class(a[k]);
      g[k] = mpq_class(x[k]) - mpq_class(a[k]);
    }
    mpq_class c0 = f[1] * g[2] - f[2] * g[1], c1 = f[2] * g[0] - f[0] * g[2],
              c2 = f[0] * g[1] - f[1] * g[0];
    if (sgn(c0 * n[0] + c1 * n[1] + c2 * n[2]) < 0)
      return false;
  }
  return true;
}

// Returns "" when every invariant of the mesher's contract holds, else what failed.
inline std::string checkMesh(const Surface& s,
  const MesherResult& r,
  const std::vector<int>& volumeSign,
  int expectedRegions)
{
  const std::int32_t n = s.pointCount();
  if (!r.ok)
    return "meshing failed: " + r.error;
  const std::int32_t nv = static_cast<std::int32_t>(r.points.size() / 3);
  if (nv < n || std::memcmp(r.points.data(), s.points.data(), sizeof(double) * 3 * n) != 0)
    return "input points are not bit-identical at ids 0..n-1";
  if (r.steinerPoints != nv - n)
    return "steinerPoints does not match the point count";
  if (r.regionCount != expectedRegions)
    return "expected " + std::to_string(expectedRegions) + " regions, got " +
      std::to_string(r.regionCount);
  const std::size_t tetCount = r.tets.size() / 4;
  if (r.regionIds.size() != tetCount)
    return "regionIds size";
  mpq_class volume = 0;
  std::map<std::array<std::int32_t, 3>, std::vector<std::int32_t>> faceRegions;
  for (std::size_t t = 0; t < tetCount; ++t)
  {
    const std::int32_t* v = &r.tets[4 * t];
    for (int i = 0; i < 4; ++i)
    {
      if (v[i] < 0 || v[i] >= nv)
        return "tet " + std::to_string(t) + " has an invalid vertex id";
    }
    if (r.regionIds[t] < 0 || r.regionIds[t] >= r.regionCount)
      return "tet " + std::to_string(t) + " has an invalid region id";
    // Shewchuk's orient3d(a,b,c,d) > 0 is det[a-d; b-d; c-d] > 0, i.e. det6(d,a,b,c) > 0.
    mpq_class d =
      det6(&r.points[3 * v[3]], &r.points[3 * v[0]], &r.points[3 * v[1]], &r.points[3 * v[2]]);
    if (sgn(d) <= 0)
      return "tet " + std::to_string(t) + " is not positively oriented";
    volume += d;
    static const int faces[4][3] = { { 1, 2, 3 }, { 0, 2, 3 }, { 0, 1, 3 }, { 0, 1, 2 } };
    for (auto& f : faces)
    {
      std::array<std::int32_t, 3> key = { v[f[0]], v[f[1]], v[f[2]] };
      std::sort(key.begin(), key.end());
      faceRegions[key].push_back(r.regionIds[t]);
    }
  }
  std::set<std::array<std::int32_t, 3>> boundary, input;
  for (auto& [key, regions] : faceRegions)
  {
    if (regions.size() > 2)
      return "a face is shared by more than two tets";
    if (regions.size() == 1 || regions[0] != regions[1])
      boundary.insert(key);
  }
  for (std::int32_t t = 0; t < s.triangleCount(); ++t)
  {
    std::array<std::int32_t, 3> key = {
      s.triangles[3 * t], s.triangles[3 * t + 1], s.triangles[3 * t + 2]
    };
    std::sort(key.begin(), key.end());
    input.insert(key);
    std::int32_t ref = r.boundaryFaceTet.at(t);
    static const int kFace[4][3] = { { 1, 3, 2 }, { 0, 2, 3 }, { 0, 3, 1 }, { 0, 1, 2 } };
    std::array<std::int32_t, 3> face;
    for (int k = 0; k < 3; ++k)
      face[k] = r.tets[4 * (ref >> 2) + kFace[ref & 3][k]];
    std::sort(face.begin(), face.end());
    if (face != key)
      return "boundaryFaceTet of triangle " + std::to_string(t) + " is wrong";
  }
  if (boundary != input)
  {
    std::size_t extra = 0, missing = 0;
    for (auto& f : boundary)
      extra += !input.count(f);
    for (auto& f : input)
      missing += !boundary.count(f);
    return "boundary faces differ from the input triangles: " + std::to_string(extra) + " extra, " +
      std::to_string(missing) + " missing";
  }
  for (std::int32_t v = n; v < nv; ++v)
  {
    for (std::int32_t t = 0; t < s.triangleCount(); ++t)
    {
      const std::int32_t* tri = &s.triangles[3 * t];
      if (onTriangleExact(
            &r.points[3 * v], &s.points[3 * tri[0]], &s.points[3 * tri[1]], &s.points[3 * tri[2]]))
        return "Steiner point " + std::to_string(v) + " lies on input triangle " +
          std::to_string(t);
    }
  }
  mpq_class expected = enclosedVolume6(s, volumeSign);
  if (volume != expected)
    return "tet volumes (" + std::to_string(volume.get_d() / 6) +
      ") differ from the enclosed volume (" + std::to_string(expected.get_d() / 6) + ")";
  return "";
}

} // namespace testing
} // namespace tetmesher
