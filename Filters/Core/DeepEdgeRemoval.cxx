#include "DeepEdgeRemoval.h"

#include "FilteredPredicates.h"
#include "Predicates.h"

#include <algorithm>
#include <cassert>

namespace tetmesher
{

DeepEdgeRemoval::DeepEdgeRemoval(TetMesh& mesh,
  VertexTetIndex& index,
  std::function<bool(VertexId, VertexId)> fixedEdge)
  : mesh_(mesh)
  , index_(index)
  , fixedEdge_(std::move(fixedEdge))
{
}

void DeepEdgeRemoval::apply(const FlipCandidate& move)
{
  if (spareEntries_.empty())
    journal.entries.emplace_back();
  else
  {
    journal.entries.push_back(std::move(spareEntries_.back()));
    spareEntries_.pop_back();
  }
  JournalEntry& entry = journal.entries.back();
  entry.old.clear();
  for (TetId t : move.oldTets)
    entry.old.push_back(
      { mesh_.vertex(t, 0), mesh_.vertex(t, 1), mesh_.vertex(t, 2), mesh_.vertex(t, 3) });
  entry.created = move.newTets;
  replaceTets(mesh_, index_, move.oldTets, move.newTets, &entry.createdIds);
  if (onCreated)
    for (TetId t : entry.createdIds)
      onCreated(t);
  journal.delta += move.newCost - move.oldCost;
  ++journal.moves;
}

void DeepEdgeRemoval::resetJournal()
{
  for (JournalEntry& entry : journal.entries)
    spareEntries_.push_back(std::move(entry));
  journal.entries.clear();
  journal.delta = 0;
  journal.moves = 0;
}

void DeepEdgeRemoval::undoTo(std::size_t mark, int delta)
{
  std::vector<TetId>& tets = undoTets_;
  auto verticesOf = [this](TetId t) -> TetVertices {
    return { mesh_.vertex(t, 0), mesh_.vertex(t, 1), mesh_.vertex(t, 2), mesh_.vertex(t, 3) };
  };
  // restoredIds_: the ids under which undos restored tets, by their vertices (in order), to
  // find where an earlier move's tet came back without searching a star for it. An entry is
  // used only while its tet is live with those vertices (then it is the one tet that has
  // them), so the nested undos of a removal can share it; cleared when the journal empties.
  while (journal.entries.size() > mark)
  {
    const JournalEntry& entry = journal.entries.back();
    tets.clear();
    for (std::size_t i = 0; i < entry.created.size(); ++i)
    {
      const TetVertices& v = entry.created[i];
      TetId id = entry.createdIds[i];
      if (verticesOf(id) != v)
      {
        // Undoing a later move put this tet back under another id: find it by its vertices.
        const TetId* restored = restoredIds_.find(v);
        id = -1;
        if (restored && !mesh_.isDeleted(*restored) && verticesOf(*restored) == v)
          id = *restored;
        else
        {
          vertexStar(mesh_, index_, v[0], star_);
          for (TetId t : star_)
          {
            if (verticesOf(t) == v)
              id = t;
          }
        }
      }
      tets.push_back(id);
    }
    // Moves are undone last first, so every tet a move created is there again.
    assert(std::find(tets.begin(), tets.end(), TetId(-1)) == tets.end());
    replaceTets(mesh_, index_, tets, entry.old, &restoredScratch_);
    if (onCreated)
      for (TetId t : restoredScratch_)
        onCreated(t);
    for (std::size_t i = 0; i < entry.old.size(); ++i)
      restoredIds_.assign(entry.old[i], restoredScratch_[i]);
    spareEntries_.push_back(std::move(journal.entries.back()));
    journal.entries.pop_back();
  }
  if (journal.entries.empty())
    restoredIds_.clear();
  journal.delta = delta;
}

void DeepEdgeRemoval::forgetCandidates()
{
  rememberedByHash_.clear();
  rememberedCount_ = 0; // the entries keep their vectors for reuse
}

bool DeepEdgeRemoval::removalCandidate(VertexId p,
  VertexId q,
  const std::vector<TetId>& shell,
  const std::vector<VertexId>& ring,
  const FlipCost& cost,
  FlipCandidate& out,
  std::int32_t& remembered)
{
  remembered = -1;
  if (!memoizeCandidates)
    return edgeRemovalCandidate(mesh_, p, q, shell, ring, cost, out);
  std::vector<VertexId>& key = keyScratch_;
  key.assign({ p, q });
  key.insert(key.end(), ring.begin(), ring.end());
  std::uint64_t hash = 0x9e3779b97f4a7c15ull;
  for (VertexId v : key)
    hash = (hash ^ static_cast<std::uint32_t>(v)) * 0x100000001b3ull;
  std::int32_t* head = rememberedByHash_.find(hash);
  for (std::int32_t e = head ? *head : -1; e >= 0; e = remembered_[e].next)
  {
    const RememberedRemoval& entry = remembered_[e];
    if (entry.key != key)
      continue;
    remembered = e;
    if (entry.ok)
    {
      out.newTets = entry.candidate.newTets;
      out.oldCost = entry.candidate.oldCost;
      out.newCost = entry.candidate.newCost;
      out.minQuality = entry.candidate.minQuality;
      out.oldTets = shell; // as edgeRemovalCandidate gives
    }
    return entry.ok;
  }
  const bool ok = edgeRemovalCandidate(mesh_, p, q, shell, ring, cost, out);
  if (rememberedCount_ == remembered_.size())
    remembered_.emplace_back();
  const auto index = static_cast<std::int32_t>(rememberedCount_++);
  RememberedRemoval& entry = remembered_[index];
  remembered = index;
  entry.key = key;
  entry.ok = ok;
  entry.flipShell.clear();
  if (ok)
  {
    entry.candidate.newTets = out.newTets;
    entry.candidate.oldCost = out.oldCost;
    entry.candidate.newCost = out.newCost;
    entry.candidate.minQuality = out.minQuality;
  }
  entry.next = head ? *head : -1;
  if (head)
    *head = index;
  else
    rememberedByHash_.insert(hash, index);
  return ok;
}

bool DeepEdgeRemoval::bestFlip(const std::vector<TetId>& shell,
  const std::vector<VertexId>& ring,
  const FlipCost& cost,
  std::int32_t remembered,
  FlipCandidate& move,
  FlipCandidate& best)
{
  const int n = static_cast<int>(ring.size());
  std::vector<VertexId>& tets = shellScratch_;
  if (remembered >= 0)
  {
    tets.clear();
    for (TetId s : shell)
      tets.insert(tets.end(),
        &mesh_.tets[4 * static_cast<std::size_t>(s)],
        &mesh_.tets[4 * static_cast<std::size_t>(s)] + 4);
    const RememberedRemoval& entry = remembered_[remembered];
    if (entry.flipShell == tets)
    {
      if (entry.flip < 0)
        return false;
      best.newTets = entry.flipCandidate.newTets;
      best.oldCost = entry.flipCandidate.oldCost;
      best.newCost = entry.flipCandidate.newCost;
      best.minQuality = entry.flipCandidate.minQuality;
      best.oldTets = { shell[entry.flip], shell[(entry.flip + n - 1) % n] }; // as flip23Candidate
      return true;
    }
  }
  // A 2-3 flip of face (p,q,ring[k]) takes ring[k] out of the ring: the best that does not
  // raise the measure.
  int found = -1;
  for (int k = 0; k < n; ++k)
  {
    TetId s = shell[k];
    if (!flip23Candidate(mesh_, s, localIndex(mesh_, s, ring[(k + 1) % n]), cost, move) ||
      move.newCost > move.oldCost)
      continue;
    if (found < 0 || betterMove(move, best))
    {
      best = move;
      found = k;
    }
  }
  if (remembered >= 0)
  {
    RememberedRemoval& entry = remembered_[remembered];
    entry.flipShell = tets;
    entry.flip = found;
    if (found >= 0)
      entry.flipCandidate = best;
  }
  return found >= 0;
}

bool DeepEdgeRemoval::remove(VertexId p, VertexId q, int level, const FlipCost& cost, int& budget)
{
  // Rings longer than this are left alone (TetGen limits its flip star the same way).
  constexpr int kMaxRing = 10;
  if (levels_.size() == depth_)
    levels_.emplace_back();
  Level& scratch = levels_[depth_];
  struct DepthGuard
  {
    std::size_t& depth;
    ~DepthGuard() { --depth; }
  } depthGuard{ ++depth_ };
  std::vector<TetId>& shell = scratch.shell;
  std::vector<VertexId>& ring = scratch.ring;
  FlipCandidate& move = scratch.move;
  FlipCandidate& best = scratch.best;
  auto positive = [this](VertexId a, VertexId b, VertexId c, VertexId d)
  {
    return predicates::orient3dFiltered(
             mesh_.point(a), mesh_.point(b), mesh_.point(c), mesh_.point(d)) > 0;
  };
  auto fixed = [this](VertexId a, VertexId b) { return fixedEdge_ && fixedEdge_(a, b); };
  while (budget > 0)
  {
    TetId t = findEdge(mesh_, index_, p, q);
    if (t < 0)
      return true;
    if (fixed(p, q) || !edgeShell(mesh_, t, p, q, shell, ring))
      return false;
    if (seen)
    {
      seen->push_back(p);
      seen->push_back(q);
      seen->insert(seen->end(), ring.begin(), ring.end());
    }
    const int n = static_cast<int>(ring.size());
    if (n > kMaxRing)
      return false;
    for (int k = 0; k < n; ++k)
    {
      if (mesh_.isConstrained(shell[k], localIndex(mesh_, shell[k], ring[(k + 1) % n])))
        return false;
    }
    --budget;
    std::int32_t remembered = -1;
    if (removalCandidate(p, q, shell, ring, cost, move, remembered) && move.newCost <= move.oldCost)
    {
      apply(move);
      return true;
    }
    if (bestFlip(shell, ring, cost, remembered, move, best))
    {
      apply(best);
      continue;
    }
    if (level == 0)
      return false;
    // No such flip: remove a link edge that blocks one. Face (p,q,r) lies between the tets
    // (p,q,u,r) and (p,q,r,w), positive; its 2-3 flip makes (p,q,u,w), (w,q,u,r) and
    // (p,w,u,r), and a non-positive one of the last two names the blocking edge, (q,r) or
    // (p,r). Only that one is tried, not every edge to the ring.
    // (The deeper removals walk shells into their own level's scratch: ring stays.)
    bool progressed = false;
    for (int k = 0; k < n && !progressed && budget > 0; ++k)
    {
      const VertexId u = ring[(k + n - 1) % n], r = ring[k], w = ring[(k + 1) % n];
      if (!positive(p, q, u, w))
        continue;
      for (VertexId end : { q, p })
      {
        const bool blocks = end == q ? !positive(w, q, u, r) : !positive(p, w, u, r);
        if (!blocks || fixed(end, r))
          continue;
        const std::size_t mark = journal.entries.size();
        const int delta = journal.delta;
        if (remove(end, r, level - 1, cost, budget))
        {
          progressed = true;
          break;
        }
        undoTo(mark, delta);
      }
    }
    if (!progressed)
      return false;
  }
  return false;
}

} // namespace tetmesher
