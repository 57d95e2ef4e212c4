# Planted mistakes of lesson 7 (tests/exercises/plant.cmake): each is applied to the
# solutions and the checker must name it (the last of 7.4, the D of 7.8 and the dropped phi*
# of 7.12 are not in the catalogue: the checker must say what it measured, and guess no
# cause). 7.10, 7.11 and 7.12 are of level 3: their first message gives the symptom and the
# place, never the catalogue's formula (REJECT); the mistake is named after the count of
# failed runs of the statement (NAMED) or the hint ladder (soa_feedback_test).
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
  EXPECT [=[symptom: it fails only where there is more than one body: [0-9]+ of those [0-9]+ cases fail, and every other case passes]=])
soa_plant(7.5 sign
  FIND [=[std::log(MatX(D).determinant())]=]
  WRONG [=[-std::log(MatX(D).determinant())]=] TYPE [=[double]=]
  EXPECT [=[likely mistake \(sign\): your result is sum_k log det D\^-1\(k\) = -log det M]=])
# Not in the catalogue: the result doubled. What was measured: the constant factor.
soa_plant(7.5 doubled
  FIND [=[double(std::log(MatX(D).determinant()))]=]
  WRONG [=[2.0 * std::log(MatX(D).determinant())]=] TYPE [=[double]=]
  EXPECT [=[log det M: wrong in [0-9]+ of [0-9]+ cases.*symptom: your result is 2.000 times the expected value in every (failing )?case]=]
  REJECT [=[the formula itself|likely mistake]=])
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
soa_plant(7.8 d-for-d-inverse
  FIND [=[Hs * MatX(r.art.D_inv[i]) * Hs.transpose()]=]
  WRONG [=[Hs * MatX(r.art.D[i]) * Hs.transpose()]=] TYPE [=[Mat6<double>]=]
  EXPECT [=[symptom: in every case, your result matches the expected value with D\(j\) in place of D\^-1\(j\) in the Upsilon recursion]=]
  REJECT [=[the formula itself|likely mistake]=])
soa_plant(7.10 neighbour-index
  FIND [=[f + 1]=]
  WRONG [=[f]=] TYPE [=[int]=]
  EXPECT [=[your pattern of the non-zero blocks of M\^-1: wrong in [0-9]+ of [0-9]+ cases.*the checker knows this mistake: it names it after 3 failed runs.*where, in case [0-9]+ \(the simplest that fails\): the row of body]=]
  REJECT [=[likely mistake|perhaps \(|strictly between|psi\(k,i\+1\)]=]
  NAMED [=[likely mistake \(neighbour index\): your zeros include the free hinge's own blocks with the bodies outboard]=])
soa_plant(7.11 dropped-term
  FIND [=[r.art.tau_bar(m, x.theta, k) * z]=]
  WRONG [=[z]=] TYPE [=[MatX]=]
  EXPECT [=[A, the dense operator of the sweep, against the library's operator: wrong in [0-9]+ of [0-9]+ cases.*the checker knows this mistake: it names it after 4 failed runs.*where, in case [0-9]+ \(the simplest that fails\): A\(]=]
  REJECT [=[likely mistake|perhaps \(|tau_bar\(j\) z\(j\)]=]
  NAMED [=[likely mistake \(dropped term\): your A\(k,i\) is -H\(k\) phi\(k,i\) G\(i\)]=])
soa_plant(7.12 bug-left
  FIND [=[Hs * beta_k]=]
  WRONG [=[Hs * eta_k]=] TYPE [=[VecX]=]
  EXPECT [=[beta, recovered from eta = \[I \+ H phi K\]\* beta: wrong in [0-9]+ of [0-9]+ cases.*the checker knows this mistake: it names it after 3 failed runs.*where, in case [0-9]+ \(the simplest that fails\): beta of body]=]
  REJECT [=[likely mistake|perhaps \(|eta\(k\)|beta\(k\)]=]
  NAMED [=[likely mistake \(the bug\): the bug is still there: your V\(k\) adds H\*\(k\) eta\(k\)]=])
soa_feedback_test(7.12 bug-left
  [=[likely mistake \(the bug\): the bug is still there: your V\(k\) adds H\*\(k\) eta\(k\)]=])
# Not in the catalogue: V(k+1) not carried to O_k by phi*(k+1,k). What was measured: only the
# cases with more than one body fail; no cause is guessed.
soa_plant(7.12 dropped-phi-star
  FIND [=[r.ws.phi[std::size_t(k - 1)].transpose_apply(V)]=]
  WRONG [=[V]=] TYPE [=[Velocity]=]
  EXPECT [=[beta, recovered from eta = \[I \+ H phi K\]\* beta: wrong in [0-9]+ of [0-9]+ cases.*symptom: it fails only where there is more than one body: [0-9]+ of those [0-9]+ cases fail, and every other case passes.*known mistakes are named after 3 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|index|direction of the sweep]=])
