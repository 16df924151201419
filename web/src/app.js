// The explorer page: holds a design, generates its mesh in the page itself
// (monge-core compiled to WebAssembly, crates/monge-wasm) on every change and
// draws it (three.js). It needs no server: `monge explore` serves it, and so
// does any static file server.
//
// This module wires the parts: the 3D view (view.js) and the layers drawn in
// it (layers.js), the handles (handles.js), the controls (controls.js), the
// files (files.js), the design's history (history.js) and the bridge to the
// module and its worker (bridge.js), around one cycle: a change generates the mesh and shows it.
import { $, current, replaceCurrent, state } from './page.js';
import { designInfo, forgetMeasure, generateMesh, loadModule, measure, measurePending, onMeasured } from './bridge.js';
import { installControls, showMetrics, showThetaRange, syncControls } from './controls.js';
import { installFiles, labelExports, netFile } from './files.js';
import { depth, record, step } from './history.js';
import { handleOnScreen, installHandles, showHandles } from './handles.js';
import { showArcs, showAxes, showColours, showMarkers, showPlanes } from './layers.js';
import {
  arcLines, axesGroup, camera, coloured, drawn, empty, fitView, frameOwed, gaussSurface, gaussWire, guideLines, markers, orbit, planesGroup,
  quality, redraw, renderer, resetDetail, resize, setGrid, setPolyline, SETTLE_MS, STEP_INDICES, surface, surfaceMaterial, timeNextFrame, wire,
} from './view.js';

let settleTimer = null;

/** The fields that edit the design, by the words the panel labels them with. */
const FIELDS = { theta: 'θ', 'samples-u': 'samples u', 'samples-v': 'samples v', kind: 'mesh', 'kind-u': 'guide u', 'kind-v': 'guide v', offset: 'offset', 'load-button': 'Load design…' };

/** The field or handle of the last refused edit, unmarked. */
function unmark() {
  $('error-source').textContent = '';
  for (const element of document.querySelectorAll('.invalid')) {
    element.classList.remove('invalid');
    element.removeAttribute('aria-invalid');
  }
  state.invalid = null;
}

/**
 * Marks where a refused edit came from: `source` is { field: id } (outlined)
 * or { handle: { guide, index } } (drawn larger, in magenta); says so under
 * the message.
 */
function mark(source) {
  unmark();
  state.invalid = source;
  if (source?.field) {
    $(source.field).classList.add('invalid');
    $(source.field).setAttribute('aria-invalid', 'true');
  }
  const where = !source ? ''
    : source.handle ? `the dragged ${source.handle.index === 'end' ? 'end' : `point ${source.handle.index}`} of guide_${source.handle.guide} (magenta in the view)`
      : `“${FIELDS[source.field]}” (outlined)`;
  $('error-source').textContent = where ? `Refused edit: ${where}.` : '';
}

/**
 * Draws a wasm `mesh` (which becomes `current`); `t0` is the time of the input
 * that caused it (null: none to time), `fast` the drag quality (no metrics yet).
 */
function showMesh(mesh, t0, fast = false) {
  const first = state.mesh === null;
  replaceCurrent(mesh);
  const header = JSON.parse(mesh.header());
  state.mesh = header;
  state.stale = false;
  unmark();
  quality(fast);
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
  $('last-valid').hidden = true;
  labelExports(false);
  state.generations += 1;
  if (t0 !== null) timeNextFrame(t0);
  redraw();
}

/**
 * The design changed at time `t0` (null: no input to time): generate its mesh
 * now, in the input's own task, so it is drawn in the very next frame. (A
 * worker's answer comes after the input's frame has begun, a frame later: a
 * drag's meshes generated in a worker of their own, latest input first, made
 * a 300 × 300 drag lag, its frames' median from about 40 to 140 ms, input to
 * frame, measured by the end-to-end test; a frame's time goes mostly to
 * software GL drawing it, see `dragFaces` in view.js.)
 * `dragging`: θ or a control point is being dragged, so the mesh is drawn in
 * drag quality without its metrics, then in full with them once the drag has
 * rested for SETTLE_MS. `name` names the design's file in messages; `source`
 * is where the edit came from ({ field } or { handle }, see `mark`), shown
 * if monge refuses it.
 */
function change(t0, dragging = false, name = '<input>', source = null) {
  clearTimeout(settleTimer);
  settleTimer = null;
  try {
    showMesh(generateMesh(JSON.stringify(state.design), name), t0, dragging);
  } catch (error) {
    showError(error, dragging, source, true);
  }
  if (dragging) {
    settleTimer = setTimeout(() => {
      settleTimer = null;
      settle();
    }, SETTLE_MS);
  }
}

/** After a drag: the metrics (of a design monge took), and the view in full quality. */
function settle() {
  quality(false); // the mesh's bounds measured again, for the handles' size
  showHandles();
  if (!state.stale) measure();
  redraw();
}

/**
 * Shows a refusal: monge's message and where the edit came from (`source`,
 * see `mark`). When the design itself was refused (`refused`: an edit, not a
 * file that was not loaded), the last valid mesh stays, greyed, and stays
 * what the exports write, labelled as such; its warnings and marks go.
 */
