// The 3D view: the renderer, the camera and its orbit controls, the scene's
// objects (the surface and its wireframe, the guides, the Gauss map, and the
// groups that the layers and the handles fill), the buffers of a grid and of a
// polyline, drag quality, and the frames with their input-to-frame latency.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { DRAG_FACES, nextDetail, startDetail } from './detail.js';
import { $, state } from './page.js';

const view = $('view');
export const renderer = new THREE.WebGLRenderer({ antialias: false });
renderer.setPixelRatio(window.devicePixelRatio);
view.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xffffff);
export const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1e5);
camera.up.set(0, 0, 1); // designs are z-up
export const orbit = new OrbitControls(camera, renderer.domElement);
scene.add(new THREE.HemisphereLight(0xffffff, 0x667788, 1.6));
const sun = new THREE.DirectionalLight(0xffffff, 1.4);
camera.add(sun);
sun.position.set(1, 2, 3);
scene.add(camera);

export const surfaceMaterial = new THREE.MeshLambertMaterial({
  color: 0xb0c4de, side: THREE.DoubleSide, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
});
export const surface = new THREE.Mesh(new THREE.BufferGeometry(), surfaceMaterial);
export const wire = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0x3a4a5a, transparent: true, opacity: 0.35 }));
export const guideLines = {
  u: new THREE.Line(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0xd02020, depthTest: false })),
  v: new THREE.Line(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0x2040d0, depthTest: false })),
};
export const handles = new THREE.Group();   // draggable control points and their polygons
export const markers = new THREE.Group();   // folds and pinches
export const gauss = new THREE.Group();     // the Gauss map beside the mesh
export const gaussSurface = new THREE.Mesh(new THREE.BufferGeometry(), new THREE.MeshLambertMaterial({ color: 0xe8c9a0, side: THREE.DoubleSide }));
export const gaussWire = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0x705030, transparent: true, opacity: 0.4 }));
const sphereWire = new THREE.Mesh(new THREE.SphereGeometry(0.995, 48, 24), new THREE.MeshBasicMaterial({ color: 0xdddddd, wireframe: true, transparent: true, opacity: 0.35 }));
gauss.add(sphereWire, gaussSurface, gaussWire);
for (const line of Object.values(guideLines)) line.renderOrder = 1;
for (const grid of [surface, wire, gaussSurface, gaussWire]) grid.frustumCulled = false; // see setGrid
/** The sphere of a dot (radius 1, scaled to each), shared by the handles and the marks. */
export const dotGeometry = new THREE.SphereGeometry(1, 12, 6);

/**
 * Removes a group's objects and frees the buffers they hold in WebGL (three.js
 * keeps a geometry's until it is disposed), except the shared dot's sphere.
 */
export function empty(group) {
  group.traverse((o) => {
    if (o !== group && o.geometry && o.geometry !== dotGeometry) o.geometry.dispose();
  });
  group.clear();
}
/** The surface with one colour per face (by panel area or by fold), shown instead of `surface`. */
export const coloured = new THREE.Mesh(new THREE.BufferGeometry(), new THREE.MeshLambertMaterial({
  vertexColors: true, side: THREE.DoubleSide, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
}));
coloured.visible = false;
/** The pencil axes L1 and L2 (§2.1.2), drawn in the Gauss map's frame, clipped to a ball. */
export const axesGroup = new THREE.Group();
axesGroup.visible = false;
gauss.add(axesGroup);
/** The planes of the curvature lines (§2.2): each drawn line closed by its chord, filled. */
export const planesGroup = new THREE.Group();
/** The cyclidic net's curvature lines (§4.4): circular arcs, drawn as chords. */
export const arcLines = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0x106030 }));
arcLines.visible = false;
planesGroup.visible = false;
scene.add(arcLines, surface, coloured, wire, guideLines.u, guideLines.v, handles, markers, gauss, planesGroup);

/**
 * Drag quality: while θ, a control point or the view is being dragged the
 * page draws at half the pixel ratio, without the wireframes (the mesh's, the
 * Gauss map's and its sphere's), each grid by at most `dragFaces` of its
 * faces a side (every k-th curvature line and the last: the mesh's own
 * vertices), and asks for the mesh without its metrics; once the drag has
 * rested for SETTLE_MS it asks again, with the metrics, and draws at full
 * quality. WebGL drawn in software (no GPU) costs about the vertices, pixels
 * and lines it draws; of a drag frame, the triangles most (a 100 × 100 frame
 * drawn by 20 lines a family instead of 50 takes about half the time), so the
 * faces a side follow what the drag frames cost (see detail.js).
 */
