// The explorer page: holds a design, generates its mesh in the page itself
// (monge-core compiled to WebAssembly, crates/monge-wasm) on every change and
// draws it (three.js). It needs no server: `monge explore` serves it, and so
// does any static file server.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import init, { generate, info, parseDesign } from '../wasm/monge_wasm.js';

const $ = (id) => document.getElementById(id);

/** Everything the page knows; `window.explorer` exposes it to the e2e test. */
const state = {
  design: null,      // the design, in the monge design-file format
  mesh: null,        // the header of the mesh shown (see Mesh.header in crates/monge-wasm)
  offset: 0,
  latencies: [],     // ms from input event to the frame that shows its mesh
  blocked: [],       // ms of each main-thread task for monge: a change (module, upload), a drag's end, the worker's answer
  generations: 0,    // meshes drawn so far
  stale: false,      // the design changed and monge refused it
  fast: false,       // drawn in drag quality (see `quality`)
  legend: null,      // the colour legend's numbers: { mode: 'area', min, max } or { mode: 'fold', folded, faces }
  name: '<input>',   // the design's file name, in messages
  net: null,         // the cyclidic net drawn: { lines, arcs } or { error }
};
/** The wasm mesh shown (for metrics and exports); freed when replaced. */
let current = null;
/** Largest grid generated (rows × cols vertices), as `monge explore`'s default. */
const MAX_VERTICES = 250000;
/** Below this smallest crossing sine the page warns that the mesh nearly pinches (§5.2). */
const LOW_CROSSING_SINE = 1e-3;

// ---------------------------------------------------------------- the scene
const view = $('view');
const renderer = new THREE.WebGLRenderer({ antialias: false });
renderer.setPixelRatio(window.devicePixelRatio);
view.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xffffff);
const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1e5);
camera.up.set(0, 0, 1); // designs are z-up
const controls = new OrbitControls(camera, renderer.domElement);
controls.addEventListener('change', () => redraw());
scene.add(new THREE.HemisphereLight(0xffffff, 0x667788, 1.6));
const sun = new THREE.DirectionalLight(0xffffff, 1.4);
camera.add(sun);
sun.position.set(1, 2, 3);
scene.add(camera);

const surfaceMaterial = new THREE.MeshLambertMaterial({
  color: 0xb0c4de, side: THREE.DoubleSide, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
});
const surface = new THREE.Mesh(new THREE.BufferGeometry(), surfaceMaterial);
const wire = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0x3a4a5a, transparent: true, opacity: 0.35 }));
const guideLines = {
  u: new THREE.Line(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0xd02020, depthTest: false })),
  v: new THREE.Line(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0x2040d0, depthTest: false })),
};
const handles = new THREE.Group();   // draggable control points and their polygons
const markers = new THREE.Group();   // folds and pinches
const gauss = new THREE.Group();     // the Gauss map beside the mesh
const gaussSurface = new THREE.Mesh(new THREE.BufferGeometry(), new THREE.MeshLambertMaterial({ color: 0xe8c9a0, side: THREE.DoubleSide }));
const gaussWire = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0x705030, transparent: true, opacity: 0.4 }));
const sphereWire = new THREE.Mesh(new THREE.SphereGeometry(0.995, 48, 24), new THREE.MeshBasicMaterial({ color: 0xdddddd, wireframe: true, transparent: true, opacity: 0.35 }));
gauss.add(sphereWire, gaussSurface, gaussWire);
for (const line of Object.values(guideLines)) line.renderOrder = 1;
/** The surface with one colour per face (by panel area or by fold), shown instead of `surface`. */
const coloured = new THREE.Mesh(new THREE.BufferGeometry(), new THREE.MeshLambertMaterial({
  vertexColors: true, side: THREE.DoubleSide, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
}));
coloured.visible = false;
/** The pencil axes L1 and L2 (§2.1.2), drawn in the Gauss map's frame, clipped to a ball. */
const axesGroup = new THREE.Group();
axesGroup.visible = false;
gauss.add(axesGroup);
/** The planes of the curvature lines (§2.2): each drawn line closed by its chord, filled. */
const planesGroup = new THREE.Group();
/** The cyclidic net's curvature lines (§4.4): circular arcs, drawn as chords. */
const arcLines = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0x106030 }));
arcLines.visible = false;
planesGroup.visible = false;
scene.add(arcLines, surface, coloured, wire, guideLines.u, guideLines.v, handles, markers, gauss, planesGroup);

let frameRequested = false;
let pendingLatency = null; // input time of the mesh uploaded but not yet drawn

/**
 * Drag quality: while θ or a control point is being dragged the page draws
 * at half the pixel ratio and without the wireframes (the mesh's, the Gauss
 * map's and its sphere's), and asks for the mesh without its metrics; once
 * the drag has rested for SETTLE_MS it asks again, with the metrics, and
 * draws at full quality. WebGL drawn in software (no GPU) costs about the
 * pixels and lines it draws.
 */
