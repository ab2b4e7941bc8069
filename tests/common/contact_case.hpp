// Pieces of a case for tests that drive the contact loop without a Simulation: the glass
// species of the test beds and the neighbour list's box for a case.
#pragma once
#include "core/case_spec.hpp"
#include "neighbour/neighbour_list.hpp"

namespace fluidem::test {

/// Glass spheres of d = 3 mm, 2500 kg/m3, E = 1e7 Pa, e = 0.8, mu = 0.4, rolling friction 0.05
/// (the material of random_bed.hpp's glass_species), named `name`.
inline SpeciesSpec glass_species_spec(const char* name) {
  SpeciesSpec sp;
  sp.name = name;
  sp.diameter = 0.003;
  sp.density = 2500.0;
  sp.material.youngs_modulus = 1e7;
  sp.material.restitution = 0.8;
  sp.material.friction = 0.4;
  sp.material.rolling_friction = 0.05;
  return sp;
}

/// The domain, its periodic axes, and a wall on every face of the others.
inline BoxGeometry box_of(const CaseSpec& s) {
  BoxGeometry b;
  b.lo = s.domain.lo;
  b.hi = s.domain.hi;
  b.periodic = s.domain.periodic;
  for (int f = 0; f < 6; ++f) b.wall[f] = !b.periodic[f / 2];
  return b;
}

} // namespace fluidem::test
