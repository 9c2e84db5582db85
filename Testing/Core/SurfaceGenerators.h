// Procedural closed triangle surfaces for the mesher's tests: boxes, spheres, tori, a slotted
// ring, a Schonhardt prism, jittered variants. Every generator returns outward-oriented
// triangles (per closed shell), so the enclosed volume follows from the divergence theorem.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <tuple>
#include <vector>

namespace tetmesher
{
namespace testing
{

struct Surface
{
  std::vector<double> points;
  std::vector<std::int32_t> triangles;
  std::int32_t pointCount() const { return static_cast<std::int32_t>(points.size() / 3); }
  std::int32_t triangleCount() const { return static_cast<std::int32_t>(triangles.size() / 3); }
  std::int32_t addPoint(double x, double y, double z)
  {
    // push_back, not insert of a list: GCC 12 warns (-Wstringop-overflow, a false positive)
    // about the inlined insert into an empty vector.
    points.push_back(x);
    points.push_back(y);
    points.push_back(z);
    return pointCount() - 1;
  }
  void addTriangle(std::int32_t a, std::int32_t b, std::int32_t c)
  {
    triangles.insert(triangles.end(), { a, b, c });
  }
  // Appends another surface (its ids shifted).
  void append(const Surface& other)
  {
    std::int32_t offset = pointCount();
    points.insert(points.end(), other.points.begin(), other.points.end());
    for (std::int32_t v : other.triangles)
      triangles.push_back(v + offset);
  }
};

// Flips triangle (a,b,c) unless its normal points away from `inside` (a point it should face
// away from). Floating point: fine for the well-shaped generators below.
inline void orientAway(Surface& s, std::int32_t t, const double* inside)
{
  std::int32_t* v = &s.triangles[3 * t];
  const double* p[3] = { &s.points[3 * v[0]], &s.points[3 * v[1]], &s.points[3 * v[2]] };
  double u[3], w[3], c[3];
  for (int k = 0; k < 3; ++k)
  {
    u[k] = p[1][k] - p[0][k];
    w[k] = p[2][k] - p[0][k];
    c[k] = (p[0][k] + p[1][k] + p[2][k]) / 3 - inside[k];
  }
  double n[3] = { u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0] };
  if (n[0] * c[0] + n[1] * c[1] + n[2] * c[2] < 0)
    std::swap(v[1], v[2]);
}

// Axis-aligned box [x0,x1]x[y0,y1]x[z0,z1] with n[axis] cells per side, triangles split
// alternately (so that the diagonals do not all agree with the Delaunay choice).
inline Surface box(const std::array<double, 3>& lo,
  const std::array<double, 3>& hi,
  const std::array<int, 3>& n,
  bool alternate = true)
{
  Surface s;
  std::map<std::array<int, 3>, std::int32_t> ids;
  auto id = [&](std::array<int, 3> g)
  {
    auto it = ids.find(g);
    if (it != ids.end())
      return it->second;
    std::array<double, 3> x;
    for (int k = 0; k < 3; ++k)
      x[k] = g[k] == n[k] ? hi[k] : lo[k] + (hi[k] - lo[k]) * g[k] / n[k];
    std::int32_t v = s.addPoint(x[0], x[1], x[2]);
    ids.emplace(g, v);
    return v;
  };
  double center[3] = { (lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2 };
  for (int axis = 0; axis < 3; ++axis)
  {
    int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    for (int side = 0; side < 2; ++side)
    {
      for (int i = 0; i < n[a1]; ++i)
      {
        for (int j = 0; j < n[a2]; ++j)
        {
          std::array<int, 3> g00, g10, g01, g11;
          g00[axis] = g10[axis] = g01[axis] = g11[axis] = side ? n[axis] : 0;
          g00[a1] = i, g00[a2] = j;
          g10[a1] = i + 1, g10[a2] = j;
          g01[a1] = i, g01[a2] = j + 1;
          g11[a1] = i + 1, g11[a2] = j + 1;
          std::int32_t v00 = id(g00), v10 = id(g10), v01 = id(g01), v11 = id(g11);
          if (!alternate || (i + j + side + axis) % 2 == 0)
          {
            s.addTriangle(v00, v10, v11);
            s.addTriangle(v00, v11, v01);
          }
          else
          {
            s.addTriangle(v00, v10, v01);
            s.addTriangle(v10, v11, v01);
          }
          orientAway(s, s.triangleCount() - 2, center);
          orientAway(s, s.triangleCount() - 1, center);
        }
      }
    }
  }
  return s;
}

inline Surface cube(int n = 1)
{
  return box({ 0, 0, 0 }, { 1, 1, 1 }, { n, n, n });
}

// cube(2) (its first outerCount triangles) with inner facets (MesherOptions::innerFacets): a
// free square sheet at z = 0.5 (two triangles, four open edges), then a fin standing on the
// bottom face's edge from (0.5, 0, 0) to (0.5, 0.5, 0), which then has three triangles.
inline Surface cubeWithInnerFacets(std::int32_t& outerCount)
{
  Surface s = cube(2);
  outerCount = s.triangleCount();
  const std::int32_t a = s.addPoint(0.25, 0.25, 0.5), b = s.addPoint(0.75, 0.25, 0.5),
                     c = s.addPoint(0.75, 0.75, 0.5), d = s.addPoint(0.25, 0.75, 0.5);
  s.addTriangle(a, b, c);
  s.addTriangle(a, c, d);
  std::int32_t p = -1, q = -1;
  for (std::int32_t v = 0; v < s.pointCount(); ++v)
  {
    const double* x = &s.points[3 * static_cast<std::size_t>(v)];
    if (x[0] == 0.5 && x[2] == 0 && (x[1] == 0 || x[1] == 0.5))
      (x[1] == 0 ? p : q) = v;
  }
  s.addTriangle(p, q, s.addPoint(0.5, 0.25, 0.3));
  return s;
}

// Icosahedron subdivided `level` times, projected on the sphere.
inline Surface icosphere(int level, double radius = 1, std::array<double, 3> c = { 0, 0, 0 })
{
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<std::array<double, 3>> p = { { -1, t, 0 },
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
  std::vector<std::array<int, 3>> f = { { 0, 11, 5 },
    { 0, 5, 1 },
    { 0, 1, 7 },
    { 0, 7, 10 },
    { 0, 10, 11 },
    { 1, 5, 9 },
    { 5, 11, 4 },
    { 11, 10, 2 },
    { 10, 7, 6 },
    { 7, 1, 8 },
    { 3, 9, 4 },
    { 3, 4, 2 },
    { 3, 2, 6 },
    { 3, 6, 8 },
    { 3, 8, 9 },
    { 4, 9, 5 },
    { 2, 4, 11 },
    { 6, 2, 10 },
    { 8, 6, 7 },
    { 9, 8, 1 } };
  for (int l = 0; l < level; ++l)
  {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b)
    {
      auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end())
        return it->second;
      p.push_back({ (p[a][0] + p[b][0]) / 2, (p[a][1] + p[b][1]) / 2, (p[a][2] + p[b][2]) / 2 });
      int id = static_cast<int>(p.size()) - 1;
      mid.emplace(key, id);
      return id;
    };
    std::vector<std::array<int, 3>> g;
    for (auto& tri : f)
    {
      int ab = midpoint(tri[0], tri[1]), bc = midpoint(tri[1], tri[2]),
          ca = midpoint(tri[2], tri[0]);
      g.push_back({ tri[0], ab, ca });
      g.push_back({ tri[1], bc, ab });
      g.push_back({ tri[2], ca, bc });
      g.push_back({ ab, bc, ca });
    }
    f.swap(g);
  }
  Surface s;
  for (auto& x : p)
  {
    double r = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    s.addPoint(c[0] + radius * x[0] / r, c[1] + radius * x[1] / r, c[2] + radius * x[2] / r);
  }
  for (auto& tri : f)
  {
    s.addTriangle(tri[0], tri[1], tri[2]);
    orientAway(s, s.triangleCount() - 1, c.data());
  }
  return s;
}

// A latitude-longitude sphere laid out like vtkSphereSource's (the most common test surface
// in VTK): two poles with fans of `theta` thin triangles, `phi - 2` rings of `theta` points.
// Every point lies on one sphere (up to rounding), the fully co-spherical case, and the pole
// fans give vertices of very high degree.
inline Surface uvSphere(int theta, int phi, double radius = 0.5)
{
  Surface s;
  const double pi = 3.14159265358979323846;
  const std::int32_t north = s.addPoint(0, 0, radius);
  const std::int32_t south = s.addPoint(0, 0, -radius);
  for (int j = 1; j < phi - 1; ++j)
  {
    const double p = pi * j / (phi - 1);
    for (int i = 0; i < theta; ++i)
    {
      const double t = 2 * pi * i / theta;
      s.addPoint(radius * std::sin(p) * std::cos(t),
        radius * std::sin(p) * std::sin(t),
        radius * std::cos(p));
    }
  }
  auto id = [&](int ring, int i) { return 2 + ring * theta + (i % theta); };
  const double centre[3] = { 0, 0, 0 };
  for (int i = 0; i < theta; ++i)
  {
    s.addTriangle(north, id(0, i), id(0, i + 1));
    orientAway(s, s.triangleCount() - 1, centre);
    s.addTriangle(south, id(phi - 3, i + 1), id(phi - 3, i));
    orientAway(s, s.triangleCount() - 1, centre);
    for (int ring = 0; ring + 1 < phi - 2; ++ring)
    {
      s.addTriangle(id(ring, i), id(ring + 1, i), id(ring + 1, i + 1));
      orientAway(s, s.triangleCount() - 1, centre);
      s.addTriangle(id(ring, i), id(ring + 1, i + 1), id(ring, i + 1));
      orientAway(s, s.triangleCount() - 1, centre);
    }
  }
  return s;
}

inline Surface torus(double R, double r, int nu, int nv)
{
  Surface s;
  const double pi = 3.14159265358979323846;
  for (int i = 0; i < nu; ++i)
  {
    double u = 2 * pi * i / nu;
    for (int j = 0; j < nv; ++j)
    {
      double v = 2 * pi * j / nv;
      s.addPoint(
        (R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
    }
  }
  auto id = [&](int i, int j) { return ((i + nu) % nu) * nv + (j + nv) % nv; };
  for (int i = 0; i < nu; ++i)
  {
    for (int j = 0; j < nv; ++j)
    {
      s.addTriangle(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      s.addTriangle(id(i, j), id(i + 1, j + 1), id(i, j + 1));
      for (int k = 2; k >= 1; --k)
      {
        // Orient away from the core circle point nearest the triangle.
        std::int32_t t = s.triangleCount() - k;
        const std::int32_t* v = &s.triangles[3 * t];
        double cx = 0, cy = 0;
        for (int m = 0; m < 3; ++m)
        {
          cx += s.points[3 * v[m]];
          cy += s.points[3 * v[m] + 1];
        }
        double a = std::atan2(cy, cx);
        double core[3] = { R * std::cos(a), R * std::sin(a), 0 };
        orientAway(s, t, core);
      }
    }
  }
  return s;
}

// Annulus with `teeth` deep slots in its outer rim, extruded to height h (like the paper's
// stator, figures 7-8). Radii: inner ri, slot bottom rs, tooth tip ro.
inline Surface slottedRing(int teeth,
  int samplesPerTooth,
  double ri,
  double rs,
  double ro,
  double h)
{
  Surface s;
  const double pi = 3.14159265358979323846;
  int n = teeth * samplesPerTooth;
  std::vector<std::int32_t> in0, in1, out0, out1;
  for (int i = 0; i < n; ++i)
  {
    double a = 2 * pi * i / n;
    double rOut = (i % samplesPerTooth) < samplesPerTooth / 2 ? ro : rs;
    in0.push_back(s.addPoint(ri * std::cos(a), ri * std::sin(a), 0));
    in1.push_back(s.addPoint(ri * std::cos(a), ri * std::sin(a), h));
    out0.push_back(s.addPoint(rOut * std::cos(a), rOut * std::sin(a), 0));
    out1.push_back(s.addPoint(rOut * std::cos(a), rOut * std::sin(a), h));
  }
  for (int i = 0; i < n; ++i)
  {
    int j = (i + 1) % n;
    // bottom (normal -z), top (+z), outer wall, inner wall; quads as two triangles.
    s.addTriangle(in0[i], in0[j], out0[j]);
    s.addTriangle(in0[i], out0[j], out0[i]);
    s.addTriangle(in1[i], out1[j], in1[j]);
    s.addTriangle(in1[i], out1[i], out1[j]);
    s.addTriangle(out0[i], out0[j], out1[j]);
    s.addTriangle(out0[i], out1[j], out1[i]);
    s.addTriangle(in0[i], in1[j], in0[j]);
    s.addTriangle(in0[i], in1[i], in1[j]);
  }
  return s;
}

// Schonhardt's twisted prism: triangles at z=0 and z=1, the top one turned by `twist`
// radians, each side quad split along its reflex diagonal, so no tetrahedralization of the
// six points alone exists.
inline Surface schonhardtPrism(double twist = 0.5)
{
  Surface s;
  const double pi = 3.14159265358979323846;
  for (int i = 0; i < 3; ++i)
    s.addPoint(std::cos(2 * pi * i / 3), std::sin(2 * pi * i / 3), 0);
  for (int i = 0; i < 3; ++i)
    s.addPoint(std::cos(2 * pi * i / 3 + twist), std::sin(2 * pi * i / 3 + twist), 1);
  s.addTriangle(0, 2, 1);
  s.addTriangle(3, 4, 5);
  for (int i = 0; i < 3; ++i)
  {
    int j = (i + 1) % 3;
    // Quad a_i a_j b_j b_i. Twisting the top counterclockwise makes a_j-b_i the convex
    // diagonal, so a_i-b_j is reflex.
    s.addTriangle(i, j, 3 + j);
    s.addTriangle(i, 3 + j, 3 + i);
  }
  return s;
}

// A stack of Schonhardt bands: `sides`-gon layers, each turned by `twist` from the one below,
// every side quad split along its reflex diagonal. Each band needs interior Steiner points.
inline Surface twistedTower(int sides, int layers, double twist, double layerHeight = 0.5)
{
  Surface s;
  const double pi = 3.14159265358979323846;
  for (int l = 0; l <= layers; ++l)
  {
    for (int i = 0; i < sides; ++i)
    {
      double a = 2 * pi * i / sides + l * twist;
      s.addPoint(std::cos(a), std::sin(a), l * layerHeight);
    }
  }
  const double middle[3] = { 0, 0, 0.5 * layers * layerHeight };
  auto id = [&](int l, int i) { return l * sides + (i % sides); };
  for (int i = 1; i + 1 < sides; ++i)
  {
    s.addTriangle(id(0, 0), id(0, i), id(0, i + 1));
    orientAway(s, s.triangleCount() - 1, middle);
    s.addTriangle(id(layers, 0), id(layers, i), id(layers, i + 1));
    orientAway(s, s.triangleCount() - 1, middle);
  }
  for (int l = 0; l < layers; ++l)
  {
    for (int i = 0; i < sides; ++i)
    {
      s.addTriangle(id(l, i), id(l, i + 1), id(l + 1, i + 1));
      s.addTriangle(id(l, i), id(l + 1, i + 1), id(l + 1, i));
      for (int k = 2; k >= 1; --k)
      {
        std::int32_t t = s.triangleCount() - k;
        double axis[3] = { 0, 0, 0 };
        for (int m = 0; m < 3; ++m)
          axis[2] += s.points[3 * s.triangles[3 * t + m] + 2] / 3;
        orientAway(s, t, axis);
      }
    }
  }
  return s;
}

// Moves every point by up to `amount` times a random vector (deterministic LCG).
inline void jitter(Surface& s, double amount, std::uint64_t seed)
{
  auto next = [&]()
  {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(seed >> 11) / 9007199254740992.0 * 2 - 1;
  };
  for (double& x : s.points)
    x += amount * next();
}

// A k x k x k block of unit cubes, each a region of its own: every shared square appears once,
// so inner edges have 3 or 4 triangles. `outer` marks the triangles on the block's boundary.
inline Surface cubeBlocks(int k, std::vector<char>& outer)
{
  Surface s;
  std::map<std::array<int, 3>, std::int32_t> ids;
  std::set<std::array<std::int32_t, 3>> seen;
  outer.clear();
  for (int x = 0; x < k; ++x)
    for (int y = 0; y < k; ++y)
      for (int z = 0; z < k; ++z)
      {
        Surface c = box({ double(x), double(y), double(z) },
          { double(x + 1), double(y + 1), double(z + 1) },
          { 1, 1, 1 },
          false);
        for (std::int32_t t = 0; t < c.triangleCount(); ++t)
        {
          std::array<std::int32_t, 3> v;
          std::array<int, 3> lo = { k, k, k }, hi = { 0, 0, 0 };
          for (int m = 0; m < 3; ++m)
          {
            const double* p = &c.points[3 * c.triangles[3 * t + m]];
            std::array<int, 3> g = { int(p[0]), int(p[1]), int(p[2]) };
            auto it = ids.find(g);
            v[m] = it != ids.end() ? it->second : (ids[g] = s.addPoint(p[0], p[1], p[2]));
            for (int a = 0; a < 3; ++a)
            {
              lo[a] = std::min(lo[a], g[a]);
              hi[a] = std::max(hi[a], g[a]);
            }
          }
          std::array<std::int32_t, 3> key = v;
          std::sort(key.begin(), key.end());
          if (!seen.insert(key).second)
            continue;
          bool onBoundary = false;
          for (int a = 0; a < 3; ++a)
            onBoundary = onBoundary || (lo[a] == hi[a] && (lo[a] == 0 || lo[a] == k));
          s.addTriangle(v[0], v[1], v[2]);
          outer.push_back(onBoundary);
        }
      }
  return s;
}

// Two unit cubes sharing the face x=1 (a multi-material surface: the shared face's edges
// have three triangles). Returns also which triangles are the shared ones.
inline Surface twoCubes(std::vector<char>& shared)
{
  Surface a = box({ 0, 0, 0 }, { 1, 1, 1 }, { 1, 1, 1 }, false);
  Surface b = box({ 1, 0, 0 }, { 2, 1, 1 }, { 1, 1, 1 }, false);
  // Merge b into a, reusing a's points on x=1 and dropping b's copy of the shared face.
  Surface s = a;
  std::vector<std::int32_t> map(b.pointCount());
  for (std::int32_t v = 0; v < b.pointCount(); ++v)
  {
    const double* p = &b.points[3 * v];
    map[v] = -1;
    for (std::int32_t w = 0; w < a.pointCount(); ++w)
    {
      if (a.points[3 * w] == p[0] && a.points[3 * w + 1] == p[1] && a.points[3 * w + 2] == p[2])
        map[v] = w;
    }
    if (map[v] < 0)
      map[v] = s.addPoint(p[0], p[1], p[2]);
  }
  shared.assign(a.triangleCount(), 0);
  for (std::int32_t t = 0; t < a.triangleCount(); ++t)
  {
    bool onShared = true;
    for (int k = 0; k < 3; ++k)
      onShared = onShared && a.points[3 * a.triangles[3 * t + k]] == 1.0;
    shared[t] = onShared;
  }
  for (std::int32_t t = 0; t < b.triangleCount(); ++t)
  {
    bool onShared = true;
    for (int k = 0; k < 3; ++k)
      onShared = onShared && b.points[3 * b.triangles[3 * t + k]] == 1.0;
    if (onShared)
      continue;
    s.addTriangle(
      map[b.triangles[3 * t]], map[b.triangles[3 * t + 1]], map[b.triangles[3 * t + 2]]);
    shared.push_back(0);
  }
  return s;
}

} // namespace testing
} // namespace tetmesher
