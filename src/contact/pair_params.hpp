// The coefficients of one species pair or one (species, wall face) contact, read by the contact
// loop. The ContactTable sets the materials' shares; each sub-model sets its own fields in its
// `mix` function (contact/models/), which says what they mean for it.
#pragma once

namespace fluidem {

struct PairParams {
  double kn = 0;                 ///< normal model: linear k_n, N/m; Hertz and jkr 4/3 E*, Pa;
                                 ///< walton_braun k1, N/m
  double normal_damping = 0;     ///< normal model: linear eta_n / sqrt(m* k_n); Hertz alpha;
                                 ///< walton_braun k1/k2 = e^2; jkr sqrt(2 pi w / E*)
  double kt = 0;                 ///< normal model: linear k_t, N/m; Hertz c_t, Pa
  double tangential_damping = 0; ///< tangential model: factor of [Deen07 eq. 30] from beta0
  double tangential_root = 0;    ///< tangential model: sqrt(2 kt / (7 kn))
  double mu = 0;                 ///< tangential model: Coulomb friction (inf: never sliding)
  double mu_r = 0;               ///< rolling model: rolling friction, dimensionless
  double rolling_damping = 0;    ///< rolling model: factor of [Deen07 eq. 27] from e
  double restitution = 0;        ///< e_n (for reports)
  double e_star = 0;             ///< effective Young's modulus, Pa (reports; Hertz)
  /// tangential model mindlin_deresiewicz: (2 - nu)/(2 (1 - nu)) of the pair (E*/(4 G*)), so
  /// that delta_t,max = mu delta_n slip_factor [Zhu07 Table 1]
  double slip_factor = 0;
};

} // namespace fluidem
