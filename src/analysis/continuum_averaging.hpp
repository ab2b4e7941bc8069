// Discrete-to-continuum averaging [Zhu07 Tables 5 and 6; Zhu & Yu 2002, Physica A 311, 185;
// Babic 1997; Goldhirsch 2010, Granular Matter 12, 239]: on a regular grid of cells, the solids
// volume fraction, the mass-weighted mean velocity, the inertia-weighted mean angular velocity,
// the kinetic (streaming) stress, the contact stress and the couple stress, averaged over the
// sampled steps of an averaging interval (time-volume average). Formulas, sign convention and
// what was reconstructed from the garbled seed text: docs/analysis.md, "Discrete-to-continuum
// averaging". In short (tension positive, compression negative; component [3a + b] = T_ab with
// a the force / moment component and b the branch / flux direction, div acting on b):
//   volume   [Zhu07 Table 5, Method 3, w = 1 for the cell holding the centre]:
//            phi = sum_p V_p / V,   rho u = sum_p m_p v_p / V,
//            T_kin = -sum_p m_p v'_p (x) v'_p / V,
//            T_con = sum_p sum_c f_pc (x) l_pc / V,   M = sum_p sum_c m_pc (x) l_pc / V,
//            l_pc = contact point - x_p, m_pc = l_pc x f_pc + rolling torque on p.
//   weighted [Zhu07 Table 6, Zhu & Yu 2002]: h(r) = Gaussian of width w truncated at c w;
//            phi = sum_p V_p h(x_p - r),   T_kin = -sum_p m_p v'_p (x) v'_p h(x_p - r),
//            T_con = sum_pairs f_ij (x) d_ij g_ij,   M = sum_pairs q_ij (x) d_ij g_ij,
//            d_ij = x_j - x_i (branch; for a wall: contact point - x_i), f_ij force on i,
//            q_ij = (m_ij - m_ji)/2 (wall: m_iw), g_ij = int_0^1 h(x_i + s d_ij - r) ds
//            (integrated exactly along the branch line).
// v' is the velocity less the cell's time-averaged mean velocity u; the time average divides the
// sums accumulated over the sampled steps by their number.
//
// Determinism: every cell sums its particles and contacts in one fixed order (bins in index
// order, items in index order), cells are independent: the results do not depend on the number
// of OpenMP threads (bitwise).
#pragma once
#include <array>
#include <cstddef>
#include <vector>

#include "particles/contact_record.hpp" // ContactSample: a plain struct (core/vec3.hpp only)
#include "particles/particle_store.hpp"

