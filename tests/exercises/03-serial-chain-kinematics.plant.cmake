# Planted mistakes of lesson 3 (tests/exercises/plant.cmake): each is applied to the
# solutions and the checker must name it (the catalogue's kinds: transpose, sign, neighbour
# index, dropped term, wrong frame, degrees, order, the given bug), or, for a mistake that is
# in no catalogue, give its symptom.
soa_plant(3.1 universal-transpose
  FIND [=[exp_so3<double>(-theta[1] * hinge.axis2) * a]=]
  WRONG [=[exp_so3<double>(theta[1] * hinge.axis2) * a]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[likely mistake \(transpose\): your first column is exp\(\+theta_2 a_2~\) a]=])
soa_plant(3.2 transpose
  FIND [=[phi[k - 1].transpose_apply(V_parent)]=]
  WRONG [=[Velocity(Vec6<double>(phi[k-1].matrix() * V_parent.vector()))]=]
  TYPE [=[Velocity]=]
  EXPECT [=[likely mistake \(transpose\): your V\(k\) takes phi\(k\+1,k\) V\(k\+1\)]=])
soa_plant(3.2 rotation-only
  FIND [=[phi[k - 1].transpose_apply(V_parent)]=]
  WRONG [=[Velocity(Vec3<double>(phi[k-1].R().transpose() * V_parent.angular()), Vec3<double>(phi[k-1].R().transpose() * V_parent.linear()))]=]
  TYPE [=[Velocity]=]
  EXPECT [=[likely mistake \(dropped term\): your V\(k\) turns V\(k\+1\) by R\* but leaves out the offset]=])
soa_plant(3.3 neighbour-index
  FIND [=[phi[k - 1].matrix()]=]
  WRONG [=[phi[k].matrix()]=] TYPE [=[Mat6<double>]=]
  EXPECT [=[likely mistake \(neighbour index\): block \(k\+1, k\) of yours holds phi\(k\+2,k\+1\)]=])
soa_plant(3.4 order
  FIND [=[phi[i - 1].matrix() * block]=]
  WRONG [=[block * phi[i - 1].matrix()]=] TYPE [=[Mat6<double>]=]
  EXPECT [=[likely mistake \(order\): your products run the wrong way]=])
soa_plant(3.5 transpose
  FIND [=[phi_iF.transpose() * B.hinge.H_star(theta.data() + B.q_offset)]=]
  WRONG [=[phi_iF * B.hinge.H_star(theta.data() + B.q_offset)]=] TYPE [=[MatX<double>]=]
  EXPECT [=[likely mistake \(transpose\): your columns are phi\(O_i, F\) H\*\(i\)]=])
soa_plant(3.5 frame-ignored
  FIND [=[ws.pose[k - 1] * frame]=]
  WRONG [=[ws.pose[k - 1]]=] TYPE [=[Pose]=]
  EXPECT [=[likely mistake \(wrong frame\): your J is the Jacobian of O_k]=])
soa_plant(3.6 unrotated-parent
  FIND [=[phi.R().transpose()]=]
  WRONG [=[Mat3<double>::Identity()]=] TYPE [=[Mat3<double>]=]
  EXPECT [=[likely mistake \(wrong frame\): your omega\(k\+1\) and v\(k\+1\) are V_parent's halves as given]=])
soa_plant(3.6 no-free-term
  FIND [=[w.cross(dv)]=]
  WRONG [=[w_p.cross(dv)]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[likely mistake \(dropped term\): your linear part has omega\(k\+1\) x dv]=])
soa_plant(3.6 relative-sign
  FIND [=[v - v_p]=]
  WRONG [=[v_p - v]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[likely mistake \(sign\): your relative velocity is v\(k\+1\) - v\(k\)]=])
# Not in the catalogue: the angular part doubled. Zero for a single body (V(n+1) = 0), so
# the report gives the symptom.
soa_plant(3.6 angular-doubled
  FIND [=[w_p.cross(dw)]=]
  WRONG [=[2.0 * w_p.cross(dw)]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[symptom: it fails only where there is more than one body: [0-9]+ of those [0-9]+ [a-z]+s fail, and every other [a-z]+ passes]=])
soa_plant(3.7 degrees
  FIND [=[theta[0] * a]=]
  WRONG [=[theta[0] * 3.14159265358979323846 / 180 * a]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[H\*\(theta\), the joint map of the planar hinge: wrong in [0-9]+ of [0-9]+ cases.*symptom: it fails only where the frames are rotated.*the checker knows this mistake: it names it after 4 failed runs.*where, in case [0-9]+ \(the simplest that fails\): column [23]]=]
  REJECT [=[likely mistake|perhaps \(|your rotation takes theta_1 in degrees|R\* ?b|R\* ?c|a~ R\*|pi/180]=]
  NAMED [=[likely mistake \(degrees\): your rotation takes theta_1 in degrees]=])
soa_plant(3.8 the-bug
  FIND [=[w.cross(R * p)]=]
  WRONG [=[w.cross(p)]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[the checker knows this mistake: it names it after 3 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|your result is the given code's]=]
  NAMED [=[likely mistake \(the given bug\): your result is the given code's]=])
