// The particle store: one contiguous array per quantity (structure of arrays), so that hot loops
// stream through exactly the data they use. Spheres (3-D) or discs moving in the x-z plane (2-D,
// y components stay zero). Mass and moment of inertia are those of a solid sphere in both cases
// (the 2-D beds of [Hoomans96] are spheres confined to a plane).
#pragma once
#include <cstdint>
#include <vector>

#include "core/vec3.hpp"

namespace fluidem {

class ParticleStore {
public:
  // Positions, m
  std::vector<double> x, y, z;
  // Velocities, m/s
  std::vector<double> vx, vy, vz;
  // Angular velocities, rad/s
  std::vector<double> wx, wy, wz;
  // Radius (m), mass (kg), inverse mass (1/kg), inverse moment of inertia (1/(kg m^2)).
  // A fixed particle (fix()) has inv_mass = inv_inertia = 0: a body of infinite mass and inertia
  // for every force, torque and collision (it never moves or turns); `mass` keeps the sphere's.
  std::vector<double> radius, mass, inv_mass, inv_inertia;
  // Species index into the species table; unique id (stable across sorting)
  std::vector<std::int32_t> species;
  std::vector<std::int64_t> id;
  // Index (0 .. output.layers-1) of the horizontal band of the initial bed the particle started
  // in (assign_layers); 0 for every particle when output.layers is 0. Constant during a run.
  std::vector<std::int32_t> layer;
  // Electric charge, C (electrostatics); 0 for an uncharged particle. Constant during a run.
  std::vector<double> charge;

  std::size_t size() const { return x.size(); }
  void reserve(std::size_t n);
  void resize(std::size_t n);
  /// Give back the arrays' spare capacity (after insertion, which grows them by appending).
  void shrink_to_fit();

  /// Append one particle at rest. Mass and inertia from radius and density. (The forces on the
  /// particles are not kept here: the contact forces are in ContactScratch, the gas forces in the
  /// coupling.)
  void add(const Vec3& position, const Vec3& velocity, double particle_radius, double density,
           std::int32_t species_index, std::int64_t particle_id);

  Vec3 position(std::size_t i) const { return {x[i], y[i], z[i]}; }
  Vec3 velocity(std::size_t i) const { return {vx[i], vy[i], vz[i]}; }
  Vec3 angular_velocity(std::size_t i) const { return {wx[i], wy[i], wz[i]}; }
  /// Hold particle i in place for the whole run: inverse mass and inertia 0 (infinite mass and
  /// inertia), velocity and angular velocity 0. Checkpoints carry it in inv_mass.
  void fix(std::size_t i);
  /// Whether particle i is fixed (fix()).
  bool fixed(std::size_t i) const { return inv_mass[i] == 0.0; }

  /// f(array) for each per-particle array, always in this order (for whatever moves whole
  /// particles: permute, the MPI exchange, so that a new array cannot be forgotten there).
  template <class F>
  void for_each_array(F&& f) {
    f(x), f(y), f(z), f(vx), f(vy), f(vz), f(wx), f(wy), f(wz);
    f(radius), f(mass), f(inv_mass), f(inv_inertia), f(species), f(id), f(layer), f(charge);
  }
  template <class F>
  void for_each_array(F&& f) const {
    const_cast<ParticleStore&>(*this).for_each_array([&](const auto& a) { f(a); });
  }

  /// Reorder every array by new_to_old (new index k takes old particle new_to_old[k]).
  void permute(const std::vector<std::uint32_t>& new_to_old);
  /// Bytes held by the arrays (capacity), for memory reports.
  std::size_t bytes() const;
};

/// Mass of a solid sphere of radius r and density rho, kg.
double sphere_mass(double r, double rho);

/// Set p.layer: split [lowest, highest] particle centre coordinate along `axis` (0, 1, 2 = x, y,
/// z) into n_layers equal slices and give each particle the index of its slice, 0 at the low
/// end; a centre on a boundary (within 1e-9 of a slice height) goes to the upper slice, the
/// highest one to the last.
/// All particles at one height (or n_layers <= 1): every index 0.
void assign_layers(ParticleStore& p, int axis, int n_layers);

} // namespace fluidem
