# Planted mistakes of lesson 5 (tests/exercises/plant.cmake): each is applied to the
# solutions and the checker must name it (the catalogue's kinds: neighbour index, wrong
# frame, dropped term, transpose, degrees, sign), or, for a mistake that is in no catalogue,
# give its symptom.
soa_plant(5.1 neighbour-index
  FIND [=[transform(phi[i - 1], R[i - 1])]=]
  WRONG [=[transform(phi[i], R[i - 1])]=] TYPE [=[SpatialInertia]=]
  EXPECT [=[likely mistake \(neighbour index\): your R\(k\) moves R\(k-1\) with phi\(k\+1,k\)]=])
soa_plant(5.1 unmoved
  FIND [=[transform(phi[i - 1], R[i - 1])]=]
  WRONG [=[R[i - 1]]=] TYPE [=[SpatialInertia]=]
  EXPECT [=[likely mistake \(wrong frame\): your R\(k\) adds R\(k-1\) as it is]=])
soa_plant(5.2 own-inertia
  FIND [=[R[std::size_t(k - 1)].matrix() * Hs]=]
  WRONG [=[B.M.matrix() * Hs]=] TYPE [=[MatX<double>]=]
  EXPECT [=[likely mistake \(dropped term\): your M\(k,k\) uses M\(k\), body k alone]=])
# Not in the catalogue: the prismatic joint map doubled. The report gives the symptom.
soa_plant(5.2 prismatic-doubled
  FIND [=[B.hinge.H_star(theta.data() + B.q_offset)]=]
  WRONG [=[B.hinge.type == HingeType::Prismatic ? MatX<double>(2.0 * B.hinge.H_star(theta.data() + B.q_offset)) : MatX<double>(B.hinge.H_star(theta.data() + B.q_offset))]=]
  TYPE [=[MatX<double>]=]
  EXPECT [=[symptom: it fails only where a hinge is prismatic: [0-9]+ of those [0-9]+ [a-z]+s fail, and every other [a-z]+ passes]=])
soa_plant(5.3 transpose
  FIND [=[phi[std::size_t(i - 2)].apply(F)]=]
  WRONG [=[Force(Vec6<double>(phi[std::size_t(i-2)].matrix().transpose() * F.vector()))]=]
  TYPE [=[Force]=]
  EXPECT [=[likely mistake \(transpose\): your force R\(j\) H\*\(j\) is carried inboard with phi\*]=])
soa_plant(5.3 degrees
  FIND [=[theta[B.q_offset] * B.hinge.axis]=]
  WRONG [=[theta[B.q_offset] * 3.14159265358979323846 / 180 * B.hinge.axis]=]
  TYPE [=[Vec3<double>]=]
  EXPECT [=[likely mistake \(degrees\): your phi\(k\+1,k\) takes theta in degrees]=])
soa_plant(5.4 sign
  FIND [=[R + phi_t * R + R * phi_t.transpose()]=]
  WRONG [=[R - phi_t * R - R * phi_t.transpose()]=] TYPE [=[MatX<double>]=]
  EXPECT [=[likely mistake \(sign\): your result subtracts phi~ R and R phi~\*]=])
soa_plant(5.5 transpose
  FIND [=[phi_M_phi_star_block(phi, R, j, i).transpose()]=]
  WRONG [=[phi_M_phi_star_block(phi, R, j, i)]=] TYPE [=[Mat6<double>]=]
  EXPECT [=[the checker knows this mistake: it names it after 4 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|your block \(i,j\), i < j, is block \(j,i\) itself]=]
  NAMED [=[likely mistake \(transpose\): your block \(i,j\), i < j, is block \(j,i\) itself]=])
soa_plant(5.6 no-angle
  FIND [=[axis[std::size_t(i - 1)].dot(axis[std::size_t(j - 1)])]=]
  WRONG [=[1.0]=] TYPE [=[double]=]
  EXPECT [=[the checker knows this mistake: it names it after 3 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|your M\(i,j\) leaves out a_i \. a_j]=]
  NAMED [=[likely mistake \(dropped term\): your M\(i,j\) leaves out a_i \. a_j]=])
