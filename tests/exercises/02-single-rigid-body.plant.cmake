# Planted mistakes of lesson 2 (tests/exercises/plant.cmake): each is applied to the
# solutions and the checker must name it (or, for one not in the catalogue, its symptom).
# Lesson 2 has no angle among its inputs (degrees vs radians does not apply) and no chain
# (no neighbouring body's index).
soa_plant(2.1 centripetal-doubled
  FIND [=[M.mass() * w.cross(w.cross(M.p()))]=]
  WRONG [=[2.0 * M.mass() * w.cross(w.cross(M.p()))]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[symptom: it fails only where the centre of mass is off the frame's origin: [0-9]+ of those [0-9]+ [a-z]+s fail, and every other [a-z]+ passes]=])
soa_plant(2.2 dropped-gyroscopic
  FIND [=[w.cross(J_C * w)]=]
  WRONG [=[Vec3<double>::Zero()]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[likely mistake \(dropped term\): the gyroscopic moment w x J\(C\) w is missing]=])
soa_plant(2.2 transpose
  FIND [=[Force(N_C + p.cross(F_C), F_C)]=]
  WRONG [=[Force(N_C, Vec3<double>(F_C - p.cross(N_C)))]=] TYPE [=[Force]=]
  EXPECT [=[likely mistake \(transpose\): your f\(x\) is phi\*\(x,C\) f\(C\)]=])
soa_plant(2.3 wrong-frame
  FIND [=[x.q.matrix() * v]=]
  WRONG [=[v]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[likely mistake \(wrong frame\): your r_dot is v in body coordinates]=])
soa_plant(2.4 no-dexp
  FIND [=[dexp_inv_right(delta, s.d.omega)]=]
  WRONG [=[s.d.omega]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[likely mistake \(dropped term\): your delta rates are the angular velocities themselves]=])
soa_plant(2.5 transpose
  FIND [=[(Vec6<double>() << w.cross(h_w) + v.cross(h_v), w.cross(h_v)).finished()]=]
  WRONG [=[(Vec6<double>() << w.cross(h_w), v.cross(h_w) + w.cross(h_v)).finished()]=]
  TYPE [=[Vec6<double>]=]
  EXPECT [=[likely mistake \(transpose\): your V_bar is V~]=])
soa_plant(2.6 sign
  FIND [=[s < 0.0]=]
  WRONG [=[s > 0.0]=] TYPE [=[bool]=]
  EXPECT [=[the checker knows this mistake: it names it after 4 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|your prediction is the opposite about every axis]=]
  NAMED [=[likely mistake \(sign\): your prediction is the opposite about every axis]=])
soa_plant(2.7 the-bug
  FIND [=[x0.q * UnitQuaternion::exp(h * w)]=]
  WRONG [=[UnitQuaternion::exp(h * w) * x0.q]=] TYPE [=[UnitQuaternion]=]
  EXPECT [=[the checker knows this mistake: it names it after 3 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|your attitude is exp\(h w\) \(x\) q0, the given code's bug]=]
  NAMED [=[likely mistake \(wrong frame\): your attitude is exp\(h w\) \(x\) q0, the given code's bug]=])