const SETTLE_MS = 150;
const DRAG_PIXEL_RATIO = 0.5;
let settleTimer = null;

/** Switches between drag quality (`fast`) and full quality. */
function quality(fast) {
  if (fast === state.fast) return;
  state.fast = fast;
  renderer.setPixelRatio(window.devicePixelRatio * (fast ? DRAG_PIXEL_RATIO : 1));
  wire.visible = !fast;
  gaussWire.visible = !fast;
  sphereWire.visible = !fast;
}

/** Draws one frame soon (at most one per animation frame). */
function redraw() {
  if (frameRequested) return;
  frameRequested = true;
  requestAnimationFrame(() => {
    frameRequested = false;
    renderer.render(scene, camera);
    if (pendingLatency !== null) {
      recordLatency(performance.now() - pendingLatency);
      pendingLatency = null;
    }
  });
}

function resize() {
  const { clientWidth: w, clientHeight: h } = view;
  renderer.setSize(w, h);
  camera.aspect = w / h;
  camera.updateProjectionMatrix();
  redraw();
}
window.addEventListener('resize', resize);

// ------------------------------------------------------------- geometry
/** Index buffers of a rows × cols grid: two triangles a face, and its edges. */
function gridIndices(rows, cols) {
  const tri = [];
  const edges = [];
  const at = (i, j) => i * cols + j;
  for (let i = 0; i < rows; i++) {
    for (let j = 0; j < cols; j++) {
      if (j + 1 < cols) edges.push(at(i, j), at(i, j + 1));
      if (i + 1 < rows) edges.push(at(i, j), at(i + 1, j));
      if (i + 1 < rows && j + 1 < cols) tri.push(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  return { tri, edges };
}

/** Puts a grid into a surface and its wireframe, reusing buffers of the same size. */
function setGrid(mesh, lines, rows, cols, positions, normals) {
  let geometry = mesh.geometry;
  const position = geometry.getAttribute('position');
  if (!position || geometry.userData.rows !== rows || geometry.userData.cols !== cols) {
    geometry.dispose();
    lines.geometry.dispose();
    geometry = new THREE.BufferGeometry();
    const { tri, edges } = gridIndices(rows, cols);
    geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(rows * cols * 3), 3));
    geometry.setAttribute('normal', new THREE.BufferAttribute(new Float32Array(rows * cols * 3), 3));
    geometry.setIndex(tri);
    geometry.userData = { rows, cols };
    mesh.geometry = geometry;
    lines.geometry = new THREE.BufferGeometry();
    lines.geometry.setAttribute('position', geometry.getAttribute('position'));
    lines.geometry.setIndex(edges);
  }
  geometry.getAttribute('position').array.set(positions);
  geometry.getAttribute('position').needsUpdate = true;
  if (normals) {
    geometry.getAttribute('normal').array.set(normals);
    geometry.getAttribute('normal').needsUpdate = true;
  } else {
    geometry.computeVertexNormals();
  }
  geometry.computeBoundingSphere();
  lines.geometry.boundingSphere = geometry.boundingSphere; // the same positions
}

function setPolyline(line, flat) {
  line.geometry.dispose();
  line.geometry = new THREE.BufferGeometry();
  line.geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(flat), 3));
}

/**
 * Draws a wasm `mesh` (which becomes `current`); `t0` is the time of the input
 * that caused it (null: none to time), `fast` the drag quality (no metrics yet).
 */
function showMesh(mesh, t0, fast = false) {
  const first = state.mesh === null;
  if (current) current.free();
  current = mesh;
  const header = JSON.parse(mesh.header());
  state.mesh = header;
  state.stale = false;
  const circular = header.kind === 'circular';
  // A circular mesh's normals are its node axes (the Gauss map); a conical
  // mesh's vertex normals are left to three.js. The arrays are views into the
  // module's memory, copied into three.js's buffers at once.
  setGrid(surface, wire, header.rows, header.cols, mesh.positions(), circular ? mesh.normals() : null);
  surfaceMaterial.color.set(0xb0c4de);
  setGrid(gaussSurface, gaussWire, header.gauss.rows, header.gauss.cols, mesh.normals(), mesh.normals());
  setPolyline(guideLines.u, mesh.guidePoints(true));
  setPolyline(guideLines.v, mesh.guidePoints(false));
  showMarkers(header);
  showColours(mesh);
  showAxes(header);
  showPlanes(header);
  if (first) fitView();
  if (fast) {
    arcLines.visible = false; // until the drag rests and the worker draws them again
    $('metrics').classList.add('pending');
  } else {
    showHandles(); // a drag moves the handles itself
    measure();
  }
  showThetaRange(header);
  $('error').hidden = true;
  state.generations += 1;
  if (t0 !== null) pendingLatency = t0;
  quality(fast);
  redraw();
}

