// How much memory a refined mesh will need, and how much the machine has, so that a size
// field asking for more is refused before anything is allocated (a clear error instead of an
// allocation failure or the kernel's out-of-memory killer an hour later).
#pragma once

#include <cstdint>
#include <string>

namespace tetmesher
{

// Peak bytes of the whole pipeline (refinement, optimisation, the VTK output and its writing)
// per interior point estimated by refineInterior (RefinementResult::estimatedPoints).
// Measured 2026-11-28: the CLI on Data/cube.vtp at --size 0.02 peaked at 339 MB resident for
// 217k points (177k estimated, 1.39M tets), i.e. 1.9 kB per estimated point with the process's
// fixed 28 MB; 2 kB leaves a little room.
constexpr double kBytesPerEstimatedPoint = 2000.0;

// Peak bytes of the boundary mesh per input point (Delaunay, recovery, regions, the VTK input
// and output). Measured 2026-11-28, CLI --boundary-only on vtkSphereSource-like spheres:
// 2.13 GB for 998k points, 239 MB for 89k points (2.1-2.4 kB per point beyond the fixed 28 MB).
constexpr double kBytesPerInputPoint = 2500.0;

// Tets per vertex of a Delaunay-like mesh (6.4-6.6 measured); with the face references
// 4 * tet + face held in 32-bit integers, a mesh can have at most 2^29 tets.
constexpr double kTetsPerPoint = 6.5;
constexpr double kMaxTets = 536870912.0; // 2^29

// The memory this process can still get without swapping: MemAvailable of /proc/meminfo on
// Linux, else the available physical pages; 0 when unknown. The smaller of that and the
// address-space limit (ulimit -v), when one is set.
double availableMemoryBytes();

// "1.5 GB", "340 MB", "12 kB": for messages.
std::string formatBytes(double bytes);

// Empty when a mesh of about `estimatedPoints` interior points fits in `limitBytes`
// (<= 0: no memory limit) and in the 32-bit indices; else the error, naming the estimate,
// the limit and what to change.
std::string checkMemoryBudget(double estimatedPoints, double limitBytes);

// The same for the boundary mesh of a surface of `pointCount` points, before its Delaunay
// tetrahedralization is built.
std::string checkBoundaryMemoryBudget(double pointCount, double limitBytes);

} // namespace tetmesher
