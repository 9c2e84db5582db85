// Input diagnosis: one small hand-built surface per defect with its exact expected diagnosis,
// clean surfaces (single and multi-material) that must pass, the corpus files in Data/, and a
// timing on a large sphere.
#include "SurfaceDiagnosis.h"
#include "TriangleIntersection.h"
#include "UnusedPoints.h"

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace tetmesher;

namespace
{

struct Surface
{
  std::vector<double> pts;
  std::vector<std::int32_t> tris;

  std::int32_t addPoint(double x, double y, double z)
  {
    pts.insert(pts.end(), { x, y, z });
    return static_cast<std::int32_t>(pts.size() / 3 - 1);
  }
  std::int32_t addTri(std::int32_t a, std::int32_t b, std::int32_t c)
  {
    tris.insert(tris.end(), { a, b, c });
    return static_cast<std::int32_t>(tris.size() / 3 - 1);
  }
  std::int32_t pointCount() const { return static_cast<std::int32_t>(pts.size() / 3); }
  std::int32_t triCount() const { return static_cast<std::int32_t>(tris.size() / 3); }
  SurfaceDiagnosis diagnose() const
  {
    return diagnoseSurface(pts.data(), pointCount(), tris.data(), triCount());
  }
  double volume() const
  {
    double v = 0;
    for (std::size_t t = 0; t < tris.size(); t += 3)
    {
      const double* a = &pts[3 * tris[t]];
      const double* b = &pts[3 * tris[t + 1]];
      const double* c = &pts[3 * tris[t + 2]];
      v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
             a[2] * (b[0] * c[1] - b[1] * c[0])) /
        6;
    }
    return v;
  }
};

// Unit cube, point id = x + 2y + 4z, 12 outward triangles (ids in comments).
Surface cube()
{
  Surface s;
  for (int i = 0; i < 8; ++i)
    s.addPoint(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  s.addTri(0, 4, 6); // 0  x=0
  s.addTri(0, 6, 2); // 1
  s.addTri(1, 3, 7); // 2  x=1
  s.addTri(1, 7, 5); // 3
  s.addTri(0, 1, 5); // 4  y=0
  s.addTri(0, 5, 4); // 5
  s.addTri(2, 6, 7); // 6  y=1
  s.addTri(2, 7, 3); // 7
  s.addTri(0, 2, 3); // 8  z=0
  s.addTri(0, 3, 1); // 9
  s.addTri(4, 5, 7); // 10 z=1
  s.addTri(4, 7, 6); // 11
  return s;
}

Surface icosphere(int levels)
{
  Surface s;
  const double t = (1 + std::sqrt(5.0)) / 2;
  const double v[12][3] = { { -1, t, 0 },
    { 1, t, 0 },
    { -1, -t, 0 },
    { 1, -t, 0 },
    { 0, -1, t },
    { 0, 1, t },
    { 0, -1, -t },
    { 0, 1, -t },
    { t, 0, -1 },
    { t, 0, 1 },
    { -t, 0, -1 },
    { -t, 0, 1 } };
  for (const auto& p : v)
  {
    const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    s.addPoint(p[0] / n, p[1] / n, p[2] / n);
  }
  std::vector<std::int32_t> f = { 0,
    11,
    5,
    0,
    5,
    1,
    0,
    1,
    7,
    0,
    7,
    10,
    0,
    10,
    11,
    1,
    5,
    9,
    5,
    11,
    4,
    11,
    10,
    2,
    10,
    7,
    6,
    7,
    1,
    8,
    3,
    9,
    4,
    3,
    4,
    2,
    3,
    2,
    6,
    3,
    6,
    8,
    3,
    8,
    9,
    4,
    9,
    5,
    2,
    4,
    11,
    6,
    2,
    10,
    8,
    6,
    7,
    9,
    8,
    1 };
  for (int l = 0; l < levels; ++l)
  {
    std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> mid;
    auto midpoint = [&](std::int32_t a, std::int32_t b)
    {
      auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if (it != mid.end())
        return it->second;
      double m[3];
      for (int k = 0; k < 3; ++k)
        m[k] = (s.pts[3 * a + k] + s.pts[3 * b + k]) / 2;
      const double n = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
      const std::int32_t id = s.addPoint(m[0] / n, m[1] / n, m[2] / n);
      mid[key] = id;
      return id;
    };
    std::vector<std::int32_t> g;
    for (std::size_t i = 0; i < f.size(); i += 3)
    {
      const std::int32_t a = f[i], b = f[i + 1], c = f[i + 2];
      const std::int32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      g.insert(g.end(), { a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca });
    }
    f.swap(g);
  }
  s.tris = f;
  return s;
}

// Multi-material voxel surface: unit cubes at integer positions; a face between two cubes of
// the list appears once (oriented out of the earlier cube), every other face once, outward.
Surface voxels(const std::vector<std::array<int, 3>>& cubes)
{
  Surface s;
  std::map<std::array<int, 3>, std::int32_t> ids;
  auto id = [&](int x, int y, int z)
  {
    const std::array<int, 3> key = { x, y, z };
    auto it = ids.find(key);
    if (it != ids.end())
      return it->second;
    return ids[key] = s.addPoint(x, y, z);
  };
  for (std::size_t c = 0; c < cubes.size(); ++c)
  {
    const auto& p = cubes[c];
    for (int axis = 0; axis < 3; ++axis)
    {
      for (int dir = -1; dir <= 1; dir += 2)
      {
        std::array<int, 3> q = p;
        q[axis] += dir;
        const auto other = std::find(cubes.begin(), cubes.end(), q);
        if (other != cubes.end() && static_cast<std::size_t>(other - cubes.begin()) < c)
          continue;
        // Quad on the face, counterclockwise seen from outside.
        const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
        std::array<int, 3> corner[4];
        const int du[4] = { 0, 1, 1, 0 }, dv[4] = { 0, 0, 1, 1 };
        for (int k = 0; k < 4; ++k)
        {
          corner[k] = p;
          corner[k][axis] += dir > 0 ? 1 : 0;
          corner[k][a1] += dir > 0 ? du[k] : dv[k];
          corner[k][a2] += dir > 0 ? dv[k] : du[k];
        }
        std::int32_t v[4];
        for (int k = 0; k < 4; ++k)
          v[k] = id(corner[k][0], corner[k][1], corner[k][2]);
        s.addTri(v[0], v[1], v[2]);
        s.addTri(v[0], v[2], v[3]);
      }
    }
  }
  return s;
}

void expectRecord(const DefectRecord& r,
  SurfaceDefect kind,
  std::vector<std::int32_t> points,
  std::vector<std::int32_t> tris)
{
  EXPECT_EQ(static_cast<int>(r.kind), static_cast<int>(kind)) << defectLabel(kind);
  EXPECT_EQ(r.pointIds, points) << defectLabel(kind);
  EXPECT_EQ(r.triangleIds, tris) << defectLabel(kind);
}

// --- Minimal readers for the corpus files (.off, .stl). ---
bool readOff(const std::string& path, Surface& s)
{
  // Line-based: header (OFF, COFF, NOFF...; counts on it or on the next line), one vertex per
  // line (extra columns such as colours ignored), one face per line (polygons as fans).
  std::ifstream in(path);
  if (!in)
    return false;
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line))
  {
    const auto hash = line.find('#');
    if (hash != std::string::npos)
      line.resize(hash);
    if (line.find_first_not_of(" \t\r") != std::string::npos)
      lines.push_back(line);
  }
  std::size_t next = 0;
  if (lines.empty())
    return false;
  std::istringstream header(lines[next++]);
  std::string tok;
  header >> tok;
  long nv = -1, nf = -1;
  if (tok.size() < 3 || tok.compare(tok.size() - 3, 3, "OFF") != 0)
    nv = std::stol(tok);
  else if (!(header >> nv) && next < lines.size())
  {
    std::istringstream counts(lines[next++]);
    counts >> nv;
    counts >> nf;
  }
  if (nf < 0)
    header >> nf;
  if (nv < 0 || nf < 0 || lines.size() < next + static_cast<std::size_t>(nv + nf))
    return false;
  for (long v = 0; v < nv; ++v)
  {
    std::istringstream ls(lines[next++]);
    double x, y, z;
    ls >> x >> y >> z;
    s.addPoint(x, y, z);
  }
  for (long f = 0; f < nf; ++f)
  {
    std::istringstream ls(lines[next++]);
    long n = 0;
    ls >> n;
    std::vector<std::int32_t> ids(static_cast<std::size_t>(std::max(n, 0L)));
    for (auto& id : ids)
      ls >> id;
    for (long k = 1; k + 1 < n; ++k)
      s.addTri(ids[0], ids[k], ids[k + 1]);
  }
  return true;
}

