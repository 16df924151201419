// The page's files: the design saved as JSON, the mesh exported as OBJ, JSON
// or binary glTF and the cyclidic net as JSON (the files `monge generate` and
// `monge smooth` write, written by the same code in the module), the mesh,
// guides and panels as a Rhino file (.3dm, written by rhino3dm in a worker,
// src/rhino-worker.js), and a design file (JSON or TOML) loaded.
import { $, fullMesh, setText, state } from './page.js';
import { generateMesh, parseDesign } from './bridge.js';
import { syncControls } from './controls.js';

/** Saves `blob` as a download named `name`. */
function download(blob, name) {
  const a = Object.assign(document.createElement('a'), { href: URL.createObjectURL(blob), download: name });
  a.click();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}

/** The bytes `monge smooth -o net.json --samples 9` writes for the wasm `mesh` (from `fullMesh`); throws monge's message when it has no net. */
export function netFile(mesh) {
  const net = mesh.smooth(1);
  try { return net.export(9); } finally { net.free(); }
}

/** The export buttons, and whether they export the last valid design (the design shown was refused). */
const EXPORTS = {
  'export-obj': 'Export OBJ', 'export-json': 'Export JSON', 'export-glb': 'Export GLB', 'export-3dm': 'Export 3DM', 'export-net': 'Export smooth net',
};

/** Labels the export buttons as exporting the last valid design (`stale`) or the design shown. */
export function labelExports(stale) {
  for (const [id, label] of Object.entries(EXPORTS)) setText($(id), stale ? `${label} (last valid design)` : label);
}

/** The .3dm writer's worker, started on the first .3dm export; its answers' resolvers, in order. */
let rhinoWorker = null;
const rhinoWaiting = [];

/**
 * The .3dm of the wasm `mesh` shown (from `fullMesh`): its vertices (f64, as
 * `monge generate` writes them), its quads (wound as the exported files), its
 * guides' samples and its panels, on the layers of src/rhino.js. Resolves to
 * the bytes; rejects with the reason when rhino3dm cannot be loaded or write it.
 */
function rhinoExport(mesh) {
  // A copy of what is shown now: the mesh may change while the worker writes.
  const data = {
    vertices: Float64Array.from(mesh.vertices()),
    faces: mesh.faces(),
    cols: state.mesh.cols,
    guides: { u: Float64Array.from(mesh.guidePoints(true)), v: Float64Array.from(mesh.guidePoints(false)) },
  };
  if (!rhinoWorker) {
    rhinoWorker = new Worker(new URL('rhino-worker.js', import.meta.url), { type: 'module' });
    rhinoWorker.onmessage = ({ data: answer }) => rhinoWaiting.shift()(answer);
    rhinoWorker.onerror = (event) => {
      // The worker itself did not start: every export waiting gets the reason; the next one starts it again.
      event.preventDefault();
      rhinoWorker.terminate();
      rhinoWorker = null;
      for (const answer of rhinoWaiting.splice(0)) answer({ error: `cannot start the .3dm writer (rhino-worker.js beside the page): ${event.message ?? 'not found'}` });
    };
  }
  return new Promise((resolve, reject) => {
    rhinoWaiting.push(({ bytes, error }) => (error ? reject(new Error(error)) : resolve(bytes)));
    rhinoWorker.postMessage(data);
  });
}

/** Shows why an export failed (monge's or rhino3dm's message); the mesh stays current. */
const exportFailed = (error) => Object.assign($('error'), { textContent: error.message, hidden: false });

/**
 * Lets the buttons save and load; a loaded design's wasm mesh is shown with
 * `showMesh(mesh, t0)`, a refused one's message with `showError(error,
 * dragging, source)`; `done()` records a loaded design as a step of the history.
 * The exports are of the design shown (a drag's preview settled first, see
 * `fullMesh`): the last valid design's when an edit was refused.
 */
export function installFiles({ showMesh, showError, done }) {
  $('save').addEventListener('click', () => {
    download(new Blob([`${JSON.stringify(state.design, null, 2)}\n`], { type: 'application/json' }), 'design.json');
  });
  $('export-net').addEventListener('click', () => {
    // The cyclidic net's JSON, as `monge smooth -o net.json` writes it (a click, not a drag: on the main thread).
    const mesh = fullMesh();
    if (!mesh) return;
    try {
      download(new Blob([netFile(mesh)]), 'net.json');
    } catch (error) {
      exportFailed(error); // no net (a conical design, a folded face): monge's message
    }
  });
  for (const format of ['obj', 'json', 'glb']) {
    // The file `monge generate` writes, written by the same code in the module.
    $(`export-${format}`).addEventListener('click', () => {
      const mesh = fullMesh();
      if (mesh) download(new Blob([mesh.export(format)]), `mesh.${format}`);
    });
  }
  $('export-3dm').addEventListener('click', async () => {
    const mesh = fullMesh();
    if (!mesh) return;
    const button = $('export-3dm');
    // Until this one is written (rhino3dm loads on the first): disabled, and marked as busy.
    Object.assign(button, { disabled: true, ariaBusy: 'true' });
    try {
      download(new Blob([await rhinoExport(mesh)]), 'mesh.3dm');
    } catch (error) {
      exportFailed(error);
    } finally {
      Object.assign(button, { disabled: false, ariaBusy: 'false' });
    }
  });
  $('load-button').addEventListener('click', () => $('load').click());
  $('load').addEventListener('change', async (event) => {
    const file = event.target.files[0];
    event.target.value = '';
    if (!file) return;
    try {
      const t0 = event.timeStamp;
      const text = parseDesign(await file.text(), file.name, file.name.toLowerCase().endsWith('.toml'));
      const mesh = generateMesh(text, file.name);
      state.design = JSON.parse(text);
      syncControls();
      state.mesh = null; // fit the view to the new design
      showMesh(mesh, t0);
      done();
    } catch (error) {
      showError(error, false, { field: 'load-button' }); // the current design stays
    }
  });
}
