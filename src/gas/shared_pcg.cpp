#include "gas/shared_pcg.hpp"
#include <algorithm>
#include <cmath>

namespace fluidem::gas {

SharedPcgResult shared_pcg(const SharedPcgOperators& op, const std::vector<double>& b,
                           std::vector<double>& x, double rel_tol, int max_iterations,
                           SharedPcgWork& work) {
  SharedPcgResult res;
  const std::size_t n = b.size();
  const double bb = op.dot(b, b);
  if (bb == 0.0) {
    x.assign(n, 0.0);
    res.converged = true;
    return res;
  }
  std::vector<double>&r = work.r, &z = work.z, &p = work.p, &q = work.q;
  for (auto* v : {&r, &z, &p, &q}) v->resize(n);
  op.apply(x, q);
  for (std::size_t i = 0; i < n; ++i) r[i] = b[i] - q[i];
  double rr = op.dot(r, r);
  res.relative_residual = std::sqrt(rr / bb);
  if (res.relative_residual <= rel_tol) {
    res.converged = true;
    return res;
  }
  op.precondition(r, z);
  std::copy(z.begin(), z.end(), p.begin());
  double gamma = op.dot(r, z);
  while (res.iterations < max_iterations) {
    op.apply(p, q);
    const double pq = op.dot(p, q);
    if (!(pq > 0.0) || !std::isfinite(pq) || !std::isfinite(gamma)) break;
    const double alpha = gamma / pq;
    for (std::size_t i = 0; i < n; ++i) {
      x[i] += alpha * p[i];
      r[i] -= alpha * q[i];
    }
    ++res.iterations;
    rr = op.dot(r, r);
    res.relative_residual = std::sqrt(rr / bb);
    if (res.relative_residual <= rel_tol) {
      res.converged = true;
      break;
    }
    op.precondition(r, z);
    const double gamma_new = op.dot(r, z);
    const double beta = gamma_new / gamma;
    gamma = gamma_new;
    for (std::size_t i = 0; i < n; ++i) p[i] = z[i] + beta * p[i];
  }
  return res;
}

} // namespace fluidem::gas
