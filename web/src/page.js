// What every part of the explorer page shares: the page's state (which
// `window.explorer` exposes to the e2e test), the wasm mesh shown, the size
// limit, and the small helpers for elements and numbers.

/** The element with id `id`. */
export const $ = (id) => document.getElementById(id);

/**
 * Sets `element`'s text to `text` when it differs: a key step or drag move
 * that leaves a label as it was costs the page no layout.
 */
export function setText(element, text) {
  if (element.textContent !== text) element.textContent = text;
}

/** A number as the page writes it: `digits` decimals, exponent form when very large or small, '—' when absent. */
export const fmt = (x, digits = 3) => (x === null || x === undefined ? '—' : Math.abs(x) >= 1e4 || (Math.abs(x) < 1e-3 && x !== 0) ? x.toExponential(2) : x.toFixed(digits));

/** Everything the page knows; `window.explorer` exposes it to the e2e test. */
export const state = {
  design: null,      // the design, in the monge design-file format
  mesh: null,        // the header of the mesh shown (see Mesh.header in crates/monge-wasm)
  offset: 0,
  latencies: [],     // ms from input event to the frame that shows its mesh
  generations: 0,    // meshes drawn so far
  stale: false,      // the design changed and monge refused it: the mesh shown is the last valid design's
  valid: null,       // the last design monge took (JSON text): the mesh shown and exported is its
  invalid: null,     // where the refused edit came from: { field: id } or { handle: { guide, index } }
  fast: false,       // drawn in drag quality (see `quality` in view.js)
  legend: null,      // the colour legend's numbers: { mode: 'area', min, max } or { mode: 'fold', folded, faces }
  name: '<input>',   // the design's file name, in messages
  net: null,         // the cyclidic net drawn: { lines, arcs } or { error }
  preview: false,    // what is drawn is a drag's preview of the design (coarser, see previewDesign in detail.js), not yet its mesh
  generated: [],     // the vertices of the last GENERATED_KEPT meshes the module generated on the main thread (for the e2e test)
};

/** How many of the meshes generated `state.generated` keeps: the latest, so that a long session does not grow it. */
export const GENERATED_KEPT = 64;

/** Largest grid generated (rows × cols vertices), as `monge explore`'s default. */
export const MAX_VERTICES = 250000;

/**
 * The wasm mesh of the design shown (for metrics and exports), never a drag's
 * preview: while one is drawn, this is the mesh of the design before it, and
 * `fullMesh` settles the drag first. Freed when replaced.
 */
export let current = null;

/** Ends a drag's preview at once: generates the design's mesh and shows it (set by app.js). */
export const settler = { now: () => {} };

/** The wasm mesh of the design shown, as exported: a drag's preview drawn is settled first (null: none yet). */
export function fullMesh() {
  if (state.preview) settler.now();
  return current;
}

/** Makes the wasm `mesh` the one shown, freeing the one it replaces. */
export function replaceCurrent(mesh) {
  if (current) current.free();
  current = mesh;
}
