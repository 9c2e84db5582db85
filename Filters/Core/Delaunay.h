// Delaunay tetrahedralization by incremental insertion (Bowyer-Watson) in a 5-tet box
// (George-Hecht-Saltel 1990, section 2).
#pragma once

#include "TetMesh.h"

#include <memory>
#include <string>
#include <vector>

namespace tetmesher
{

struct DelaunayOptions
{
  // Box corners are placed this many bounding-box diagonals away from the points.
  double boxEnlargement = 0.5;
  // Check the result exhaustively (exact) after construction; for tests and debugging.
  bool validate = false;
  // Large BRIO rounds are split in two halves of space, inserted side by side (see
  // Delaunay.cxx). The triangulation is the same either way (the symbolic perturbation makes
  // it unique); only the tets' numbering differs. false: one insertion sequence.
  bool partitioned = true;
  // Threads for the two halves: 0 = two when the machine has two CPUs, 1 = one after the
  // other. The mesh, numbering included, does not depend on it.
  int threads = 0;
  // Input points on a small lattice (SmallLattice.h) are tested by exact double evaluation
  // instead of the filtered predicates with their exact fallback; the answers, hence the
  // mesh, are the same. false: the general predicates always (for tests).
  bool smallLatticePredicates = true;
  // The symbolic perturbation's order of the input points: point v is perturbed as if its id
  // were perturbationRank[v] (a permutation of 0..n-1; nullptr: its id). Only exact ties
  // depend on it (PerturbationOrder.h); the mesh is then Delaunay for that order.
  const VertexId* perturbationRank = nullptr;
  // Points not to insert (skip[v] != 0; nullptr: none): they stay vertices that no tet uses
  // (unused input points on the surface, UnusedPoints.h).
  const std::uint8_t* skip = nullptr;
};

struct DelaunayResult
{
  bool ok = false;
  std::string error;
  // Vertex ids that were exact duplicates of an earlier vertex (not inserted), and for
  // each the id of the vertex it duplicates.
  std::vector<VertexId> duplicates;
  std::vector<VertexId> duplicateOf;
  // Ids of the 8 box corner vertices appended after the input points.
  VertexId firstBoxVertex = -1;
};

// Triangulates mesh.coords (vertex ids 0..n-1, n = mesh.vertexCount() on entry). Appends the
// 8 box corners as vertices n..n+7, then inserts the input points in BRIO/Hilbert order.
// On return every live tet is positively oriented, the box tets are present (no ghost
// tets), and mesh.neighbors is symmetric with kNoNeighbor only on the box's faces.
DelaunayResult buildDelaunay(TetMesh& mesh, const DelaunayOptions& options = {});

// The same for the n points at `points` (3 doubles each, left untouched; not mesh.coords' own
// storage, which this replaces), without a copy of them in mesh.coords first: on return
// mesh.coords holds them, then the 8 box corners, as the overload above leaves it.
DelaunayResult buildDelaunay(TetMesh& mesh,
  const double* points,
  VertexId n,
  const DelaunayOptions& options = {});

// Scratch buffers reused across insertions, so that inserting does not allocate.
struct InsertionWorkspace;
InsertionWorkspace* createInsertionWorkspace();
void destroyInsertionWorkspace(InsertionWorkspace* workspace);
// Owns a workspace: std::unique_ptr<InsertionWorkspace, InsertionWorkspaceDeleter>.
struct InsertionWorkspaceDeleter
{
  void operator()(InsertionWorkspace* workspace) const { destroyInsertionWorkspace(workspace); }
};

enum class InsertStatus
{
  Inserted,
  Duplicate,    // an existing vertex has the same coordinates
  OnConstraint, // the point lies exactly on a constrained face: not inserted
  OutsideMesh,  // the walk left the triangulation (point outside the box)
  Postponed     // MeshHalves: the walk or the cavity would reach the other side's tets
};

struct InsertResult
{
  InsertStatus status;
  TetId tet;         // a live tet incident to the new vertex (Inserted), or the duplicate's tet
  VertexId existing; // the duplicated vertex (Duplicate)
};

// Inserts vertex v (already in mesh.coords) into a valid triangulation. The walk starts at
// `hint` (any live tet). The cavity is the set of tets whose circumsphere contains v
// (insphereSoS), grown by adjacency from the tet containing v, never across a constrained
// face (TetMesh flags), and shrunk until v sees every cavity boundary face strictly
// positively, so the result is valid even when constraints make it non-Delaunay. Constraint
// flags on the cavity boundary are preserved. A point on a constrained face or edge (or on
// the hull of the mesh) is refused with OnConstraint; the mesh is then unchanged. If the walk
// reaches the hull (a non-convex mesh), the point is searched exhaustively before
// OutsideMesh is returned. Uses scratch bits 0 and 1 of mesh.flags and clears them again.
InsertResult insertVertex(TetMesh& mesh, VertexId v, TetId hint, InsertionWorkspace& workspace);

// Locates the live tet containing point p (exact walk that terminates), starting at hint.
// Returns -1 if p is outside the triangulation.
TetId locatePoint(const TetMesh& mesh, const double* p, TetId hint);

// The same walk without the exhaustive search: -1 when it reaches the hull of the mesh (p
// outside, or a non-convex mesh between hint and p) or when hint is not a live tet.
TetId walkToPoint(const TetMesh& mesh, const double* p, TetId hint);

// Tet ids moved by MeshHalves::finish: those in [from, to) now are `shift` lower.
struct TetRelocation
{
  TetId from = 0, to = 0, shift = 0;
  TetId map(TetId t) const { return t >= from && t < to ? t - shift : t; }
};

// Two threads inserting into one (constrained) mesh, for callers that choose the points as
// they go (InteriorRefinement's lattice), as buildDelaunay's halves do. Side 0 owns the
// vertices whose coordinate `axis` is below `split`, side 1 the others, and a tet is a side's
// when its 4 vertices are. Between construction and finish(), side k may call locate(k, ...)
// and insert(k, ...) only, from one thread per side; they answer Postponed (leaving the mesh
// unchanged) where the walk would cross a face of the other side's vertices alone or the
// cavity would take a tet that is not the side's own. Nothing else may touch the mesh then.
// Each side reads nothing the other writes: the result does not depend on the threads'
// timing. New tets take slots from a private range per side, about slotsPerPoint * points.
class MeshHalves
{
public:
  MeshHalves(TetMesh& mesh,
    int axis,
    double split,
    std::size_t points0,
    std::size_t points1,
    std::size_t slotsPerPoint = 8);
  ~MeshHalves();
  MeshHalves(const MeshHalves&) = delete;
  MeshHalves& operator=(const MeshHalves&) = delete;

  bool owns(int side, VertexId v) const;
  // The tet containing p, walking from hint (a live tet that is the side's or has a vertex of
  // the side); -1 when the walk reaches the hull, -2 when it would leave the side's tets.
  TetId locate(int side, const double* p, TetId hint);
  // insertVertex for side k: v's coordinates must be in mesh.coords (their size fixed
  // beforehand). Returns Postponed instead of touching the other side's tets.
  InsertResult insert(int side, VertexId v, TetId hint);
  // Closes the gap the sides' slot ranges left: side 1's tets move down to follow side 0's
  // (returned: the caller moves its own per-tet data and tet ids the same way); the mesh is an
  // ordinary one again. The destructor calls it if the caller did not.
  TetRelocation finish();

private:
  struct State;
  std::unique_ptr<State> state_;
};

} // namespace tetmesher