/** Colour of `t` in [0, 1] on the panel-area scale: blue (smallest) to red (largest). */
const ramp = (t) => new THREE.Color().setHSL(0.66 * (1 - t), 0.85, 0.5);
const FOLDED = new THREE.Color(0xff2020);
const UNFOLDED = new THREE.Color(0xb0c4de);

/**
 * Colours the faces of the wasm `mesh` as the `colour` control asks: by panel
 * area (§4.8) or by fold (§5.2), both measured in the module, with a legend;
 * `state.legend` holds the legend's numbers.
 */
function showColours(mesh) {
  const mode = $('colour').value;
  coloured.visible = mode !== 'none';
  surface.visible = !coloured.visible;
  const legend = $('legend');
  legend.hidden = !coloured.visible;
  coloured.material.color.set(0xffffff);
  if (!coloured.visible) {
    state.legend = null;
    return;
  }
  const values = mode === 'area' ? mesh.faceAreas() : mesh.foldedFaces();
  let [min, max, folded] = [Infinity, -Infinity, 0];
  for (const x of values) {
    min = Math.min(min, x);
    max = Math.max(max, x);
    folded += x;
  }
  // Two triangles, six corners, a face, in the order of the faces (gridIndices).
  const geometry = surface.geometry.toNonIndexed();
  const colours = new Float32Array(3 * geometry.getAttribute('position').count);
  values.forEach((x, k) => {
    const c = mode === 'fold' ? (x ? FOLDED : UNFOLDED) : ramp(max > min ? (x - min) / (max - min) : 0.5);
    for (let v = 6 * k; v < 6 * k + 6; v++) c.toArray(colours, 3 * v);
  });
  geometry.setAttribute('color', new THREE.BufferAttribute(colours, 3));
  coloured.geometry.dispose();
  coloured.geometry = geometry;
  if (mode === 'area') {
    state.legend = { mode, min, max };
    const stops = [0, 0.25, 0.5, 0.75, 1].map((t) => `${ramp(t).getStyle()} ${100 * t}%`).join(', ');
    legend.innerHTML = '<div>panel area</div><div class="bar"></div><div class="ends"><span class="min"></span><span class="max"></span></div>';
    legend.querySelector('.bar').style.background = `linear-gradient(to right, ${stops})`;
    legend.querySelector('.min').textContent = fmt(min, 4);
    legend.querySelector('.max').textContent = fmt(max, 4);
  } else {
    state.legend = { mode, folded, faces: values.length };
    legend.innerHTML = '<div>fold (§5.2)</div><div><span class="swatch folded"></span><span class="folded-count"></span>'
      + '<span class="swatch unfolded"></span><span class="unfolded-count"></span></div>';
    legend.querySelector('.swatch.folded').style.background = FOLDED.getStyle();
    legend.querySelector('.swatch.unfolded').style.background = UNFOLDED.getStyle();
    legend.querySelector('.folded-count').textContent = `folded: ${folded}`;
    legend.querySelector('.unfolded-count').textContent = `not folded: ${values.length - folded}`;
  }
}

/** Radius of the ball (the Gauss sphere's radius is 1) to which the pencil axes are clipped. */
const AXIS_CLIP = 3;

/** The pencil axes L1 (of the v-lines) and L2 (of the u-lines) of the header's Gauss map (§2.1.2). */
function showAxes(header) {
  axesGroup.clear();
  const notes = [];
  for (const [name, color] of [['l1', 0x109010], ['l2', 0x9020b0]]) {
    const axis = header.axes[name];
    const label = name.toUpperCase();
    if (!axis) {
      notes.push(`${label} is at infinity (not drawn)`);
      continue;
    }
    const point = new THREE.Vector3().fromArray(axis.point);
    const distance = point.length();
    if (distance >= AXIS_CLIP) {
      notes.push(`${label} is ${fmt(distance)} from the centre, beyond the drawn ball of radius ${AXIS_CLIP}`);
      continue;
    }
    notes.push(`${label} at ${fmt(distance)} from the centre`);
    const half = Math.sqrt(AXIS_CLIP ** 2 - distance ** 2);
    const dir = new THREE.Vector3().fromArray(axis.dir);
    const line = new THREE.Line(new THREE.BufferGeometry().setFromPoints([
      point.clone().addScaledVector(dir, -half), point.clone().addScaledVector(dir, half),
    ]), new THREE.LineBasicMaterial({ color, depthTest: false }));
    line.renderOrder = 2;
    line.userData = { axis: name };
    axesGroup.add(line);
  }
  $('axes-note').textContent = axesGroup.visible ? `pencil axes: ${notes.join('; ')}` : '';
}

/** At most this many planes of each family are drawn (evenly spaced, the last line included). */
const PLANES_PER_FAMILY = 12;

