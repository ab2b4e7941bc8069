#!/usr/bin/env python3
"""Parcel check behind the choice of the [Chang08] eq. (1) reconstruction (src/core/body_force.hpp):
non-colliding particles with linear drag (tau) in candidate cos-cos fields, periodic 0.1 m box, 20 s;
prints the number density within 0.1 L of CC1, CC2, GC and the corner over the mean, and the mean
x velocity at GC and CC. Needs numpy; ~10 min."""
import numpy as np
L=0.1;k=2*np.pi/L;A=0.1
c=lambda a: np.cos(k*a); s=lambda a: np.sin(k*a)
fields={
 'B_yz_zx_xy': lambda x,y,z:(c(y)*c(z),c(z)*c(x),c(x)*c(y)),
 'C_xy_yz_zx': lambda x,y,z:(c(x)*c(y),c(y)*c(z),c(z)*c(x)),
 'C2_xz_yx_zy': lambda x,y,z:(c(x)*c(z),c(y)*c(x),c(z)*c(y)),
 'negB': lambda x,y,z:(-c(y)*c(z),-c(z)*c(x),-c(x)*c(y)),
 'negC': lambda x,y,z:(-c(x)*c(y),-c(y)*c(z),-c(z)*c(x)),
 'negC2': lambda x,y,z:(-c(x)*c(z),-c(y)*c(x),-c(z)*c(y)),
 'cs': lambda x,y,z:(c(x)*s(y),c(y)*s(z),c(z)*s(x)),
}
rng=np.random.default_rng(1)
for tau in (0.3,1.0):
 for name,F in fields.items():
  N=20000; X=rng.random((N,3))*L; V=np.zeros((N,3)); dt=2e-3
  for it in range(int(20/dt)):
    f=np.array(F(X[:,0],X[:,1],X[:,2])).T*A
    V+= dt*(f-V/tau); X=(X+dt*V)%L
  def frac(cn):
    d=X-np.array(cn); d-=L*np.round(d/L); return np.mean(np.sum(d*d,1)<(0.1*L)**2)/0.0041888
  u=lambda cn: V[np.sum(((X-np.array(cn)+L/2)%L-L/2)**2,1)<(0.1*L)**2,0].mean()
  print(f"tau={tau} {name:12s} CC1 {frac([L/4]*3):6.2f} CC2 {frac([3*L/4]*3):6.2f} GC {frac([L/2]*3):6.2f} O {frac([0,0,0]):6.2f}  uGC {u([L/2]*3):.3f} uCC {u([L/4]*3):.3f}")