export const SETTLE_MS = 150;
const DRAG_PIXEL_RATIO = 0.5;
/** The Gauss map's size beside the mesh: its unit sphere is drawn at this share of the mesh's bounding radius. */
const GAUSS_SCALE = 0.4;
/** The drag frames' detail, from the latencies of those drawn so far (see detail.js). */
let detail = startDetail();

/** The faces a side the mesh is drawn by at most in the next drag frame, at which a drag's preview is generated. */
export const dragLevelFaces = () => DRAG_FACES[detail.level];

/** Drag frames start again from the finest detail, and `drawn.byDetail` afresh (for the e2e test). */
export function resetDetail() {
  detail = startDetail();
  drawn.byDetail.clear();
}

/**
 * The faces a side that `grid` is drawn by at most in drag quality: the
 * Gauss map, at most GAUSS_SCALE of the mesh's size on the screen, by as
 * many fewer, so that its lines are no further apart there than the mesh's.
 */
const dragFaces = (grid) => (grid === gaussSurface ? Math.floor(GAUSS_SCALE * dragLevelFaces()) : dragLevelFaces());

/**
 * The full-quality frame is drawn offscreen, in steps of at most STEP_INDICES
 * indices (20 000 triangles or 30 000 segments), one step an animation frame
 * once the previous one has been drawn (a fence), and then shown at once. The
 * main thread never waits for the drawing (software GL draws in the GPU
 * process), and an input that comes meanwhile abandons it and waits for one
 * step at most.
 */
export const STEP_INDICES = 60000;

let scheduled = false;  // an animation frame is requested
let dirty = false;      // the scene changed since the last frame was drawn or begun
let build = null;       // the full-quality frame being drawn: { steps, next, fence }
let pendingLatency = null; // input time of the change not yet drawn
const awaiting = [];    // input times of frames drawn whose task has not ended yet
/**
 * What the last frames drew (for the e2e test): the last drag frame's
 * primitives and the mesh's faces a side in it (`detail`), the last drag
 * frame's primitives at each such detail, the full frame's steps' indices.
 */
export const drawn = { drag: null, detail: null, byDetail: new Map(), steps: [] };
const gl = renderer.getContext();
/**
 * The full-quality frame is drawn into `target`, then copied onto the canvas
 * (blitFramebuffer). The target is marked as three.js marks an XR target so
 * that it holds what the canvas would, 8-bit sRGB written by the same shaders:
 * the copy is exact, and cheap, where a textured quad from an sRGB texture
 * costs software GL about as much as the frame.
 */
const target = new THREE.WebGLRenderTarget(1, 1, { colorSpace: THREE.SRGBColorSpace, internalFormat: 'RGBA8' });
target.isXRRenderTarget = true;

/**
 * The end of a frame's task: a message posted in the animation frame is
 * received after the frame's rendering and compositing (in software GL, the
 * canvas read back), which the time from the input to it includes.
 */
const frameEnd = new MessageChannel();
frameEnd.port1.onmessage = () => {
  const { t0, drag } = awaiting.shift();
  recordLatency(performance.now() - t0, drag);
};

/** Switches between drag quality (`fast`) and full quality; the next frame drawn shows it. */
export function quality(fast) {
  if (fast === state.fast) return;
  state.fast = fast;
  if (!fast) {
    bound(surface, wire);
    bound(gaussSurface, gaussWire);
  }
  wire.visible = !fast;
  gaussWire.visible = !fast;
  sphereWire.visible = !fast;
}

/** The view is being orbited, zoomed or panned: drag quality until it rests. */
let viewSettle = null;
orbit.addEventListener('start', () => {
  clearTimeout(viewSettle);
  viewSettle = null;
  quality(true);
});
orbit.addEventListener('end', () => {
  viewSettle = setTimeout(() => {
    viewSettle = null;
    quality(false);
    redraw();
  }, SETTLE_MS);
});
orbit.addEventListener('change', () => redraw());

/** Draws the scene again soon, in the quality asked for (a full-quality frame being drawn is begun again). */
export function redraw() {
  dirty = true;
  schedule();
}

function schedule() {
  if (scheduled) return;
  scheduled = true;
  requestAnimationFrame(tick);
}