/**
 * The planes of the curvature lines (§2.2) of the drawn mesh, when shown: each
 * of a few rows and columns closed by its chord and filled (a fan from its first
 * vertex), which lies in the line's plane as the line is planar.
 */
function showPlanes(header) {
  planesGroup.clear();
  if (!planesGroup.visible) return;
  const drawn = surface.geometry.getAttribute('position').array;
  const { rows, cols } = header;
  const family = (count, length, at, color, name) => {
    const step = Math.max(1, Math.ceil((count - 1) / (PLANES_PER_FAMILY - 1)));
    const lines = [];
    for (let l = 0; l < count - 1; l += step) lines.push(l);
    lines.push(count - 1);
    const material = new THREE.MeshBasicMaterial({ color, transparent: true, opacity: 0.18, side: THREE.DoubleSide, depthWrite: false });
    for (const l of lines) {
      const flat = new Float32Array(3 * length);
      for (let k = 0; k < length; k++) flat.set(drawn.subarray(3 * at(l, k), 3 * at(l, k) + 3), 3 * k);
      const fan = [];
      for (let k = 1; k + 1 < length; k++) fan.push(0, k, k + 1);
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.BufferAttribute(flat, 3));
      geometry.setIndex(fan);
      const plane = new THREE.Mesh(geometry, material);
      plane.userData = { family: name, line: l };
      planesGroup.add(plane);
    }
  };
  family(rows, cols, (i, j) => i * cols + j, 0x3050c0, 'row'); // row 0 is guide_v (blue)
  family(cols, rows, (j, i) => i * cols + j, 0xc03030, 'column'); // column 0 is guide_u (red)
}

/** Red and orange marks where the mesh folds or nearly pinches (§5.2), and the warnings. */
function showMarkers(header) {
  markers.clear();
  const size = meshSize();
  const r = header.report;
  const warnings = [];
  const marks = [];
  if (Math.abs(header.theta_deg - 90) < 1) {
    warnings.push(`θ = ${header.theta_deg}° is at or near the singular θ = +90°, where every Gauss circle passes through the corner normal: expect a degenerate mesh.`);
  }
  if (r.first_fold) {
    warnings.push(`The mesh folds over itself / pinches (§5.2) in ${r.folded_faces} faces, first at face (${r.first_fold.join(', ')}) (marked in red).`);
    marks.push({ kind: 'fold', face: r.first_fold });
  }
  if (r.min_crossing_sine < LOW_CROSSING_SINE) {
    warnings.push(`Low crossing sine ${r.min_crossing_sine.toExponential(1)} at face (${r.min_crossing_face.join(', ')}): the mesh nearly pinches there (§5.2) (marked in orange).`);
    marks.push({ kind: 'pinch', face: r.min_crossing_face });
  }
  for (const m of marks) {
    const color = m.kind === 'fold' ? 0xff0000 : 0xff8800;
    const dot = new THREE.Mesh(new THREE.SphereGeometry(0.02 * size, 16, 8), new THREE.MeshBasicMaterial({ color, depthTest: false }));
    dot.position.fromArray(current.faceCentre(...m.face));
    dot.renderOrder = 2;
    markers.add(dot);
    if (m.kind === 'fold' && header.kind === 'circular') markers.add(faceHighlight(header, m.face, color));
  }
  $('warnings').replaceChildren(...warnings.map((w) => Object.assign(document.createElement('li'), { textContent: w })));
}

/** Face (i, j) of the drawn grid, filled with `color` on top of the surface. */
function faceHighlight(header, [i, j], color) {
  const drawn = surface.geometry.getAttribute('position').array;
  const v = (a, b) => Array.from(drawn.subarray(3 * (a * header.cols + b), 3 * (a * header.cols + b) + 3));
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array([...v(i, j), ...v(i + 1, j), ...v(i + 1, j + 1), ...v(i, j + 1)]), 3));
  geometry.setIndex([0, 1, 2, 0, 2, 3]);
  return new THREE.Mesh(geometry, new THREE.MeshBasicMaterial({ color, side: THREE.DoubleSide, depthTest: false }));
}

function meshSize() {
  return surface.geometry.boundingSphere ? surface.geometry.boundingSphere.radius : 1;
}

/** Looks at the whole mesh, with the Gauss map beside it. */
function fitView() {
  const { center, radius } = surface.geometry.boundingSphere;
  gauss.scale.setScalar(0.4 * radius);
  gauss.position.copy(center).add(new THREE.Vector3(1.5 * radius, 0, 0));
  const target = center.clone().add(new THREE.Vector3(0.6 * radius, 0, 0));
  controls.target.copy(target);
  camera.position.copy(target).add(new THREE.Vector3(-0.7, -3.6, 2.2).multiplyScalar(radius));
  camera.near = radius / 100;
  camera.far = radius * 100;
  camera.updateProjectionMatrix();
  controls.update();
}

