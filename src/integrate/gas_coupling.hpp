// One flow step of the discrete particle model, shared by both particle engines
// [Hoomans96 Fig. 7; Deen07 §3; Zhu07 §3.2 scheme 3]. At time t^n, with particles at x^n, v^n:
//   1. porosity eps^{n+1} from x^n (porosity by cell or porous cube, coupling/porosity.hpp);
//   2. per particle c_i = V_i K(eps_i, |u^n_i - v^n_i|) from the drag closure;
//   3. the gas gets the semi-implicit sink S = sum_i w c_i (v^n_i - u^{n+1}) / V_cell and is
//      advanced to t^{n+1} = t^n + DT (gas/gas_solver.hpp);
//   4. the particles get drag_i = c_i (u^{n+1}_i - v^n_i) (exactly minus what the gas got) and,
//      in Model A, -V_i grad p^{n+1} [Zhu07 eq. 5].
//   coupling.mode "one_way" skips the gas's sink in 3 and steps the gas with porosity 1 (the
//   particles still see their own porosity); "frozen" skips 3 (a prescribed field). These forces
//   act unchanged over the next
//      DT: the hard-sphere engine takes them as one velocity kick before its collision sequence
//      [Hoomans96 eq. 33, Fig. 7], the soft-sphere DEM adds them in each of its sub-steps.
// The gas settings of the case are completed here from the particle domain: dimension, lo/hi,
// 2-D depth (the domain's y extent) and gravity are the simulation's own.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/case_spec.hpp"
#include "coupling/exchange.hpp"
#include "coupling/rank_sum.hpp"
#include "coupling/smoothing.hpp"
#include "gas/gas_solver.hpp"
#include "integrate/fluid_forces.hpp"
#include "integrate/force_sources.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

/// Gas fields at the interior cell centres, x fastest (index i + nx (j + ny k)), for output.
struct CellFields {
  std::array<int, 3> cells{};
  std::vector<double> porosity, pressure;
  std::array<std::vector<double>, 3> gas_velocity;    ///< interstitial, mean of the two faces
  std::array<std::vector<double>, 3> solids_velocity; ///< mass-weighted mean over the particles
                                                      ///< whose centre is in the cell; 0 if none
};

class GasCoupling {
public:
  /// The gas settings of `spec` completed from its domain and simulation sections.
  static gas::GasSettings complete_settings(const CaseSpec& spec);

  /// Validates the coupling (InputError naming the key), builds the gas solver and sets the
  /// initial porosity from the particles (old = new, so the first step starts at rest).
  GasCoupling(const CaseSpec& spec, const ParticleStore& p);
  ~GasCoupling();

  /// Steps 1-4 above, from `time` to `time + dt`. InstabilityError if the gas solver fails.
  /// With [coupling.forces]: their held forces are added to force() (fluid_forces.hpp), and
  /// their reaction of the step before goes to the gas (two-way).
  void step(const ParticleStore& p, double time, double dt);

  /// A distributed run: step() is then given this rank's own particles, and the sums over the
  /// particles into the gas are taken over all ranks in fixed point (coupling/rank_sum.hpp), so
  /// that every rank steps the same gas, bit for bit, on any rank count. The ranks share the
  /// gas's step (gas::GasSolver::share; solver: the ranks of `ranks`).
  void distribute(coupling::RankSum ranks, const gas::SharedSolve& solver) {
    ranks_ = std::move(ranks);
    gas_->share(solver);
  }
  /// Distributed runs: the bytes of the fixed-point sums reduced over the ranks so far, and
  /// their reductions (the grid-sized ones).
  double bytes_summed_over_ranks() const {
    return porosity_scratch_.fixed.bytes_reduced() + f_.fixed.bytes_reduced();
  }
  long sums_over_ranks() const {
    return porosity_scratch_.fixed.reductions() + f_.fixed.reductions();
  }

  /// [coupling.forces], for n particles and the flow step flow_dt (every step() must be that
  /// long: the Basset history's samples are uniform in time).
  void set_up_fluid_forces(double flow_dt, std::size_t n, const BodyForceSpec* field);
  /// The inertia [coupling.forces] adds to a moving particle of diameter d (virtual mass and
  /// the newest Basset interval), kg; 0 without them. The set-up makes p.inv_mass 1/(m + it).
  double added_inertia(double d) const { return fluid_ ? fluid_->added_inertia(d) : 0.0; }
  const FluidForces* fluid_forces() const { return fluid_.get(); }
  /// The fluid torque on each particle, N m, held over the current flow step; nullptr without
  /// [coupling.forces] torque.
  const double* torque(int d) const { return fluid_ ? fluid_->torque(d) : nullptr; }
  /// On ranks, the [coupling.forces] state travels with the particles (FluidForces::save):
  /// its numbers per particle (0 without fluid forces), the state of the particles the next
  /// step() is given, and that of the last step's, particle by particle.
  std::size_t fluid_state_width() const {
    return fluid_ ? FluidForces::width(settings_.forces) : 0;
  }
  void load_fluid_state(std::span<const double> in, std::size_t n) { fluid_->load(in, n); }
  void save_fluid_state(std::span<double> out) const { fluid_->save(out); }