bool readStl(const std::string& path, Surface& s)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
    return false;
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::map<std::array<double, 3>, std::int32_t> ids;
  auto point = [&](double x, double y, double z)
  {
    const std::array<double, 3> key = { x, y, z };
    auto it = ids.find(key);
    if (it != ids.end())
      return it->second;
    const std::int32_t id = s.addPoint(x, y, z);
    ids[key] = id;
    return id;
  };
  std::uint32_t n = 0;
  if (data.size() >= 84)
    std::memcpy(&n, data.data() + 80, 4);
  if (data.size() >= 84 && data.size() == 84 + 50 * static_cast<std::size_t>(n))
  {
    for (std::uint32_t t = 0; t < n; ++t)
    {
      std::int32_t v[3];
      for (int k = 0; k < 3; ++k)
      {
        float c[3];
        std::memcpy(c, data.data() + 84 + 50 * static_cast<std::size_t>(t) + 12 + 12 * k, 12);
        v[k] = point(c[0], c[1], c[2]);
      }
      s.addTri(v[0], v[1], v[2]);
    }
    return true;
  }
  std::istringstream text(data);
  std::string tok;
  std::vector<std::int32_t> face;
  while (text >> tok)
  {
    if (tok == "vertex")
    {
      double x, y, z;
      text >> x >> y >> z;
      face.push_back(point(x, y, z));
    }
    else if (tok == "endloop")
    {
      if (face.size() == 3)
        s.addTri(face[0], face[1], face[2]);
      face.clear();
    }
  }
  return s.triCount() > 0;
}

bool readSurface(const std::string& path, Surface& s)
{
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".off")
    return readOff(path, s);
  if (ext == ".stl")
    return readStl(path, s);
  return false;
}

} // namespace

TEST(SurfaceDiagnosis, EmptyInput)
{
  const SurfaceDiagnosis d = diagnoseSurface(nullptr, 0, nullptr, 0);
  ASSERT_EQ(d.defects.size(), 1u);
  EXPECT_EQ(d.defects[0].kind, SurfaceDefect::Empty);
  EXPECT_FALSE(d.ok());
  const double p[3] = { 0, 0, 0 };
  EXPECT_EQ(diagnoseSurface(p, 1, nullptr, 0).count(SurfaceDefect::Empty), 1);
}

TEST(SurfaceDiagnosis, CleanCube)
{
  const Surface s = cube();
  EXPECT_DOUBLE_EQ(s.volume(), 1.0);
  const SurfaceDiagnosis d = s.diagnose();
  EXPECT_TRUE(d.ok()) << d.summary();
  EXPECT_TRUE(d.defects.empty());
  EXPECT_EQ(d.summary(), "no defects");
}

TEST(SurfaceDiagnosis, CleanIcosphere)
{
  const Surface s = icosphere(3);
  EXPECT_GT(s.volume(), 4.0);
  const SurfaceDiagnosis d = s.diagnose();
  EXPECT_TRUE(d.defects.empty()) << d.summary();
}

TEST(SurfaceDiagnosis, TwoCubesSharingAFaceAreValidMultiMaterial)
{
  // Cube A = [0,1]^3, cube B = [1,2]x[0,1]^2; the face x=1 appears once (oriented out of A):
  // its 4 boundary edges carry 3 triangles each.
  Surface s = cube();
  std::int32_t id[8];
  for (int i = 0; i < 8; ++i)
    id[i] = (i & 1) ? s.addPoint(2, (i >> 1) & 1, (i >> 2) & 1) : (i | 1);
  // B's faces except x=1 (its x=0 side), with B's outward orientation.
  const int faces[10][3] = { { 1, 3, 7 },
    { 1, 7, 5 },
    { 0, 1, 5 },
    { 0, 5, 4 },
    { 2, 6, 7 },
    { 2, 7, 3 },
    { 0, 2, 3 },
    { 0, 3, 1 },
    { 4, 5, 7 },
    { 4, 7, 6 } };
  for (const auto& f : faces)
    s.addTri(id[f[0]], id[f[1]], id[f[2]]);
  const SurfaceDiagnosis d = s.diagnose();
  EXPECT_TRUE(d.defects.empty()) << d.summary();
}