// ----------------------------------------------------- control points
/** The points of a guide that can be dragged (a B-spline's control points, a `points` guide's points), or null. */
function controlPoints(name) {
  const spec = state.design[`guide_${name}`];
  return spec.bspline ? spec.bspline.control_points : spec.points ?? null;
}

/** The end of an `arc` guide (its start turned by angle_deg about the normal through the centre), or null. */
function arcEnd(name) {
  const arc = state.design[`guide_${name}`].arc;
  if (!arc) return null;
  const centre = new THREE.Vector3().fromArray(arc.center);
  const axis = new THREE.Vector3().fromArray(arc.normal).normalize();
  return new THREE.Vector3().fromArray(arc.start).sub(centre).applyAxisAngle(axis, THREE.MathUtils.degToRad(arc.angle_deg)).add(centre);
}

/** A handle: a dot at `p` that drags `index` of guide `name`. */
function handle(p, name, index, color, radius) {
  const dot = new THREE.Mesh(new THREE.SphereGeometry(radius, 16, 8), new THREE.MeshBasicMaterial({ color, depthTest: false }));
  dot.position.copy(p);
  dot.renderOrder = 3;
  dot.userData = { guide: name, index };
  return dot;
}

function showHandles() {
  handles.clear();
  const radius = 0.018 * meshSize();
  for (const [name, color] of [['u', 0xd02020], ['v', 0x2040d0]]) {
    const end = arcEnd(name);
    if (end) handles.add(handle(end, name, 'end', color, radius));
    const points = controlPoints(name);
    if (!points) continue;
    const polygon = new THREE.Line(new THREE.BufferGeometry(), new THREE.LineDashedMaterial({ color, dashSize: radius, gapSize: radius, depthTest: false }));
    setPolyline(polygon, points.flat());
    polygon.computeLineDistances();
    handles.add(polygon);
    points.forEach((p, index) => handles.add(handle(new THREE.Vector3().fromArray(p), name, index, index === 0 ? 0x777777 : color, radius)));
  }
}

const raycaster = new THREE.Raycaster();
let drag = null; // { guide, index, plane, origin, tangent } or, for an arc's end, { guide, index: 'end', plane, arc }

function pointerRay(event) {
  const rect = renderer.domElement.getBoundingClientRect();
  const ndc = new THREE.Vector2(((event.clientX - rect.left) / rect.width) * 2 - 1, -((event.clientY - rect.top) / rect.height) * 2 + 1);
  raycaster.setFromCamera(ndc, camera);
  return raycaster.ray;
}

renderer.domElement.addEventListener('pointerdown', (event) => {
  if (!state.mesh) return;
  pointerRay(event);
  const hit = raycaster.intersectObjects(handles.children.filter((c) => c.isMesh))[0];
  // The first point is shared by both guides: it stays.
  if (!hit || hit.object.userData.index === 0) return;
  const { guide, index } = hit.object.userData;
  if (index === 'end') {
    const arc = state.design[`guide_${guide}`].arc;
    const centre = new THREE.Vector3().fromArray(arc.center);
    drag = { guide, index, arc, plane: new THREE.Plane().setFromNormalAndCoplanarPoint(new THREE.Vector3().fromArray(arc.normal).normalize(), centre) };
    startDrag(event);
    return;
  }
  const points = controlPoints(guide);
  const origin = new THREE.Vector3().fromArray(points[0]);
  const normal = new THREE.Vector3().fromArray(state.mesh.guides[guide].plane_normal);
  drag = {
    guide, index, origin,
    plane: new THREE.Plane().setFromNormalAndCoplanarPoint(normal, origin),
    tangent: new THREE.Vector3().fromArray(points[1]).sub(origin).normalize(),
  };
  startDrag(event);
}, { capture: true });

/** A handle was grabbed: the pointer drags it, not the view. */
function startDrag(event) {
  controls.enabled = false;
  renderer.domElement.setPointerCapture(event.pointerId);
  event.stopImmediatePropagation();
}

/**
 * The arc's swept angle (degrees) that puts its end nearest `p` (a point of its
 * plane): the angle from start to `p` about the normal, the turn nearest the
 * current angle, kept within (−360°, 360°) and away from 0.
 */
function arcAngle(arc, p) {
  const centre = new THREE.Vector3().fromArray(arc.center);
  const axis = new THREE.Vector3().fromArray(arc.normal).normalize();
  const from = new THREE.Vector3().fromArray(arc.start).sub(centre);
  const to = p.clone().sub(centre);
  const angle = THREE.MathUtils.radToDeg(Math.atan2(axis.dot(from.clone().cross(to)), from.dot(to)));
  const turned = angle + 360 * Math.round((arc.angle_deg - angle) / 360);
  const sign = Math.sign(turned) || Math.sign(arc.angle_deg);
  return sign * Math.min(Math.max(Math.abs(turned), 0.1), 359.9);
}

