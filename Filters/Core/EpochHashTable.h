// Open-addressing hash table (linear probing) cleared in O(1) by an epoch: a slot is live only
// when its epoch is the table's. For the scratch of boundary recovery's flip searches (memos of
// exact tests, sets of tried faces and edges), emptied thousands of times per surface: one
// allocation per growth instead of one per entry, and the slots stay for the next search. Also
// the refinement's grids of cells: a look-up reads one or two slots, where std::unordered_map
// follows a bucket's pointers.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tetmesher
{

// A hash of 64-bit keys that spreads every input bit (the splitmix64 finaliser): packed grid
// cell indices differ in few, low bits, and the table keeps only the low bits of the hash.
struct MixHash64
{
  std::size_t operator()(std::uint64_t x) const
  {
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ULL;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebULL;
    return static_cast<std::size_t>(x ^ (x >> 31));
  }
};

template<typename Key, typename Value, typename Hash>
class EpochHashTable
{
public:
  // The value of k, or nullptr.
  const Value* find(const Key& k) const
  {
    if (slots_.empty())
      return nullptr;
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t i = Hash()(k) & mask;; i = (i + 1) & mask)
    {
      if (slots_[i].epoch != epoch_)
        return nullptr;
      if (slots_[i].key == k)
        return &slots_[i].value;
    }
  }

  Value* find(const Key& k)
  {
    return const_cast<Value*>(static_cast<const EpochHashTable*>(this)->find(k));
  }
  // Adds k with `value` and returns true, or returns false (and changes nothing) when k is in.
  bool insert(const Key& k, const Value& value = Value())
  {
    if (2 * (size_ + 1) > slots_.size())
      grow();
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t i = Hash()(k) & mask;; i = (i + 1) & mask)
    {
      if (slots_[i].epoch != epoch_)
      {
        slots_[i] = { k, value, epoch_ };
        ++size_;
        return true;
      }
      if (slots_[i].key == k)
        return false;
    }
  }

  // Sets k's value, adding k when it is not in.
  void assign(const Key& k, const Value& value)
  {
    if (Value* known = find(k))
      *known = value;
    else
      insert(k, value);
  }

  void clear()
  {
    size_ = 0;
    if (++epoch_ == 0)
    {
      for (Slot& slot : slots_)
        slot.epoch = 0;
      epoch_ = 1;
    }
  }

private:
  struct Slot
  {
    Key key{};
    Value value{};
    std::uint32_t epoch = 0; // live when equal to epoch_
  };
  void grow()
  {
    std::vector<Slot> old(std::max<std::size_t>(64, 2 * slots_.size()));
    old.swap(slots_);
    const std::uint32_t live = epoch_;
    epoch_ = 1;
    size_ = 0;
    for (const Slot& slot : old)
      if (slot.epoch == live)
        insert(slot.key, slot.value);
  }

  std::vector<Slot> slots_;
  std::size_t size_ = 0;
  std::uint32_t epoch_ = 1;
};

} // namespace tetmesher