TEST(SurfaceDiagnosis, VoxelMultiMaterialConfigurationsAreValid)
{
  const Surface one = voxels({ { 0, 0, 0 } });
  EXPECT_DOUBLE_EQ(one.volume(), 1.0);
  EXPECT_TRUE(one.diagnose().defects.empty()) << one.diagnose().summary();
  const std::vector<std::vector<std::array<int, 3>>> cases = {
    { { 0, 0, 0 }, { 1, 0, 0 } },                           // shared face
    { { 0, 0, 0 }, { 1, 1, 0 } },                           // shared edge only
    { { 0, 0, 0 }, { 1, 1, 1 } },                           // shared vertex only
    { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 } },              // L: 4 triangles on an edge
    { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 } }, // 2x2 block
    { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 }, { 0, 0, 1 } }, // block + one on top
    { { 0, 0, 0 }, { 2, 0, 0 }, { 1, 0, 0 } },                           // a row, middle last
  };
  for (const auto& c : cases)
  {
    const Surface s = voxels(c);
    const SurfaceDiagnosis d = s.diagnose();
    EXPECT_TRUE(d.defects.empty()) << c.size() << " cubes: " << d.summary();
  }
}

TEST(SurfaceDiagnosis, VoxelWithMissingFaceIsOpen)
{
  // L of three cubes with the top face of the corner cube removed: 3 of its edges become open
  // (the 4th, on the face shared with the middle cube, goes from 3 triangles to 2). The corner
  // cube no longer bounds a region, so the 3 edges where its walls meet the middle cube's
  // faces are reported as non-manifold too.
  Surface s = voxels({ { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 } });
  s.tris.resize(s.tris.size() - 6); // the last face of the last cube (+z of (1,1,0))
  const SurfaceDiagnosis d = s.diagnose();
  EXPECT_EQ(d.count(SurfaceDefect::OpenEdge), 3) << d.summary();
  EXPECT_EQ(d.count(SurfaceDefect::NonManifoldEdge), 3) << d.summary();
  EXPECT_EQ(d.defects.size(), 6u) << d.summary();
  EXPECT_FALSE(d.ok());
}

TEST(SurfaceDiagnosis, SortAroundEdge)
{
  const double u[3] = { 0, 0, 0 }, v[3] = { 0, 0, 1 };
  const double w0[3] = { 1, 0, 0 }, w1[3] = { 0, -1, 0.3 }, w2[3] = { -1, 0, 5 };
  const double w3[3] = { 1, 1, 0 }, w4[3] = { 0, 1, -2 }, w5[3] = { 2, 0, 3 };
  const double w6[3] = { 1, -1e-300, 0 };
  const std::vector<const double*> w = { w0, w1, w2, w3, w4, w5, w6 };
  // Counterclockwise about +z from angle 0: 0 (w0, w5), 45, 90, 180, 270, just below 360.
  const std::vector<std::size_t> expected = { 0, 5, 3, 4, 2, 1, 6 };
  EXPECT_EQ(sortAroundEdge(u, v, w), expected);
  // Reversed axis: clockwise.
  const std::vector<std::size_t> reversed = { 0, 5, 6, 1, 2, 4, 3 };
  EXPECT_EQ(sortAroundEdge(v, u, w), reversed);
}

TEST(SurfaceDiagnosis, TwoCubesEachWithItsOwnCopyOfTheSharedFace)
{
  // The common mistake for multi-material input: the interface written twice (once per cube,
  // opposite orientations). Reported as duplicated triangles, nothing else.
  Surface s = voxels({ { 0, 0, 0 } });
  const Surface b = voxels({ { 1, 0, 0 } });
  std::map<std::array<double, 3>, std::int32_t> ids;
  for (std::int32_t i = 0; i < s.pointCount(); ++i)
    ids[{ s.pts[3 * i], s.pts[3 * i + 1], s.pts[3 * i + 2] }] = i;
  std::vector<std::int32_t> map(b.pointCount());
  for (std::int32_t i = 0; i < b.pointCount(); ++i)
  {
    const std::array<double, 3> p = { b.pts[3 * i], b.pts[3 * i + 1], b.pts[3 * i + 2] };
    map[i] = ids.count(p) ? ids[p] : (ids[p] = s.addPoint(p[0], p[1], p[2]));
  }
  for (std::int32_t t : b.tris)
    s.tris.push_back(map[t]);
  const SurfaceDiagnosis d = s.diagnose();
  EXPECT_EQ(d.count(SurfaceDefect::DuplicateTriangle), 2) << d.summary();
  EXPECT_EQ(d.defects.size(), 2u) << d.summary();
}

TEST(SurfaceDiagnosis, CubeSplitByInternalWallIsValid)
{
  // The diagonal section x=y (points 0,3,7,4) splits the cube into two prisms: its boundary
  // edges carry 3 triangles, and each triangle separates two different regions.
  Surface s = cube();
  s.addTri(0, 3, 7);
  s.addTri(0, 7, 4);
  const SurfaceDiagnosis d = s.diagnose();
  EXPECT_TRUE(d.defects.empty()) << d.summary();
}

TEST(SurfaceDiagnosis, InvalidPointId)
{
  Surface s = cube();
  s.addTri(0, 1, 99);
  const SurfaceDiagnosis d = s.diagnose();
  ASSERT_EQ(d.defects.size(), 1u) << d.summary();
  expectRecord(d.defects[0], SurfaceDefect::InvalidPointId, { 0, 1, 99 }, { 12 });
}

TEST(SurfaceDiagnosis, NonFiniteCoordinates)
{
  Surface s = cube();
  s.pts[3 * 5] = std::numeric_limits<double>::quiet_NaN();
  s.pts[3 * 6 + 2] = -std::numeric_limits<double>::infinity();
  const SurfaceDiagnosis d = s.diagnose();
  ASSERT_EQ(d.defects.size(), 2u) << d.summary();
  expectRecord(d.defects[0], SurfaceDefect::NonFiniteCoordinate, { 5 }, {});
  expectRecord(d.defects[1], SurfaceDefect::NonFiniteCoordinate, { 6 }, {});
}