renderer.domElement.addEventListener('pointermove', (event) => {
  if (!drag) return;
  const t0 = performance.now();
  const p = pointerRay(event).intersectPlane(drag.plane, new THREE.Vector3());
  if (!p) return;
  if (drag.index === 'end') {
    drag.arc.angle_deg = arcAngle(drag.arc, p);
    showHandles();
    change(t0, true);
    return;
  }
  if (drag.index === 1) {
    // P1 − P0 is the start tangent: slide along it so the guides still meet at 90°.
    const s = Math.max(p.clone().sub(drag.origin).dot(drag.tangent), 1e-3 * meshSize());
    p.copy(drag.origin).addScaledVector(drag.tangent, s);
  }
  controlPoints(drag.guide)[drag.index] = p.toArray();
  showHandles();
  change(t0, true);
});

for (const type of ['pointerup', 'pointercancel']) {
  renderer.domElement.addEventListener(type, () => {
    drag = null;
    controls.enabled = true;
  });
}

// ------------------------------------------------------------ computing
/**
 * The metrics and the cyclidic net's arcs are measured in a Web Worker
 * (src/worker.js, its own copy of the module), so that the main thread only
 * generates and draws: at 300 × 300 faces the metrics take ~45 ms.
 */
const worker = new Worker(new URL('worker.js', import.meta.url), { type: 'module' });
let measureId = 0;         // the latest request to the worker
let measuring = false;     // its answer has not come yet

/** Asks the worker for the metrics (and arcs) of the design shown. */
function measure() {
  measureId += 1;
  measuring = true;
  $('metrics').classList.add('pending');
  worker.postMessage({
    id: measureId, text: JSON.stringify(state.design), name: state.name, offset: state.offset,
    maxVertices: MAX_VERTICES, arcs: $('show-arcs').checked,
  });
}

worker.onmessage = ({ data }) => {
  if (data.id !== measureId) return; // a newer design is being measured
  const start = performance.now();
  measuring = false;
  if (data.error) return; // the main thread shows monge's message for this design
  showArcs(data.net);
  showMetrics(state.mesh, data);
  $('metrics').classList.remove('pending');
  redraw();
  state.blocked.push(performance.now() - start);
};

/** Draws the net's arcs (`net.segments`: chord ends, f32), or says why there is no net. */
function showArcs(net) {
  state.net = net && (net.error ? { error: net.error } : { lines: net.lines, arcs: net.arcs });
  arcLines.visible = Boolean(net && !net.error);
  if (arcLines.visible) {
    arcLines.geometry.dispose();
    arcLines.geometry = new THREE.BufferGeometry();
    arcLines.geometry.setAttribute('position', new THREE.BufferAttribute(net.segments, 3));
  }
}
/**
 * The design changed at time `t0` (null: no input to time): generate its mesh
 * now, in the input's own task, so it is drawn in the very next frame.
 * `dragging`: θ or a control point is being dragged, so the mesh is drawn in
 * drag quality without its metrics, then in full with them once the drag has
 * rested for SETTLE_MS. `name` names the design's file in messages.
 */
function change(t0, dragging = false, name = '<input>') {
  clearTimeout(settleTimer);
  settleTimer = null;
  const start = performance.now();
  try {
    showMesh(generateMesh(JSON.stringify(state.design), name), t0, dragging);
  } catch (error) {
    showError(error, dragging);
  }
  state.blocked.push(performance.now() - start);
  if (dragging) {
    settleTimer = setTimeout(() => {
      settleTimer = null;
      if (!state.stale) settle();
    }, SETTLE_MS);
  }
}

/** After a drag: the metrics, and the mesh in full quality. */
function settle() {
  const start = performance.now();
  showHandles();
  measure();
  quality(false);
  redraw();
  state.blocked.push(performance.now() - start);
}

/** The wasm mesh of a design (JSON text) at the page's offset; throws the CLI's message. */
function generateMesh(text, name) {
  const start = performance.now();
  const mesh = generate(text, name, state.offset, MAX_VERTICES);
  generateMs = performance.now() - start;
  state.name = name;
  return mesh;
}
let generateMs = 0; // how long the last generation took

/** Shows a refusal: monge's message, the mesh greyed as no longer current. */
function showError(error, fast = false) {
  const box = $('error');
  box.textContent = error.message;
  box.hidden = false;
  // The admissible θ, when the guides themselves are valid.
  try {
    showThetaRange(JSON.parse(info(JSON.stringify(state.design), '<input>', MAX_VERTICES)));
  } catch {
    // the guides are invalid: the message says why
  }
  state.stale = true;
  measureId += 1; // an answer for the refused design's predecessor is stale
  measuring = false;
  arcLines.visible = false;
  surfaceMaterial.color.set(0xcccccc);
  coloured.material.color.set(0xcccccc);
  quality(fast);
  redraw();
}

