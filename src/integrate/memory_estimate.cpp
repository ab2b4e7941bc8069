#include "integrate/memory_estimate.hpp"

#include <fmt/format.h>

#include "contact/contact_table.hpp"
#include "hardsphere/collision_operator.hpp"
#include "particles/insertion.hpp"

namespace fluidem {

namespace {

/// A coupled run per gas cell, bytes: the solver's fields and matrices, hypre's multigrid
/// hierarchy, porosity and exchange fields, the fields writer. From the maximum resident size
/// of whole runs (bench/RESULTS.md, "Memory per cell").
constexpr double kGasBytesPerCell = 750.0;
/// A run with [output.continuum] per averaging cell, bytes: the 36 running sums, the 35 fields
/// of a result and the writer's copy. Calibrated as above.
constexpr double kContinuumBytesPerCell = 870.0;

double product(const std::array<int, 3>& n) {
  return static_cast<double>(n[0]) * static_cast<double>(n[1]) * static_cast<double>(n[2]);
}

} // namespace

std::vector<MemoryShare> case_memory_shares(const CaseSpec& spec, std::optional<double> particles) {
  std::vector<MemoryShare> shares;
  MemoryShare p = particle_memory_share(spec);
  if (particles) {
    p.what = fmt::format("{:.3g} particles", *particles);
    p.bytes = *particles * kBytesPerParticle;
  }
  shares.push_back(p);
  if (spec.simulation.engine == Engine::HardSphere) {
    const auto n = static_cast<double>(spec.species.size());
    shares.push_back({"species",
                      fmt::format("the collision laws of {:.0f} species ({:.3g} pairs)", n, n * n),
                      n * (n + 6.0) * static_cast<double>(sizeof(hardsphere::CollisionLaw))});
  } else {
    shares.push_back(ContactTable::memory_share(spec));
  }
  if (spec.gas) {
    const double cells = product(spec.gas->cells);
    shares.push_back({"gas.cells", fmt::format("the gas grid of {:.3g} cells", cells),
                      cells * kGasBytesPerCell});
  }
  if (spec.output.continuum) {
    const double cells = product(spec.output.continuum->cells);
    shares.push_back({"output.continuum.cells",
                      fmt::format("the continuum averaging grid of {:.3g} cells", cells),
                      cells * kContinuumBytesPerCell});
  }
  return shares;
}

} // namespace fluidem
