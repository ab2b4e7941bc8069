// What a non-contact pair kernel returns: the force along the line of centres, its potential and
// its stiffness (the pure functions of noncontact/kernels/, each cited in its file).
#pragma once

namespace fluidem::kernels {

struct PairForce {
  /// Along the line of centres, N: > 0 pushes the two apart, < 0 pulls them together.
  double force = 0.0;
  /// The potential energy of the pair, J (zero at the end of the range: a shifted potential).
  double potential = 0.0;
  /// |dF/d(separation)|, N/m: how stiff the force is here (the time-step rule).
  double stiffness = 0.0;
};

} // namespace fluidem::kernels
