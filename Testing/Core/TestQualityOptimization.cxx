// optimizeMesh: on boundary meshes of procedural surfaces and on meshes with interior points,
// the optimiser keeps every invariant (no inverted tet by exact orient3d, constrained faces
// and boundary coordinates unchanged, region volumes unchanged, symmetric adjacency, regions
// consistent) and never lowers the minimum Q or minimum dihedral angle; it is deterministic,
// and on a cube with jittered interior points it reaches documented quality thresholds.
#include "Delaunay.h"
#include "MeshAssembly.h"
#include "Mesher.h"
#include "OptimizationContext.h"
#include "Predicates.h"
#include "QualityOptimization.h"
#include "SurfaceGenerators.h"
#include "TetQuality.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <utility>

using namespace tetmesher;
namespace tt = tetmesher::testing;

namespace
{

bool buildRegionMesh(const tt::Surface& s, RegionMesh& out)
{
  MesherResult r =
    meshSurface(s.points.data(), s.pointCount(), s.triangles.data(), s.triangleCount());
  if (!r.ok)
  {
    ADD_FAILURE() << r.error;
    return false;
  }
  return assembleRegionMesh(r.points, r.tets, r.regionIds, out);
}

// Inserts the points of a k^3 grid in [lo,hi]^3 (cell centres, jittered by up to `jitter`
// cell sizes) with the constrained Delaunay kernel; new tets take the region of their hint.
int insertGrid(RegionMesh& rm, double lo, double hi, int k, double jitter, std::uint64_t seed)
{
  auto next = [&]()
  {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(seed >> 11) / 9007199254740992.0 * 2 - 1;
  };
  InsertionWorkspace* ws = createInsertionWorkspace();
  TetMesh& m = rm.mesh;
  int inserted = 0;
  TetId hint = 0;
  while (m.isDeleted(hint))
    ++hint;
  const double step = (hi - lo) / k;
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j)
      for (int l = 0; l < k; ++l)
      {
        double x = lo + (i + 0.5 + jitter * next()) * step;
        double y = lo + (j + 0.5 + jitter * next()) * step;
        double z = lo + (l + 0.5 + jitter * next()) * step;
        VertexId v = m.addVertex(x, y, z);
        InsertResult r = insertVertex(m, v, hint, *ws);
        if (r.status == InsertStatus::Inserted)
        {
          ++inserted;
          hint = r.tet;
        }
        rm.region.resize(static_cast<std::size_t>(m.tetCapacity()), rm.region[0]);
      }
  destroyInsertionWorkspace(ws);
  return inserted;
}

using Face = std::array<VertexId, 3>;

struct Snapshot
{
  std::vector<Face> constrained; // sorted triples, sorted, with multiplicity (both sides)
  std::vector<std::pair<VertexId, std::array<double, 3>>> boundaryPoints;
  std::map<std::int32_t, double> regionVolume;
  std::vector<VertexId> usedVertices; // in some live tet
};

double tetVolume(const TetMesh& m, TetId t)
{
  const double* a = m.point(m.vertex(t, 0));
  const double* b = m.point(m.vertex(t, 1));
  const double* c = m.point(m.vertex(t, 2));
  const double* d = m.point(m.vertex(t, 3));
  double u[3], v[3], w[3];
  for (int k = 0; k < 3; ++k)
  {
    u[k] = a[k] - d[k];
    v[k] = b[k] - d[k];
    w[k] = c[k] - d[k];
  }
  return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
           u[2] * (v[0] * w[1] - v[1] * w[0])) /
    6;
}

Snapshot snapshot(const RegionMesh& rm)
{
  const TetMesh& m = rm.mesh;
  Snapshot s;
  std::vector<char> isBoundary(static_cast<std::size_t>(m.vertexCount()), 0);
  for (TetId t = 0; t < m.tetCapacity(); ++t)
  {
    if (m.isDeleted(t))
      continue;
    s.regionVolume[rm.region[static_cast<std::size_t>(t)]] += tetVolume(m, t);
    for (int f = 0; f < 4; ++f)
      if (m.isConstrained(t, f))
      {
        Face face;
        for (int k = 0; k < 3; ++k)
        {
          face[k] = m.vertex(t, kFaceVertices[f][k]);
          isBoundary[static_cast<std::size_t>(face[k])] = 1;
        }
        std::sort(face.begin(), face.end());
        s.constrained.push_back(face);
      }
  }
  std::sort(s.constrained.begin(), s.constrained.end());
  std::vector<char> used(static_cast<std::size_t>(m.vertexCount()), 0);
  for (TetId t = 0; t < m.tetCapacity(); ++t)
    if (!m.isDeleted(t))
      for (int i = 0; i < 4; ++i)
        used[static_cast<std::size_t>(m.vertex(t, i))] = 1;
  for (VertexId v = 0; v < m.vertexCount(); ++v)
    if (used[static_cast<std::size_t>(v)])
      s.usedVertices.push_back(v);
  for (VertexId v = 0; v < m.vertexCount(); ++v)
    if (isBoundary[static_cast<std::size_t>(v)])
      s.boundaryPoints.push_back({ v, { m.point(v)[0], m.point(v)[1], m.point(v)[2] } });
  return s;
}

