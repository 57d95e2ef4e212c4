# Planted mistakes of lesson 6 (tests/exercises/plant.cmake): each is applied to the
# solutions and the checker must name it, or give its symptom when no catalogue entry is it.
soa_plant(6.1 transpose
  FIND [=[phi6 * P_plus_prev * phi6.transpose()]=]
  WRONG [=[phi6.transpose() * P_plus_prev * phi6]=] TYPE [=[Mat6]=]
  EXPECT [=[likely mistake \(transpose\): your P\(k\) carries P\+\(k-1\) as phi\*\(k,k-1\) P\+ phi\(k,k-1\)]=])
soa_plant(6.1 one-dof-gain
  FIND [=[PHs * s.D.inverse()]=]
  WRONG [=[PHs / s.D(0, 0)]=] TYPE [=[MatX<double>]=]
  EXPECT [=[G\(k\) = P H\* D\^-1: wrong in [0-9]+ of [0-9]+ cases.*symptom: it fails only where a hinge has several degrees of freedom: [0-9]+ of those [0-9]+ [a-z]+s fail, and every other [a-z]+ passes]=])
soa_plant(6.2 transpose
  FIND [=[Mat6::Identity() - G * H_star.transpose()]=]
  WRONG [=[Mat6::Identity() - H_star * G.transpose()]=] TYPE [=[Mat6]=]
  EXPECT [=[likely mistake \(transpose\): your result is tau_bar\* = I - H\* G\*]=])
soa_plant(6.3 neighbour-index
  FIND [=[soa::transform_symmetric(ws.phi[std::size_t(k - 2)], P_plus)]=]
  WRONG [=[soa::transform_symmetric(ws.phi[std::size_t(k - 1)], P_plus)]=] TYPE [=[Mat6]=]
  EXPECT [=[likely mistake \(neighbour index\): your P\(k\) carries P\+\(k-1\) with phi\(k\+1,k\)]=])
soa_plant(6.4 sign
  FIND [=[A + L * B.transpose() - B * L - L * C * L]=]
  WRONG [=[A + L * B.transpose() - B * L + L * C * L]=] TYPE [=[Mat3<double>]=]
  EXPECT [=[likely mistake \(sign\): your top-left block adds L C' L]=])
soa_plant(6.4 wrong-frame
  FIND [=[tilde(phi.l())]=]
  WRONG [=[tilde(Vec3<double>(R * phi.l()))]=] TYPE [=[Mat3<double>]=]
  EXPECT [=[likely mistake \(wrong frame\): your L is the cross-product matrix of R l]=])
soa_plant(6.5 dropped-z
  FIND [=[fd.art.P_plus[j] * fd.alpha_plus[j].vector() + fd.z_plus[j].vector()]=]
  WRONG [=[fd.art.P_plus[j] * fd.alpha_plus[j].vector()]=] TYPE [=[Vec6<double>]=]
  EXPECT [=[likely mistake \(dropped term\): z\+\(k\) is missing from your f\(k\)]=])
soa_plant(6.6 neighbour-index
  FIND [=[ws.phi[j - 1].matrix() * y.back()]=]
  WRONG [=[ws.phi[j].matrix() * y.back()]=] TYPE [=[Vec6<double>]=]
  EXPECT [=[likely mistake \(neighbour index\): your y\(k\) takes phi\(k\+1,k\) y\(k-1\)]=])
soa_plant(6.6 dropped-b
  FIND [=[gyroscopic_force(m.body(k).M, ws.V[j]).vector()]=]
  WRONG [=[Vec6<double>::Zero()]=] TYPE [=[Vec6<double>]=]
  EXPECT [=[likely mistake \(dropped term\): b\(k\), the gyroscopic force, is missing]=])
soa_plant(6.6 gravity-doubled
  FIND [=[gravity_base_acceleration(m).vector()]=]
  WRONG [=[2.0 * gravity_base_acceleration(m).vector()]=] TYPE [=[Vec6<double>]=]
  EXPECT [=[y\(k\), the composite-body bias: wrong in [0-9]+ of [0-9]+ cases.*symptom: it fails only where gravity is on: [0-9]+ of those [0-9]+ [a-z]+s fail, and every other [a-z]+ passes]=])
soa_plant(6.7 the-given-bug
  FIND [=[tau_bar * Pk]=]
  WRONG [=[Pk * tau_bar]=] TYPE [=[Mat6]=]
  EXPECT [=[the checker knows this mistake: it names it after 3 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|your P\(k\) is the given code's]=]
  NAMED [=[likely mistake \(the given bug\): your P\(k\) is the given code's]=])
soa_plant(6.8 wrong-part
  FIND [=[MatX<double>(m.body(k).hinge.H_star(theta.data() + m.body(k).q_offset))]=]
  WRONG [=[(MatX<double>(6, m.body(k).hinge.nv())
              << m.body(k).hinge.H_star(theta.data() + m.body(k).q_offset).bottomRows(3),
          m.body(k).hinge.H_star(theta.data() + m.body(k).q_offset).topRows(3)).finished()]=]
  TYPE [=[MatX<double>]=]
  EXPECT [=[the checker knows this mistake: it names it after 3 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|your columns have the angular and the linear rows swapped]=]
  NAMED [=[likely mistake \(wrong part\): your columns have the angular and the linear rows swapped]=])
soa_plant(6.9 sign
  FIND [=[-art.G[j].transpose() * alpha_plus]=]
  WRONG [=[art.G[j].transpose() * alpha_plus]=] TYPE [=[VecX<double>]=]
  EXPECT [=[beta_dot, the hinge accelerations: wrong in [0-9]+ of [0-9]+ cases.*the checker knows this mistake: it names it after 4 failed runs.*where, in case [0-9]+ \(the simplest that fails\): beta_dot of body]=]
  REJECT [=[likely mistake|perhaps \(|G\*\(k\) alpha|phi\*\(k\+1,k\) alpha|your beta_dot\(k\) is \+G\*\(k\) alpha\+\(k\)]=]
  NAMED [=[likely mistake \(sign\): your beta_dot\(k\) is \+G\*\(k\) alpha\+\(k\)]=])
soa_plant(6.9 wrong-frame
  FIND [=[ws.phi[j].matrix().transpose() * alpha]=]
  WRONG [=[alpha]=] TYPE [=[Vec6<double>]=]
  EXPECT [=[beta_dot, the hinge accelerations: wrong in [0-9]+ of [0-9]+ cases.*the checker knows this mistake: it names it after 4 failed runs.*where, in case [0-9]+ \(the simplest that fails\): beta_dot of body]=]
  REJECT [=[likely mistake|perhaps \(|G\*\(k\) alpha|phi\*\(k\+1,k\) alpha|your alpha\+\(k\) is alpha\(k\+1\) as it is]=]
  NAMED [=[likely mistake \(wrong frame\): your alpha\+\(k\) is alpha\(k\+1\) as it is]=])