  /// The gas force on each particle (drag + pressure), N, held over the current flow step.
  const std::vector<double>& force(int d) const { return force_[static_cast<std::size_t>(d)]; }

  const gas::GasSolver& solver() const { return *gas_; }
  /// Wall seconds spent in the gas solver's steps so far (the rest of step(): the coupling).
  double solver_seconds() const { return solver_seconds_; }
  /// The part of solver_seconds() in the pressure solves.
  double pressure_seconds() const { return gas_->linear_counters().pressure_seconds; }

  /// Checkpoint state: the gas solver's and the force on each particle of the last flow step
  /// (it acts until the next one: soft-sphere runs may be checkpointed between flow steps).
  struct State {
    gas::GasSolver::State gas;
    std::array<std::vector<double>, 3> force;
    std::vector<std::pair<std::string, std::vector<double>>> fluid; ///< FluidForces::state
  };
  State state() const {
    return {gas_->state(), force_,
            fluid_ ? fluid_->state() : std::vector<std::pair<std::string, std::vector<double>>>{}};
  }
  /// The names of the fluid-force state a checkpoint of this run holds (empty without them).
  std::vector<std::string> fluid_state_names() const;
  void restore(const State& s) {
    gas_->restore(s.gas);
    force_ = s.force;
    if (fluid_) fluid_->restore(s.fluid);
  }
  /// The particles were reordered (ParticleStore::permute with the same new_to_old): the force
  /// on each particle, held until the next flow step, follows them.
  void permute(const std::vector<std::uint32_t>& new_to_old);
  /// See gas::GasSolver::reset_solver_history (called when a checkpoint is written).
  void reset_solver_history() { gas_->reset_solver_history(); }
  const coupling::ParticleGasForces& exchange() const { return f_; }
  /// The drag closure's name (the case's, or the default closure's when the case gives none).
  const std::string& drag_name() const { return settings_.drag; }

  /// Bottom-to-top pressure drop, Pa: mean pressure on the bottom face (along gravity) minus
  /// the mean on the top face, each face's pressure the mean of its ghost and first interior
  /// cell, as the solver sees it (docs/coupling.md).
  double pressure_drop() const;
  /// Superficial gas velocity at time t, m/s: the volume flow prescribed into the domain by
  /// every inflow boundary cell (face, regions, time profiles; gas::inflow_velocity, superficial)
  /// divided by the domain's cross-section normal to gravity. The x-axis of a pressure-drop
  /// against velocity curve [Chang08 §3.4].
  double superficial_velocity(double t) const;
  /// Pressure at each probe of spec.output.probes, Pa (interpolated, gas::pressure_at).
  std::vector<double> probe_pressures() const;
  /// The fields written to fields.h5.
  void cell_fields(const ParticleStore& p, CellFields& out) const;

private:
  /// coupling.hold_gas_at_rest: a uniform force on the gas removing its mean momentum along the
  /// periodic axes within the coming flow step of length dt.
  void hold_at_rest(double dt);
  /// coupling.mode = "frozen": the prescribed velocity on every face, the hydrostatic pressure.
  void set_frozen_field();
  /// coupling.mode = "one_way": a porosity of 1 everywhere, swapped into the solver for its steps.
  std::vector<double> empty_porosity_;
  std::unique_ptr<FluidForces> fluid_; ///< [coupling.forces]; null without any
  std::vector<ProbeSpec> probes_;
  std::unique_ptr<gas::GasSolver> gas_;
  coupling::CouplingSettings settings_;
  coupling::ParticleGasForces f_;
  std::optional<coupling::RankSum> ranks_;     ///< distribute()
  coupling::PorosityScratch porosity_scratch_; ///< kept between flow steps: no allocation
  coupling::CouplingSmoother smoother_;        ///< coupling.smoothing_length (off: unused)
  std::array<std::vector<double>, 3> force_;
  double solver_seconds_ = 0.0;
  int vertical_ = 2;      ///< the axis of gravity (z if there is none)
  bool falls_low_ = true; ///< gravity points to the low side of that axis
};

/// The gas's force on the particles (drag + pressure) as a force source: held over each flow
/// step; its work is done by the gas, from outside the particle system's energy balance.
class GasForceSource final : public ForceSource {
public:
  explicit GasForceSource(GasCoupling& gas) : gas_(gas) {}
  std::string_view name() const override { return "gas"; }
  EnergyRole energy_role() const override { return EnergyRole::External; }
  const double* force(int axis) const override { return gas_.force(axis).data(); }
  const double* torque(int axis) const override { return gas_.torque(axis); }
  void permute(const std::vector<std::uint32_t>& new_to_old) override { gas_.permute(new_to_old); }

private:
  GasCoupling& gas_;
};

} // namespace fluidem