// "" when the mesh is valid and keeps the invariants of `before`.
std::string check(const RegionMesh& rm, const Snapshot& before)
{
  const TetMesh& m = rm.mesh;
  std::ostringstream err;
  if (rm.region.size() < static_cast<std::size_t>(m.tetCapacity()))
    return "region vector shorter than tet capacity";
  for (TetId t = 0; t < m.tetCapacity(); ++t)
  {
    if (m.isDeleted(t))
      continue;
    if (predicates::orient3d(m.point(m.vertex(t, 0)),
          m.point(m.vertex(t, 1)),
          m.point(m.vertex(t, 2)),
          m.point(m.vertex(t, 3))) <= 0)
      err << "tet " << t << " not positive; ";
    for (int f = 0; f < 4; ++f)
    {
      FaceRef n = m.neighbor(t, f);
      if (n == kNoNeighbor)
      {
        if (!m.isConstrained(t, f))
          err << "hull face " << t << "." << f << " not constrained; ";
        continue;
      }
      TetId u = faceTet(n);
      int g = faceIndex(n);
      if (m.isDeleted(u) || m.neighbor(u, g) != makeFaceRef(t, f))
      {
        err << "asymmetric neighbour " << t << "." << f << "; ";
        continue;
      }
      Face a, b;
      for (int k = 0; k < 3; ++k)
      {
        a[k] = m.vertex(t, kFaceVertices[f][k]);
        b[k] = m.vertex(u, kFaceVertices[g][k]);
      }
      std::sort(a.begin(), a.end());
      std::sort(b.begin(), b.end());
      if (a != b)
        err << "glued faces differ " << t << "." << f << "; ";
      if (m.isConstrained(t, f) != m.isConstrained(u, g))
        err << "constraint flag asymmetric " << t << "." << f << "; ";
      if (!m.isConstrained(t, f) &&
        rm.region[static_cast<std::size_t>(t)] != rm.region[static_cast<std::size_t>(u)])
        err << "region changes across free face " << t << "." << f << "; ";
    }
  }
  Snapshot after = snapshot(rm);
  if (after.constrained != before.constrained)
    err << "constrained faces changed; ";
  if (after.boundaryPoints != before.boundaryPoints)
    err << "boundary vertices moved; ";
  // No vertex may vanish (inserted ones may appear).
  if (!std::includes(after.usedVertices.begin(),
        after.usedVertices.end(),
        before.usedVertices.begin(),
        before.usedVertices.end()))
    err << "a vertex dropped out of the mesh; ";
  if (after.regionVolume.size() != before.regionVolume.size())
    err << "region set changed; ";
  for (const auto& [r, vol] : before.regionVolume)
  {
    auto it = after.regionVolume.find(r);
    if (it == after.regionVolume.end() || std::abs(it->second - vol) > 1e-12 * std::abs(vol))
      err << "volume of region " << r << " changed; ";
  }
  std::string s = err.str();
  return s.size() > 2000 ? s.substr(0, 2000) : s;
}

void report(const char* name, const OptimizationResult& r)
{
  std::printf(
    "[%s] tets %d -> %d  Qmin %.4f -> %.4f  Qmean %.4f -> %.4f  "
    "min dihedral %.2f -> %.2f deg  share below target %.3f -> %.3f\n"
    "    2-3 %d  3-2 %d  edge removals %d  multi-face %d  smoothed %d  passes %d  %.3f s\n",
    name,
    r.tetsBefore,
    r.tetsAfter,
    r.minQualityBefore,
    r.minQualityAfter,
    r.meanBefore,
    r.meanAfter,
    r.minDihedralBefore,
    r.minDihedralAfter,
    r.shareBelowTargetBefore,
    r.shareBelowTargetAfter,
    r.flips23,
    r.flips32,
    r.edgeRemovals,
    r.multiFaceRemovals,
    r.smoothedVertices,
    r.passesRun,
    r.seconds);
}

