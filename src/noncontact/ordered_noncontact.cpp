#include "noncontact/ordered_noncontact.hpp"

#include "core/parallel.hpp"
#include "noncontact/pair_forces.hpp"

namespace fluidem {

void ordered_noncontact_forces(const NonContactSpec& spec, const OrderedRows& rows,
                               const ParticleStore& p, std::vector<double>& f,
                               std::vector<double>& u) {
  const std::size_t n = rows.owned();
  f.resize(3 * n);
  u.resize(n);
  const BoxGeometry& box = rows.box();
  parallel_for(n, threaded_particles(n), [&](std::size_t i) {
    NonContactTerm sum;
    for (std::uint32_t k = rows.offset[i]; k < rows.offset[i + 1]; ++k)
      add_pair_term(sum, noncontact_pair(spec, box, p, i, rows.partner[k]));
    for (std::uint32_t k = rows.wall_offset[i]; k < rows.wall_offset[i + 1]; ++k)
      add_wall_term(sum, noncontact_wall(spec, box, p, i, rows.wall_face[k]));
    f[3 * i] = sum.force.x, f[3 * i + 1] = sum.force.y, f[3 * i + 2] = sum.force.z;
    u[i] = sum.potential;
  });
}

} // namespace fluidem