/** One animation frame: a drag frame, or the next step of the full-quality frame, or showing it. */
function tick() {
  scheduled = false;
  if (dirty) {
    dirty = false;
    abandon();
    if (state.fast) {
      drawDrag();
      frameDrawn(true);
      return;
    }
    build = { steps: fullSteps(), next: 0, fence: null };
    drawn.steps = [];
  }
  if (!build) return;
  if (build.fence) {
    if (gl.getSyncParameter(build.fence, gl.SYNC_STATUS) !== gl.SIGNALED) {
      schedule();
      return;
    }
    gl.deleteSync(build.fence);
    build.fence = null;
  }
  if (build.next < build.steps.length) {
    drawStep(build.steps[build.next], build.next === 0);
    build.next += 1;
    build.fence = gl.fenceSync(gl.SYNC_GPU_COMMANDS_COMPLETE, 0);
    schedule();
    return;
  }
  build = null;
  if (!warm) warmUp();
  pixelRatio(1);
  renderer.state.bindFramebuffer(gl.READ_FRAMEBUFFER, renderer.properties.get(target).__webglFramebuffer);
  renderer.state.bindFramebuffer(gl.DRAW_FRAMEBUFFER, null);
  gl.blitFramebuffer(0, 0, target.width, target.height, 0, 0, target.width, target.height, gl.COLOR_BUFFER_BIT, gl.NEAREST);
  renderer.state.bindFramebuffer(gl.READ_FRAMEBUFFER, null);
  frameDrawn(false);
}

/**
 * The drag frames draw on the canvas, whose software GL pipelines differ from
 * the target's, each compiled when first drawn (about half a second): the
 * first full frame shown draws a drag frame under it, so that the first drag
 * does not wait.
 */
let warm = false;
function warmUp() {
  warm = true;
  const fast = state.fast;
  quality(true);
  drawDrag();
  quality(fast);
}

/** The target sized as the canvas at the device's pixel ratio. */
function fitTarget() {
  const size = renderer.getSize(new THREE.Vector2()).multiplyScalar(window.devicePixelRatio).floor();
  if (target.width !== size.x || target.height !== size.y) target.setSize(size.x, size.y);
}

function abandon() {
  if (build?.fence) gl.deleteSync(build.fence);
  build = null;
}

function pixelRatio(factor) {
  const ratio = window.devicePixelRatio * factor;
  if (renderer.getPixelRatio() !== ratio) renderer.setPixelRatio(ratio); // clears the canvas
}

/**
 * `grid` drawn by at most `dragFaces` of its faces a side (null: all of
 * them): a geometry of its own, of every k-th curvature line and the last,
 * whose vertices and normals are gathered from the grid's. A drag frame so
 * sends software GL these few vertices only, not the whole grid's (at 300 ×
 * 300 faces, 4 MB a frame); the grid's are sent when a full frame draws it.
 * One such geometry a grid's buffers, made again when the stride changes
 * (and freed with them, see `setGrid`).
 */
function dragGeometry(grid) {
  const full = grid.geometry;
  const { rows, cols } = full.userData;
  if (!rows) return null;
  const step = Math.ceil((Math.max(rows, cols) - 1) / dragFaces(grid));
  if (step <= 1) return null;
  let coarse = full.userData.coarse;
  if (!coarse || coarse.step !== step) {
    coarse?.geometry.dispose();
    const [rs, cs] = [everyStep(rows, step), everyStep(cols, step)];
    const geometry = new THREE.BufferGeometry();
    for (const name of ['position', 'normal']) geometry.setAttribute(name, new THREE.BufferAttribute(new Float32Array(3 * rs.length * cs.length), 3));
    geometry.setIndex(gridTriangles(cs.length, everyStep(rs.length, 1), everyStep(cs.length, 1)));
    coarse = { step, rs, cs, geometry };
    full.userData.coarse = coarse;
  }
  const { rs, cs, geometry } = coarse;
  for (const name of ['position', 'normal']) {
    const from = full.getAttribute(name).array;
    const to = geometry.getAttribute(name);
    let k = 0;
    for (const i of rs) {
      for (const j of cs) {
        to.array.set(from.subarray(3 * (i * cols + j), 3 * (i * cols + j) + 3), k);
        k += 3;
      }
    }
    to.needsUpdate = true;
  }
  return geometry;
}