// ------------------------------------------------------------ controls
const fmt = (x, digits = 3) => (x === null || x === undefined ? '—' : Math.abs(x) >= 1e4 || (Math.abs(x) < 1e-3 && x !== 0) ? x.toExponential(2) : x.toFixed(digits));

/** The first words of a long message. */
const brief = (text, n = 90) => (text.length > n ? `${text.slice(0, n)}…` : text);

/** The metrics table of the mesh with header `answer`, from the worker's `measured`. */
function showMetrics(answer, measured) {
  const m = JSON.parse(measured.metrics);
  const net = state.net;
  const worst = (w) => (w ? `${fmt(w.value)} at (${w.at.join(', ')})` : '—');
  const rows = [
    ['grid', `${answer.rows} × ${answer.cols} vertices, ${m.faces} faces`],
    ['mesh', `${answer.kind}, ${answer.mode}${answer.offset ? `, offset ${answer.offset}` : ''}`],
    ['face planarity', worst(m.face_planarity)],
    answer.kind === 'circular' ? ['circularity', worst(m.circularity)] : ['conical error', worst(m.conical)],
    ['row / column planarity', `${fmt(m.row_planarity.value)} / ${fmt(m.column_planarity.value)}`],
    ['torsion', worst(m.torsion)],
    ['max error (relative)', fmt(m.max_error)],
    ['panel area', `${fmt(m.panel_area.min)} … ${fmt(m.panel_area.max)}`],
    ['edge length', `${fmt(m.edge_length.min)} … ${fmt(m.edge_length.max)}`],
    ...(net ? [['cyclidic net (§4.4)', net.error ? brief(net.error.slice(net.error.indexOf(': ') + 2)) : `${net.lines} curvature lines, ${net.arcs} circular arcs`]] : []),
    ['in the page (wasm)', `generate ${fmt(generateMs, 2)} ms; in the worker: metrics ${fmt(measured.metricsMs, 2)} ms`],
  ];
  $('metrics').replaceChildren(...rows.map(([k, v]) => {
    const tr = document.createElement('tr');
    tr.append(Object.assign(document.createElement('td'), { textContent: k }), Object.assign(document.createElement('td'), { textContent: v }));
    return tr;
  }));
}

/** The admissible θ in words and as green on the slider. */
function showThetaRange({ theta_range: r, mode }) {
  const slider = $('theta');
  if (mode === 'characteristic') {
    $('theta-range').textContent = 'admissible: every θ in (−180°, 180°] (singular at +90°)';
    slider.style.background = '';
    return;
  }
  $('theta-range').textContent = `admissible: |θ| in [${r.min_deg.toFixed(2)}°, ${r.max_deg.toFixed(2)}°]`;
  const pct = (deg) => `${((deg + 180) / 360) * 100}%`;
  const ok = '#b5e3b5';
  const no = '#f3c0c0';
  slider.style.background = `linear-gradient(to right, ${no} ${pct(-r.max_deg)}, ${ok} ${pct(-r.max_deg)} ${pct(-r.min_deg)}, ${no} ${pct(-r.min_deg)} ${pct(r.min_deg)}, ${ok} ${pct(r.min_deg)} ${pct(r.max_deg)}, ${no} ${pct(r.max_deg)})`;
}

function recordLatency(ms) {
  state.latencies.push(ms);
  const recent = state.latencies.slice(-50).sort((a, b) => a - b);
  const median = recent[Math.floor(recent.length / 2)];
  $('latency').textContent = `input → drawn frame: ${ms.toFixed(1)} ms (median of the last ${recent.length}: ${median.toFixed(1)} ms)`;
}

/** Puts the design's values into the controls. */
function syncControls() {
  const d = state.design;
  $('theta').value = d.theta_deg;
  $('theta-value').textContent = Number(d.theta_deg).toFixed(1);
  $('kind').value = d.mesh === 'conical' ? 'conical' : 'circular';
  for (const g of ['u', 'v']) {
    const spec = d[`guide_${g}`];
    const sampled = spec.bspline || spec.arc || spec.parabola;
    $(`samples-${g}`).value = sampled ? sampled.samples : spec.points.length;
    $(`samples-${g}`).disabled = !sampled;
  }
}