// Finite coordinates that the predicates cannot decide exactly (overflow beyond 1e50,
// underflow below 1e-40) are named like non-finite ones, and their triangles are kept out of
// the geometric checks.
TEST(SurfaceDiagnosis, CoordinatesBeyondTheExactRange)
{
  Surface s = cube();
  s.pts[3 * 2 + 1] = 7.8e143;
  s.pts[3 * 4] = -1e-45;
  s.pts[3 * 5] = std::numeric_limits<double>::quiet_NaN();
  // The ends of the range are exact. (Point 6 is out of all proportion, but every triangle
  // on it also has an unusable point, so the proportion check does not see it.)
  s.pts[3 * 6] = 1e50;
  s.pts[3 * 6 + 1] = -1e-40;
  const SurfaceDiagnosis d = s.diagnose();
  ASSERT_EQ(d.defects.size(), 3u) << d.summary();
  expectRecord(d.defects[0], SurfaceDefect::NonFiniteCoordinate, { 5 }, {});
  expectRecord(d.defects[1], SurfaceDefect::CoordinateOutOfRange, { 2 }, {});
  expectRecord(d.defects[2], SurfaceDefect::CoordinateOutOfRange, { 4 }, {});
  EXPECT_NE(d.summary().find("2 points with coordinates too large or too small to decide exactly"),
    std::string::npos)
    << d.summary();
}

TEST(SurfaceDiagnosis, PointOutOfAllProportion)
{
  // A unit cube with one corner pulled far out (as a corrupted coordinate would): valid for
  // the exact checks, but no double lies between the scales of its edges.
  Surface s = cube();
  s.pts[3 * 6 + 2] = 2e15; // 2e15 x the shortest edge (1) from the median
  SurfaceDiagnosis d = s.diagnose();
  ASSERT_EQ(d.defects.size(), 1u) << d.summary();
  expectRecord(d.defects[0], SurfaceDefect::OutlyingPoint, { 6 }, {});
  EXPECT_FALSE(d.ok());
  EXPECT_NE(d.summary().find("out of all proportion"), std::string::npos) << d.summary();
  // Up to the bound it is a (thin) surface like any other; scaling never matters.
  s.pts[3 * 6 + 2] = 5e14;
  EXPECT_TRUE(s.diagnose().ok()) << s.diagnose().summary();
  Surface tiny = cube();
  for (double& x : tiny.pts)
    x *= 1e-30;
  EXPECT_TRUE(tiny.diagnose().ok()) << tiny.diagnose().summary();
}

TEST(SurfaceDiagnosis, DuplicatePointUnusedIsLeftOut)
{
  // An unused copy of a point is no defect: the mesh leaves it out (a warning says so).
  Surface s = cube();
  s.addPoint(1, 1, 0); // same as point 3
  const SurfaceDiagnosis d = s.diagnose();
  ASSERT_EQ(d.defects.size(), 1u) << d.summary();
  expectRecord(d.defects[0], SurfaceDefect::UnusedPointLeftOut, { 8 }, {});
  EXPECT_TRUE(d.ok());
}

TEST(SurfaceDiagnosis, UnusedPointIsOnlyAWarning)
{
  Surface s = cube();
  s.addPoint(0.5, 0.5, 0.5);
  const SurfaceDiagnosis d = s.diagnose();
  ASSERT_EQ(d.defects.size(), 1u) << d.summary();
  expectRecord(d.defects[0], SurfaceDefect::UnusedPoint, { 8 }, {});
  EXPECT_TRUE(d.ok());
}

// Unused points on the surface (exactly in a triangle, on an edge or at a corner) and copies of
// an unused point are left out of the mesh, named apart with the lowest triangle that holds
// them or the point they equal; those inside, beside the surface in its plane or a hair off it
// are not.
TEST(SurfaceDiagnosis, UnusedPointsLeftOutAreNamedApart)
{
  Surface s = cube();
  s.addPoint(0.25, 0.75, 0);   // 8: in triangle 8
  s.addPoint(0.5, 0.5, 0);     // 9: on the diagonal of triangles 8 and 9
  s.addPoint(0.5, 0, 0);       // 10: on the cube's edge of triangles 4 and 9
  s.addPoint(0.5, 0.5, 0.5);   // 11: inside
  s.addPoint(2, 0.5, 0);       // 12: in the plane z = 0, beside the face
  s.addPoint(0.5, 0.5, 1e-30); // 13: off the face
  s.addPoint(1, 1, 0);         // 14: equal to point 3, a corner of triangle 2
  s.addPoint(0.5, 0.5, 0.5);   // 15: equal to point 11
  const std::vector<LeftOutPoint> found =
    unusedPointsLeftOut(s.pts.data(), s.pointCount(), s.tris.data(), s.triCount());
  const std::vector<std::array<std::int32_t, 3>> expected = {
    { 8, 8, -1 }, { 9, 8, -1 }, { 10, 4, -1 }, { 14, 2, 3 }, { 15, -1, 11 }
  };
  ASSERT_EQ(found.size(), expected.size());
  for (std::size_t i = 0; i < found.size(); ++i)
  {
    EXPECT_EQ(found[i].point, expected[i][0]) << i;
    EXPECT_EQ(found[i].triangle, expected[i][1]) << i;
    EXPECT_EQ(found[i].equalTo, expected[i][2]) << i;
  }
  const SurfaceDiagnosis d = s.diagnose();
  EXPECT_TRUE(d.ok()) << d.summary();
  EXPECT_EQ(d.count(SurfaceDefect::UnusedPointLeftOut), 5) << d.summary();
  EXPECT_EQ(d.count(SurfaceDefect::UnusedPoint), 3) << d.summary();
  EXPECT_EQ(d.count(SurfaceDefect::DuplicatePoint), 0) << d.summary();
  // A triangle with an id out of range holds nothing (the diagnosis names it).
  s.addTri(0, 1, 99);
  EXPECT_EQ(unusedPointsLeftOut(s.pts.data(), s.pointCount(), s.tris.data(), s.triCount()).size(),
    expected.size());
}

TEST(SurfaceDiagnosis, UnmergedPointsGiveOpenEdgesNotIntersections)
{
  // Triangle 9 (0,3,1) uses a copy of point 3: the coincident copies touch, but that is
  // reported once, as coincident points (plus the open edges it causes).
  Surface s = cube();
  const std::int32_t copy = s.addPoint(1, 1, 0);
  s.tris[3 * 9 + 1] = copy;
  const SurfaceDiagnosis d = s.diagnose();
  EXPECT_EQ(d.count(SurfaceDefect::DuplicatePoint), 1) << d.summary();
  EXPECT_EQ(d.count(SurfaceDefect::OpenEdge), 4) << d.summary();
  EXPECT_EQ(d.defects.size(), 5u) << d.summary();
  EXPECT_EQ(d.count(SurfaceDefect::SelfIntersection), 0) << d.summary();
}

