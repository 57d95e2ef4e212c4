# Planted mistakes of lesson 8 (tests/exercises/plant.cmake): each is applied to the
# solutions and the checker must name it, or, for a mistake the catalogue does not have, give
# its symptom.
soa_plant(8.1 neighbour-index
  FIND [=[ws.phi[j - 1].apply(Force(r.z_plus[j - 1]))]=]
  WRONG [=[ws.phi[j].apply(Force(r.z_plus[j - 1]))]=]
  EXPECT [=[likely mistake \(neighbour index\): your z\(k\) takes phi\(k\+1,k\) z\+\(k-1\)]=])
soa_plant(8.1 coriolis-doubled
  FIND [=[art.P[j] * ws.a[j].vector() + gyroscopic_force(B.M, ws.V[j]).vector()]=]
  WRONG [=[2.0 * art.P[j] * ws.a[j].vector() + gyroscopic_force(B.M, ws.V[j]).vector()]=]
  TYPE [=[Vec6]=]
  EXPECT [=[symptom: it fails only where it moves \(the velocities are not zero\): [0-9]+ of those [0-9]+ [a-z]+s fail, and every other [a-z]+ passes]=])
soa_plant(8.2 transpose
  FIND [=[ws.phi[j].transpose_apply(next)]=]
  WRONG [=[Acceleration(ws.phi[j].matrix() * next.vector())]=]
  EXPECT [=[likely mistake \(transpose\): your alpha\+\(k\) is phi\(k\+1,k\) alpha\(k\+1\)]=])
soa_plant(8.2 wrong-frame
  FIND [=[G.transpose() * alpha_plus.vector()]=]
  WRONG [=[G.transpose() * next.vector()]=] TYPE [=[VecX<double>]=]
  EXPECT [=[likely mistake \(wrong frame\): your beta_dot\(k\) takes G\*\(k\) alpha\(k\+1\)]=])
soa_plant(8.3 transpose
  FIND [=[phi * P_plus[j - 1] * phi.transpose()]=]
  WRONG [=[phi.transpose() * P_plus[j - 1] * phi]=] TYPE [=[Mat6<double>]=]
  EXPECT [=[likely mistake \(transpose\): your P\(k\) takes phi\*\(k,k-1\) P\+\(k-1\)]=])
soa_plant(8.3 external-sign
  FIND [=[f_ext[j].vector()]=]
  WRONG [=[-f_ext[j].vector()]=] TYPE [=[Vec6]=]
  EXPECT [=[likely mistake \(sign\): your b\(k\) adds f_ext\(k\)]=])
soa_plant(8.3 no-projection
  FIND [=[P - g[j] * Ps.transpose()]=]
  WRONG [=[P]=] TYPE [=[Mat6<double>]=]
  EXPECT [=[likely mistake \(dropped term\): your P\(k\) takes phi P\(k-1\) phi\*]=])
soa_plant(8.3 pitch-doubled
  FIND [=[h.pitch * h.axis]=]
  WRONG [=[2 * h.pitch * h.axis]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[symptom: it fails only where a hinge is helical: [0-9]+ of those [0-9]+ [a-z]+s fail, and every other [a-z]+ passes]=])
soa_plant(8.4 wrong-inertia
  FIND [=[fd.art.P_plus[j]]=]
  WRONG [=[fd.art.P[j]]=] TYPE [=[Mat6<double>]=]
  EXPECT [=[likely mistake \(wrong inertia\): your f\(k\) is P\(k\) alpha\+\(k\) \+ z\+\(k\)]=])
soa_plant(8.5 equal-weights
  FIND [=[h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)]=]
  WRONG [=[h / 4 * (k1v + k2v + k3v + k4v)]=] TYPE [=[VecX<double>]=]
  EXPECT [=[likely mistake \(wrong weights\)]=])
soa_plant(8.6 bug-kept
  FIND [=[Hs * bd]=]
  WRONG [=[Hs * nu[j]]=] TYPE [=[Vec6]=]
  EXPECT [=[the checker knows this mistake: it names it after 3 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|your beta_dot is the given code's]=]
  NAMED [=[likely mistake \(bug still there\): your beta_dot is the given code's]=])
soa_plant(8.7 dropped-term
  FIND [=[z + P * (Hs * beta_dot.segment(B.v_offset, nk))]=]
  WRONG [=[z]=] TYPE [=[Vec6]=]
  EXPECT [=[the checker knows this mistake: it names it after 5 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|across a prescribed hinge your z\+\(k\) is z\(k\)]=]
  NAMED [=[likely mistake \(dropped term\): across a prescribed hinge your z\+\(k\) is z\(k\)]=])