/** The grids drawn by at most `dragFaces` of their faces a side. */
function drawDrag() {
  pixelRatio(DRAG_PIXEL_RATIO);
  const grids = [surface, gaussSurface].map((m) => [m, m.geometry, dragGeometry(m)]).filter(([, , coarse]) => coarse);
  for (const [m, , coarse] of grids) m.geometry = coarse;
  renderer.render(scene, camera);
  drawn.drag = renderer.info.render.triangles + renderer.info.render.lines;
  drawn.detail = dragFaces(surface);
  drawn.byDetail.set(drawn.detail, drawn.drag);
  for (const [m, full] of grids) m.geometry = full;
}

const drawable = (o) => o.isMesh || o.isLine || o.isPoints;
const indexCount = (o) => (o.geometry.index ?? o.geometry.getAttribute('position'))?.count ?? 0;

/**
 * The steps of the full-quality frame, in the order one render would draw
 * them: the opaque objects, then the transparent ones (each by renderOrder), each step at most
 * STEP_INDICES indices (whole faces and segments): a large object in ranges,
 * small ones together. A step is { objects, range: [start, count] | null }.
 */
function fullSteps() {
  const objects = [];
  scene.traverseVisible((o) => { if (drawable(o)) objects.push(o); });
  const steps = [];
  for (const transparent of [false, true]) {
    let small = { objects: [], range: null, indices: 0 };
    // Those drawn over the rest (guides, handles, marks) last, as one render draws them.
    const kind = objects.filter((k) => k.material.transparent === transparent).sort((a, b) => a.renderOrder - b.renderOrder);
    for (const o of kind) {
      const n = indexCount(o);
      if (n > STEP_INDICES) {
        for (let start = 0; start < n; start += STEP_INDICES) steps.push({ objects: [o], range: [start, Math.min(STEP_INDICES, n - start)] });
        continue;
      }
      if (small.indices + n > STEP_INDICES) {
        steps.push(small);
        small = { objects: [], range: null, indices: 0 };
      }
      small.objects.push(o);
      small.indices += n;
    }
    if (small.objects.length) steps.push(small);
  }
  return steps;
}

/** Draws one step offscreen, the first clearing the frame. */
function drawStep({ objects, range }, first) {
  if (first) fitTarget();
  const hidden = [];
  scene.traverseVisible((o) => { if (drawable(o) && !objects.includes(o)) hidden.push(o); });
  for (const o of hidden) o.visible = false;
  if (range) objects[0].geometry.setDrawRange(...range);
  // Only the first step clears (a coloured background clears whatever autoClear says).
  const background = scene.background;
  if (!first) scene.background = null;
  renderer.setRenderTarget(target);
  renderer.autoClear = first;
  renderer.render(scene, camera);
  drawn.steps.push(range ? range[1] : objects.reduce((n, o) => n + indexCount(o), 0));
  renderer.autoClear = true;
  renderer.setRenderTarget(null);
  scene.background = background;
  if (range) objects[0].geometry.setDrawRange(0, Infinity);
  for (const o of hidden) o.visible = true;
}

/**
 * The next frame drawn shows the result of the input at time `t0` (an event's
 * timeStamp): its latency is recorded then, from the earliest such input it
 * is the first to show.
 */
export function timeNextFrame(t0) {
  if (pendingLatency === null) pendingLatency = t0;
}

/**
 * A frame was drawn (a drag frame: `drag`): the latency of the input it shows
 * is measured at the end of its task.
 */
function frameDrawn(drag) {
  if (pendingLatency === null) return;
  awaiting.push({ t0: pendingLatency, drag });
  pendingLatency = null;
  frameEnd.port2.postMessage(null);
}

/** Whether a frame is still to be drawn or shown, or its latency measured, or the view is settling. */
export const frameOwed = () => scheduled || build !== null || pendingLatency !== null || awaiting.length > 0 || viewSettle !== null;

/** Shows a frame's latency (`drag`: of a drag frame, which the drag frames' detail follows). */
function recordLatency(ms, drag) {
  state.latencies.push(ms);
  const recent = state.latencies.slice(-50).sort((a, b) => a - b);
  const median = recent[Math.floor(recent.length / 2)];
  if (drag) detail = nextDetail(detail, ms);
  $('latency').textContent = `input → end of the frame's task: ${ms.toFixed(1)} ms (median of the last ${recent.length}: ${median.toFixed(1)} ms); `
    + `drag frames drawn by at most ${dragLevelFaces()} faces a side`;
}

export function resize() {
  const { clientWidth: w, clientHeight: h } = view;
  renderer.setSize(w, h);
  camera.aspect = w / h;
  camera.updateProjectionMatrix();
  redraw();
}
window.addEventListener('resize', resize);

