# Planted mistakes of lesson 7 (tests/exercises/plant.cmake): each is applied to the
# solutions and the checker must name it (the last of 7.4 is not in the catalogue: the
# checker must give its symptom).
soa_plant(7.1 transpose
  FIND [=[phi * r.art.tau_bar(m, x.theta, k)]=]
  WRONG [=[phi.transpose() * r.art.tau_bar(m, x.theta, k)]=] TYPE [=[Mat6<double>]=]
  EXPECT [=[likely mistake \(transpose\): your E_psi\(k\+1,k\) is phi\*\(k\+1,k\) tau_bar\(k\)]=])
soa_plant(7.2 sign
  FIND [=[I - op.H * psi * K]=]
  WRONG [=[I + op.H * psi * K]=] TYPE [=[MatX]=]
  EXPECT [=[likely mistake \(sign\): your L_inv is I \+ H psi K]=])
soa_plant(7.3 wrong-frame
  FIND [=[phi.transpose() * Upsilon * phi]=]
  WRONG [=[Upsilon]=] TYPE [=[Mat6<double>]=]
  EXPECT [=[likely mistake \(wrong frame\): your Upsilon\+\(k\) is Upsilon\(k\+1\) as it is]=])
soa_plant(7.3 transpose
  FIND [=[tau.transpose() * U * tau]=]
  WRONG [=[tau * U * tau.transpose()]=] TYPE [=[Mat6<double>]=]
  EXPECT [=[likely mistake \(transpose\): your Upsilon\(k\) = tau_bar\(k\) U tau_bar\*\(k\)]=])
soa_plant(7.3 sign
  FIND [=[D_inv + G.transpose() * U * G]=]
  WRONG [=[D_inv - G.transpose() * U * G]=] TYPE [=[MatX]=]
  EXPECT [=[likely mistake \(sign\): your M\^-1\(k,k\) is D\^-1\(k\) - G\* Upsilon\+ G]=])
soa_plant(7.4 neighbour-index
  FIND [=[r.ws.phi[j - 1].apply(z_plus)]=]
  WRONG [=[r.ws.phi[j].apply(z_plus)]=]
  EXPECT [=[likely mistake \(neighbour index\): your z\(k\) takes phi\(k\+1,k\) z\+\(k-1\)]=])
soa_plant(7.4 dropped-gain
  FIND [=[z.vector() + r.art.G[j] * eps]=]
  WRONG [=[z.vector()]=] TYPE [=[Vec6<double>]=]
  EXPECT [=[likely mistake \(dropped term\): your z\+\(k\) is z\(k\): the gain term]=])
soa_plant(7.4 alpha-doubled
  FIND [=[alpha_plus.vector() + H_star(m, x, k) * yk]=]
  WRONG [=[2.0 * alpha_plus.vector() + H_star(m, x, k) * yk]=] TYPE [=[Vec6<double>]=]
  EXPECT [=[symptom: every case unless there is more than one body passes]=])
soa_plant(7.5 sign
  FIND [=[std::log(MatX(D).determinant())]=]
  WRONG [=[-std::log(MatX(D).determinant())]=] TYPE [=[double]=]
  EXPECT [=[likely mistake \(sign\): your result is sum_k log det D\^-1\(k\) = -log det M]=])
soa_plant(7.6 transpose
  FIND [=[u.Upsilon[std::size_t(i - 1)] * psi_ij]=]
  WRONG [=[psi_ij.transpose() * u.Upsilon[std::size_t(i - 1)]]=] TYPE [=[Mat6<double>]=]
  EXPECT [=[likely mistake \(transpose\): your Omega\(i,j\) is psi\*\(i,j\) Upsilon\(i\)]=])
soa_plant(7.7 dropped-term
  FIND [=[z - MatX(art.G[std::size_t(k - 1)]) * Hz]=]
  WRONG [=[z]=] TYPE [=[MatX]=]
  EXPECT [=[likely mistake \(dropped term\): your z_i\(k\+1\) is phi\(k\+1,k\) z_i\(k\)]=])
soa_plant(7.8 wrong-frame
  FIND [=[phi.transpose() * U * phi]=]
  WRONG [=[U]=] TYPE [=[Mat6<double>]=]
  EXPECT [=[likely mistake \(wrong frame\): your result is Upsilon\(k\), at O_k]=])
soa_plant(7.10 neighbour-index
  FIND [=[f + 1]=]
  WRONG [=[f]=] TYPE [=[int]=]
  EXPECT [=[likely mistake \(neighbour index\): your zeros include the free hinge's own blocks with the bodies outboard]=])
soa_plant(7.11 dropped-term
  FIND [=[r.art.tau_bar(m, x.theta, k) * z]=]
  WRONG [=[z]=] TYPE [=[MatX]=]
  EXPECT [=[likely mistake \(dropped term\): your A\(k,i\) is -H\(k\) phi\(k,i\) G\(i\)]=])
soa_plant(7.12 bug-left
  FIND [=[Hs * beta_k]=]
  WRONG [=[Hs * eta_k]=] TYPE [=[VecX]=]
  EXPECT [=[likely mistake \(the bug\): the bug is still there: your V\(k\) adds H\*\(k\) eta\(k\)]=])