// Optimises and checks every invariant; returns the result for thresholds.
OptimizationResult optimizeAndCheck(const char* name,
  RegionMesh& rm,
  const OptimizationOptions& options = {})
{
  Snapshot before = snapshot(rm);
  EXPECT_EQ(check(rm, before), "") << name << ": input invalid";
  OptimizationResult r = optimizeMesh(rm, options);
  report(name, r);
  EXPECT_TRUE(r.ok) << r.error;
  EXPECT_EQ(check(rm, before), "") << name;
  EXPECT_GE(r.minQualityAfter, r.minQualityBefore) << name;
  EXPECT_GE(r.minDihedralAfter, r.minDihedralBefore) << name;
  return r;
}

double snapshotMinQ(RegionMesh rm)
{
  OptimizationOptions none;
  none.passes = 0;
  return optimizeMesh(rm, none).minQualityBefore;
}

RegionMesh jitteredGridCube(int k, int faceCells = 3)
{
  RegionMesh rm;
  EXPECT_TRUE(buildRegionMesh(tt::cube(faceCells), rm));
  int inserted = insertGrid(rm, 0, 1, k, 0.3, 12345);
  EXPECT_EQ(inserted, k * k * k);
  return rm;
}

// Two unit cubes sharing a face (two regions) with `count` random interior points, each in
// the region of the tet it lands in.
RegionMesh twoCubesWithPoints(int count)
{
  std::vector<char> shared;
  RegionMesh rm;
  EXPECT_TRUE(buildRegionMesh(tt::twoCubes(shared), rm));
  // Points inside both cubes (x in (0,2)): each takes the region of the tet it lands in.
  InsertionWorkspace* ws = createInsertionWorkspace();
  std::uint64_t seed = 99;
  auto next = [&]()
  {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(seed >> 11) / 9007199254740992.0;
  };
  for (int i = 0; i < count; ++i)
  {
    double x = 0.05 + 1.9 * next(), y = 0.05 + 0.9 * next(), z = 0.05 + 0.9 * next();
    TetId loc = locatePoint(rm.mesh, std::array<double, 3>{ x, y, z }.data(), 0);
    EXPECT_GE(loc, 0);
    if (loc < 0)
      continue;
    std::int32_t region = rm.region[static_cast<std::size_t>(loc)];
    VertexId v = rm.mesh.addVertex(x, y, z);
    InsertResult r = insertVertex(rm.mesh, v, loc, *ws);
    rm.region.resize(static_cast<std::size_t>(rm.mesh.tetCapacity()), region);
    if (r.status == InsertStatus::Inserted)
    {
      // The cavity stays inside one region: relabel the new ball.
      for (TetId t = 0; t < rm.mesh.tetCapacity(); ++t)
        if (!rm.mesh.isDeleted(t))
          for (int k = 0; k < 4; ++k)
            if (rm.mesh.vertex(t, k) == v)
              rm.region[static_cast<std::size_t>(t)] = region;
    }
  }
  destroyInsertionWorkspace(ws);
  return rm;
}

} // namespace

TEST(QualityOptimization, CubeTwelveTriangles)
{
  RegionMesh rm;
  ASSERT_TRUE(buildRegionMesh(tt::cube(1), rm));
  optimizeAndCheck("cube 12 triangles", rm);
}

TEST(QualityOptimization, SubdividedCubeBoundaryMesh)
{
  RegionMesh rm;
  ASSERT_TRUE(buildRegionMesh(tt::cube(3), rm));
  OptimizationResult r = optimizeAndCheck("cube 3x3 faces", rm);
  EXPECT_GT(r.flips23 + r.flips32 + r.edgeRemovals, 0);
}

TEST(QualityOptimization, Icosphere)
{
  RegionMesh rm;
  ASSERT_TRUE(buildRegionMesh(tt::icosphere(2), rm));
  OptimizationResult r = optimizeAndCheck("icosphere 2", rm);
  EXPECT_GT(r.flips23 + r.flips32 + r.edgeRemovals, 0);
  EXPECT_GT(r.minQualityAfter, r.minQualityBefore);
}