function showError(error, fast = false, source = null, refused = false) {
  const box = $('error');
  box.textContent = error.message;
  box.hidden = false;
  mark(source);
  if (!refused) return;
  // The admissible θ, when the guides themselves are valid.
  try {
    showThetaRange(designInfo());
  } catch {
    // the guides are invalid: the message says why
  }
  state.stale = true;
  forgetMeasure(); // an answer for the refused design's predecessor is stale
  $('warnings').replaceChildren();
  empty(markers);
  $('last-valid').hidden = current === null;
  labelExports(current !== null);
  showHandles(); // where the refused edit put them
  arcLines.visible = false;
  surfaceMaterial.color.set(0xcccccc);
  coloured.material.color.set(0xcccccc);
  quality(fast);
  redraw();
}

/** Undo (`back`) or redo one step of the design's history, asked at time `t0`. */
function travel(back, t0) {
  if (!step(back)) return;
  syncControls();
  change(t0);
}

installHandles(change, record);
installControls(change, record, (error, source) => showError(error, false, source));
installFiles({ showMesh, showError, done: record });
onMeasured((answer, measured) => {
  showArcs(measured.net);
  showMetrics(answer, measured);
});
$('undo').addEventListener('click', (event) => travel(true, event.timeStamp));
$('redo').addEventListener('click', (event) => travel(false, event.timeStamp));
$('fit').addEventListener('click', () => {
  fitView();
  redraw();
});
// Ctrl+Z / Ctrl+Shift+Z (Ctrl+Y) undo and redo the design, wherever the focus
// is: never the browser's own undo of a field, nor a step of the θ slider.
window.addEventListener('keydown', (event) => {
  const key = event.key.toLowerCase();
  if (!(event.ctrlKey || event.metaKey) || event.altKey || (key !== 'z' && key !== 'y')) return;
  event.preventDefault();
  event.stopPropagation();
  travel(key === 'z' && !event.shiftKey, event.timeStamp);
}, { capture: true });

/**
 * The design to start from: the one `monge explore DESIGN` serves at
 * api/design, else (any static server) the built-in default-design.json.
 */
async function startDesign() {
  // `monge explore` marks the page it serves with <meta name="monge-design">;
  // a static server's page has no such mark and asks for nothing it lacks.
  const served = document.querySelector('meta[name="monge-design"]')?.content;
  return (await fetch(served ?? 'default-design.json')).json();
}

async function start() {
  resize();
  await loadModule();
  state.design = await startDesign();
  syncControls();
  change(performance.now());
  record();
}

/** For the e2e test: state, and where a control point is on the screen. */
window.explorer = {
  state,
  handleOnScreen,
  /** Undo and redo steps available. */
  history: depth,
  /** The camera: looks from `position` at `target`; returns its frame for the test's own ray. */
  look: (position, target) => {
    orbit.target.fromArray(target);
    camera.position.fromArray(position);
    orbit.update();
    redraw();
  },
  camera: () => {
    camera.updateMatrixWorld();
    const rect = document.querySelector('#view canvas').getBoundingClientRect();
    return { world: camera.matrixWorld.toArray(), fov: camera.fov, rect: { left: rect.left, top: rect.top, width: rect.width, height: rect.height } };
  },
  /** The shown mesh's vertices, f64, as `monge generate` writes them. */
  vertices: () => Array.from(current.vertices()),
  /** The shown mesh's metrics (JSON text), measured in the module. */
  metrics: () => current.metrics(),
  /** The mesh file `monge generate` writes (`obj` or `json`), as text. */
  exported: (format) => new TextDecoder().decode(current.export(format)),
  /**
   * What the last frames drew: `drag`, the primitives of the last drag frame,
   * whose mesh was drawn by at most `detail` faces a side; `byDetail`, the
   * primitives of the last drag frame at each such detail since
   * `resetDetail`; `steps`, the indices each step of the last full-quality
   * frame drew, each at most `stepIndices`; `geometries`, those whose buffers
   * WebGL holds.
   */
  frames: () => ({
    drag: drawn.drag, detail: drawn.detail, byDetail: Object.fromEntries(drawn.byDetail), steps: [...drawn.steps], stepIndices: STEP_INDICES, geometries: renderer.info.memory.geometries,
  }),
  /** Drag frames start again from the finest detail (see detail.js). */
  resetDetail,
  idle: () => !frameOwed() && settleTimer === null && !measurePending(),
  /** The vertices the surface is drawn with (f32), as three.js holds them. */
  drawnVertices: () => Array.from(surface.geometry.getAttribute('position').array),
  /** The cyclidic net drawn: { lines, arcs, segments } (chord ends), or { error }, or null. */
  arcs: () => (state.net && !state.net.error ? { ...state.net, segments: arcLines.visible ? arcLines.geometry.getAttribute('position').count / 2 : 0 } : state.net),
  /** The JSON `monge smooth -o net.json --samples 9` writes for the design shown, as text. */
  netExport: () => new TextDecoder().decode(netFile()),
  /** What the pencil axes and planes views draw: [{ axis }] and [{ family, line }]. */
  drawn: () => ({
    axes: axesGroup.visible ? axesGroup.children.map((c) => c.userData) : [],
    planes: planesGroup.visible ? planesGroup.children.map((c) => c.userData) : [],
  }),
};
start();
