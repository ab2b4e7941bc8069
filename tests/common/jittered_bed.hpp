// A dense test bed for the contact loops: a jittered lattice of glass spheres (d = 3 mm) in a
// closed 6 x 6 x 6 cm box, with overlaps of up to a few percent of a diameter, random velocities
// and spins; one or two species of the same material, radii equal or spread by +-1%.
#pragma once
#include <random>
#include <string>

#include "contact_case.hpp"
#include "core/case_spec.hpp"
#include "particles/particle_store.hpp"

namespace fluidem::test {

constexpr double kJitteredD = 0.003;
constexpr double kJitteredL = 0.06; // box edge along x and y
constexpr double kJitteredH = 0.06; // box height

inline CaseSpec jittered_bed_spec(int species, const std::string& normal) {
  CaseSpec s;
  s.simulation.dimension = 3;
  s.domain.lo = {0.0, 0.0, 0.0};
  s.domain.hi = {kJitteredL, kJitteredL, kJitteredH};
  for (int k = 0; k < species; ++k) // d = kJitteredD
    s.species.push_back(test::glass_species_spec(k == 0 ? "glass" : "glass_b"));
  s.contact.normal.name = normal;
  if (normal == "jkr")
    s.contact.normal.coefficients["adhesion_energy"] = 0.2;
  else if (normal != "hertz")
    s.contact.normal.coefficients["stiffness"] = 2000.0;
  // Walton & Braun's spring (history of its own) with the Mindlin-Deresiewicz tangential force.
  s.contact.tangential.name = normal == "walton_braun" ? "mindlin_deresiewicz" : "history";
  s.contact.rolling.name = "spring_dashpot";
  return s;
}

/// A jittered lattice of `layers` layers, spacing 0.97 d, random velocities and spins, the
/// first layer on the floor and the outer columns against the side walls. Species alternate
/// between 0 and species - 1 by particle; radii are d/2 or spread by +-1% (`spread`).
inline ParticleStore jittered_bed(int layers, int species, bool spread) {
  ParticleStore p;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double a = 0.97 * kJitteredD;
  const int nxy = static_cast<int>((kJitteredL - kJitteredD) / a) + 1;
  std::int64_t id = 0;
  for (int k = 0; k < layers; ++k)
    for (int j = 0; j < nxy; ++j)
      for (int i = 0; i < nxy; ++i) {
        const Vec3 x{0.49 * kJitteredD + i * a + 0.02 * kJitteredD * u(rng),
                     0.49 * kJitteredD + j * a + 0.02 * kJitteredD * u(rng),
                     0.49 * kJitteredD + k * a + 0.02 * kJitteredD * u(rng)};
        const Vec3 v{0.3 * u(rng), 0.3 * u(rng), 0.3 * u(rng)};
        const double r = 0.5 * kJitteredD * (spread ? 1.0 + 0.01 * u(rng) : 1.0);
        p.add(x, v, r, 2500.0, static_cast<int>(id % species), id);
        ++id;
        const std::size_t n = p.size() - 1;
        p.wx[n] = 50.0 * u(rng), p.wy[n] = 50.0 * u(rng), p.wz[n] = 50.0 * u(rng);
      }
  return p;
}

} // namespace fluidem::test