TEST(QualityOptimization, JitteredIcosphere)
{
  tt::Surface s = tt::icosphere(2);
  tt::jitter(s, 0.02, 7);
  RegionMesh rm;
  ASSERT_TRUE(buildRegionMesh(s, rm));
  optimizeAndCheck("jittered icosphere 2", rm);
}

TEST(QualityOptimization, TwoCubesSharingAFace)
{
  std::vector<char> shared;
  RegionMesh rm;
  ASSERT_TRUE(buildRegionMesh(tt::twoCubes(shared), rm));
  optimizeAndCheck("two cubes", rm);
}

TEST(QualityOptimization, TwoCubesWithInteriorPoints)
{
  RegionMesh rm = twoCubesWithPoints(60);
  OptimizationResult r = optimizeAndCheck("two cubes + 60 interior points", rm);
  EXPECT_GT(r.smoothedVertices, 0);
}

TEST(QualityOptimization, JitteredGridCubeReachesThresholds)
{
  RegionMesh rm = jitteredGridCube(6);
  const double q0 = snapshotMinQ(rm);
  // Stage 1: the paper's Q; stage 2: the smallest dihedral angle, Q guarded by its minimum.
  OptimizationOptions options;
  options.passes = 30;
  options.qualityTarget = 0.45;
  options.dihedralTarget = 31.7; // 0.45 of the regular tet's
  options.insertion = false;     // flips and smoothing alone here; insertion below
  std::vector<double> progressSeen;
  Snapshot before = snapshot(rm);
  OptimizationResult r = optimizeMesh(rm,
    options,
    nullptr,
    [&](double x)
    {
      progressSeen.push_back(x);
      return true;
    });
  report("cube 3x3 + jittered 6^3 grid, Q then dihedral", r);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(check(rm, before), "");
  EXPECT_GT(r.minQualityAfter, q0);
  EXPECT_GT(r.smoothedVertices, 0);
  EXPECT_GT(r.flips23 + r.flips32 + r.edgeRemovals + r.multiFaceRemovals, 0);
  ASSERT_FALSE(progressSeen.empty());
  EXPECT_TRUE(std::is_sorted(progressSeen.begin(), progressSeen.end()));
  EXPECT_LE(progressSeen.back(), 1.0);
  // Documented thresholds: on this input the optimiser reaches Q_min 0.354 and a minimum
  // dihedral angle of 19.9 degrees (from 0.020 and 1.1 degrees). These small inputs are
  // sensitive to the order of the moves (before lifted tets with no bad neighbour were
  // left alone: 0.387, 19.0; before each tet was queued once: 0.385, 21.5; with 8 smoothing
  // steps instead of 2: 0.380, 20.7; with 3: 0.353, 21.2; with 4: 0.373, 17.5), so the
  // bounds are loose.
  EXPECT_GE(r.minQualityAfter, 0.35);
  EXPECT_GE(r.minDihedralAfter, 18.5);

  // With vertex insertion (the default) the same input reaches Q min 0.382 and a minimum
  // dihedral angle of 20.5 degrees (22.0 when smoothing took gains down to 1e-8; 19.8, 21.2,
  // 19.9 with the least gain at 1e-7, 3e-7, 3e-6; 0.379 and 20.8 with 8 smoothing steps;
  // 0.415 and 19.4 before each tet was queued once): as order-sensitive as above, so the
  // angle's bound sits below that spread.
  RegionMesh withInsertion = jitteredGridCube(6);
  options.insertion = true;
  Snapshot beforeInsertion = snapshot(withInsertion);
  OptimizationResult ri = optimizeMesh(withInsertion, options, nullptr);
  report("cube 3x3 + jittered 6^3 grid, Q then dihedral, insertion", ri);
  ASSERT_TRUE(ri.ok) << ri.error;
  EXPECT_EQ(check(withInsertion, beforeInsertion), "");
  EXPECT_GT(ri.insertedVertices, 0);
  EXPECT_GE(ri.minQualityAfter, 0.37);
  EXPECT_GE(ri.minDihedralAfter, 19.5);
}

TEST(QualityOptimization, LargerJitteredGridTiming)
{
  RegionMesh rm = jitteredGridCube(14, 12);
  OptimizationResult r = optimizeAndCheck("cube 12x12 + jittered 14^3 grid", rm);
  EXPECT_LT(r.seconds, 30.0);
}

