// Energy housekeeping of the particle phase [Hoomans96 eq. 51]: kinetic, rotational and
// potential energy (relative to the origin: e_pot = -sum m g.x). The elastic energy stored in
// contacts and the cumulative dissipated energy come from the contact module.
#pragma once
#include <array>

#include "particles/particle_store.hpp"

namespace fluidem {

struct Energies {
  double kinetic = 0.0;    ///< sum 1/2 m v^2, J
  double rotational = 0.0; ///< sum 1/2 I w^2, J
  double potential = 0.0;  ///< -sum m g.x, J
};

/// Over the moving particles: fixed ones (ParticleStore::fix) never move and count as walls.
Energies particle_energies(const ParticleStore& p, const std::array<double, 3>& gravity);

/// Height of a settled 2-D bed's surface above z_lo: the mean over columns of width
/// `column_width` of the highest disc top (z + r) whose centre lies in the column.
double bed_surface_height(const ParticleStore& p, double x_lo, double x_hi, double z_lo,
                          double column_width);

/// Area fraction of a settled 2-D bed, "the area under the upper layers of particles"
/// [Hoomans96 §5.1]: total disc area / (width x bed_surface_height).
double settled_area_fraction(const ParticleStore& p, double x_lo, double x_hi, double z_lo);

} // namespace fluidem
