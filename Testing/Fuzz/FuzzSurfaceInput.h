// Decoding of fuzzer bytes into a small triangle surface, shared by the libFuzzer target
// (FuzzSurface.cxx) and the regression test (Testing/Core/TestFuzzRegressions.cxx), so that a
// crash file found by the fuzzer replays through exactly the same entry.
//
// Layout (all integers little endian):
//   byte 0: mode = b & 3, flags = b >> 2
//     mode 0: "lattice": byte 1 gives n = 1 + b % 48 points, each as three int16 scaled by
//             1/256; then every 3 bytes are a triangle, each index taken modulo n.
//     mode 1: "grid": like mode 0 but each coordinate is one int8 taken modulo 5 (values
//             -4..4 step 1), so that coincident points, collinear and coplanar configurations
//             are frequent.
//     mode 2: "real surface": uint16 point count n, then n points as three raw IEEE doubles,
//             then every 6 bytes a triangle of three uint16 indices, each taken modulo n.
//             Seeds are Data/ surfaces converted by make_seeds.py; mutating raw doubles gives
//             NaN, Inf, huge and tiny coordinates.
//     mode 3: "real surface, float": as mode 2 with float32 coordinates (small mutations keep
//             the surface nearly intact).
//     flags bit 0: MesherOptions::enclosedShellsAreHoles
//     flags bit 1: also run meshSurface with validateInput = false on input that the
//                  diagnosis refuses (the mesher must still fail cleanly, not crash), with
//                  a time limit of kUncheckedSeconds
//     flags bit 2: DiagnosisOptions::maxRecordsPerKind = 3
//     flags bit 3: on a surface the mesher accepts (of at most kMaxPipelineTriangles), also
//                  run the whole pipeline, meshVolume: size field, interior points (at most
//                  kMaxPipelinePoints), optimisation
//     flags bit 4: inner facets (MesherOptions::innerFacets, DiagnosisOptions::innerFacets):
//                  open edges and triangles with one region on both sides pass the checks
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace tetmesher
{
namespace fuzz
{

struct FuzzSurface
{
  std::vector<double> points;
  std::vector<std::int32_t> triangles;
  bool enclosedShellsAreHoles = false;
  bool meshInvalidInput = false;
  bool limitRecords = false;
  bool fullPipeline = false;
  bool innerFacets = false;
  std::int32_t pointCount() const { return static_cast<std::int32_t>(points.size() / 3); }
  std::int32_t triangleCount() const { return static_cast<std::int32_t>(triangles.size() / 3); }
};

// Bounds that keep one execution short.
constexpr std::size_t kMaxPoints = 4000;
constexpr std::size_t kMaxTriangles = 8000;
constexpr std::int32_t kMaxPipelineTriangles = 1000;
constexpr int kMaxPipelinePoints = 3000;
// MesherOptions::maxSeconds of the flag-bit-1 run (unchecked input): see FuzzSurfaceCheck.h.
constexpr double kUncheckedSeconds = 3.0;

inline FuzzSurface decodeFuzzSurface(const std::uint8_t* data, std::size_t size)
{
  FuzzSurface s;
  if (size < 2)
    return s;
  const int mode = data[0] & 3;
  const int flags = data[0] >> 2;
  s.enclosedShellsAreHoles = (flags & 1) != 0;
  s.meshInvalidInput = (flags & 2) != 0;
  s.limitRecords = (flags & 4) != 0;
  s.fullPipeline = (flags & 8) != 0;
  s.innerFacets = (flags & 16) != 0;
  std::size_t pos = 1;
  std::size_t n = 0;
  if (mode == 0 || mode == 1)
  {
    n = 1 + data[pos++] % 48;
    const std::size_t bytesPerCoordinate = mode == 0 ? 2 : 1;
    for (std::size_t i = 0; i < 3 * n; ++i)
    {
      if (pos + bytesPerCoordinate > size)
        break;
      if (mode == 0)
      {
        const std::int16_t v = static_cast<std::int16_t>(data[pos] | (data[pos + 1] << 8));
        s.points.push_back(v / 256.0);
      }
      else
      {
        s.points.push_back(static_cast<std::int8_t>(data[pos]) % 5);
      }
      pos += bytesPerCoordinate;
    }
    s.points.resize(3 * (s.points.size() / 3));
    n = s.points.size() / 3;
    if (n == 0)
      return s;
    while (pos + 3 <= size && s.triangles.size() < 3 * kMaxTriangles)
    {
      for (int k = 0; k < 3; ++k)
        s.triangles.push_back(static_cast<std::int32_t>(data[pos + k] % n));
      pos += 3;
    }
    return s;
  }
  if (pos + 2 > size)
    return s;
  n = data[pos] | (data[pos + 1] << 8);
  pos += 2;
  if (n > kMaxPoints)
    n = kMaxPoints;
  const std::size_t bytesPerCoordinate = mode == 2 ? 8 : 4;
  for (std::size_t i = 0; i < 3 * n && pos + bytesPerCoordinate <= size; ++i)
  {
    if (mode == 2)
    {
      double v;
      std::memcpy(&v, data + pos, 8);
      s.points.push_back(v);
    }
    else
    {
      float v;
      std::memcpy(&v, data + pos, 4);
      s.points.push_back(v);
    }
    pos += bytesPerCoordinate;
  }
  s.points.resize(3 * (s.points.size() / 3));
  n = s.points.size() / 3;
  if (n == 0)
    return s;
  while (pos + 6 <= size && s.triangles.size() < 3 * kMaxTriangles)
  {
    for (int k = 0; k < 3; ++k)
      s.triangles.push_back(
        static_cast<std::int32_t>((data[pos + 2 * k] | (data[pos + 2 * k + 1] << 8)) % n));
    pos += 6;
  }
  return s;
}

} // namespace fuzz
} // namespace tetmesher
