// SOA Course Companion: the 3D view of a serial chain (docs/viewer.md, notes page "Viewing a
// chain in 3D").
//
// The page only renders. Every pose, velocity, force, energy and tip point comes from
// window.SOA_VIEW (data.js), computed by the library; nothing here integrates or differentiates.
// Course notation (docs/conventions.md): body 1 is the tip, O_k is the frame of body k at its
// hinge, V(k) = [omega; v] the spatial velocity of O_k, f(k) = [N; F] the inter-body force on
// body k at its hinge O_k. All vectors of data.js are in world axes unless named "body frame";
// quaternions are [x, y, z, w] and rotate body-frame vectors into world ones.
(function () {
  'use strict';

  const root = document.getElementById('soa-view');
  const $ = (id) => document.getElementById(id);

  // One table of colours for the 3D view and the legend: angular quantities warm (orange,
  // red), linear ones cool (blues); angular arrows have a double head.
  const COLORS = {
    background: 0xf4f5f7,
    grid: 0xc9ced6,
    gridCentre: 0xaab1bc,
    bodies: [0x8f9bb0, 0x5f6b80],
    hinge: 0x2b2f3a,
    axis: 0x111111,
    omega: 0xf39c12,
    v: 0x2e86de,
    N: 0xc0392b,
    F: 0x1a3f8f,
    tip: 0x8e44ad,
    tipDim: 0xd7bfe3,
    fixed: 0x1e8449,
    x: 0xe03131,
    y: 0x2f9e44,
    z: 0x1c5fd1,
  };

  // What the toggles show; `on` is the default when the URL has no `show=`.
  const TOGGLES = [
    { key: 'frames', text: 'frames O<sub>k</sub>', on: true },
    { key: 'axes', text: 'hinge axes', on: true },
    { key: 'ellipsoids', text: 'ellipsoids', on: false },
    { key: 'V', text: 'velocities V', on: false },
    { key: 'f', text: 'forces f', on: false },
    { key: 'tip', text: 'tip path', on: true },
    { key: 'fixed', text: 'fixed vectors', on: true },
  ];

  // ---------------------------------------------------------------------------------------
  // Errors: a clear message in the page instead of a blank canvas.

  function errorCount() {
    return window.SOA_ERRORS || 0;
  }

  // Shows `text` over the view, disables the controls and counts it as an error.
  function fail(text) {
    const box = $('soa-message');
    const head = document.createElement('strong');
    head.textContent = 'The viewer has nothing to draw.';
    box.append(head, document.createElement('br'), text);
    box.hidden = false;
    $('soa-panel').hidden = true;
    $('soa-canvas').style.visibility = 'hidden';
    for (const id of ['soa-play', 'soa-slider', 'soa-speed']) $(id).disabled = true;
    window.SOA_ERRORS = errorCount() + 1;
    root.setAttribute('data-errors', String(errorCount()));
    console.error('SOA viewer: ' + text);
  }

  const isNumbers = (a, n) =>
    Array.isArray(a) && a.length === n && a.every((x) => typeof x === 'number' && isFinite(x));

  // What is wrong with body b, or ''.
  function problemWithBody(body, b) {
    const where = 'data.js: body ' + b + ' ("' + (body && body.name) + '"): ';
    if (!body || typeof body !== 'object') return where + 'not an object.';
    for (const key of ['axis', 'segment', 'com', 'radii'])
      if (!isNumbers(body[key], 3)) return where + '"' + key + '" must be 3 numbers.';
    if (!isNumbers(body.axes_quaternion, 4)) return where + '"axes_quaternion" must be 4 numbers.';
    if (!isNumbers([body.mass], 1)) return where + '"mass" must be a number.';
    return '';
  }

  // What is wrong with run i of nb bodies, or ''.
  function problemWithRun(r, i, nb) {
    const where = 'data.js: run ' + i + ' ("' + (r && r.label) + '"): ';
    const n = r && Array.isArray(r.t) ? r.t.length : 0;
    if (n === 0) return where + 'no frames.';
    if (!isNumbers(r.t, n) || !isNumbers(r.energy, n))
      return where + '"t" and "energy" must be ' + n + ' numbers each.';
    for (let k = 1; k < n; ++k) if (!(r.t[k] >= r.t[k - 1])) return where + '"t" must not decrease.';
    const width = { pose: 7 * nb, tip: 3, V: 6 * nb, f: 6 * nb };
    for (const key in width) {
      if (r[key] === undefined && (key === 'V' || key === 'f')) continue; // optional
      if (!Array.isArray(r[key]) || r[key].length !== n || !r[key].every((row) =>
          isNumbers(row, width[key])))
        return where + '"' + key + '" must be ' + n + ' rows of ' + width[key] + ' numbers.';
    }
    return '';
  }

  // The first problem that stops the page from drawing `data`, or '' when there is none.
  function problemWith(data) {
    if (data === undefined || data === null || typeof data !== 'object')
      return 'data.js is missing, or it did not set window.SOA_VIEW: write the folder again ' +
             '(soa view, or soa simulate --view).';
    if (data.format !== 1)
      return 'data.js is in format ' + JSON.stringify(data.format) + ', and this page reads ' +
             'format 1: write the folder again with the soa that wrote data.js.';
    if (typeof THREE === 'undefined' || typeof THREE.OrbitControls !== 'function')
      return 'three.min.js or OrbitControls.js did not load: they must be beside index.html.';
    if (!Array.isArray(data.bodies) || data.bodies.length === 0) return 'data.js: no bodies.';
    if (!Array.isArray(data.runs) || data.runs.length === 0) return 'data.js: no runs.';
    const nb = data.bodies.length;
    const tip = data.tip;
    if (tip && tip.body >= 0 && !(tip.body < nb && isNumbers(tip.point, 3)))
      return 'data.js: "tip" must name a body (0 to ' + (nb - 1) + ') and a point.';
    for (const f of data.fixed || [])
      if (!isNumbers(f.origin, 3) || !isNumbers(f.vector, 3))
        return 'data.js: each fixed vector needs an "origin" and a "vector" of 3 numbers.';
    const problems = data.bodies.map(problemWithBody)
                         .concat(data.runs.map((r, i) => problemWithRun(r, i, nb)));
    return problems.find((p) => p !== '') || '';
  }

  // ---------------------------------------------------------------------------------------
  // Small helpers.

  const vec = (a, i) => new THREE.Vector3(a[i || 0], a[(i || 0) + 1], a[(i || 0) + 2]);

  // A number with 3 significant digits, without trailing zeros ("2.3", "0.0012", "1.2e-7").
  function fmt(x) {
    return String(Number(x.toPrecision(3)));
  }

  // A readable grid step: 1, 2 or 5 times a power of ten, near `x`.
  function niceStep(x) {
    const p = Math.pow(10, Math.floor(Math.log10(x)));
    const m = x / p;
    return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p;
  }

  // The last index i with times[i] <= t (0 when t is before the first).
  function frameAt(times, t) {
    let lo = 0;
    let hi = times.length - 1;
    while (lo < hi) {
      const mid = (lo + hi + 1) >> 1;
      if (times[mid] <= t) lo = mid;
      else hi = mid - 1;
    }
    return lo;
  }

  // World position of the body-frame point `p` of body `b` in a pose row (p + q p q^-1).
  function worldPoint(pose, b, p) {
    const q = new THREE.Quaternion(pose[7 * b + 3], pose[7 * b + 4], pose[7 * b + 5],
                                   pose[7 * b + 6]);
    return p.clone().applyQuaternion(q).add(vec(pose, 7 * b));
  }

  // The world box around body b's inertia ellipsoid (which also holds the box drawn for a
  // body without a segment): half-width sqrt(sum_i (R_ji a_i)^2) along world axis j, R the
  // rotation from the principal axes to the world's.
  function ellipsoidBox(pose, b, body) {
    const q = new THREE.Quaternion().fromArray(pose, 7 * b + 3)
                  .multiply(new THREE.Quaternion().fromArray(body.axes_quaternion));
    const e = new THREE.Matrix4().makeRotationFromQuaternion(q).elements; // column-major
    const half = new THREE.Vector3();
    for (let j = 0; j < 3; ++j) {
      let sum = 0;
      for (let i = 0; i < 3; ++i) sum += Math.pow(e[4 * i + j] * body.radii[i], 2);
      half.setComponent(j, Math.sqrt(sum));
    }
    const com = worldPoint(pose, b, vec(body.com));
    return new THREE.Box3(com.clone().sub(half), com.clone().add(half));
  }

  const hasTip = (data) => !!(data.tip && data.tip.body >= 0);

  // The course's number k of each body (1 at the tip; locked bodies, merged into the body
  // they hang from, have none: null).
  function courseNumbers(bodies) {
    const k = new Array(bodies.length).fill(null);
    let next = 1;
    for (let i = bodies.length - 1; i >= 0; --i)
      if (bodies[i].hinge !== 'locked') k[i] = next++;
    return k;
  }

  // ---------------------------------------------------------------------------------------
  // The run's extent and the arrows' scales (over every run and frame: the scale of a
  // quantity does not change while playing, and is the same in every view).

  function measure(data) {
    const box = new THREE.Box3();
    const nb = data.bodies.length;
    let reach = 0;
    let radius = 0;
    for (const b of data.bodies) {
      reach += vec(b.segment).length();
      radius = Math.max(radius, b.radii[0], b.radii[1], b.radii[2]);
    }
    for (const r of data.runs) {
      for (const pose of r.pose) {
        for (let b = 0; b < nb; ++b) {
          const body = data.bodies[b];
          box.expandByPoint(vec(pose, 7 * b));
          box.expandByPoint(worldPoint(pose, b, vec(body.segment)));
          box.union(ellipsoidBox(pose, b, body));
        }
      }
      if (hasTip(data)) for (const tip of r.tip) box.expandByPoint(vec(tip));
    }
    const size = Math.max(box.getSize(new THREE.Vector3()).length(), reach, 2 * radius) || 1;
    const fixed = Array.isArray(data.fixed) ? data.fixed : [];
    const max = { omega: 0, v: 0, N: 0, F: 0, fixed: 0 };
    const grow = (key, row, i) => (max[key] = Math.max(max[key], vec(row, i).length()));
    for (const r of data.runs) {
      for (const row of r.V || []) for (let b = 0; b < nb; ++b) {
        grow('omega', row, 6 * b);
        grow('v', row, 6 * b + 3);
      }
      for (const row of r.f || []) for (let b = 0; b < nb; ++b) {
        grow('N', row, 6 * b);
        grow('F', row, 6 * b + 3);
      }
    }
    for (const fv of fixed) grow('fixed', fv.vector, 0);
    // Rounding is not drawn: a moment N below 1e-9 of the largest force times the size (the
    // planar pendulum's N, about 1e-15 N m), an angular velocity below 1e-9 of the largest
    // linear one over the size, counts as zero (and the legend says so).
    const rounding = { omega: false, N: false };
    if (max.N > 0 && max.N <= 1e-9 * max.F * size) (max.N = 0), (rounding.N = true);
    if (max.omega > 0 && max.omega * size <= 1e-9 * max.v) (max.omega = 0), (rounding.omega = true);
    // metres of arrow per unit of the quantity: the largest is 30 % of the chain's size
    const scale = {};
    for (const key in max) scale[key] = max[key] > 0 ? (0.3 * size) / max[key] : 0;
    // the framed extent also holds the fixed vectors
    for (const fv of fixed) {
      box.expandByPoint(vec(fv.origin));
      box.expandByPoint(vec(fv.origin).addScaledVector(vec(fv.vector), scale.fixed));
    }
    if (box.isEmpty()) box.expandByPoint(new THREE.Vector3());
    // the size of one body, for what is drawn on each (hinge balls, axes, frames, rods): the
    // median length of the segments, at most the whole size (a 50-link chain is 50 links long)
    const lengths = data.bodies.map((b) => vec(b.segment).length()).filter((l) => l > 1e-9 * size);
    lengths.sort((a, b) => a - b);
    const link = lengths.length ? Math.min(size, lengths[lengths.length >> 1]) : size;
    return { box, size, link, bodies: nb, max, scale, fixed, rounding };
  }

  // ---------------------------------------------------------------------------------------
  // Shapes. Unit geometries shared by every mesh, scaled and placed per use.

  const shapes = {};
  function makeShapes() {
    shapes.cylinder = new THREE.CylinderBufferGeometry(1, 1, 1, 16).translate(0, 0.5, 0);
    shapes.cone = new THREE.ConeBufferGeometry(1, 1, 16).translate(0, 0.5, 0);
    shapes.sphere = new THREE.SphereBufferGeometry(1, 24, 16);
    shapes.box = new THREE.BoxBufferGeometry(2, 2, 2);
  }

  const materials = {};
  function material(color, opacity) {
    const key = color + '/' + (opacity || 1);
    if (!materials[key]) {
      materials[key] = new THREE.MeshPhongMaterial({ color, shininess: 30 });
      if (opacity) {
        materials[key].transparent = true;
        materials[key].opacity = opacity;
        materials[key].depthWrite = false;
      }
    }
    return materials[key];
  }

  const Y = new THREE.Vector3(0, 1, 0);

  // A solid rod of radius r from a to b (in the parent's frame).
  function rod(a, b, r, color) {
    const mesh = new THREE.Mesh(shapes.cylinder, material(color));
    const d = b.clone().sub(a);
    const len = d.length();
    mesh.position.copy(a);
    if (len > 0) mesh.quaternion.setFromUnitVectors(Y, d.divideScalar(len));
    mesh.scale.set(r, len, r);
    return mesh;
  }

  function ball(at, r, color, opacity) {
    const mesh = new THREE.Mesh(shapes.sphere, material(color, opacity));
    mesh.position.copy(at);
    mesh.scale.setScalar(r);
    return mesh;
  }

  // An arrow (shaft + head) along +y, placed by placeArrow(); `double` for angular vectors.
  function makeArrow(color, double, r) {
    const arrow = new THREE.Group();
    arrow.add(new THREE.Mesh(shapes.cylinder, material(color)));
    arrow.add(new THREE.Mesh(shapes.cone, material(color)));
    if (double) arrow.add(new THREE.Mesh(shapes.cone, material(color)));
    arrow.userData.r = r;
    return arrow;
  }

  // Puts `arrow` at `origin` along `v` (metres); hidden when v is negligible.
  function placeArrow(arrow, origin, v, tiny) {
    const len = v.length();
    arrow.userData.zero = !(len > tiny);
    if (arrow.userData.zero) return;
    const r = arrow.userData.r;
    const head = Math.min(0.4 * len, 7 * r);
    const [shaft, cone1, cone2] = arrow.children;
    arrow.position.copy(origin);
    arrow.quaternion.setFromUnitVectors(Y, v.clone().divideScalar(len));
    shaft.scale.set(r, len - head, r);
    cone1.position.y = len - head;
    cone1.scale.set(2.6 * r, head, 2.6 * r);
    if (cone2) {
      cone2.position.y = len - 1.7 * head;
      cone2.scale.set(2.6 * r, head, 2.6 * r);
    }
  }

  // Three rods along the frame's x (red), y (green), z (blue) axes.
  function triad(len, r) {
    const g = new THREE.Group();
    const o = new THREE.Vector3();
    g.add(rod(o, new THREE.Vector3(len, 0, 0), r, COLORS.x));
    g.add(rod(o, new THREE.Vector3(0, len, 0), r, COLORS.y));
    g.add(rod(o, new THREE.Vector3(0, 0, len), r, COLORS.z));
    return g;
  }

  function line(points, color) {
    const g = new THREE.BufferGeometry().setFromPoints(points);
    return new THREE.Line(g, new THREE.LineBasicMaterial({ color }));
  }

  // ---------------------------------------------------------------------------------------
  // One view per run: its own scene with the chain, the arrows, the tip path and the labels.

  // A text label over the view at a world point (`cat`: the toggle that shows it, or '').
  function label(view, text, color, cat) {
    const el = document.createElement('div');
    el.className = 'soa-label';
    el.textContent = text;
    el.style.color = '#' + new THREE.Color(color).getHexString();
    view.cell.appendChild(el);
    const l = { el, at: new THREE.Vector3(), cat };
    view.labels.push(l);
    return l;
  }

  // Ground grid (z up) under the run's extent, and the world axes x, y, z on it.
  // (GridHelper lies in x-z and is turned to x-y.)
  function addGround(view, m) {
    const step = niceStep(m.size / 6);
    const c = m.box.getCenter(new THREE.Vector3());
    const extent = m.box.getSize(new THREE.Vector3());
    const half = Math.ceil((Math.max(extent.x, extent.y) / 2 + step) / step);
    const grid = new THREE.GridHelper(2 * half * step, 2 * half, COLORS.gridCentre, COLORS.grid);
    grid.rotation.x = Math.PI / 2;
    const floor = m.box.min.z - 0.05 * m.size;
    grid.position.set(Math.round(c.x / step) * step, Math.round(c.y / step) * step, floor);
    view.scene.add(grid);
    // the world axes under the world origin (on the grid's edge if the origin is off it)
    const edge = (half - 1) * step;
    const clamp = (x, c) => Math.min(Math.max(x, c - edge), c + edge);
    const corner = new THREE.Vector3(clamp(0, grid.position.x), clamp(0, grid.position.y), floor);
    const axes = triad(step, 0.004 * m.size);
    axes.position.copy(corner);
    view.scene.add(axes);
    const names = ['x', 'y', 'z'];
    const colors = [COLORS.x, COLORS.y, COLORS.z];
    for (let i = 0; i < 3; ++i) {
      const l = label(view, names[i], colors[i], '');
      l.at.copy(corner).setComponent(i, corner.getComponent(i) + 1.15 * step);
    }
    view.gridStep = step;
  }

  // Adds `object` to `group` and to the list of a toggle.
  function part(group, object, list) {
    group.add(object);
    list.push(object);
  }

  // Body b: its solid (origin to `segment`), its hinge, hinge axis, frame and ellipsoid, all
  // in one group placed by the body's pose.
  function addBody(view, b, body, k, m) {
    const s = m.size;
    // what is drawn on a body scales with one body (m.link), within the whole chain's size
    const thick = Math.min(0.009 * s, Math.max(0.09 * m.link, 0.003 * s));
    const reach = Math.min(0.12 * s, 0.9 * m.link);
    const g = new THREE.Group();
    const color = COLORS.bodies[b % COLORS.bodies.length];
    const o = new THREE.Vector3();
    const seg = vec(body.segment);
    let frameSize = Math.min(0.1 * s, 0.8 * m.link);
    if (seg.length() > 1e-9 * s) {
      g.add(rod(o, seg, thick, color));
      g.add(ball(seg, 1.2 * thick, color));
    } else {
      // no segment (a single free body): the uniform box of the same inertia about the centre
      // of mass (half sides sqrt(3/5) times the ellipsoid's semi-axes), its frame outside it
      const box = new THREE.Mesh(shapes.box, material(color));
      const r = vec(body.radii).multiplyScalar(Math.sqrt(0.6));
      box.scale.set(r.x || 0.05 * s, r.y || 0.05 * s, r.z || 0.05 * s);
      frameSize = Math.max(0.1 * s, 1.3 * Math.max(r.x, r.y, r.z) + vec(body.com).length());
      box.position.copy(vec(body.com));
      box.quaternion.fromArray(body.axes_quaternion);
      g.add(box);
    }
    g.add(ball(o, 2.4 * thick, COLORS.hinge));
    const axis = vec(body.axis);
    if (axis.length() > 0) {
      axis.normalize().multiplyScalar(reach);
      part(g, rod(axis.clone().negate(), axis, 0.45 * thick, COLORS.axis), view.show.axes);
    }
    part(g, triad(frameSize, 0.4 * thick), view.show.frames);
    if (body.mass > 0) {
      const e = new THREE.Mesh(shapes.sphere, material(color, 0.3));
      e.position.copy(vec(body.com));
      e.quaternion.fromArray(body.axes_quaternion);
      e.scale.copy(vec(body.radii));
      e.renderOrder = 1;
      part(g, e, view.show.ellipsoids);
    }
    view.scene.add(g);
    view.bodies.push(g);
    // every frame named on a short chain; on a long one the base and the tip only
    const n = m.bodies;
    const name = (k === null ? '' : 'O' + k + ' ') + body.name;
    view.frameLabels.push(n <= 12 || b === 0 || b === n - 1
      ? label(view, name, COLORS.hinge, 'frames') : null);
  }

  // The arrows of V(k) (omega, v) and f(k) (N, F) at each body's origin.
  function addArrows(view, nb, m) {
    const r = Math.min(0.006 * m.size, 0.06 * m.link);
    for (let b = 0; b < nb; ++b) {
      const a = {
        omega: makeArrow(COLORS.omega, true, r),
        v: makeArrow(COLORS.v, false, r),
        N: makeArrow(COLORS.N, true, r),
        F: makeArrow(COLORS.F, false, r),
      };
      for (const key in a) view.scene.add(a[key]);
      view.arrows.push(a);
    }
  }

  // The tip's path over the whole run (dimmed) and up to the current frame, and the tip.
  function addTipPath(view, run, m) {
    const points = run.tip.map((p) => vec(p));
    const all = line(points, COLORS.tipDim);
    view.sofar = line(points, COLORS.tip);
    view.tipBall = ball(new THREE.Vector3(), Math.min(0.014 * m.size, 0.14 * m.link), COLORS.tip);
    for (const o of [all, view.sofar, view.tipBall]) {
      view.scene.add(o);
      view.show.tip.push(o);
    }
  }

  // Vectors fixed in space (e.g. the angular momentum of a torque-free body), with labels.
  function addFixed(view, m) {
    for (const fv of m.fixed) {
      const arrow = makeArrow(COLORS.fixed, false, 0.007 * m.size);
      const v = vec(fv.vector).multiplyScalar(m.scale.fixed);
      placeArrow(arrow, vec(fv.origin), v, 0);
      if (arrow.userData.zero) continue;
      view.scene.add(arrow);
      view.show.fixed.push(arrow);
      const l = label(view, fv.label, COLORS.fixed, 'fixed');
      l.at.copy(vec(fv.origin)).add(v);
    }
  }

  function addLights(view) {
    view.scene.add(new THREE.HemisphereLight(0xffffff, 0x9aa5b4, 0.65));
    view.light = new THREE.DirectionalLight(0xffffff, 0.55);
    view.scene.add(view.light);
    view.scene.add(view.light.target);
  }

  function buildView(data, run, m, knum) {
    const cell = document.createElement('div'); // the view's labels, clipped to its cell
    cell.className = 'soa-cell';
    $('soa-labels').appendChild(cell);
    const view = {
      cell,
      run,
      scene: new THREE.Scene(),
      bodies: [],
      arrows: [],
      labels: [],
      frameLabels: [],
      show: { frames: [], axes: [], ellipsoids: [], tip: [], fixed: [] },
      frame: -1,
    };
    addLights(view);
    addGround(view, m);
    data.bodies.forEach((body, b) => addBody(view, b, body, knum[b], m));
    addArrows(view, data.bodies.length, m);
    if (hasTip(data)) addTipPath(view, run, m);
    addFixed(view, m);
    const title = document.createElement('div');
    title.className = 'soa-run-label';
    title.textContent = run.label;
    cell.appendChild(title);
    return view;
  }

  // ---------------------------------------------------------------------------------------
  // Posing a view at one of its frames: the chain, the arrows, the path so far.

  // The arrows of body b: V(k) = [omega; v] at O_k and f(k) = [N; F] on body k at its hinge
  // O_k, from the run's rows V and f (6 per body: angular part first), shown by the toggles V, f.
  const ARROWS = [
    { key: 'omega', rows: 'V', at: 0 },
    { key: 'v', rows: 'V', at: 3 },
    { key: 'N', rows: 'f', at: 0 },
    { key: 'F', rows: 'f', at: 3 },
  ];

  function poseArrows(view, b, k, origin, m, show) {
    for (const { key, rows, at } of ARROWS) {
      const arrow = view.arrows[b][key];
      const values = view.run[rows];
      if (values) {
        const v = vec(values[k], 6 * b + at).multiplyScalar(m.scale[key]); // in metres
        placeArrow(arrow, origin, v, 1e-9 * m.size);
      }
      arrow.visible = !!values && show[rows] && !arrow.userData.zero;
    }
  }

  function poseView(view, k, data, m, show) {
    const pose = view.run.pose[k];
    view.bodies.forEach((g, b) => {
      g.position.fromArray(pose, 7 * b);
      g.quaternion.fromArray(pose, 7 * b + 3);
      g.updateMatrixWorld(true);
      if (view.frameLabels[b]) view.frameLabels[b].at.copy(g.position);
      poseArrows(view, b, k, g.position, m, show);
    });
    if (view.sofar) {
      view.sofar.geometry.setDrawRange(0, k + 1);
      view.tip = view.bodies[data.tip.body].localToWorld(vec(data.tip.point));
      view.tipBall.position.copy(view.tip);
    }
    view.frame = k;
  }

  // ---------------------------------------------------------------------------------------
  // The page: controls, layout, drawing.

  function parseUrl(n0) {
    const q = new URLSearchParams(window.location.search);
    const out = { paused: q.get('paused') === '1', frame: null, t: null, show: null };
    if (q.has('frame')) {
      const k = Math.floor(Number(q.get('frame')));
      if (Number.isFinite(k)) out.frame = Math.min(Math.max(k, 0), n0 - 1);
    }
    if (q.has('t') && Number.isFinite(Number(q.get('t')))) out.t = Number(q.get('t'));
    if (q.has('show')) out.show = q.get('show').split(',').filter((s) => s);
    return out;
  }

  function start(data) {
    makeShapes();
    const m = measure(data);
    const knum = courseNumbers(data.bodies);
    const url = parseUrl(data.runs[0].t.length);
    const show = {};
    for (const t of TOGGLES) show[t.key] = url.show ? url.show.includes(t.key) : t.on;

    const renderer = new THREE.WebGLRenderer({
      canvas: $('soa-canvas'),
      antialias: true,
      preserveDrawingBuffer: true, // data-drawn reads the pixels back after drawing
    });
    renderer.setPixelRatio(window.devicePixelRatio || 1);
    renderer.setClearColor(COLORS.background, 1);

    const views = data.runs.map((run) => buildView(data, run, m, knum));
    const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 100);
    camera.up.set(0, 0, 1); // z up: gravity is along -z in the scenes
    const controls = new THREE.OrbitControls(camera, renderer.domElement);
    controls.enableKeys = false; // the arrow keys step frames

    const times = data.runs.map((r) => r.t);
    const t0 = Math.min(...times.map((t) => t[0]));
    const t1 = Math.max(...times.map((t) => t[t.length - 1]));
    const still = !(t1 > t0);
    const page = {
      data, m, show, views, renderer, camera, controls, t0, t1, still,
      time: t0, playing: false, speed: 1, dirty: true, cells: [], lastDrawn: -1e9,
    };
    if (url.frame !== null) page.time = data.runs[0].t[url.frame];
    else if (url.t !== null) page.time = Math.min(Math.max(url.t, t0), t1);
    page.playing = !still && !url.paused;

    fillHeader(data);
    fillBodies(data, knum);
    fillLegend(page);
    makeToggles(page);
    makeReadout(page);
    wireControls(page);
    layout(page);
    frameCamera(page);
    controls.addEventListener('change', () => (page.dirty = true));
    window.addEventListener('resize', () => {
      layout(page);
      page.dirty = true;
    });
    draw(page);
    animate(page);
  }

  // Advances the time while playing and draws when something changed (when paused: only
  // on demand, after a control, the mouse or a resize).
  function animate(page) {
    let last = null;
    const tick = (now) => {
      requestAnimationFrame(tick);
      if (page.playing) advance(page, last === null ? 0 : (now - last) / 1000);
      last = now;
      if (page.dirty) draw(page);
    };
    requestAnimationFrame(tick);
  }

  function fillHeader(data) {
    $('soa-title').textContent = data.title || 'SOA viewer';
    document.title = (data.title || 'chain') + ' — SOA viewer';
    $('soa-note').textContent = data.note || '';
  }

  // The bodies, base first as in the file, with the course's k (1 at the tip).
  function fillBodies(data, knum) {
    const box = $('soa-bodies');
    data.bodies.forEach((b, i) => {
      const row = document.createElement('div');
      const k = knum[i] === null ? '' : 'k = ' + knum[i] + ': ';
      const mass = b.mass > 0 ? ', ' + fmt(b.mass) + ' kg' : '';
      row.textContent = k + b.name + ' (' + b.hinge + mass + ')';
      box.appendChild(row);
    });
  }

  function legendRow(color, glyph, text, scale) {
    const row = document.createElement('div');
    row.className = 'soa-legend-row';
    const sw = document.createElement('span');
    sw.textContent = glyph;
    sw.style.color = '#' + new THREE.Color(color).getHexString();
    sw.style.fontWeight = 'bold';
    row.appendChild(sw);
    const t = document.createElement('span');
    t.innerHTML = text + (scale ? ' <span class="soa-scale">' + scale + '</span>' : '');
    row.appendChild(t);
    $('soa-legend').appendChild(row);
  }

  function legendHead(html) {
    const row = document.createElement('div');
    row.className = 'soa-legend-head';
    row.innerHTML = html;
    $('soa-legend').appendChild(row);
  }

  // Colours and arrow scales: "1 m = 2.3 rad/s" means an arrow 1 m long stands for 2.3 rad/s.
  function fillLegend(page) {
    const { m, data } = page;
    const per = (key, unit) => (m.scale[key] > 0 ? '1 m = ' + fmt(1 / m.scale[key]) + ' ' + unit
                                                 : m.rounding[key] ? '(zero but for rounding)'
                                                 : '(all zero)');
    const hasV = data.runs.some((r) => r.V);
    const hasF = data.runs.some((r) => r.f);
    if (hasV) {
      legendHead('V(k) = [&omega;; v], velocity of O<sub>k</sub>');
      legendRow(COLORS.omega, '↠', '&omega; angular', per('omega', 'rad/s'));
      legendRow(COLORS.v, '→', 'v linear', per('v', 'm/s'));
    }
    if (hasF) {
      legendHead('f(k) = [N; F], force on body k at O<sub>k</sub>');
      legendRow(COLORS.N, '↠', 'N moment', per('N', 'N·m'));
      legendRow(COLORS.F, '→', 'F force', per('F', 'N'));
    }
    if (hasV || hasF || m.fixed.length > 0) legendHead('');
    if (hasTip(data)) legendRow(COLORS.tip, '⁓', 'tip path', '');
    if (m.fixed.length > 0) legendRow(COLORS.fixed, '→', 'fixed vectors', per('fixed', ''));
    legendRow(COLORS.x, 'x', '<span style="color:#2f9e44;font-weight:bold">y</span> ' +
              '<span style="color:#1c5fd1;font-weight:bold">z</span> frame axes', '');
    legendRow(COLORS.axis, '—', 'hinge axis', '');
    const g = data.gravity || [0, 0, 0];
    const gn = Math.hypot(g[0], g[1], g[2]);
    const gtext = gn > 0 ? ', g = ' + fmt(gn) + ' m/s²' + (g[0] === 0 && g[1] === 0 && g[2] < 0
                                                            ? ' along −z' : '') : '';
    legendRow(COLORS.grid, '#', 'grid: ' + fmt(page.views[0].gridStep) + ' m' + gtext, '');
  }

  function makeToggles(page) {
    const box = $('soa-toggles');
    const data = page.data;
    const has = {
      V: data.runs.some((r) => r.V),
      f: data.runs.some((r) => r.f),
      tip: hasTip(data),
      fixed: page.m.fixed.length > 0,
      ellipsoids: data.bodies.some((b) => b.mass > 0),
    };
    for (const t of TOGGLES) {
      const label = document.createElement('label');
      const input = document.createElement('input');
      input.type = 'checkbox';
      input.id = 'soa-show-' + t.key;
      input.disabled = has[t.key] === false; // nothing of that kind in the data
      input.checked = page.show[t.key] && !input.disabled;
      input.addEventListener('change', () => {
        page.show[t.key] = input.checked;
        page.views.forEach((v) => (v.frame = -1)); // re-pose: arrows depend on the toggles
        page.dirty = true;
      });
      label.appendChild(input);
      label.insertAdjacentHTML('beforeend', ' ' + t.text);
      box.appendChild(label);
    }
  }

  // Per run: its frame, time, energy and relative energy drift.
  function makeReadout(page) {
    const box = $('soa-readout');
    for (const view of page.views) {
      const div = document.createElement('div');
      div.className = 'soa-run';
      div.innerHTML = '<div class="soa-run-name"></div><div class="soa-num"></div>' +
                      '<div class="soa-num"></div><div class="soa-num"></div>';
      div.firstChild.textContent = view.run.label;
      box.appendChild(div);
      view.readout = div.children;
    }
  }

  function updateReadout(page) {
    for (const view of page.views) {
      const r = view.run;
      const k = view.frame;
      const e = r.energy[k];
      const e0 = r.energy[0];
      const [, frame, energy, drift] = view.readout;
      frame.textContent = 'frame ' + (k + 1) + ' / ' + r.t.length + ', t = ' +
                          r.t[k].toFixed(3) + ' s';
      energy.textContent = 'E = ' + e.toPrecision(7) + ' J';
      if (e === e0) {
        drift.textContent = 'E − E0 = 0';
        drift.className = 'soa-num';
      } else if (e0 !== 0) {
        const d = (e - e0) / Math.abs(e0);
        drift.textContent = '(E − E0)/|E0| = ' + (d >= 0 ? '+' : '') + d.toExponential(2);
        drift.className = 'soa-num' + (Math.abs(d) > 1e-3 ? ' soa-drift-big' : '');
      } else {
        drift.textContent = 'E − E0 = ' + (e - e0).toExponential(2) + ' J';
      }
    }
  }

  function setPlaying(page, on) {
    page.playing = on && !page.still;
    if (page.playing && page.time >= page.t1) page.time = page.t0; // play again from the start
    page.dirty = true;
  }

  // Steps run 0 by one frame (dir = -1 or +1) and pauses.
  function stepFrame(page, dir) {
    const t = page.data.runs[0].t;
    const k = Math.min(Math.max(frameAt(t, page.time) + dir, 0), t.length - 1);
    page.time = t[k];
    setPlaying(page, false);
  }

  function wireControls(page) {
    const play = $('soa-play');
    const slider = $('soa-slider');
    slider.min = page.t0;
    slider.max = page.t1;
    slider.step = 'any';
    play.addEventListener('click', () => {
      setPlaying(page, !page.playing);
      play.blur(); // the space bar is ours, not the focused button's
    });
    slider.addEventListener('input', () => {
      page.time = Number(slider.value);
      setPlaying(page, false);
    });
    $('soa-speed').addEventListener('change', (e) => {
      page.speed = Number(e.target.value);
      e.target.blur();
    });
    document.addEventListener('keydown', (e) => {
      if (e.code === 'Space') {
        e.preventDefault();
        setPlaying(page, !page.playing);
      } else if ((e.code === 'ArrowLeft' || e.code === 'ArrowRight') && e.target !== slider) {
        e.preventDefault();
        stepFrame(page, e.code === 'ArrowLeft' ? -1 : 1);
      }
    });
    if (page.still) {
      play.disabled = slider.disabled = $('soa-speed').disabled = true;
      play.textContent = 'still';
      play.title = 'one frame: the chain at rest, nothing to play';
    }
  }

  function advance(page, dt) {
    page.time += Math.min(Math.max(dt, 0), 0.1) * page.speed;
    if (page.time >= page.t1) {
      page.time = page.t1;
      page.playing = false;
    }
    page.dirty = true;
  }

  function updateControls(page) {
    const play = $('soa-play');
    if (!page.still) play.innerHTML = page.playing ? '&#10074;&#10074; pause' : '&#9654; play';
    $('soa-slider').value = page.time;
    $('soa-clock').textContent = page.still
        ? 'one frame (t = ' + page.t0.toFixed(3) + ' s): nothing to play'
        : 't = ' + page.time.toFixed(3) + ' s / ' + page.t1.toFixed(3) + ' s';
  }

  // Cells of the stage, one per run: side by side up to 3 runs, else the grid whose cells are
  // nearest to a 4:3 landscape shape.
  function layout(page) {
    const stage = $('soa-stage');
    const w = stage.clientWidth;
    const h = stage.clientHeight;
    const n = page.views.length;
    let best = { cols: n, rows: 1, badness: 0 };
    for (let cols = 1; n > 3 && cols <= n; ++cols) {
      const rows = Math.ceil(n / cols);
      const badness = Math.abs(Math.log(w / cols / (h / rows) / 1.33));
      if (cols === 1 || badness < best.badness - 1e-9) best = { cols, rows, badness };
    }
    const cw = Math.floor(w / best.cols);
    const ch = Math.floor(h / best.rows);
    page.renderer.setSize(w, h, false);
    page.size = { w, h };
    page.cells = page.views.map((view, i) => {
      const cell = { x: (i % best.cols) * cw, y: Math.floor(i / best.cols) * ch, w: cw, h: ch };
      Object.assign(view.cell.style, { left: cell.x + 'px', top: cell.y + 'px',
                                       width: cell.w + 'px', height: cell.h + 'px' });
      return cell;
    });
    page.camera.aspect = cw / ch;
    page.camera.updateProjectionMatrix();
  }

  // Looks at the run's extent from the front (-y), a little from the right and above, from
  // the nearest distance at which every corner of the extent is in view.
  function frameCamera(page) {
    const { camera, controls, m } = page;
    const centre = m.box.getCenter(new THREE.Vector3());
    const back = new THREE.Vector3(0.45, -1, 0.3).normalize(); // from the centre to the eye
    const right = new THREE.Vector3().crossVectors(camera.up, back).normalize();
    const up = new THREE.Vector3().crossVectors(back, right);
    const ty = Math.tan((camera.fov * Math.PI) / 360);
    const tx = ty * camera.aspect;
    const margin = 0.15 * m.size; // room for the frames, the arrows and the labels
    let dist = 0;
    for (let i = 0; i < 8; ++i) {
      const c = new THREE.Vector3(i & 1 ? m.box.max.x : m.box.min.x,
                                  i & 2 ? m.box.max.y : m.box.min.y,
                                  i & 4 ? m.box.max.z : m.box.min.z).sub(centre);
      const z = c.dot(back);
      dist = Math.max(dist, (Math.abs(c.dot(right)) + margin) / tx + z,
                      (Math.abs(c.dot(up)) + margin) / ty + z);
    }
    camera.position.copy(centre).addScaledVector(back, dist);
    camera.near = dist / 100;
    camera.far = dist * 10;
    camera.updateProjectionMatrix();
    controls.target.copy(centre);
    controls.update();
  }

  // Places the HTML labels of a view over its cell (hidden behind the camera or outside).
  function placeLabels(page, view, cell) {
    const p = new THREE.Vector3();
    for (const l of view.labels) {
      p.copy(l.at).project(page.camera);
      const x = ((p.x + 1) / 2) * cell.w; // in the cell's box
      const y = ((1 - p.y) / 2) * cell.h;
      const inside = p.z > -1 && p.z < 1 && x >= 0 && x < cell.w && y >= 0 && y < cell.h;
      const on = inside && (l.cat === '' || page.show[l.cat]);
      l.el.style.display = on ? 'block' : 'none';
      if (on) {
        l.el.style.left = x + 'px';
        l.el.style.top = y + 'px';
        // to the left of its point when it would run out of the cell
        const flip = x + l.el.offsetWidth + 6 > cell.w;
        l.el.style.transform = flip ? 'translate(calc(-100% - 8px), -100%)' : '';
      }
    }
  }

  function applyToggles(page, view) {
    for (const key in view.show) for (const o of view.show[key]) o.visible = page.show[key];
  }

  // Draws every run at the page's time, each in its cell, then the readout and the test hooks.
  function draw(page) {
    const { renderer, camera, controls, data, m } = page;
    page.dirty = false;
    renderer.setScissorTest(false);
    renderer.clear();
    renderer.setScissorTest(true);
    page.views.forEach((view, i) => {
      const k = frameAt(view.run.t, page.time);
      if (k !== view.frame) poseView(view, k, data, m, page.show);
      applyToggles(page, view);
      view.light.position.copy(camera.position);
      view.light.target.position.copy(controls.target);
      const c = page.cells[i];
      const y = page.size.h - c.y - c.h; // WebGL counts rows from the bottom
      renderer.setViewport(c.x, y, c.w, c.h);
      renderer.setScissor(c.x, y, c.w, c.h);
      renderer.render(view.scene, camera);
      placeLabels(page, view, c);
    });
    updateReadout(page);
    updateControls(page);
    report(page);
  }

  // ---------------------------------------------------------------------------------------
  // Test hooks: the data- attributes of #soa-view (docs/viewer.md).

  let pixels = null;

  // The fraction of the canvas' pixels that differ from the background.
  function drawnFraction(renderer) {
    const gl = renderer.getContext();
    const w = gl.drawingBufferWidth;
    const h = gl.drawingBufferHeight;
    if (!pixels || pixels.length !== 4 * w * h) pixels = new Uint8Array(4 * w * h);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
    const bg = new THREE.Color(COLORS.background);
    const [r, g, b] = [bg.r * 255, bg.g * 255, bg.b * 255];
    let differ = 0;
    for (let i = 0; i < pixels.length; i += 4) {
      if (Math.abs(pixels[i] - r) > 2 || Math.abs(pixels[i + 1] - g) > 2 ||
          Math.abs(pixels[i + 2] - b) > 2)
        ++differ;
    }
    return differ / (w * h);
  }

  // The URLs the page loaded: the document, its scripts and style sheets, and whatever the
  // Resource Timing API lists (Chromium lists no file:// loads there, but would list others).
  function resources() {
    const urls = [window.location.href];
    for (const s of document.scripts) if (s.src) urls.push(s.src);
    for (const l of document.querySelectorAll('link[href]')) urls.push(l.href);
    for (const e of performance.getEntriesByType('resource')) urls.push(e.name);
    return urls.filter((u, i) => urls.indexOf(u) === i);
  }

  function report(page) {
    const view = page.views[0];
    const run = view.run;
    root.setAttribute('data-frame', String(view.frame));
    root.setAttribute('data-time', String(run.t[view.frame]));
    if (view.tip) root.setAttribute('data-tip', [view.tip.x, view.tip.y, view.tip.z].join(','));
    // reading the pixels back costs a few ms: at most 4 times a second while playing
    const now = performance.now();
    if (!page.playing || now - page.lastDrawn > 250) {
      root.setAttribute('data-drawn', drawnFraction(page.renderer).toFixed(4));
      page.lastDrawn = now;
    }
    root.setAttribute('data-resources', resources().join(' '));
    root.setAttribute('data-errors', String(errorCount()));
    root.setAttribute('data-ready', '1');
  }

  // ---------------------------------------------------------------------------------------

  root.setAttribute('data-errors', String(errorCount()));
  const problem = problemWith(window.SOA_VIEW);
  if (problem) {
    fail(problem);
    return;
  }
  try {
    start(window.SOA_VIEW);
  } catch (e) {
    fail('The page could not draw the chain: ' + e.message +
         (/WebGL/i.test(e.message) ? ' (this browser has no WebGL)' : ''));
  }
})();
