#include "integrate/force_sources.hpp"

#include <stdexcept>

namespace fluidem {

void StepForceSource::permute(const std::vector<std::uint32_t>& new_to_old) {
  for (std::vector<double>& f : forces_) {
    if (f.size() != new_to_old.size()) continue; // not evaluated yet
    const std::vector<double> old = f;
    for (std::size_t k = 0; k < new_to_old.size(); ++k) f[k] = old[new_to_old[k]];
  }
  permuted(new_to_old);
}

void ForceSources::add(ForceSource* source) {
  if (source == nullptr) throw std::logic_error("ForceSources::add: no source");
  sources_.push_back(source);
  books_work_ = books_work_ || source->energy_role() == EnergyRole::Dissipative;
  if (auto* s = dynamic_cast<StepForceSource*>(source)) step_sources_.push_back(s);
}

void ForceSources::add(std::unique_ptr<ForceSource> source) {
  add(source.get());
  owned_.push_back(std::move(source));
}

const double* ForceSources::total(int axis) const {
  if (sources_.empty()) return nullptr;
  if (sources_.size() == 1) return sources_.front()->force(axis);
  const auto& s = sum_[static_cast<std::size_t>(axis)];
  return s.empty() ? nullptr : s.data();
}

const double* ForceSources::total_torque(int axis) const {
  if (torque_sources_ == 0) return nullptr;
  if (torque_sources_ == 1) return torque_source_->torque(axis);
  const auto& s = torque_sum_[static_cast<std::size_t>(axis)];
  return s.empty() ? nullptr : s.data();
}

void ForceSources::refresh(std::size_t n) {
  torque_sources_ = 0;
  torque_source_ = nullptr;
  for (const ForceSource* src : sources_)
    if (src->torque(0) != nullptr) {
      ++torque_sources_;
      torque_source_ = src;
    }
  if (torque_sources_ > 1)
    for (int a = 0; a < 3; ++a) {
      std::vector<double>& s = torque_sum_[static_cast<std::size_t>(a)];
      s.assign(n, 0.0);
      for (const ForceSource* src : sources_)
        if (const double* t = src->torque(a))
          for (std::size_t i = 0; i < n; ++i) s[i] += t[i];
    }
  if (sources_.size() < 2) return; // read directly
  for (int a = 0; a < 3; ++a) {
    std::vector<double>& s = sum_[static_cast<std::size_t>(a)];
    s.assign(n, 0.0);
    for (const ForceSource* src : sources_) // in list order: the same sum on every run
      if (const double* f = src->force(a))
        for (std::size_t i = 0; i < n; ++i) s[i] += f[i];
  }
}

void ForceSources::evaluate_step_sources(const ParticleStore& p, double t) {
  for (StepForceSource* s : step_sources_) s->evaluate(p, t);
  refresh(p.size());
}

double ForceSources::potential_energy(const ParticleStore& p) const {
  double e = 0.0;
  for (const ForceSource* s : sources_)
    if (s->energy_role() == EnergyRole::Conservative) e += s->potential_energy(p);
  return e;
}

double ForceSources::dissipated_work(const ParticleStore& p, double dt) const {
  double w = 0.0;
  for (const ForceSource* s : sources_) {
    if (s->energy_role() != EnergyRole::Dissipative) continue;
    const double *fx = s->force(0), *fy = s->force(1), *fz = s->force(2);
    if (fx == nullptr) continue;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.fixed(i)) continue; // a fixed particle does not move: no work
      w += fx[i] * p.vx[i] + fy[i] * p.vy[i] + fz[i] * p.vz[i];
    }
  }
  return -dt * w;
}

void ForceSources::permute(const std::vector<std::uint32_t>& new_to_old) {
  for (ForceSource* s : sources_) s->permute(new_to_old);
  refresh(new_to_old.size());
}

void ForceSources::kick(ParticleStore& p, double dt) const {
  const double *fx = total(0), *fy = total(1), *fz = total(2);
  if (fx == nullptr) return;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double a = dt * p.inv_mass[i];
    p.vx[i] += a * fx[i];
    p.vy[i] += a * fy[i];
    p.vz[i] += a * fz[i];
  }
  const double *tx = total_torque(0), *ty = total_torque(1), *tz = total_torque(2);
  if (tx == nullptr) return;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double b = dt * p.inv_inertia[i];
    p.wx[i] += b * tx[i];
    p.wy[i] += b * ty[i];
    p.wz[i] += b * tz[i];
  }
}

} // namespace fluidem