TEST(QualityOptimization, SmoothingMoveBoundsHold)
{
  // The bounds on smoothing moves per pass (OptimizationOptions::maxSmoothingMovesPerVertex,
  // smoothingMovesPerFreeVertex): each one bites on this input, and the counts stay within.
  const int vertices = jitteredGridCube(14, 12).mesh.vertexCount();
  OptimizationOptions unbounded;
  unbounded.dihedralTarget = 0; // one stage: passesRun counts its passes only
  unbounded.insertion = false;  // no new vertices
  unbounded.maxSmoothingMovesPerVertex = 0;
  unbounded.smoothingMovesPerFreeVertex = 0;
  RegionMesh free = jitteredGridCube(14, 12);
  OptimizationResult u = optimizeAndCheck("cube 12x12 + 14^3 grid, Q stage", free, unbounded);

  OptimizationOptions perVertex = unbounded;
  perVertex.maxSmoothingMovesPerVertex = 1;
  RegionMesh once = jitteredGridCube(14, 12);
  OptimizationResult b = optimizeAndCheck("... 1 move per vertex and pass", once, perVertex);
  EXPECT_LE(b.smoothedVertices, b.passesRun * vertices);
  EXPECT_LT(b.smoothedVertices, u.smoothedVertices);

  // The bound on all moves of a pass is never below 1000 (kMinSmoothingMoveBudget).
  OptimizationOptions total = unbounded;
  total.smoothingMovesPerFreeVertex = 1e-6;
  RegionMesh few = jitteredGridCube(14, 12);
  OptimizationResult f = optimizeAndCheck("... 1000 moves per pass", few, total);
  EXPECT_LE(f.smoothedVertices, f.passesRun * 1000);
  EXPECT_LT(f.smoothedVertices, u.smoothedVertices);

  // Bounded, the optimiser still lifts the worst tets past the target's neighbourhood (the
  // minima never decrease: optimizeAndCheck).
  for (const OptimizationResult* x : { &u, &b, &f })
  {
    EXPECT_GT(x->smoothedVertices, 0);
    EXPECT_GT(x->minQualityAfter, 0.3);
  }
}

TEST(QualityOptimization, VertexInsertionKeepsInvariants)
{
  // Insertion is tried once the other moves stall; check every invariant with it on.
  const char* names[4] = { "icosphere 2 + insertion",
    "jittered icosphere 2 + insertion",
    "cube + 4^3 grid + insertion",
    "two cubes + 60 points + insertion" };
  for (int surface = 0; surface < 4; ++surface)
  {
    RegionMesh rm;
    if (surface == 0)
      ASSERT_TRUE(buildRegionMesh(tt::icosphere(2), rm));
    else if (surface == 1)
    {
      tt::Surface s = tt::icosphere(2);
      tt::jitter(s, 0.02, 7);
      ASSERT_TRUE(buildRegionMesh(s, rm));
    }
    else if (surface == 2)
      rm = jitteredGridCube(4);
    else
      rm = twoCubesWithPoints(60);
    const VertexId verticesBefore = rm.mesh.vertexCount();
    OptimizationOptions options;
    options.insertion = true;
    options.passes = 10;
    OptimizationResult r = optimizeAndCheck(names[surface], rm, options);
    std::printf("    inserted vertices %d\n", r.insertedVertices);
    EXPECT_EQ(rm.mesh.vertexCount(), verticesBefore + r.insertedVertices);
    if (surface == 0)
    {
      EXPECT_GT(r.insertedVertices, 0);
    }
  }
}

TEST(QualityOptimization, MinDihedralMeasure)
{
  RegionMesh rm = jitteredGridCube(5);
  OptimizationOptions options;
  options.measure = QualityMeasure::MinDihedral;
  options.qualityTarget = 0.4;
  optimizeAndCheck("cube + 5^3 grid, MinDihedral", rm, options);
}

