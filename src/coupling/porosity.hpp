// Gas volume fraction (porosity) per gas cell from the particles [Deen07 §3.5].
//
//  - cell method [Deen07 eq. 33]: eps = 1 - sum_i f_i V_i / V_cell with f_i V_i the EXACT volume
//    of sphere i inside the cell (3-D), or, in 2-D (discs in the x-z plane, one cell across y),
//    the exact area of disc i inside the cell converted to a 3-D porosity with
//    [Hoomans96 eq. 49]: eps_3D = 1 - 2/sqrt(pi sqrt 3) (1 - eps_2D)^(3/2).
//  - porous cube [Deen07 eq. 34-37]: particle i is a cube of side a d_i centred on it (a >=
//    (pi/6)^(1/3) [eq. 35], typically 3-5) with solid fraction pi/(6 a^3) [eq. 36]; the cell gets
//    its overlap with the cube times that fraction [eq. 37]: the weights of cube_mapping.hpp,
//    which also map the gas to the particle [eq. 38-39]. The cube is shifted to lie inside
//    the domain (so no solid volume is lost at walls; a domain narrower than the cube gets the
//    whole volume in its width). In 2-D the square of side a d carries the disc area pi d^2/4,
//    then [Hoomans96 eq. 49].
// Solid outside the domain (cell method: a sphere overlapping a wall) is not counted. Along a
// periodic axis nothing is outside: the part of a sphere (or cube) beyond the periodic face is
// counted in the image cells at the other end.
#pragma once
#include "core/coupling_settings.hpp"
#include "core/vec3.hpp"
#include "coupling/cube_mapping.hpp"
#include "coupling/rank_sum.hpp"
#include "gas/gas_grid.hpp"
#include "particles/particle_store.hpp"
#include <array>
#include <vector>

namespace fluidem::coupling {

/// InputError if cube_factor < (pi/6)^(1/3) (porous cube) or not finite.
void validate(const PorositySettings& s);

/// Area of the disc |(y, z)| < r inside the quadrant {y < Y, z < Z}, exact, m^2.
double disc_quadrant_area(double r, double Y, double Z);
/// Volume of the ball |x| < R inside the octant {x < X, y < Y, z < Z}, m^3, in closed form
/// (sqrt, atan2): spherical cap, two-plane wedge [Strobl16, see .cpp], three-plane corner
/// (divergence theorem + Gauss-Bonnet), planes on the centre's side reduced to these by
/// inclusion-exclusion. Absolute error ~1e-15 R^3 (tests: <= 1e-15 R^3 against 40-digit values);
/// bitwise symmetric in (X, Y, Z).
double ball_octant_volume(double R, double X, double Y, double Z);
/// Volume of the sphere (centre c, radius R) inside the box [lo, hi], m^3.
double sphere_box_volume(const Vec3& c, double R, const std::array<double, 3>& lo,
                         const std::array<double, 3>& hi);
/// Area of the disc (centre (cx, cz), radius R) inside the rectangle [x0, x1] x [z0, z1], m^2.
double disc_rect_area(double cx, double cz, double R, double x0, double x1, double z0, double z1);

/// A cell with less gas than this is all solid to round-off (a cell inside a sphere: the
/// cell method on cells smaller than the particles; or overlapping particles): an error.
inline constexpr double min_porosity = 1e-6;

/// [Hoomans96 eq. 49]: 3-D porosity from the 2-D (area) porosity of a disc layer.
double porosity_2d_to_3d(double eps_2d);

/// The cells a sphere covers, c0..c1 per axis (1..1 across y in 2-D); along periodic axes on
/// the unwrapped index range (folded onto their images when the parts are stored).
struct CellRange {
  std::array<int, 3> c0{1, 1, 1}, c1{1, 1, 1};
  long count() const {
    return static_cast<long>(c1[0] - c0[0] + 1) * (c1[1] - c0[1] + 1) * (c1[2] - c0[2] + 1);
  }
};

/// Work space of solid_fraction / compute_porosity, kept between calls by the caller so that
/// a flow step does not allocate (the per-particle parts of the cell method, the solid field,
/// the porous cube's weights).
struct PorosityScratch {
  std::vector<long> offset;     ///< cell method: first entry of particle i (size n + 1)
  std::vector<CellRange> range; ///< cell method: the cells of particle i
  std::vector<long> cell;       ///< cell method: grid index of each entry
  std::vector<double> part; ///< cell method: solid fraction of the entry's cell from its particle
  std::vector<double> solid;
  CubeWeights cube;
  FixedPointSum fixed; ///< with ranks: the fixed-point sums
};

/// Solid volume fraction (1 - eps) per cell (padded layout of the grid; ghosts set to 0):
/// 3-D: solid volume / V_cell; 2-D: solid AREA fraction in the x-z plane, before eq. 49.
/// `periodic` per axis (y is ignored on 2-D grids).
/// Cell method: the particles' parts are computed independently (OpenMP threads from a few
/// hundred particles on) and then summed per cell in particle order by one thread: the result
/// does not depend on the number of threads (bitwise).
void solid_fraction(const gas::GasGrid& g, const ParticleStore& p, const PorositySettings& s,
                    std::vector<double>& out, const std::array<bool, 3>& periodic = {});
/// The same with caller-kept work space (no allocation once warmed up). With `ranks`: `p` is
/// this rank's particles, and `out` the sum over all ranks' in fixed point (rank_sum.hpp).
void solid_fraction(const gas::GasGrid& g, const ParticleStore& p, const PorositySettings& s,
                    std::vector<double>& out, const std::array<bool, 3>& periodic,
                    PorosityScratch& scratch, const RankSum* ranks = nullptr);

/// Porosity of every interior cell into eps (size = g.size()); ghosts along periodic axes get
/// the images, other ghosts are untouched. 2-D grids use [Hoomans96 eq. 49]. Throws
/// InstabilityError if a cell's porosity is below min_porosity.
void compute_porosity(const gas::GasGrid& g, const ParticleStore& p, const PorositySettings& s,
                      std::vector<double>& eps, const std::array<bool, 3>& periodic);
void compute_porosity(const gas::GasGrid& g, const ParticleStore& p, const PorositySettings& s,
                      std::vector<double>& eps, const std::array<bool, 3>& periodic,
                      PorosityScratch& scratch, const RankSum* ranks = nullptr);

} // namespace fluidem::coupling