/** Every `step`-th of `n` lines, and the last. */
function everyStep(n, step) {
  const lines = [];
  for (let l = 0; l < n - 1; l += step) lines.push(l);
  lines.push(n - 1);
  return lines;
}

/** Two triangles a face of a rows × cols grid drawn by its rows `rs` and columns `cs`. */
function gridTriangles(cols, rs, cs) {
  const tri = [];
  const at = (i, j) => i * cols + j;
  for (let a = 0; a + 1 < rs.length; a++) {
    for (let b = 0; b + 1 < cs.length; b++) {
      const [i, k, j, l] = [rs[a], rs[a + 1], cs[b], cs[b + 1]];
      tri.push(at(i, j), at(k, j), at(k, l), at(i, j), at(k, l), at(i, l));
    }
  }
  return tri;
}

/** The edges of a rows × cols grid. */
function gridEdges(rows, cols) {
  const edges = [];
  const at = (i, j) => i * cols + j;
  for (let i = 0; i < rows; i++) {
    for (let j = 0; j < cols; j++) {
      if (j + 1 < cols) edges.push(at(i, j), at(i, j + 1));
      if (i + 1 < rows) edges.push(at(i, j), at(i + 1, j));
    }
  }
  return edges;
}

/**
 * Puts a grid into a surface and its wireframe. Each keeps two sets of
 * buffers, reused while the grid's size stays: the design's mesh's and a
 * drag's preview's (`preview`, see `previewDesign` in detail.js), so that a
 * drag that rests does not build the whole grid's triangles and edges again
 * (drag quality may also draw a coarser copy, see `dragGeometry`).
 */
export function setGrid(mesh, lines, rows, cols, positions, normals, preview = false) {
  const slots = mesh.userData.slots ??= {};
  const slot = preview ? 'preview' : 'full';
  let held = slots[slot];
  if (!held || held.rows !== rows || held.cols !== cols) {
    if (held) {
      held.geometry.userData.coarse?.geometry.dispose();
      held.geometry.dispose();
      held.lines.dispose();
    }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(rows * cols * 3), 3));
    geometry.setAttribute('normal', new THREE.BufferAttribute(new Float32Array(rows * cols * 3), 3));
    geometry.setIndex(gridTriangles(cols, everyStep(rows, 1), everyStep(cols, 1)));
    geometry.userData = { rows, cols, coarse: null };
    const edges = new THREE.BufferGeometry();
    edges.setAttribute('position', geometry.getAttribute('position'));
    edges.setIndex(gridEdges(rows, cols));
    held = { rows, cols, geometry, lines: edges };
    slots[slot] = held;
  }
  const { geometry } = held;
  mesh.geometry = geometry;
  lines.geometry = held.lines;
  geometry.getAttribute('position').array.set(positions);
  geometry.getAttribute('position').needsUpdate = true;
  if (normals) {
    geometry.getAttribute('normal').array.set(normals);
    geometry.getAttribute('normal').needsUpdate = true;
  } else {
    geometry.computeVertexNormals();
  }
  // Its bounds (the handles' size, the fitted view) are measured again when
  // the drag rests; the grids are never culled, so stale bounds hide nothing.
  if (!state.fast || !geometry.boundingSphere) bound(mesh, lines);
}

/** Measures the bounding sphere of a grid `mesh` and its wireframe `lines`. */
function bound(mesh, lines) {
  mesh.geometry.computeBoundingSphere();
  lines.geometry.boundingSphere = mesh.geometry.boundingSphere; // the same positions
}

export function setPolyline(line, flat) {
  line.geometry.dispose();
  line.geometry = new THREE.BufferGeometry();
  line.geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(flat), 3));
}

export function meshSize() {
  return surface.geometry.boundingSphere ? surface.geometry.boundingSphere.radius : 1;
}

/** Looks at the whole mesh, with the Gauss map beside it. */
export function fitView() {
  const { center, radius } = surface.geometry.boundingSphere;
  gauss.scale.setScalar(GAUSS_SCALE * radius);
  gauss.position.copy(center).add(new THREE.Vector3(1.5 * radius, 0, 0));
  const target = center.clone().add(new THREE.Vector3(0.6 * radius, 0, 0));
  orbit.target.copy(target);
  camera.position.copy(target).add(new THREE.Vector3(-0.7, -3.6, 2.2).multiplyScalar(radius));
  camera.near = radius / 100;
  camera.far = radius * 100;
  camera.updateProjectionMatrix();
  orbit.update();
}