TEST(QualityOptimization, SizeScaled)
{
  RegionMesh rm = jitteredGridCube(5);
  std::vector<double> h(static_cast<std::size_t>(rm.mesh.vertexCount()));
  for (VertexId v = 0; v < rm.mesh.vertexCount(); ++v)
    h[static_cast<std::size_t>(v)] = 0.1 + 0.2 * rm.mesh.point(v)[0];
  const std::vector<double> hBefore = h;
  Snapshot before = snapshot(rm);
  OptimizationResult r = optimizeMesh(rm, {}, &h);
  report("cube + 5^3 grid, size-scaled", r);
  EXPECT_TRUE(r.ok);
  EXPECT_EQ(check(rm, before), "");
  EXPECT_GE(r.minQualityAfter, r.minQualityBefore);
  EXPECT_GE(r.minDihedralAfter, r.minDihedralBefore);
  EXPECT_EQ(h, hBefore); // the caller's sizes untouched

  // With insertion the inserted vertices get sizes internally; the caller's h is unchanged.
  RegionMesh sphere;
  ASSERT_TRUE(buildRegionMesh(tt::icosphere(2), sphere));
  std::vector<double> hs(static_cast<std::size_t>(sphere.mesh.vertexCount()), 0.3);
  const std::vector<double> hsBefore = hs;
  OptimizationOptions options;
  options.insertion = true;
  options.passes = 6;
  before = snapshot(sphere);
  r = optimizeMesh(sphere, options, &hs);
  report("icosphere 2, size-scaled + insertion", r);
  EXPECT_TRUE(r.ok);
  EXPECT_EQ(check(sphere, before), "");
  EXPECT_GT(r.insertedVertices, 0);
  EXPECT_EQ(hs, hsBefore);
  EXPECT_GE(r.minQualityAfter, r.minQualityBefore);
  EXPECT_GE(r.minDihedralAfter, r.minDihedralBefore);
}

// TetQuality's measure of live tet t (Q size-scaled when h is given). TetMesh tets are
// positive in Shewchuk's sign, measureTet expects VTK's: swap a and b.
TetShape freshShape(const RegionMesh& rm, TetId t, const std::vector<double>* h)
{
  const VertexId a = rm.mesh.vertex(t, 0), b = rm.mesh.vertex(t, 1), c = rm.mesh.vertex(t, 2),
                 d = rm.mesh.vertex(t, 3);
  if (!h)
    return measureTet(rm.mesh.point(b), rm.mesh.point(a), rm.mesh.point(c), rm.mesh.point(d));
  const double hh[4] = { (*h)[static_cast<std::size_t>(b)],
    (*h)[static_cast<std::size_t>(a)],
    (*h)[static_cast<std::size_t>(c)],
    (*h)[static_cast<std::size_t>(d)] };
  return measureTetScaled(
    rm.mesh.point(b), rm.mesh.point(a), rm.mesh.point(c), rm.mesh.point(d), hh);
}

// The minimum Q and dihedral angle over the live tets, measured afresh (the optimiser's are
// measured the same way, through a cache): Q size-scaled when h is given.
std::pair<double, double> freshMinima(const RegionMesh& rm, const std::vector<double>* h)
{
  double q = 2, dih = 180;
  for (TetId t = 0; t < rm.mesh.tetCapacity(); ++t)
  {
    if (rm.mesh.isDeleted(t))
      continue;
    const TetShape s = freshShape(rm, t, h);
    q = std::min(q, s.quality);
    dih = std::min(dih, s.minDihedral);
  }
  return { q, dih };
}

TEST(QualityOptimization, DefaultsAndReportedMinima)
{
  // The defaults: a Q stage to 0.35, then a dihedral stage to 25 degrees, vertex insertion as
  // a bounded last resort.
  const OptimizationOptions defaults;
  EXPECT_EQ(defaults.qualityTarget, 0.35);
  EXPECT_EQ(defaults.dihedralTarget, 25.0);
  EXPECT_TRUE(defaults.insertion);
  EXPECT_EQ(defaults.maxInsertedVertices, -1);

  // The reported minima are those of the mesh (the quality cache is never stale), with one
  // stage, with two, and with two stages, a size field and inserted vertices.
  for (int variant = 0; variant < 3; ++variant)
  {
    RegionMesh rm = jitteredGridCube(5);
    OptimizationOptions options;
    if (variant == 0)
      options.dihedralTarget = 0;
    std::vector<double> h;
    if (variant == 2)
    {
      options.insertion = true;
      h.resize(static_cast<std::size_t>(rm.mesh.vertexCount()));
      for (VertexId v = 0; v < rm.mesh.vertexCount(); ++v)
        h[static_cast<std::size_t>(v)] = 0.1 + 0.2 * rm.mesh.point(v)[0];
    }
    const char* names[3] = { "cube + 5^3 grid, Q stage only",
      "cube + 5^3 grid, defaults",
      "cube + 5^3 grid, defaults, size-scaled + insertion" };
    Snapshot before = snapshot(rm);
    OptimizationResult r = optimizeMesh(rm, options, h.empty() ? nullptr : &h);
    report(names[variant], r);
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(check(rm, before), "");
    EXPECT_GE(r.minQualityAfter, r.minQualityBefore);
    EXPECT_GE(r.minDihedralAfter, r.minDihedralBefore);
    if (variant == 2)
    {
      // Inserted vertices: their size is the mean of their first tet's (as the optimiser
      // sets it), which this check cannot know; compare only without insertions.
      if (r.insertedVertices > 0)
        continue;
    }
    const auto [q, dih] = freshMinima(rm, h.empty() ? nullptr : &h);
    EXPECT_EQ(r.minQualityAfter, q) << names[variant];
    EXPECT_EQ(r.minDihedralAfter, dih) << names[variant];
  }
}