TEST(SurfaceDiagnosis, DegenerateRepeatedId)
{
  Surface s = cube();
  s.addTri(0, 0, 1);
  const SurfaceDiagnosis d = s.diagnose();
  ASSERT_EQ(d.defects.size(), 1u) << d.summary();
  expectRecord(d.defects[0], SurfaceDefect::DegenerateTriangle, { 0, 0, 1 }, { 12 });
}

TEST(SurfaceDiagnosis, DegenerateCollinearCap)
{
  // Point 8 at the middle of edge 0-1; triangle 4 split at it, and the zero-area triangle
  // (0,1,8) closes the surface. Point 8 touches triangle 9 (which still has edge 0-1): the
  // triangles on each side of it are T-junctions, i.e. genuine intersections.
  Surface s = cube();
  const std::int32_t m = s.addPoint(0.5, 0, 0);
  s.tris[3 * 4 + 1] = m; // 4: (0,8,5)
  const std::int32_t t12 = s.addTri(m, 1, 5);
  const std::int32_t t13 = s.addTri(0, 1, m);
  const SurfaceDiagnosis d = s.diagnose();
  ASSERT_EQ(d.defects.size(), 3u) << d.summary();
  expectRecord(d.defects[0], SurfaceDefect::DegenerateTriangle, { 0, 1, 8 }, { t13 });
  expectRecord(d.defects[1], SurfaceDefect::SelfIntersection, { 0, 8, 5, 0, 3, 1 }, { 4, 9 });
  expectRecord(d.defects[2], SurfaceDefect::SelfIntersection, { 0, 3, 1, 8, 1, 5 }, { 9, t12 });
}

TEST(SurfaceDiagnosis, DuplicateTriangle)
{
  Surface s = cube();
  s.addTri(6, 4, 0); // triangle 0 reversed
  s.addTri(4, 6, 0); // triangle 0, rotated
  const SurfaceDiagnosis d = s.diagnose();
  ASSERT_EQ(d.defects.size(), 1u) << d.summary();
  expectRecord(d.defects[0], SurfaceDefect::DuplicateTriangle, { 0, 4, 6 }, { 0, 12, 13 });
  EXPECT_EQ(d.summary(), "1 duplicated triangle (points 0-4-6; triangles 0=12=13)");
}

TEST(SurfaceDiagnosis, OpenEdges)
{
  Surface s = cube();
  s.tris.resize(33); // drop triangle 11 (4,7,6)
  const SurfaceDiagnosis d = s.diagnose();
  ASSERT_EQ(d.defects.size(), 3u) << d.summary();
  expectRecord(d.defects[0], SurfaceDefect::OpenEdge, { 4, 6 }, { 0 });
  expectRecord(d.defects[1], SurfaceDefect::OpenEdge, { 4, 7 }, { 10 });
  expectRecord(d.defects[2], SurfaceDefect::OpenEdge, { 6, 7 }, { 6 });
  EXPECT_EQ(d.summary(), "3 open edges (points 4-6, 4-7, 6-7; triangles 0, 10, 6)");
  EXPECT_EQ(d.summary(2), "3 open edges (points 4-6, 4-7, ...; triangles 0, 10, ...)");
}

TEST(SurfaceDiagnosis, NonManifoldFin)
{
  // A fin hanging off edge 0-1, outside the cube: 3 triangles on 0-1, but the fin has the
  // same region on both sides.
  Surface s = cube();
  const std::int32_t tip = s.addPoint(0.5, -1, -1);
  const std::int32_t fin = s.addTri(0, 1, tip);
  const SurfaceDiagnosis d = s.diagnose();
  ASSERT_EQ(d.defects.size(), 3u) << d.summary();
  expectRecord(d.defects[0], SurfaceDefect::OpenEdge, { 0, 8 }, { fin });
  expectRecord(d.defects[1], SurfaceDefect::OpenEdge, { 1, 8 }, { fin });
  expectRecord(d.defects[2], SurfaceDefect::NonManifoldEdge, { 0, 1 }, { 4, 9, fin });
}

TEST(SurfaceDiagnosis, NonManifoldDanglingInternalWall)
{
  // Half of the diagonal wall x=y inside the cube, triangle (0,3,7) only: it does not split
  // the cube, so it has the same region on both sides.
  Surface s = cube();
  s.addTri(0, 3, 7);
  const SurfaceDiagnosis d = s.diagnose();
  // Edges 0-3 and 3-7 carry 3 triangles; the wall's free edge 0-7 is open.
  ASSERT_EQ(d.count(SurfaceDefect::OpenEdge), 1) << d.summary();
  ASSERT_EQ(d.count(SurfaceDefect::NonManifoldEdge), 2) << d.summary();
  EXPECT_EQ(d.defects[1].pointIds, (std::vector<std::int32_t>{ 0, 3 }));
  EXPECT_EQ(d.defects[2].pointIds, (std::vector<std::int32_t>{ 3, 7 }));
  EXPECT_EQ(d.defects.size(), 3u);
}

TEST(SurfaceDiagnosis, InconsistentOrientation)
{
  Surface s = cube();
  s.tris[1] = 6; // triangle 0: (0,4,6) -> (0,6,4)
  s.tris[2] = 4;
  const SurfaceDiagnosis d = s.diagnose();
  ASSERT_EQ(d.defects.size(), 3u) << d.summary();
  expectRecord(d.defects[0], SurfaceDefect::InconsistentOrientation, { 0, 4 }, { 0, 5 });
  expectRecord(d.defects[1], SurfaceDefect::InconsistentOrientation, { 0, 6 }, { 0, 1 });
  expectRecord(d.defects[2], SurfaceDefect::InconsistentOrientation, { 4, 6 }, { 0, 11 });
  EXPECT_TRUE(d.ok()); // a warning: the mesh does not depend on orientation
}

