// The explorer page: holds a design, generates its mesh in the page itself
// (monge-core compiled to WebAssembly, crates/monge-wasm) on every change and
// draws it (three.js). It needs no server: `monge explore` serves it, and so
// does any static file server.
//
// This module wires the parts: the 3D view (view.js) and the layers drawn in
// it (layers.js), the handles (handles.js), the controls (controls.js), the
// files (files.js), the design's history (history.js) and the bridge to the
// module and its worker (bridge.js), around one cycle: a change generates the mesh and shows it.
import { $, current, fullMesh, GENERATED_KEPT, setText, settler, state } from './page.js';
import {
  adopt, designInfo, forgetMeasure, generateMesh, loadModule, measure, measurePending, onMeasured, previewMesh,
} from './bridge.js';
import { installControls, showMetrics, showThetaRange, syncControls } from './controls.js';
import { installFiles, labelExports, netFile } from './files.js';
import { depth, record, step } from './history.js';
import { handleOnScreen, installHandles, showHandles } from './handles.js';
import { showArcs, showAxes, showColours, showMarkers, showPlanes } from './layers.js';
import {
  arcLines, axesGroup, camera, coloured, dragLevelFaces, drawn, empty, fitView, frameOwed, gaussSurface, gaussWire, guideLines, markers, orbit,
  planesGroup, quality, redraw, renderer, resetDetail, resize, setGrid, setPolyline, SETTLE_MS, STEP_INDICES, surface, surfaceMaterial,
  timeNextFrame, wire,
} from './view.js';

/** The drag being previewed: { name, source (see `mark`), valid (the last design, JSON text, whose preview monge took, or null) }. */
let dragging = null;
/** Its end, SETTLE_MS after its last move. */
let settleTimer = null;
/** The end of a drag under way, one step a task (a generator, see `settleSteps`), or null. */
let settling = null;

/** The fields that edit the design, by the words the panel labels them with. */
const FIELDS = { theta: 'θ', 'samples-u': 'samples u', 'samples-v': 'samples v', kind: 'mesh', 'kind-u': 'guide u', 'kind-v': 'guide v', offset: 'offset', 'load-button': 'Load design…' };

/** The field or handle of the last refused edit, unmarked. */
function unmark() {
  setText($('error-source'), '');
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
  setText($('error-source'), where ? `Refused edit: ${where}.` : '');
}

/**
 * The steps that draw a wasm `mesh`, each a task of its own when a drag rests
 * (see `settleSteps`): the surface's buffers, then the Gauss map's, the guides
 * and the layers. `t0` is the time of the input that caused it (null: none to
 * time). `preview`: a drag's preview (see `previewDesign` in detail.js), drawn
 * in drag quality without its metrics, then freed, `current` staying the mesh
 * of the design before the drag; otherwise the mesh, from `generateMesh`,
 * becomes `current`, drawn in full quality with its metrics.
 */
function meshSteps(mesh, t0, preview = false) {
  let header = null;
  return [() => {
    const first = state.mesh === null;
    if (!preview && mesh !== current) adopt(mesh);
    header = JSON.parse(mesh.header());
    state.mesh = header;
    state.preview = preview;
    state.stale = false;
    unmark();
    // A circular mesh's normals are its node axes (the Gauss map); a conical
    // mesh's vertex normals are left to three.js. The arrays are views into the
    // module's memory, copied into three.js's buffers at once.
    setGrid(surface, wire, header.rows, header.cols, mesh.positions(), header.kind === 'circular' ? mesh.normals() : null, preview);
    if (first) fitView();
  }, () => {
    quality(preview);
    surfaceMaterial.color.set(0xb0c4de);
    setGrid(gaussSurface, gaussWire, header.gauss.rows, header.gauss.cols, mesh.normals(), mesh.normals(), preview);
    setPolyline(guideLines.u, mesh.guidePoints(true));
    setPolyline(guideLines.v, mesh.guidePoints(false));
    showMarkers(header, mesh);
    showColours(mesh);
    showAxes(header);
    showPlanes(header);
    if (preview) {
      arcLines.visible = false; // until the drag rests and the worker draws them again
      $('metrics').classList.add('pending');
      mesh.free();
    } else {
      showHandles(); // a drag moves the handles itself
      measure();
    }
    showThetaRange(header);
    for (const id of ['error', 'last-valid']) if (!$(id).hidden) $(id).hidden = true;
    labelExports(false);
    state.generations += 1;
    if (t0 !== null) timeNextFrame(t0);
    redraw();
  }];
}

/** Draws a wasm `mesh` at once (see `meshSteps`); a design's mesh ends any drag's preview. */
function showMesh(mesh, t0, preview = false) {
  if (!preview) endDrag();
  for (const step of meshSteps(mesh, t0, preview)) step();
}