// The optimiser keeps the smallest dihedral angle as a cosine and scores the dihedral stage by
// sin(angle / 2); qualityTarget keeps its public unit (angle / 70.53 degrees) for the
// MinDihedral measure. The share it reports below the target must be the share of tets whose
// smallest dihedral angle (TetQuality's) is below target * 70.53 degrees, before and after.
TEST(QualityOptimization, MinDihedralTargetInDegrees)
{
  for (double angle = 1; angle < 180; angle += 1)
    EXPECT_LT(optimization::dihedralScoreOfDegrees(angle - 0.5),
      optimization::dihedralScoreOfDegrees(angle))
      << angle;
  RegionMesh rm = jitteredGridCube(5);
  OptimizationOptions options;
  options.measure = QualityMeasure::MinDihedral;
  options.qualityTarget = 0.4; // 28.2 degrees
  auto shareBelow = [&]()
  {
    int below = 0, count = 0;
    for (TetId t = 0; t < rm.mesh.tetCapacity(); ++t)
    {
      if (rm.mesh.isDeleted(t))
        continue;
      below += freshShape(rm, t, nullptr).minDihedral <
        options.qualityTarget * optimization::kRegularDihedral;
      ++count;
    }
    return static_cast<double>(below) / count;
  };
  const double before = shareBelow();
  ASSERT_GT(before, 0.0); // the target is above some tets' angles
  OptimizationResult r = optimizeMesh(rm, options);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.shareBelowTargetBefore, before);
  EXPECT_EQ(r.shareBelowTargetAfter, shareBelow());
  EXPECT_LT(r.shareBelowTargetAfter, before);
}

TEST(QualityOptimization, VertexSizeTooShort)
{
  RegionMesh rm = jitteredGridCube(3);
  std::vector<double> h(3, 0.1);
  const FlatArray<std::int32_t> tetsBefore = rm.mesh.tets;
  OptimizationResult r = optimizeMesh(rm, {}, &h);
  EXPECT_FALSE(r.ok);
  EXPECT_FALSE(r.error.empty());
  EXPECT_EQ(rm.mesh.tets, tetsBefore);
}

TEST(QualityOptimization, Deterministic)
{
  RegionMesh a = jitteredGridCube(5);
  RegionMesh b = a;
  optimizeMesh(a, {});
  optimizeMesh(b, {});
  EXPECT_EQ(a.mesh.coords, b.mesh.coords);
  EXPECT_EQ(a.mesh.tets, b.mesh.tets);
  EXPECT_EQ(a.mesh.neighbors, b.mesh.neighbors);
  EXPECT_EQ(a.mesh.flags, b.mesh.flags);
  EXPECT_EQ(a.region, b.region);
}

TEST(QualityOptimization, AbortViaProgress)
{
  RegionMesh rm = jitteredGridCube(4);
  Snapshot before = snapshot(rm);
  OptimizationResult r = optimizeMesh(rm, {}, nullptr, [](double) { return false; });
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.error, "aborted");
  EXPECT_EQ(check(rm, before), "");
}

TEST(QualityOptimization, ChecksRejectCorruption)
{
  // The checks above must be able to fail: move a boundary vertex, invert a tet.
  RegionMesh rm = jitteredGridCube(3);
  Snapshot before = snapshot(rm);
  ASSERT_EQ(check(rm, before), "");
  RegionMesh moved = rm;
  moved.mesh.coords[0] += 1e-3;
  EXPECT_NE(check(moved, before), "");
  RegionMesh inverted = rm;
  std::swap(inverted.mesh.tets[0], inverted.mesh.tets[1]);
  EXPECT_NE(check(inverted, before), "");
}