$('theta').addEventListener('input', (event) => {
  const t0 = performance.now();
  state.design.theta_deg = Number(event.target.value);
  $('theta-value').textContent = state.design.theta_deg.toFixed(1);
  change(t0, true);
});
for (const g of ['u', 'v']) {
  $(`samples-${g}`).addEventListener('change', (event) => {
    const spec = state.design[`guide_${g}`];
    (spec.bspline || spec.arc || spec.parabola).samples = Math.round(Number(event.target.value));
    change(performance.now());
  });
}
$('kind').addEventListener('change', (event) => {
  if (event.target.value === 'conical') state.design.mesh = 'conical';
  else delete state.design.mesh;
  change(performance.now());
});
$('offset').addEventListener('change', (event) => {
  state.offset = Number(event.target.value) || 0;
  change(performance.now());
});
$('show-gauss').addEventListener('change', (event) => {
  gauss.visible = event.target.checked;
  redraw();
});
$('show-axes').addEventListener('change', (event) => {
  axesGroup.visible = event.target.checked;
  if (state.mesh) showAxes(state.mesh);
  redraw();
});
$('show-planes').addEventListener('change', (event) => {
  planesGroup.visible = event.target.checked;
  if (state.mesh) showPlanes(state.mesh);
  redraw();
});
$('show-arcs').addEventListener('change', () => {
  if (state.mesh && !state.stale) measure();
  else arcLines.visible = false;
  redraw();
});
$('colour').addEventListener('change', () => {
  if (current) showColours(current);
  redraw();
});

/** Saves `blob` as a download named `name`. */
function download(blob, name) {
  const a = Object.assign(document.createElement('a'), { href: URL.createObjectURL(blob), download: name });
  a.click();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}

$('save').addEventListener('click', () => {
  download(new Blob([`${JSON.stringify(state.design, null, 2)}\n`], { type: 'application/json' }), 'design.json');
});
$('export-net').addEventListener('click', () => {
  // The cyclidic net's JSON, as `monge smooth -o net.json` writes it (a click, not a drag: on the main thread).
  if (!current || state.stale) return;
  try {
    const net = current.smooth(1);
    try { download(new Blob([net.export(9)]), 'net.json'); } finally { net.free(); }
  } catch (error) {
    // No net (a conical design, a folded face): monge's message; the mesh stays current.
    Object.assign($('error'), { textContent: error.message, hidden: false });
  }
});
for (const format of ['obj', 'json']) {
  // The file `monge generate` writes, written by the same code in the module.
  $(`export-${format}`).addEventListener('click', () => {
    if (current && !state.stale) download(new Blob([current.export(format)]), `mesh.${format}`);
  });
}
$('load-button').addEventListener('click', () => $('load').click());
$('load').addEventListener('change', async (event) => {
  const file = event.target.files[0];
  event.target.value = '';
  if (!file) return;
  try {
    const t0 = performance.now();
    const text = parseDesign(await file.text(), file.name, file.name.toLowerCase().endsWith('.toml'));
    const mesh = generateMesh(text, file.name);
    state.design = JSON.parse(text);
    syncControls();
    state.mesh = null; // fit the view to the new design
    showMesh(mesh, t0);
  } catch (error) {
    showError(error); // the current design stays
  }
});

// ---------------------------------------------------------------- start
/**
 * The design to start from: the one `monge explore DESIGN` serves at
 * api/design, else (any static server) the built-in default-design.json.
 */
async function startDesign() {
  const given = await fetch('api/design').catch(() => null);
  if (given && given.ok && (given.headers.get('content-type') || '').startsWith('application/json')) return given.json();
  return (await fetch('default-design.json')).json();
}

async function start() {
  resize();
  await init({ module_or_path: new URL('monge_wasm_bg.wasm', import.meta.url) });
  state.design = await startDesign();
  syncControls();
  change(performance.now());
}

/** For the e2e test: state, and where a control point is on the screen. */
window.explorer = {
  state,
  handleOnScreen(guide, index) {
    const p = (index === 'end' ? arcEnd(guide) : new THREE.Vector3().fromArray(controlPoints(guide)[index])).project(camera);
    const rect = renderer.domElement.getBoundingClientRect();
    return { x: rect.left + ((p.x + 1) / 2) * rect.width, y: rect.top + ((1 - p.y) / 2) * rect.height };
  },
  /** The shown mesh's vertices, f64, as `monge generate` writes them. */
  vertices: () => Array.from(current.vertices()),
  /** The shown mesh's metrics (JSON text), measured in the module. */
  metrics: () => current.metrics(),
  /** The mesh file `monge generate` writes (`obj` or `json`), as text. */
  exported: (format) => new TextDecoder().decode(current.export(format)),
  idle: () => pendingLatency === null && settleTimer === null && !measuring,
  /** The cyclidic net drawn: { lines, arcs, segments } (chord ends), or { error }, or null. */
  arcs: () => (state.net && !state.net.error ? { ...state.net, segments: arcLines.visible ? arcLines.geometry.getAttribute('position').count / 2 : 0 } : state.net),
  /** The JSON `monge smooth -o net.json --samples 9` writes for the design shown, as text. */
  netExport: () => { const net = current.smooth(1); try { return new TextDecoder().decode(net.export(9)); } finally { net.free(); } },
  /** What the pencil axes and planes views draw: [{ axis }] and [{ family, line }]. */
  drawn: () => ({
    axes: axesGroup.visible ? axesGroup.children.map((c) => c.userData) : [],
    planes: planesGroup.visible ? planesGroup.children.map((c) => c.userData) : [],
  }),
};
start();
