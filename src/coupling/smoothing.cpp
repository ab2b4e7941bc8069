#include "coupling/smoothing.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "coupling/interpolation.hpp"

namespace fluidem::coupling {

namespace {

/// Active nodes (mask over the padded grid) and the links between neighbours.
DiffusionDomain build_domain(const gas::GasGrid& g, const std::array<bool, 3>& periodic,
                             const std::vector<unsigned char>& active) {
  DiffusionDomain dom;
  std::vector<int> compact(g.size(), -1);
  for (int k = 0; k < g.padded[2]; ++k)
    for (int j = 0; j < g.padded[1]; ++j)
      for (int i = 0; i < g.padded[0]; ++i) {
        const long q = g.idx(i, j, k);
        if (!active[static_cast<std::size_t>(q)]) continue;
        compact[static_cast<std::size_t>(q)] = static_cast<int>(dom.node.size());
        dom.node.push_back(q);
      }
  for (std::size_t m = 0; m < dom.node.size(); ++m) {
    const long q = dom.node[m];
    const std::array<int, 3> c{
        static_cast<int>(q % g.padded[0]), static_cast<int>((q / g.padded[0]) % g.padded[1]),
        static_cast<int>(q / (static_cast<long>(g.padded[0]) * g.padded[1]))};
    for (int e = 0; e < 3; ++e) {
      const auto ue = static_cast<std::size_t>(e);
      // The + neighbour along e; on a periodic axis index n is followed by index 1.
      long nb = q + g.stride[ue];
      if (periodic[ue] && c[ue] == g.n[ue]) nb = q - (g.n[ue] - 1) * g.stride[ue];
      if (nb == q || nb < 0 || nb >= static_cast<long>(g.size())) continue;
      const int b = compact[static_cast<std::size_t>(nb)];
      if (b < 0) continue;
      dom.link_a.push_back(static_cast<int>(m));
      dom.link_b.push_back(b);
      dom.link_ax.push_back(static_cast<unsigned char>(e));
    }
  }
  return dom;
}

/// y = (I + L_alpha) x, L_alpha in flux form.
void apply(const DiffusionDomain& dom, const std::array<double, 3>& alpha,
           const std::vector<double>& x, std::vector<double>& y) {
  const std::size_t m = dom.size();
  for (std::size_t i = 0; i < m; ++i) y[i] = x[i];
  for (std::size_t l = 0; l < dom.link_a.size(); ++l) {
    const auto a = static_cast<std::size_t>(dom.link_a[l]);
    const auto b = static_cast<std::size_t>(dom.link_b[l]);
    const double f = alpha[dom.link_ax[l]] * (x[a] - x[b]);
    y[a] += f;
    y[b] -= f;
  }
}

double dot(const std::vector<double>& a, const std::vector<double>& b, std::size_t m) {
  double s = 0.0;
  for (std::size_t i = 0; i < m; ++i) s += a[i] * b[i];
  return s;
}

} // namespace

DiffusionDomain cell_domain(const gas::GasGrid& g, const std::array<bool, 3>& periodic) {
  std::vector<unsigned char> active(g.size(), 0);
  for (int k = 1; k <= g.n[2]; ++k)
    for (int j = 1; j <= g.n[1]; ++j)
      for (int i = 1; i <= g.n[0]; ++i) active[static_cast<std::size_t>(g.idx(i, j, k))] = 1;
  return build_domain(g, periodic, active);
}

DiffusionDomain face_domain(const gas::GasGrid& g, const std::array<bool, 3>& periodic,
                            const std::vector<unsigned char>& role, unsigned char solved_role) {
  std::vector<unsigned char> active(g.size(), 0);
  for (std::size_t q = 0; q < role.size() && q < active.size(); ++q)
    active[q] = role[q] == solved_role ? 1 : 0;
  return build_domain(g, periodic, active);
}

void diffuse(const DiffusionDomain& dom, const std::array<double, 3>& h, double sigma, int steps,
             std::vector<double>& a, DiffusionScratch& s) {
  const std::size_t m = dom.size();
  if (m == 0 || !(sigma > 0.0) || steps < 1) return;
  // D dtau = sigma^2 / (2 steps); alpha_e = D dtau / h_e^2.
  const double d_dtau = sigma * sigma / (2.0 * steps);
  const std::array<double, 3> alpha{d_dtau / (h[0] * h[0]), d_dtau / (h[1] * h[1]),
                                    d_dtau / (h[2] * h[2])};
  for (auto* v : {&s.x, &s.b, &s.r, &s.p, &s.ap}) v->resize(m);
  for (std::size_t i = 0; i < m; ++i) s.b[i] = a[static_cast<std::size_t>(dom.node[i])];
  constexpr double tol = 1e-14; // relative 2-norm residual of each step's system
  const int max_iter = 1000 + 10 * static_cast<int>(std::sqrt(static_cast<double>(m)));
  for (int step = 0; step < steps; ++step) {
    // CG from x = b: r = b - A b.
    const double bb = dot(s.b, s.b, m);
    if (bb == 0.0) break; // zero field: stays zero
    for (std::size_t i = 0; i < m; ++i) s.x[i] = s.b[i];
    apply(dom, alpha, s.x, s.ap);
    for (std::size_t i = 0; i < m; ++i) s.r[i] = s.b[i] - s.ap[i];
    double rr = dot(s.r, s.r, m);
    const double stop = tol * tol * bb;
    for (std::size_t i = 0; i < m; ++i) s.p[i] = s.r[i];
    int it = 0;
    while (rr > stop) {
      if (++it > max_iter)
        throw InstabilityError("coupling.smoothing_length: the diffusion solve did not converge (" +
                               std::to_string(max_iter) + " CG iterations, relative residual " +
                               std::to_string(std::sqrt(rr / bb)) + ")");
      apply(dom, alpha, s.p, s.ap);
      const double pap = dot(s.p, s.ap, m);
      if (!(pap > 0.0)) break;
      const double al = rr / pap;
      double rr_new = 0.0;
      for (std::size_t i = 0; i < m; ++i) {
        s.x[i] += al * s.p[i];
        s.r[i] -= al * s.ap[i];
        rr_new += s.r[i] * s.r[i];
      }
      const double beta = rr_new / rr;
      rr = rr_new;
      for (std::size_t i = 0; i < m; ++i) s.p[i] = s.r[i] + beta * s.p[i];
    }
    // Flux form: phi^{m+1} = phi^m - L_alpha phi*, each link's flux to one node and from the
    // other (the sum is kept to round-off). s.r is free: it holds the new field.
    for (std::size_t i = 0; i < m; ++i) s.r[i] = s.b[i];
    for (std::size_t l = 0; l < dom.link_a.size(); ++l) {
      const auto la = static_cast<std::size_t>(dom.link_a[l]);
      const auto lb = static_cast<std::size_t>(dom.link_b[l]);
      const double f = alpha[dom.link_ax[l]] * (s.x[la] - s.x[lb]);
      s.r[la] -= f;
      s.r[lb] += f;
    }
    std::swap(s.b, s.r);
  }
  for (std::size_t i = 0; i < m; ++i) a[static_cast<std::size_t>(dom.node[i])] = s.b[i];
}

void CouplingSmoother::configure(const gas::GasGrid& g, const std::array<bool, 3>& periodic,
                                 const std::array<const std::vector<unsigned char>*, 3>& face_role,
                                 unsigned char solved_role, double sigma) {
  if (!(sigma >= 0.0) || std::isinf(sigma)) // (the case reader names the key's location)
    throw InputError("coupling.smoothing_length: " + std::to_string(sigma) +
                     " is out of range (allowed: 0 (off) or a length > 0, m)");
  g_ = g;
  periodic_ = periodic;
  if (g.dimension == 2) periodic_[1] = false; // one cell across y: nothing to link
  sigma_ = sigma;
  if (!(sigma > 0.0)) return;
  cells_ = cell_domain(g, periodic_);
  for (int d = 0; d < 3; ++d)
    faces_[static_cast<std::size_t>(d)] =
        face_domain(g, periodic_, *face_role[static_cast<std::size_t>(d)], solved_role);
  solid_.assign(g.size(), 0.0);
}

void CouplingSmoother::configure(const gas::GasSolver& gs, double sigma, bool smooth_velocity) {
  configure(gs.grid(), periodic_axes(gs), {&gs.face_role(0), &gs.face_role(1), &gs.face_role(2)},
            gas::GasSolver::solved, sigma);
  smooth_velocity_ = smooth_velocity;
}

void CouplingSmoother::smooth_momentum_source(gas::GasSolver& gs) {
  if (!enabled()) return;
  for (int d = 0; d < 3; ++d) {
    smooth_faces(d, gs.drag_coefficient(d));
    smooth_faces(d, gs.drag_velocity_term(d));
    smooth_faces(d, gs.explicit_source(d));
  }
}

void CouplingSmoother::smooth_porosity(std::vector<double>& eps, double min_eps) {
  if (!enabled()) return;
  for (const long q : cells_.node)
    solid_[static_cast<std::size_t>(q)] = 1.0 - eps[static_cast<std::size_t>(q)];
  diffuse(cells_, g_.h, sigma_, smoothing_steps, solid_, scratch_);
  for (const long q : cells_.node) {
    const auto uq = static_cast<std::size_t>(q);
    const double e = 1.0 - solid_[uq];
    eps[uq] = e > 1.0 ? 1.0 : e;
    if (!(eps[uq] >= min_eps))
      throw InstabilityError("coupling.smoothing_length: smoothed porosity " + std::to_string(e) +
                             " below " + std::to_string(min_eps) + " in cell " + std::to_string(q));
  }
  gas::fill_periodic_ghosts(g_, periodic_, eps);
}

void CouplingSmoother::smooth_faces(int d, std::vector<double>& a) {
  if (!enabled()) return;
  diffuse(faces_[static_cast<std::size_t>(d)], g_.h, sigma_, smoothing_steps, a, scratch_);
}

} // namespace fluidem::coupling
