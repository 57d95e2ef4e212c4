# Planted mistakes of lesson 4 (tests/exercises/plant.cmake): each is applied to the
# solutions and the checker must name it.
soa_plant(4.1 neighbour-index
  FIND [=[phi[i - 1].apply(g.f[i - 1])]=]
  WRONG [=[phi[i].apply(g.f[i - 1])]=]
  EXPECT [=[likely mistake \(neighbour index\): your f\(k\) takes phi\(k\+1,k\)]=])
soa_plant(4.2 gravity-sign
  FIND [=[-m.gravity]=]
  WRONG [=[m.gravity]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[likely mistake \(sign\): your base acceleration is alpha\(n\+1\) = \[0; \+g\]]=])
soa_plant(4.2 unrotated-l
  FIND [=[Rt * phi[i].l()]=]
  WRONG [=[phi[i].l()]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[likely mistake \(wrong frame\)]=])
soa_plant(4.2 coriolis-doubled
  FIND [=[w_parent.cross(be * a)]=]
  WRONG [=[2.0 * w_parent.cross(be * a)]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[symptom: it fails only where it moves \(the velocities are not zero\): [0-9]+ of those [0-9]+ [a-z]+s fail, and every other [a-z]+ passes]=])
soa_plant(4.3 transpose
  FIND [=[phi.transpose() * op.H.transpose()]=]
  WRONG [=[phi * op.H.transpose()]=] TYPE [=[MatX<double>]=]
  EXPECT [=[likely mistake \(transpose\): your result is H phi\* M phi H\*]=])
soa_plant(4.5 dropped-b
  FIND [=[op.M * (phi.transpose() * op.a) + op.b]=]
  WRONG [=[op.M * (phi.transpose() * op.a)]=] TYPE [=[VecX<double>]=]
  EXPECT [=[likely mistake \(dropped term\): b \(gyroscopic less external forces\) is missing]=])
soa_plant(4.6 wrong-frame
  FIND [=[ws.pose[std::size_t(k - 1)].R().transpose() * m.gravity]=]
  WRONG [=[m.gravity]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[likely mistake \(wrong frame\)]=])
soa_plant(4.7 transpose
  FIND [=[B.transpose() * (es.op.M * B_dot + es.h_breve * B)]=]
  WRONG [=[(B.transpose() * (es.op.M * B_dot + es.h_breve * B)).transpose()]=]
  TYPE [=[MatX<double>]=]
  EXPECT [=[likely mistake \(transpose\): your result is C_v\*]=])
soa_plant(4.8 slide-once
  FIND [=[2.0 * beta * pitch * w.cross(axis)]=]
  WRONG [=[beta * pitch * w.cross(axis)]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[the checker knows this mistake: it names it after 4 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|your linear part has h beta omega' x a once]=]
  NAMED [=[likely mistake \(dropped term\): your linear part has h beta omega' x a once]=])
soa_plant(4.9 sign
  FIND [=[-a.dot(moment)]=]
  WRONG [=[a.dot(moment)]=] TYPE [=[double]=]
  EXPECT [=[the checker knows this mistake: it names it after 4 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|your signs are those of gravity's torque]=]
  NAMED [=[likely mistake \(sign\): your signs are those of gravity's torque]=])
soa_plant(4.9 pose-of-hinge
  FIND [=[ws.pose[std::size_t(i - 1)].apply(Mi.p())]=]
  WRONG [=[O.apply(Mi.p())]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[symptom: it fails only where there is more than one body: [0-9]+ of those [0-9]+ [a-z]+s fail, and every other [a-z]+ passes]=])