TEST(SurfaceDiagnosis, SelfIntersectionPiercingTetrahedron)
{
  // A tetrahedron whose apex pokes through the top face, inside triangle 10 (4,5,7).
  Surface s = cube();
  const std::int32_t a = s.addPoint(0.6, 0.1, 0.5);
  const std::int32_t b = s.addPoint(0.9, 0.1, 0.5);
  const std::int32_t c = s.addPoint(0.8, 0.4, 0.5);
  const std::int32_t apex = s.addPoint(0.7, 0.2, 1.5);
  s.addTri(a, c, b);
  const std::int32_t t13 = s.addTri(a, b, apex);
  const std::int32_t t14 = s.addTri(b, c, apex);
  const std::int32_t t15 = s.addTri(c, a, apex);
  const SurfaceDiagnosis d = s.diagnose();
  ASSERT_EQ(d.defects.size(), 3u) << d.summary();
  expectRecord(d.defects[0], SurfaceDefect::SelfIntersection, { 4, 5, 7, 8, 9, 11 }, { 10, t13 });
  expectRecord(d.defects[1], SurfaceDefect::SelfIntersection, { 4, 5, 7, 9, 10, 11 }, { 10, t14 });
  expectRecord(d.defects[2], SurfaceDefect::SelfIntersection, { 4, 5, 7, 10, 8, 11 }, { 10, t15 });
  EXPECT_EQ(d.summary(), "3 intersecting triangle pairs (triangles 10-13, 10-14, 10-15)");
}

TEST(SurfaceDiagnosis, SelfIntersectionCoplanarOverlap)
{
  // Tet A above z=0 and tet B below it, their bases overlapping in the plane z=0.
  Surface s;
  s.addPoint(0, 0, 0);
  s.addPoint(2, 0, 0);
  s.addPoint(0, 2, 0);
  s.addPoint(0, 0, 1);
  s.addPoint(0.5, 0.5, 0);
  s.addPoint(3, 0.5, 0);
  s.addPoint(0.5, 3, 0);
  s.addPoint(0.5, 0.5, -1);
  s.addTri(0, 2, 1); // 0 base of A
  s.addTri(0, 1, 3); // 1
  s.addTri(0, 3, 2); // 2
  s.addTri(1, 2, 3); // 3 slanted face of A, touches B's base along x+y=2
  s.addTri(4, 5, 6); // 4 base of B
  s.addTri(4, 7, 5); // 5 side y=0.5 of B
  s.addTri(4, 6, 7); // 6 side x=0.5 of B
  s.addTri(5, 7, 6); // 7
  EXPECT_NEAR(s.volume(), 2.0 / 3 + 2.5 * 2.5 / 6, 1e-12);
  const SurfaceDiagnosis d = s.diagnose();
  std::vector<std::vector<std::int32_t>> pairs;
  for (const DefectRecord& r : d.defects)
  {
    EXPECT_EQ(r.kind, SurfaceDefect::SelfIntersection);
    pairs.push_back(r.triangleIds);
  }
  const std::vector<std::vector<std::int32_t>> expected = {
    { 0, 4 }, { 0, 5 }, { 0, 6 }, { 3, 4 }, { 3, 5 }, { 3, 6 }
  };
  EXPECT_EQ(pairs, expected) << d.summary();
}

TEST(SurfaceDiagnosis, TrianglePairPredicates)
{
  const double o[3] = { 0, 0, 0 }, x[3] = { 1, 0, 0 }, y[3] = { 0, 1, 0 }, xy[3] = { 1, 1, 0 };
  const double z[3] = { 0, 0, 1 }, m[3] = { 0.5, 0.5, 0 }, nx[3] = { -1, 0, 0 };
  const double ny[3] = { 0, -1, 0 }, d[3] = { 0.25, 0.25, 0 };
  const std::int32_t i0[3] = { 0, 1, 2 };
  {
    // Coplanar, sharing edge o-x, third vertices on opposite sides: fine.
    const double* p[3] = { o, x, y };
    const double* q[3] = { x, o, ny };
    const std::int32_t qi[3] = { 1, 0, 3 };
    EXPECT_FALSE(trianglesIntersectImproperly(p, i0, q, qi));
    // Same side: overlap.
    const double* r[3] = { x, o, d };
    const std::int32_t ri[3] = { 1, 0, 4 };
    EXPECT_TRUE(trianglesIntersectImproperly(p, i0, r, ri));
  }
  {
    // Coplanar, sharing vertex o only, angles apart: fine; angles overlapping: intersect.
    const double* p[3] = { o, x, m };
    const double* q[3] = { o, nx, ny };
    const std::int32_t qi[3] = { 0, 5, 6 };
    EXPECT_FALSE(trianglesIntersectImproperly(p, i0, q, qi));
    const double* r[3] = { o, xy, y };
    const std::int32_t ri[3] = { 0, 7, 8 };
    EXPECT_TRUE(trianglesIntersectImproperly(p, i0, r, ri));
  }
  {
    // Sharing vertex o, not coplanar, one edge lying in the other's plane inside its angle.
    const double* p[3] = { o, x, y };
    const double* q[3] = { o, d, z };
    const std::int32_t qi[3] = { 0, 9, 10 };
    EXPECT_TRUE(trianglesIntersectImproperly(p, i0, q, qi));
    const double* r[3] = { o, nx, z };
    const std::int32_t ri[3] = { 0, 11, 12 };
    EXPECT_FALSE(trianglesIntersectImproperly(p, i0, r, ri));
  }
  EXPECT_TRUE(isTriangleDegenerate(o, m, xy));
  EXPECT_FALSE(isTriangleDegenerate(o, x, m));
}

