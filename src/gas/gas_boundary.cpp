// Boundary cell assignment by geometry [Hoomans96 Table 1, §3.5].
#include "gas/gas_boundary.hpp"

namespace fluidem::gas {

BoundaryPatch BoundaryPatch::of(BoundaryType t, const InflowProfile& inflow, double porosity,
                                double pressure) {
  const BoundaryKind& k = boundary_kind(t);
  return {t, inflow, porosity, pressure, k.normal, k.pressure, k.porosity, k.tangential};
}

BoundaryMap::BoundaryMap(const GasSettings& s, const GasGrid& g) : grid_(g) {
  for (int side = 0; side < 6; ++side) {
    const int axis = side / 2;
    const int a1 = axis == 0 ? 1 : 0, a2 = axis == 2 ? 1 : 2;
    GasBoundary b = s.boundary[side];
    if (s.dimension == 2 && axis == 1)
      b = GasBoundary{BoundaryType::wall_free_slip, {}, 0.4, s.initial_pressure, {}};
    if (boundary_kind(b.type).normal == NormalRule::periodic) periodic_[axis] = true;
    const int base = static_cast<int>(patches_.size());
    patches_.push_back(BoundaryPatch::of(b.type, b.inflow, b.porosity, b.pressure));
    for (const BoundaryRegion& r : b.regions)
      patches_.push_back(BoundaryPatch::of(r.type, r.inflow, r.porosity, r.pressure));
    std::vector<int>& index = index_[side];
    index.assign(static_cast<std::size_t>(g.padded[a1]) * g.padded[a2], base);
    for (int q = 1; q <= g.n[a2]; ++q)
      for (int p = 1; p <= g.n[a1]; ++p) {
        const double t1 = g.lo[a1] + (p - 0.5) * g.h[a1];
        const double t2 = g.lo[a2] + (q - 0.5) * g.h[a2];
        for (std::size_t r = 0; r < b.regions.size(); ++r) {
          const BoundaryRegion& reg = b.regions[r];
          const bool in1 = (s.dimension == 2 && a1 == 1) || (t1 >= reg.lo[0] && t1 <= reg.hi[0]);
          const bool in2 = (s.dimension == 2 && a2 == 1) || (t2 >= reg.lo[1] && t2 <= reg.hi[1]);
          if (in1 && in2) index[p + g.padded[a1] * q] = base + 1 + static_cast<int>(r);
        }
      }
  }
  for (int side = 0; side < 6; ++side) {
    tangential_[side].resize(index_[side].size());
    for (std::size_t q = 0; q < index_[side].size(); ++q)
      tangential_[side][q] = patches_[index_[side][q]].tangential;
  }
  for (const BoundaryPatch& p : patches_) {
    any_pressure_ = any_pressure_ || p.pressure_rule == GhostRule::prescribed;
    any_outflow_ = any_outflow_ || p.normal == NormalRule::outflow;
  }
}

} // namespace fluidem::gas