namespace fluidem {

enum class AveragingMethod { Volume, Weighted };

/// The averaging grid: cells[0] x cells[1] x cells[2] cells of size spacing from lo; cell
/// (i,j,k) is element i + nx (j + ny k) of every field. Periodic axes wrap distances (minimum
/// image) and branches. 2-D runs (discs in the x-z plane): cells[1] = 1 and the y extent is
/// the box depth, the volume the cells' (so phi is the volume fraction of the spheres in the
/// slab); the weighted method's Gaussian is then 2-D in x-z, uniform over the depth.
struct ContinuumGrid {
  std::array<int, 3> cells{1, 1, 1};
  std::array<double, 3> lo{0.0, 0.0, 0.0};
  std::array<double, 3> spacing{1.0, 1.0, 1.0};
  std::array<bool, 3> periodic{false, false, false};
  int dimension = 3; ///< 2: discs in x-z (cells[1] must be 1)
  std::size_t size() const {
    return static_cast<std::size_t>(cells[0]) * static_cast<std::size_t>(cells[1]) *
           static_cast<std::size_t>(cells[2]);
  }
  double cell_volume() const { return spacing[0] * spacing[1] * spacing[2]; }
};

struct ContinuumSettings {
  AveragingMethod method = AveragingMethod::Volume;
  double width = 0.0;  ///< m, Gaussian standard deviation w (weighted only), > 0
  double cutoff = 3.0; ///< the Gaussian is zero beyond cutoff * width (weighted only), > 0
  /// Cells are summed by OpenMP threads when particles + contacts exceed this (the volume
  /// method; a sixteenth of it for the weighted one, whose cells cost more): a parallel region
  /// costs more than a small bed's sums. The results do not depend on it.
  std::size_t parallel_threshold = 50000;
};

/// Time-volume averaged fields, one value per cell (x fastest). Tensors: component [3a + b].
struct ContinuumFields {
  std::vector<double> solid_fraction;                ///< phi, -
  std::array<std::vector<double>, 3> velocity;       ///< u, m/s (0 where no mass)
  std::array<std::vector<double>, 3> angular_vel;    ///< inertia-weighted mean omega, rad/s
  std::array<std::vector<double>, 9> kinetic_stress; ///< Pa
  std::array<std::vector<double>, 9> contact_stress; ///< Pa
  std::array<std::vector<double>, 9> couple_stress;  ///< N/m (contact part)
  /// theta = sum w m |v - u|^2 / (D sum w m) = -tr(kinetic_stress) / (D rho_s phi), m^2/s^2,
  /// D = 3 (2 for discs in x-z); 0 where no mass [Deen07 §6.2; Goldschmidt et al. 2002].
  std::vector<double> granular_temperature;
  long samples = 0; ///< steps averaged
};

/// The accumulated sums of an averaging interval (kept in checkpoints).
struct ContinuumState {
  std::vector<double> sums; ///< kAccumulators per cell, see continuum_averaging.cpp
  long samples = 0;
};

class ContinuumAverager {
public:
  /// std::invalid_argument (naming the bad setting) for a grid without cells, non-positive
  /// spacing, a non-positive width or cutoff (weighted), a cutoff radius above half a periodic
  /// length, or a 2-D grid with cells[1] != 1.
  ContinuumAverager(const ContinuumGrid& grid, const ContinuumSettings& settings);

  /// Add one step: the particles and that step's contacts (ContactRecord::samples; each
  /// sample's indices refer to `p`).
  void accumulate(const ParticleStore& p, const std::vector<ContactSample>& contacts);
  /// The time averages of the steps accumulated since the last reset (all zero if none).
  ContinuumFields result() const;
  void reset();
  long samples() const { return state_.samples; }

  const ContinuumGrid& grid() const { return grid_; }
  const ContinuumSettings& settings() const { return settings_; }
  const ContinuumState& state() const { return state_; }
  /// Restore accumulated sums (restart); std::invalid_argument if the size does not fit.
  void set_state(ContinuumState s);

  /// The weight h(r) of the weighted method at distance vector r (2-D: r_y ignored), 1/m^3.
  double weight(double rx, double ry, double rz) const;
  /// int_0^1 h(a + s d) ds for the segment from a to a + d (relative to the field point), 1/m^3.
  double segment_weight(const Vec3& a, const Vec3& d) const;

private:
  void accumulate_volume(const ParticleStore& p, const std::vector<ContactSample>& contacts);
  void accumulate_weighted(const ParticleStore& p, const std::vector<ContactSample>& contacts);
  std::array<int, 3> cell_of(double x, double y, double z) const;
  /// Flat index i + nx (j + ny k) of cell (i, j, k).
  std::size_t flat(const std::array<int, 3>& c) const;
  /// key_[i] = flat index of particle i's cell; start_/order_ = the particles binned by cell.
  void bin_particles(const ParticleStore& p);
  Vec3 min_image(Vec3 d) const;

  ContinuumGrid grid_;
  ContinuumSettings settings_;
  ContinuumState state_;
  double norm_ = 0.0;   ///< Gaussian prefactor (truncated normalisation)
  double radius_ = 0.0; ///< cutoff radius, m
  std::array<double, 3> length_{};
  // Scratch reused between steps (bins).
  std::vector<std::size_t> key_, start_, order_, seg_start_, seg_order_;
};

} // namespace fluidem
