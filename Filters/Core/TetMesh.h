// TetMesh: the flat-array tetrahedral mesh shared by every stage of the mesher.
//
// Layout (after Gmsh HXT): 4 vertex ids per tet, 4 neighbour references per tet encoded
// as 4*t+f (the face of the neighbour that is glued to ours), one flag byte per tet.
// Deleted slots are kept on a free list and reused, so ids stay small and arrays dense.
//
// Conventions every stage relies on:
//  - A live tet (a,b,c,d) is positively oriented: orient3d(a,b,c,d) > 0 in Shewchuk's
//    convention, i.e. det[a-d; b-d; c-d] > 0 (d lies below the plane of a,b,c seen ccw).
//  - Face f of a tet is the face opposite its vertex f; kFaceVertices[f] lists that face's
//    vertices ordered so that their right-hand normal points out of the tet.
//  - kNoNeighbor marks a face on the hull of the triangulation.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace tetmesher
{

using VertexId = std::int32_t;
using TetId = std::int32_t;
using FaceRef = std::int32_t; // 4*t+f

constexpr FaceRef kNoNeighbor = -1;
constexpr VertexId kDeletedTet = -1;

// Outward-oriented vertex triples of the face opposite each vertex of a positive tet.
constexpr int kFaceVertices[4][3] = { { 1, 3, 2 }, { 0, 2, 3 }, { 0, 3, 1 }, { 0, 1, 2 } };

// Per-tet flag bits. Bits 0..3: face f is a constraint (an input triangle) that the
// Delaunay cavity must not cross. Bits 4..7 are scratch bits for one algorithm at a time.
enum TetFlag : std::uint8_t
{
  kConstrainedFace0 = 1u << 0,
  kScratchBit0 = 1u << 4,
  kScratchBit1 = 1u << 5,
  kScratchBit2 = 1u << 6,
  kScratchBit3 = 1u << 7,
};

inline FaceRef makeFaceRef(TetId t, int f)
{
  return 4 * t + f;
}
inline TetId faceTet(FaceRef r)
{
  return r >> 2;
}
inline int faceIndex(FaceRef r)
{
  return r & 3;
}

// An allocator whose value-less construct leaves the element uninitialised, so that resize()
// of the tet arrays writes nothing: the Delaunay kernel sizes private ranges for two threads
// and each thread first touches (page faults, zeroing) the slots it fills.
template<typename T>
struct UninitializedAllocator : std::allocator<T>
{
  template<typename U>
  struct rebind
  {
    using other = UninitializedAllocator<U>;
  };
  UninitializedAllocator() = default;
  template<typename U>
  UninitializedAllocator(const UninitializedAllocator<U>&) noexcept
  {
  }
  template<typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible<U>::value)
  {
    ::new (static_cast<void*>(p)) U;
  }
  template<typename U, typename... Args>
  void construct(U* p, Args&&... args)
  {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

// A std::vector that resize() does not fill (see UninitializedAllocator).
template<typename T>
using FlatArray = std::vector<T, UninitializedAllocator<T>>;

// Tet slots set aside for one of two threads that edit one mesh side by side (the
// optimiser's halves of space): the slots it freed, then a range of fresh ones. A thread only
// ever writes slots of its own pool, so neither needs a lock.
struct TetSlotPool
{
  std::vector<TetId> freeTets;
  TetId next = 0, end = 0; // fresh slots [next, end)
  std::size_t available() const { return freeTets.size() + static_cast<std::size_t>(end - next); }
};

struct TetMesh
{
  std::vector<double> coords;    // 3 doubles per vertex
  FlatArray<VertexId> tets;      // 4 per tet; tets[4t] == kDeletedTet marks a free slot
  FlatArray<FaceRef> neighbors;  // 4 per tet
  FlatArray<std::uint8_t> flags; // 1 per tet
  std::vector<TetId> freeTets;   // deleted slots available for reuse

  VertexId vertexCount() const { return static_cast<VertexId>(coords.size() / 3); }
  TetId tetCapacity() const { return static_cast<TetId>(tets.size() / 4); }
  TetId liveTetCount() const { return tetCapacity() - static_cast<TetId>(freeTets.size()); }
  const double* point(VertexId v) const { return &coords[3 * static_cast<std::size_t>(v)]; }

  VertexId addVertex(double x, double y, double z)
  {
    coords.push_back(x);
    coords.push_back(y);
    coords.push_back(z);
    return vertexCount() - 1;
  }

  bool isDeleted(TetId t) const { return tets[4 * static_cast<std::size_t>(t)] == kDeletedTet; }
  VertexId vertex(TetId t, int i) const { return tets[4 * static_cast<std::size_t>(t) + i]; }
  FaceRef neighbor(TetId t, int f) const { return neighbors[4 * static_cast<std::size_t>(t) + f]; }
  bool isConstrained(TetId t, int f) const { return (flags[t] >> f) & 1u; }

  void setConstrained(TetId t, int f, bool on)
  {
    if (on)
      flags[t] = static_cast<std::uint8_t>(flags[t] | (1u << f));
    else
      flags[t] = static_cast<std::uint8_t>(flags[t] & ~(1u << f));
  }

  // Creates a tet with no neighbours and no flags, reusing a free slot when there is one.
  TetId addTet(VertexId a, VertexId b, VertexId c, VertexId d)
  {
    TetId t;
    if (!freeTets.empty())
    {
      t = freeTets.back();
      freeTets.pop_back();
    }
    else
    {
      // push_back, not resize: its in-capacity path inlines (resize's does not, and was 9% of
      // the Delaunay kernel's time).
      t = tetCapacity();
      for (VertexId v : { a, b, c, d })
        tets.push_back(v);
      for (int f = 0; f < 4; ++f)
        neighbors.push_back(kNoNeighbor);
      flags.push_back(0);
      return t;
    }
    setTet(t, a, b, c, d);
    return t;
  }
  // addTet in a slot of `pool` (which must have one available).
  TetId addTet(TetSlotPool& pool, VertexId a, VertexId b, VertexId c, VertexId d)
  {
    TetId t;
    if (!pool.freeTets.empty())
    {
      t = pool.freeTets.back();
      pool.freeTets.pop_back();
    }
    else
      t = pool.next++;
    setTet(t, a, b, c, d);
    return t;
  }

  // Frees the slot. Neighbours still pointing here must be re-glued by the caller.
  void deleteTet(TetId t)
  {
    tets[4 * static_cast<std::size_t>(t)] = kDeletedTet;
    freeTets.push_back(t);
  }
  void deleteTet(TetSlotPool& pool, TetId t)
  {
    tets[4 * static_cast<std::size_t>(t)] = kDeletedTet;
    pool.freeTets.push_back(t);
  }

  // Glues face f of t to face g of u (both directions). u may be kNoNeighbor-encoded.
  void glue(TetId t, int f, TetId u, int g)
  {
    neighbors[4 * static_cast<std::size_t>(t) + f] = makeFaceRef(u, g);
    neighbors[4 * static_cast<std::size_t>(u) + g] = makeFaceRef(t, f);
  }

  // Slot t (in range) becomes tet (a,b,c,d) with no neighbours and no flags.
  void setTet(TetId t, VertexId a, VertexId b, VertexId c, VertexId d)
  {
    std::size_t base = 4 * static_cast<std::size_t>(t);
    tets[base] = a;
    tets[base + 1] = b;
    tets[base + 2] = c;
    tets[base + 3] = d;
    for (int f = 0; f < 4; ++f)
      neighbors[base + f] = kNoNeighbor;
    flags[t] = 0;
  }

  void setHull(TetId t, int f) { neighbors[4 * static_cast<std::size_t>(t) + f] = kNoNeighbor; }
};

} // namespace tetmesher
