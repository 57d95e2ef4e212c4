# Planted mistakes of lesson 1 (tests/exercises/plant.cmake): each is applied to the
# solutions and the checker must name it (or, for one not in the catalogue, its symptom).
soa_plant(1.1 wrong-frame
  FIND [=[phi_xy.l().cross(F)]=]
  WRONG [=[phi_xy.l().cross(f_y.linear())]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[likely mistake \(wrong frame\): your moment takes l x F\(y\) with F\(y\) still in y-coordinates]=])
soa_plant(1.1 moment-doubled
  FIND [=[N_y + offset_moment]=]
  WRONG [=[N_y + 2.0 * offset_moment]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[symptom: it fails only where the frames are offset: [0-9]+ of those [0-9]+ [a-z]+s fail, and every other [a-z]+ passes]=])
soa_plant(1.2 transpose
  FIND [=[Acceleration(x * w, y * w + x * v)]=]
  WRONG [=[Acceleration(x * w + y * v, x * v)]=]
  EXPECT [=[likely mistake \(transpose\): your result is X_bar Y]=])
soa_plant(1.3 transpose
  FIND [=[R * J_C * R.transpose()]=]
  WRONG [=[R.transpose() * J_C * R]=] TYPE [=[Mat3<double>]=]
  EXPECT [=[likely mistake \(transpose\): your J\(C\) is rotated with R\* J R]=])
soa_plant(1.4 degrees
  FIND [=[theta / 2]=]
  WRONG [=[theta * 3.14159265358979323846 / 360]=] TYPE [=[double]=]
  EXPECT [=[likely mistake \(degrees\): your angle is read as degrees.*case [0-3] \(the simplest that fails\) as code \(paste into a program\):[^(]*soa::Vec3<double> n = soa::Vec3<double>.[0-9], [0-9], [0-9].;[^(]*double theta = -?[0-9](\.5)?;]=])
soa_plant(1.5 dropped-coupling
  FIND [=[w.dot(h.cross(v))]=]
  WRONG [=[0.0]=] TYPE [=[double]=]
  EXPECT [=[likely mistake \(dropped term\): the term that couples w and v]=])
# Not in the catalogue: the 1/2 of the linear term left out. The report says what it
# measured (the variant the result equals; where it fails), and guesses no cause.
soa_plant(1.5 half-missing
  FIND [=[0.5 * M_x.mass() * v.squaredNorm()]=]
  WRONG [=[M_x.mass() * v.squaredNorm()]=] TYPE [=[double]=]
  EXPECT [=[T = 1/2 V\*\(x\) M\(x\) V\(x\), the kinetic energy: wrong in [0-9]+ of [0-9]+ cases.*symptom: in every failing case, your result matches the expected value with 1/2 m v\* v taken without its 1/2.*T about x = T about y \(slides 72-73\): wrong in [0-9]+ of [0-9]+ cases.*symptom: it fails only where the frames are offset: [0-9]+ of those [0-9]+ cases fail, and every other case passes]=]
  REJECT [=[offset l|is wrong|likely mistake]=])
soa_plant(1.6 sign
  FIND [=[-v_xy + w_xy.cross(phi_xy.l())]=]
  WRONG [=[-v_xy - w_xy.cross(phi_xy.l())]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[likely mistake \(sign\): your v\(y,x\) subtracts w\(x,y\) x l\(x,y\)]=])
soa_plant(1.7 closed-form-at-small-angles
  FIND [=[t < 1e-2]=]
  WRONG [=[t < 0.0]=] TYPE [=[bool]=]
  EXPECT [=[exp\(xi\^\) at small angles, theta from 1e-9 to 1e-2 \(where the closed forms of g2 and g3 cancel\): wrong in]=])
soa_plant(1.8 dropped-term
  FIND [=[x.cross(N) + y.cross(F)]=]
  WRONG [=[x.cross(N)]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[the checker knows this mistake: it names it after 3 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|the y x F term of the moment part is missing]=]
  NAMED [=[likely mistake \(dropped term\): the y x F term of the moment part is missing]=])
soa_plant(1.9 missed-case
  FIND [=[y_zero ? 0 : 2]=]
  WRONG [=[4]=] TYPE [=[int]=]
  EXPECT [=[the checker knows this mistake: it names it after 3 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|your rank is 4 for every X]=]
  NAMED [=[likely mistake \(missed case\): your rank is 4 for every X]=])
