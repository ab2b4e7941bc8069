// A narrow column of the Tsuji particles [Hoomans96 Table 2] for coupled tests: aluminium
// spheres d = 4 mm, 2700 kg/m3, e = e_w = 0.9, mu = mu_w = 0.3, in a 3-D box, by default one
// particle deep (a pseudo-2-D bed: the centres stay in the plane y = d/2), gas cells of
// 10 mm x 20 mm, one cell deep (the whole depth), air (ideal gas, 293 K), distributor porosity 0.4
// at the bottom inflow, prescribed pressure at the top, no-slip side walls, drag ergun_wen_yu,
// porosity by cell (exact sphere volumes: no 2-D conversion, so the solid volume the gas sees is
// the particles' own). The particles start at random positions in the whole column and fall.
// periodic_sides: no side walls, the column is periodic along x and y (a piece of a wide bed),
// gas cells 10 mm across y too.
#pragma once
#include <algorithm>
#include <cmath>

#include "core/case_spec.hpp"

namespace fluidem::test {

struct TsujiColumn {
  Engine engine = Engine::HardSphere;
  double width = 0.04, height = 0.3, depth = 0.004; ///< m
  long count = 400;
  double end_time = 1.0; ///< s
  gas::InflowProfile inflow{gas::InflowMode::constant, 2.5};
  bool periodic_sides = false;
  double cell_width = 0.01, cell_height = 0.02; ///< gas cells: across (x, and y if periodic), up; m
};

inline CaseSpec tsuji_column(const TsujiColumn& c) {
  const double d = 0.004;
  CaseSpec s;
  s.source_file = "tsuji column (test)";
  s.simulation.engine = c.engine;
  s.simulation.dimension = 3;
  s.simulation.end_time = c.end_time;
  if (c.engine == Engine::HardSphere) s.simulation.time_step = 1e-4;
  s.domain.lo = {0.0, 0.0, 0.0};
  s.domain.hi = {c.width, c.depth, c.height};
  s.domain.periodic = {c.periodic_sides, c.periodic_sides, false};
  SpeciesSpec sp;
  sp.name = "aluminium";
  sp.diameter = d;
  sp.density = 2700.0;
  sp.material.restitution = 0.9;
  sp.material.friction = 0.3;
  s.species.push_back(sp);
  for (auto& w : s.domain.wall_material) w = sp.material;
  InsertSpec ins;
  ins.species = sp.name;
  ins.count = c.count;
  ins.placement = Placement::Random;
  ins.region_lo = s.domain.lo;
  ins.region_hi = s.domain.hi;
  s.inserts.push_back(ins);
  gas::GasSettings g;
  g.cells = {static_cast<int>(std::lround(c.width / c.cell_width)),
             c.periodic_sides ? std::max(1, static_cast<int>(std::lround(c.depth / c.cell_width)))
                              : 1,
             static_cast<int>(std::lround(c.height / c.cell_height))};
  g.time_step = c.engine == Engine::SoftSphere ? 1e-4 : 0.0;
  g.boundary[gas::bottom].type = gas::BoundaryType::inflow;
  g.boundary[gas::bottom].inflow = c.inflow;
  g.boundary[gas::bottom].porosity = 0.4;
  g.boundary[gas::top].type = gas::BoundaryType::pressure;
  s.gas = g;
  return s;
}

/// Weight of the particles less their buoyancy in the gas, per unit bed cross-section, Pa.
inline double bed_weight_per_area(const CaseSpec& s, double particle_mass, double gas_density) {
  const double area = (s.domain.hi[0] - s.domain.lo[0]) * (s.domain.hi[1] - s.domain.lo[1]);
  const double rho_p = s.species[0].density;
  return static_cast<double>(s.inserts[0].count) * particle_mass * 9.81 *
         (1.0 - gas_density / rho_p) / area;
}

} // namespace fluidem::test