// Coplanar pairs (the planar faces of CAD parts) take a test in the plane: a separating axis
// without a shared vertex, the angles at the shared vertex with one. In a tilted plane, so the
// projection matters; coordinates o + i u + j w are exact. Each case in both orientations.
TEST(SurfaceDiagnosis, CoplanarTrianglePairsInATiltedPlane)
{
  std::vector<std::array<double, 3>> pts;
  std::map<std::pair<int, int>, std::int32_t> ids;
  auto at = [&](int i, int j)
  {
    auto it = ids.find({ i, j });
    if (it != ids.end())
      return it->second;
    pts.push_back({ 0.5 + i * 1.0 + j * 0.0, -1.0 + i * 2.0 + j * 1.0, 2.0 + i * 0.0 + j * 3.0 });
    return ids[{ i, j }] = static_cast<std::int32_t>(pts.size() - 1);
  };
  auto meet = [&](std::array<std::array<int, 2>, 3> a, std::array<std::array<int, 2>, 3> b)
  {
    std::int32_t ia[3], ib[3];
    for (int k = 0; k < 3; ++k)
    {
      ia[k] = at(a[k][0], a[k][1]);
      ib[k] = at(b[k][0], b[k][1]);
    }
    const double* p[3] = { pts[ia[0]].data(), pts[ia[1]].data(), pts[ia[2]].data() };
    const double* q[3] = { pts[ib[0]].data(), pts[ib[1]].data(), pts[ib[2]].data() };
    const double* pr[3] = { p[0], p[2], p[1] };
    const std::int32_t iar[3] = { ia[0], ia[2], ia[1] };
    const bool r = trianglesIntersectImproperly(p, ia, q, ib);
    EXPECT_EQ(r, trianglesIntersectImproperly(pr, iar, q, ib));
    EXPECT_EQ(r, trianglesIntersectImproperly(q, ib, p, ia));
    return r;
  };
  for (int k = 0; k < 8; ++k)
    at(k % 4, k / 4); // ids in a fixed order, whatever the cases ask first
  // No shared vertex.
  EXPECT_FALSE(meet({ { { 0, 0 }, { 1, 0 }, { 0, 1 } } }, { { { 2, 0 }, { 3, 0 }, { 2, 1 } } }));
  EXPECT_TRUE(meet({ { { 0, 0 }, { 2, 0 }, { 0, 2 } } }, { { { 1, 1 }, { 3, 1 }, { 1, 3 } } }))
    << "a vertex on the other's edge is a common point";
  EXPECT_TRUE(meet({ { { 0, 0 }, { 4, 0 }, { 0, 4 } } }, { { { 1, 1 }, { 2, 1 }, { 1, 2 } } }))
    << "one inside the other";
  EXPECT_FALSE(meet({ { { 0, 0 }, { 4, 0 }, { 0, 4 } } }, { { { 3, 3 }, { 4, 3 }, { 3, 4 } } }))
    << "boxes overlap, triangles do not";
  EXPECT_TRUE(meet({ { { 0, 0 }, { 4, 0 }, { 0, 4 } } }, { { { 1, -1 }, { 3, -1 }, { 2, 1 } } }))
    << "edges cross";
  // Sharing vertex (0,0) only.
  EXPECT_FALSE(meet({ { { 0, 0 }, { 1, 0 }, { 1, 1 } } }, { { { 0, 0 }, { -1, 0 }, { -1, -1 } } }));
  EXPECT_FALSE(meet({ { { 0, 0 }, { 1, 0 }, { 0, 1 } } }, { { { 0, 0 }, { -1, 0 }, { 0, -1 } } }))
    << "collinear edges in opposite directions meet only in the vertex";
  EXPECT_TRUE(meet({ { { 0, 0 }, { 2, 0 }, { 0, 1 } } }, { { { 0, 0 }, { 1, 0 }, { 0, -1 } } }))
    << "edges along the same ray overlap";
  EXPECT_TRUE(meet({ { { 0, 0 }, { 2, 0 }, { 0, 2 } } }, { { { 0, 0 }, { 1, 1 }, { 2, 1 } } }))
    << "an edge inside the other's angle";
  EXPECT_FALSE(meet({ { { 0, 0 }, { 2, 0 }, { 1, 1 } } }, { { { 0, 0 }, { 1, 2 }, { 0, 2 } } }))
    << "two triangles of a fan with a gap between them";
}

TEST(SurfaceDiagnosis, CorpusFiles)
{
  // Every .off/.stl in Data/ must be valid input. TETMESHER_DIAGNOSE_FILES (':'-separated
  // paths) adds more files, e.g. procedural surfaces exported by scripts/make_corpus.py.
  std::vector<std::string> files;
  const std::filesystem::path data =
    std::filesystem::path(__FILE__).parent_path().parent_path().parent_path() / "Data";
  if (std::filesystem::is_directory(data))
  {
    for (const auto& entry : std::filesystem::directory_iterator(data))
    {
      const std::string ext = entry.path().extension().string();
      if (ext == ".off" || ext == ".stl")
        files.push_back(entry.path().string());
    }
  }
  if (const char* extra = std::getenv("TETMESHER_DIAGNOSE_FILES"))
  {
    std::stringstream list(extra);
    std::string path;
    while (std::getline(list, path, ':'))
    {
      if (!path.empty())
        files.push_back(path);
    }
  }
  std::sort(files.begin(), files.end());
  for (const std::string& path : files)
  {
    Surface s;
    if (!readSurface(path, s))
    {
      ADD_FAILURE() << "cannot read " << path;
      continue;
    }
    const auto start = std::chrono::steady_clock::now();
    const SurfaceDiagnosis d = s.diagnose();
    const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::printf("%s: %d points, %d triangles, %.1f ms: %s\n",
      path.c_str(),
      s.pointCount(),
      s.triCount(),
      ms,
      d.ok() ? "ok" : d.summary(5).c_str());
    EXPECT_TRUE(d.ok()) << path << "\n" << d.summary();
  }
}

TEST(SurfaceDiagnosis, FineSphereInsideTiltedCoarseBox)
{
  // Nested shells with very different triangle sizes: the box's big tilted triangles cover
  // many grid cells and take the "large triangle" path.
  // Tilted box around the sphere (valid), then an axis-aligned box whose face x=0 cuts it.
  for (double shift : { 0.0, 2.5 })
  {
    Surface s = icosphere(5);
    const std::int32_t offset = s.pointCount();
    const Surface box = cube();
    const double angle = shift == 0 ? 0.5 : 0.0;
    const double c = std::cos(angle), sn = std::sin(angle);
    for (std::int32_t i = 0; i < box.pointCount(); ++i)
    {
      const double x = 5 * (box.pts[3 * i] - 0.5), y = 5 * (box.pts[3 * i + 1] - 0.5),
                   z = 5 * (box.pts[3 * i + 2] - 0.5);
      const double y1 = c * y - sn * z, z1 = sn * y + c * z;
      s.addPoint(c * x - sn * z1 + shift, y1, sn * x + c * z1);
    }
    for (std::int32_t t : box.tris)
      s.tris.push_back(t + offset);
    const SurfaceDiagnosis d = s.diagnose();
    if (shift == 0)
      EXPECT_TRUE(d.defects.empty()) << d.summary();
    else
    {
      EXPECT_GT(d.count(SurfaceDefect::SelfIntersection), 0) << d.summary();
      EXPECT_EQ(d.count(SurfaceDefect::SelfIntersection), static_cast<int>(d.defects.size()));
      for (const DefectRecord& r : d.defects)
        EXPECT_GE(r.triangleIds[1], s.triCount() - 12); // always a sphere/box pair
    }
  }
}