/**
 * The design changed at time `t0` (null: no input to time): generate its mesh
 * now, in the input's own task, so it is drawn in the very next frame. (A
 * worker's answer comes after the input's frame has begun, a frame later: a
 * drag's meshes generated in a worker of their own, latest input first, made
 * a 300 × 300 drag lag, its frames' median from about 40 to 140 ms, input to
 * frame, measured by the end-to-end test; a frame's time goes mostly to
 * software GL drawing it, see `dragFaces` in view.js.)
 * `drag`: θ or a control point is being dragged, so what is generated and
 * drawn is the design's preview at the drag frames' detail (its guides
 * sampled as coarsely, see `previewDesign`: a move costs the coarse grid, not
 * the design's), in drag quality without its metrics; once the drag has
 * rested for SETTLE_MS, the design's own mesh, in full, with them (see
 * `settleSteps`). `name` names the design's file in messages; `source` is
 * where the edit came from ({ field } or { handle }, see `mark`), shown if
 * monge refuses it.
 */
function change(t0, drag = false, name = '<input>', source = null) {
  if (!drag) {
    try {
      showMesh(generateMesh(JSON.stringify(state.design), name), t0);
    } catch (error) {
      endDrag();
      showError(error, false, source, true);
    }
    return;
  }
  endDrag(false);
  forgetMeasure(); // the metrics of the design before the drag are not shown over its preview
  dragging ??= { valid: null };
  Object.assign(dragging, { name, source });
  try {
    showMesh(previewMesh(dragLevelFaces(), name), t0, true);
    dragging.valid = JSON.stringify(state.design);
  } catch (error) {
    showError(error, true, source, true);
  }
  state.preview = true; // the design's own mesh is still to come
  settleTimer = setTimeout(settle, SETTLE_MS);
}

/**
 * Stops the end of a drag, pending or under way (a mesh it generated and did
 * not show yet is freed); `forget`: and the drag itself (a design's mesh, or
 * its refusal, is shown instead).
 */
function endDrag(forget = true) {
  clearTimeout(settleTimer);
  settleTimer = null;
  settling?.return();
  settling = null;
  if (!forget) return;
  dragging = null;
  state.preview = false;
}

/**
 * The end of a drag: the design's own mesh generated, then drawn in full
 * quality with its metrics (`meshSteps`), one step a task, so that no task
 * takes both the generation and the copy of a 300 × 300 grid. When monge
 * refuses the design, its message, over the mesh of the last design whose
 * preview it took (the last valid design, exported; or, when monge refuses
 * that one's mesh too, the last valid one's before the drag).
 */
function* settleSteps({ name, source, valid }) {
  let mesh = null;
  try {
    let refusal = null;
    try {
      mesh = generateMesh(JSON.stringify(state.design), name);
    } catch (error) {
      refusal = error;
    }
    if (refusal && valid !== null && valid !== state.valid) {
      yield;
      try {
        mesh = generateMesh(valid, name);
      } catch {
        // the mesh of the last valid design before the drag stays
      }
    }
    if (mesh ?? current) {
      for (const step of meshSteps(mesh ?? current, null)) {
        yield;
        step();
      }
    }
    if (refusal) showError(refusal, false, source, true);
    state.preview = false;
  } finally {
    if (mesh && mesh !== current) mesh.free(); // abandoned before it was shown
  }
}

/**
 * Ends the drag being previewed: `settleSteps` one a task, or all at once
 * (`now`: an export asks for the design's mesh, see `fullMesh`).
 */
function settle(now = false) {
  clearTimeout(settleTimer);
  settleTimer = null;
  if (!settling) {
    if (!dragging) return;
    settling = settleSteps(dragging);
    dragging = null;
  }
  const run = settling;
  const next = () => {
    if (settling !== run) return; // abandoned, or done at once
    if (run.next().done) settling = null;
    else setTimeout(next);
  };
  if (!now) {
    next();
    return;
  }
  while (!run.next().done);
  settling = null;
}
settler.now = () => settle(true);

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
  /** How many of the meshes generated `state.generated` keeps. */
  generatedKept: GENERATED_KEPT,
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
  vertices: () => Array.from(fullMesh().vertices()),
  /** The shown mesh's metrics (JSON text), measured in the module. */
  metrics: () => fullMesh().metrics(),
  /** The mesh file `monge generate` writes (`obj` or `json`), as text. */
  exported: (format) => new TextDecoder().decode(fullMesh().export(format)),
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
  idle: () => !frameOwed() && settleTimer === null && settling === null && !measurePending(),
  /** The vertices the surface is drawn with (f32), as three.js holds them. */
  drawnVertices: () => Array.from(surface.geometry.getAttribute('position').array),
  /** The cyclidic net drawn: { lines, arcs, segments } (chord ends), or { error }, or null. */
  arcs: () => (state.net && !state.net.error ? { ...state.net, segments: arcLines.visible ? arcLines.geometry.getAttribute('position').count / 2 : 0 } : state.net),
  /** The JSON `monge smooth -o net.json --samples 9` writes for the design shown, as text. */
  netExport: () => new TextDecoder().decode(netFile(fullMesh())),
  /** What the pencil axes and planes views draw: [{ axis }] and [{ family, line }]. */
  drawn: () => ({
    axes: axesGroup.visible ? axesGroup.children.map((c) => c.userData) : [],
    planes: planesGroup.visible ? planesGroup.children.map((c) => c.userData) : [],
  }),
};
start();
