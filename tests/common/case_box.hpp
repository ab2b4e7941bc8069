// The neighbour list's box for a case (tests that drive the contact loop without a Simulation):
// the domain, its periodic axes, and a wall on every face of the others.
#pragma once
#include "core/case_spec.hpp"
#include "neighbour/neighbour_list.hpp"

namespace fluidem::test {

inline BoxGeometry box_of(const CaseSpec& s) {
  BoxGeometry b;
  b.lo = s.domain.lo;
  b.hi = s.domain.hi;
  b.periodic = s.domain.periodic;
  for (int f = 0; f < 6; ++f) b.wall[f] = !b.periodic[f / 2];
  return b;
}

} // namespace fluidem::test
