// The 3D view: the renderer, the camera and its orbit controls, the scene's
// objects (the surface and its wireframe, the guides, the Gauss map, and the
// groups that the layers and the handles fill), the buffers of a grid and of a
// polyline, drag quality, and the frames with their input-to-frame latency.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
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
orbit.addEventListener('change', () => redraw());
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
export const SETTLE_MS = 150;
const DRAG_PIXEL_RATIO = 0.5;

/** Switches between drag quality (`fast`) and full quality. */
export function quality(fast) {
  if (fast === state.fast) return;
  state.fast = fast;
  renderer.setPixelRatio(window.devicePixelRatio * (fast ? DRAG_PIXEL_RATIO : 1));
  wire.visible = !fast;
  gaussWire.visible = !fast;
  sphereWire.visible = !fast;
}

/** Draws one frame soon (at most one per animation frame). */
export function redraw() {
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

/** The next frame shows the result of the input at time `t0`: its latency is recorded then. */
export function timeNextFrame(t0) {
  pendingLatency = t0;
}

/** Whether a mesh has been uploaded but not drawn yet. */
export const frameOwed = () => pendingLatency !== null;

function recordLatency(ms) {
  state.latencies.push(ms);
  const recent = state.latencies.slice(-50).sort((a, b) => a - b);
  const median = recent[Math.floor(recent.length / 2)];
  $('latency').textContent = `input → drawn frame: ${ms.toFixed(1)} ms (median of the last ${recent.length}: ${median.toFixed(1)} ms)`;
}

export function resize() {
  const { clientWidth: w, clientHeight: h } = view;
  renderer.setSize(w, h);
  camera.aspect = w / h;
  camera.updateProjectionMatrix();
  redraw();
}
window.addEventListener('resize', resize);

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
export function setGrid(mesh, lines, rows, cols, positions, normals) {
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
  gauss.scale.setScalar(0.4 * radius);
  gauss.position.copy(center).add(new THREE.Vector3(1.5 * radius, 0, 0));
  const target = center.clone().add(new THREE.Vector3(0.6 * radius, 0, 0));
  orbit.target.copy(target);
  camera.position.copy(target).add(new THREE.Vector3(-0.7, -3.6, 2.2).multiplyScalar(radius));
  camera.near = radius / 100;
  camera.far = radius * 100;
  camera.updateProjectionMatrix();
  orbit.update();
}
