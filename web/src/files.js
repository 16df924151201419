// The page's files: the design saved as JSON, the mesh exported as OBJ or
// JSON and the cyclidic net as JSON (the files `monge generate` and
// `monge smooth` write, written by the same code in the module), and a design
// file (JSON or TOML) loaded.
import { $, current, state } from './page.js';
import { generateMesh, parseDesign } from './bridge.js';
import { syncControls } from './controls.js';

/** Saves `blob` as a download named `name`. */
function download(blob, name) {
  const a = Object.assign(document.createElement('a'), { href: URL.createObjectURL(blob), download: name });
  a.click();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}

/** The bytes `monge smooth -o net.json --samples 9` writes for the design shown; throws monge's message when it has no net. */
export function netFile() {
  const net = current.smooth(1);
  try { return net.export(9); } finally { net.free(); }
}

/** The export buttons, and whether they export the last valid design (the design shown was refused). */
const EXPORTS = { 'export-obj': 'Export OBJ', 'export-json': 'Export JSON', 'export-net': 'Export smooth net' };

/** Labels the export buttons as exporting the last valid design (`stale`) or the design shown. */
export function labelExports(stale) {
  for (const [id, label] of Object.entries(EXPORTS)) $(id).textContent = stale ? `${label} (last valid design)` : label;
}

/**
 * Lets the buttons save and load; a loaded design's wasm mesh is shown with
 * `showMesh(mesh, t0)`, a refused one's message with `showError(error,
 * dragging, source)`; `done()` records a loaded design as a step of the history.
 * The exports are of the mesh shown: the last valid design's when an edit was refused.
 */
export function installFiles({ showMesh, showError, done }) {
  $('save').addEventListener('click', () => {
    download(new Blob([`${JSON.stringify(state.design, null, 2)}\n`], { type: 'application/json' }), 'design.json');
  });
  $('export-net').addEventListener('click', () => {
    // The cyclidic net's JSON, as `monge smooth -o net.json` writes it (a click, not a drag: on the main thread).
    if (!current) return;
    try {
      download(new Blob([netFile()]), 'net.json');
    } catch (error) {
      // No net (a conical design, a folded face): monge's message; the mesh stays current.
      Object.assign($('error'), { textContent: error.message, hidden: false });
    }
  });
  for (const format of ['obj', 'json']) {
    // The file `monge generate` writes, written by the same code in the module.
    $(`export-${format}`).addEventListener('click', () => {
      if (current) download(new Blob([current.export(format)]), `mesh.${format}`);
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
      done();
    } catch (error) {
      showError(error, false, { field: 'load-button' }); // the current design stays
    }
  });
}
