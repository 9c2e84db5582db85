// Removal of an edge by a bounded sequence of flips (TetGen's flipnm): an edge removal, else
// the best 2-3 flip of a face around the edge (it takes one vertex out of the edge's ring),
// else, one level down, first removing the link edge that makes such a flip invalid. Every
// move is kept in a journal so that a sequence that does not pay off can be undone. Used by
// boundary recovery (moves that never raise its measure) and by the removal of recovery
// Steiner points (any valid move: the measure is empty).
#pragma once

#include "EpochHashTable.h"
#include "Flips.h"

#include <deque>
#include <functional>
#include <vector>

namespace tetmesher
{

class DeepEdgeRemoval
{
public:
  // One move, kept to undo it. Tets are named by their vertices too: undoing a later move
  // restores earlier tets under other ids.
  struct JournalEntry
  {
    std::vector<TetId> createdIds;
    std::vector<TetVertices> created, old;
  };
  struct Journal
  {
    std::vector<JournalEntry> entries;
    int delta = 0; // change of the measure over the whole mesh (each move prices its region)
    int moves = 0; // made, undone or not
  };

  // `fixedEdge` (may be empty) names edges that are never removed, besides those with a
  // constrained face around them.
  DeepEdgeRemoval(TetMesh& mesh,
    VertexTetIndex& index,
    std::function<bool(VertexId, VertexId)> fixedEdge = {});

  // Removes edge (p,q) by moves that never raise `cost`; `level` link levels, `budget` moves
  // at most (decremented per shell examined). On failure the moves made stay in the journal
  // for the caller to undo.
  bool remove(VertexId p, VertexId q, int level, const FlipCost& cost, int& budget);
  // Undoes the moves after the first `mark` entries and sets the journal's delta.
  void undoTo(std::size_t mark, int delta);
  // Empties the journal (for a new attempt, or to keep the moves made), keeping the entries'
  // buffers for the next moves.
  void resetJournal();

  Journal journal;
  // When set, collects the vertices of every shell examined (to tell when a failed attempt
  // could succeed: once one of their tets changed).
  std::vector<VertexId>* seen = nullptr;
  // When set, called with the id of every tet a move or an undo creates (a caller that keeps
  // per-tet data, such as regions, fills it in).
  std::function<void(TetId)> onCreated;

  // When set, edge removal candidates are remembered by their edge and ring: attempts that
  // are undone come back to the same shells (boundary recovery: over half of the shells a
  // flip search examines), and the ring determines the shell's tets, hence the candidate.
  // Valid for one measure and fixed points: call forgetCandidates when the measure changes.
  // (The constrained faces around the edge are checked before the candidate, on every call.)
  bool memoizeCandidates = false;
  void forgetCandidates();

private:
  void apply(const FlipCandidate& move);
  // edgeRemovalCandidate for the shell and ring of (p,q) (as edgeShell walks them), remembered
  // when memoizeCandidates is set; `remembered` is then the entry's index (else -1).
  bool removalCandidate(VertexId p,
    VertexId q,
    const std::vector<TetId>& shell,
    const std::vector<VertexId>& ring,
    const FlipCost& cost,
    FlipCandidate& out,
    std::int32_t& remembered);
  // The best 2-3 flip of a face around (p,q) that does not raise `cost` (false: none), with
  // the answer remembered in entry `remembered` when that is not -1.
  bool bestFlip(const std::vector<TetId>& shell,
    const std::vector<VertexId>& ring,
    const FlipCost& cost,
    std::int32_t remembered,
    FlipCandidate& move,
    FlipCandidate& best);

  TetMesh& mesh_;
  VertexTetIndex& index_;
  std::function<bool(VertexId, VertexId)> fixedEdge_;
  std::vector<TetId> star_;
  // Scratch kept between calls (no allocation per move or shell): journal entries no longer
  // in the journal, and remove's vectors per recursion depth (a deque: references to a
  // shallower level's stay valid while a deeper one is added).
  std::vector<JournalEntry> spareEntries_;
  struct Level
  {
    std::vector<TetId> shell;
    std::vector<VertexId> ring;
    FlipCandidate move, best;
  };
  std::deque<Level> levels_;
  std::size_t depth_ = 0;
  std::vector<TetId> undoTets_;
  struct RememberedRemoval
  {
    std::vector<VertexId> key; // p, q, then the ring
    bool ok = false;
    FlipCandidate candidate; // without its old tets (their ids change)
    std::int32_t next = -1;  // the next entry of the same hash, or -1
    // The best flip of bestFlip, for the shell whose tets' vertices (4 per tet, in order)
    // are flipShell (empty: not computed): the new tets' vertex order follows the old tets',
    // and the shapes that break ties follow that order. flip: its ring index, or -1 (none).
    std::vector<VertexId> flipShell;
    int flip = -1;
    FlipCandidate flipCandidate; // without its old tets
  };
  EpochHashTable<std::uint64_t, std::int32_t, MixHash64> rememberedByHash_;
  std::vector<RememberedRemoval> remembered_; // the first rememberedCount_ are live
  std::size_t rememberedCount_ = 0;
  std::vector<VertexId> keyScratch_, shellScratch_;
  struct TetVerticesHash
  {
    std::size_t operator()(const TetVertices& t) const
    {
      std::uint64_t h = 0x9e3779b97f4a7c15ull;
      for (VertexId v : t)
        h = (h ^ static_cast<std::uint32_t>(v)) * 0x100000001b3ull;
      return static_cast<std::size_t>(h ^ (h >> 29));
    }
  };
  EpochHashTable<TetVertices, TetId, TetVerticesHash> restoredIds_; // undoTo
  std::vector<TetId> restoredScratch_;
};

} // namespace tetmesher