// Vertex insertion is bounded per stage: none when the budget is 0, at most the budget when
// set, and the mesh's minimum quality never below the run without insertion's floor.
TEST(QualityOptimization, InsertionBudget)
{
  for (int budget : { 0, 3 })
  {
    RegionMesh rm = jitteredGridCube(5);
    OptimizationOptions options;
    options.maxInsertedVertices = budget;
    OptimizationResult r = optimizeMesh(rm, options, nullptr);
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_LE(r.insertedVertices, 2 * budget); // two stages, each with its own budget
    EXPECT_GE(r.minQualityAfter, r.minQualityBefore);
  }
}

// The optimiser's inlined measure gives the same Q and smallest dihedral angle, bit for bit,
// as measureTetForOptimization (what vtkTetQuality reports), plain and size-scaled, and
// measureTetQuality the same Q as measureTet, on random,
// nearly flat, inverted and degenerate tets, with one h or four: otherwise "never worse after
// optimisation" could fail by a rounding in the reported figures.
TEST(QualityOptimization, InlinedMeasureMatchesTetQuality)
{
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(-1.0, 1.0), hs(0.05, 2.0);
  int positive = 0;
  for (int i = 0; i < 20000; ++i)
  {
    double p[4][3];
    for (auto& x : p)
      for (double& c : x)
        c = u(rng);
    if (i % 4 == 1) // nearly flat: d close to the plane of a, b, c
      for (int k = 0; k < 3; ++k)
        p[3][k] = (p[0][k] + p[1][k] + p[2][k]) / 3 + 1e-9 * u(rng);
    if (i % 50 == 7) // degenerate: two equal points
      for (int k = 0; k < 3; ++k)
        p[3][k] = p[1][k];
    // The Q-only measure (the histogram before optimisation) too.
    ASSERT_EQ(measureTetQuality(p[0], p[1], p[2], p[3]), measureTet(p[0], p[1], p[2], p[3]).quality)
      << i;
    double h[4] = { hs(rng), hs(rng), hs(rng), hs(rng) };
    if (i % 3 == 0) // one h at the four vertices: the measure's fast path
      h[1] = h[2] = h[3] = h[0];
    for (const double* hp : { static_cast<const double*>(nullptr), static_cast<const double*>(h) })
    {
      const TetShape ref = measureTetForOptimization(p[0], p[1], p[2], p[3], hp);
      const optimization::TetEval e =
        optimization::measureForOptimization(p[0], p[1], p[2], p[3], hp);
      const bool pos = ref.signedVolume > 0;
      positive += pos;
      ASSERT_EQ(e.q, pos ? ref.quality : 0.0) << i;
      ASSERT_EQ(optimization::dihedralDegrees(e.dihCosine), pos ? ref.minDihedral : 0.0) << i;
    }
  }
  EXPECT_GT(positive, 10000); // both orientations were exercised
}

// The dihedral stage starts from the Q stage's quality cache (Context::adoptCache): every
// entry it takes over must be what measuring the tet anew gives under its own measure (the
// scores differ between the stages), and the Context it took them from must not keep them.
TEST(QualityOptimization, AdoptedCacheMatchesFreshMeasures)
{
  RegionMesh rm = jitteredGridCube(4);
  OptimizationOptions qOptions, dihOptions;
  dihOptions.measure = QualityMeasure::MinDihedral;
  optimization::Context first(rm, qOptions, nullptr);
  optimization::Context second(rm, dihOptions, nullptr);
  int live = 0;
  for (TetId t = 0; t < rm.mesh.tetCapacity(); ++t)
    if (!rm.mesh.isDeleted(t))
    {
      first.quality(t);
      ++live;
    }
  ASSERT_GT(live, 100);
  second.adoptCache(first);
  for (TetId t = 0; t < rm.mesh.tetCapacity(); ++t)
  {
    if (rm.mesh.isDeleted(t))
      continue;
    const optimization::TetEval adopted = second.quality(t), fresh = second.evalTet(t);
    ASSERT_EQ(adopted.score, fresh.score) << t;
    ASSERT_EQ(adopted.q, fresh.q) << t;
    ASSERT_EQ(adopted.dihCosine, fresh.dihCosine) << t;
    ASSERT_NE(adopted.score, adopted.q) << t; // the two measures do differ here
    ASSERT_EQ(first.quality(t).score, first.evalTet(t).score) << t;
  }
}