TEST(SurfaceDiagnosis, GridAgreesWithBruteForce)
{
  // Random soup of triangles on a shared pool of points (many shared vertices and edges) with
  // a few big ones: the grid must find exactly the pairs an all-pairs test finds.
  std::uint64_t state = 12345;
  auto next = [&]()
  {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state >> 11) / 9007199254740992.0;
  };
  for (int round = 0; round < 3; ++round)
  {
    Surface s;
    for (int i = 0; i < 300; ++i)
      s.addPoint(next(), next(), next() * (round == 2 ? 0 : 1)); // round 2: all coplanar
    std::set<std::array<std::int32_t, 3>> seen;
    while (s.triCount() < 500)
    {
      const bool big = s.triCount() % 50 == 0;
      std::array<std::int32_t, 3> v;
      v[0] = static_cast<std::int32_t>(next() * 300);
      for (int k = 1; k < 3; ++k)
        v[k] = big ? static_cast<std::int32_t>(next() * 300)
                   : (v[0] + 1 + static_cast<std::int32_t>(next() * 5)) % 300;
      std::array<std::int32_t, 3> key = v;
      std::sort(key.begin(), key.end());
      if (key[0] == key[1] || key[1] == key[2] || !seen.insert(key).second)
        continue;
      const double* p0 = &s.pts[3 * v[0]];
      const double* p1 = &s.pts[3 * v[1]];
      const double* p2 = &s.pts[3 * v[2]];
      if (isTriangleDegenerate(p0, p1, p2))
        continue;
      s.addTri(v[0], v[1], v[2]);
    }
    std::vector<std::vector<std::int32_t>> expected;
    for (std::int32_t a = 0; a < s.triCount(); ++a)
    {
      for (std::int32_t b = a + 1; b < s.triCount(); ++b)
      {
        const std::int32_t* ia = &s.tris[3 * a];
        const std::int32_t* ib = &s.tris[3 * b];
        const double* pa[3] = { &s.pts[3 * ia[0]], &s.pts[3 * ia[1]], &s.pts[3 * ia[2]] };
        const double* pb[3] = { &s.pts[3 * ib[0]], &s.pts[3 * ib[1]], &s.pts[3 * ib[2]] };
        if (trianglesIntersectImproperly(pa, ia, pb, ib))
          expected.push_back({ a, b });
      }
    }
    const SurfaceDiagnosis d = s.diagnose();
    std::vector<std::vector<std::int32_t>> pairs;
    for (const DefectRecord& r : d.defects)
    {
      if (r.kind == SurfaceDefect::SelfIntersection)
        pairs.push_back(r.triangleIds);
    }
    EXPECT_GT(expected.size(), 10u);
    EXPECT_EQ(pairs, expected) << "round " << round;
  }
}

TEST(SurfaceDiagnosis, RecordLimit)
{
  Surface s = cube();
  s.tris.resize(33);
  DiagnosisOptions options;
  options.maxRecordsPerKind = 2;
  const SurfaceDiagnosis d =
    diagnoseSurface(s.pts.data(), s.pointCount(), s.tris.data(), s.triCount(), options);
  EXPECT_EQ(d.count(SurfaceDefect::OpenEdge), 2);
  EXPECT_TRUE(d.truncated);
}

TEST(SurfaceDiagnosis, InvalidCorpusFiles)
{
  // Real models kept in Data/invalid/ because they are not valid mesher input.
  const std::filesystem::path dir =
    std::filesystem::path(__FILE__).parent_path().parent_path().parent_path() / "Data" / "invalid";
  if (!std::filesystem::is_directory(dir))
    GTEST_SKIP() << "no " << dir;
  {
    // An unmerged soup: every point repeated, so every edge is open.
    Surface s;
    ASSERT_TRUE(readSurface((dir / "boeing.off").string(), s));
    const SurfaceDiagnosis d = s.diagnose();
    EXPECT_EQ(d.count(SurfaceDefect::DuplicatePoint), 1237) << d.summary();
    EXPECT_EQ(d.count(SurfaceDefect::OpenEdge), 2714) << d.summary();
    EXPECT_EQ(d.count(SurfaceDefect::SelfIntersection), 0) << d.summary();
  }
  {
    // Non-convex letters as polygons, read here as fans: two zero-area triangles and fan
    // triangles that cross (cut by their ears, as the mesher does, the surface is valid).
    Surface s;
    ASSERT_TRUE(readSurface((dir / "mpi.off").string(), s));
    const SurfaceDiagnosis d = s.diagnose();
    ASSERT_EQ(d.count(SurfaceDefect::DegenerateTriangle), 2) << d.summary();
    EXPECT_EQ(d.defects[0].triangleIds, (std::vector<std::int32_t>{ 74 }));
    EXPECT_EQ(d.defects[1].triangleIds, (std::vector<std::int32_t>{ 111 }));
    EXPECT_EQ(d.count(SurfaceDefect::SelfIntersection), 147) << d.summary();
  }
}

TEST(SurfaceDiagnosis, PerformanceLargeSphere)
{
  const Surface s = icosphere(7); // 327680 triangles
  const auto start = std::chrono::steady_clock::now();
  const SurfaceDiagnosis d = s.diagnose();
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("diagnosis of %d triangles: %.3f s\n", s.triCount(), seconds);
  EXPECT_TRUE(d.defects.empty()) << d.summary();
}

TEST(SurfaceDiagnosis, ErrorsLeaveOutWarningsAndKeepTruncation)
{
  // What a refusal names: the errors alone, and "1000+" when the records were capped.
  SurfaceDiagnosis d;
  d.truncated = true;
  d.defects.push_back({ SurfaceDefect::OpenEdge, { 0, 1 }, { 3 } });
  d.defects.push_back({ SurfaceDefect::InconsistentOrientation, { 1, 2 }, { 4, 5 } });
  d.defects.push_back({ SurfaceDefect::UnusedPoint, { 7 }, {} });
  const SurfaceDiagnosis e = d.errors();
  ASSERT_EQ(e.defects.size(), 1u);
  EXPECT_EQ(e.defects[0].kind, SurfaceDefect::OpenEdge);
  EXPECT_TRUE(e.truncated);
  EXPECT_EQ(e.summary().rfind("1+ open edge", 0), 0u) << e.summary();
  EXPECT_FALSE(d.ok());
  SurfaceDiagnosis warningsOnly;
  warningsOnly.defects = { d.defects[1], d.defects[2] };
  EXPECT_TRUE(warningsOnly.ok());
}
