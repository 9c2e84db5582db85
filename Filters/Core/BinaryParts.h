// The binary layout of a double, for the exact stages that treat coordinates as integers
// times a power of two (Predicates.cxx, SmallLattice.cxx).
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace tetmesher
{

// A finite double as significand * 2^exponent (significand < 2^53, 0 for zero), and the
// widening of [lowest, highest] to the positions of its lowest and highest set bits (left as
// they are for zero).
struct BinaryParts
{
  std::uint64_t significand;
  int exponent;
};

inline BinaryParts binaryParts(double x, int& lowest, int& highest)
{
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  int e = static_cast<int>((bits >> 52) & 0x7FF);
  std::uint64_t m = bits & ((std::uint64_t(1) << 52) - 1);
  if (e != 0)
    m |= std::uint64_t(1) << 52;
  else
    e = 1; // subnormal
  if (m != 0)
  {
    lowest = std::min(lowest, e - 1075 + __builtin_ctzll(m));
    highest = std::max(highest, e - 1075 + 63 - __builtin_clzll(m));
  }
  return { m, e - 1075 };
}

} // namespace tetmesher
