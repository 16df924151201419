// The bridge to monge: the wasm module on the main thread (a design's mesh,
// its admissible θ, a design file read) and the Web Worker (src/worker.js, its
// own copy of the module) that measures the metrics and the cyclidic net's
// arcs of the design shown.
import init, { generate, info, parseDesign } from '../wasm/monge_wasm.js';
import { $, GENERATED_KEPT, MAX_VERTICES, replaceCurrent, state } from './page.js';
import { previewDesign } from './detail.js';
import { redraw } from './view.js';

/** Reads a design file's text (JSON or TOML) into design JSON text; throws the CLI's message. */
export { parseDesign };

/** Loads the module on the main thread. */
export const loadModule = () => init({ module_or_path: new URL('monge_wasm_bg.wasm', import.meta.url) });

/** How long the last generation of a design's mesh took (ms). */
export let generateMs = 0;

/** The wasm mesh of a design (JSON text) at the page's offset; its vertices are noted in `state.generated` (the latest GENERATED_KEPT). */
function generateAt(text, name) {
  const mesh = generate(text, name, state.offset, MAX_VERTICES);
  state.generated.push(mesh.vertices().length / 3);
  if (state.generated.length > GENERATED_KEPT) state.generated.splice(0, state.generated.length - GENERATED_KEPT);
  return mesh;
}

/** The design (JSON text) and file name of each mesh `generateMesh` made. */
const designs = new WeakMap();

/** The wasm mesh of a design (JSON text, named `name` in messages) at the page's offset; throws the CLI's message. */
export function generateMesh(text, name) {
  const start = performance.now();
  const mesh = generateAt(text, name);
  generateMs = performance.now() - start;
  designs.set(mesh, { text, name });
  return mesh;
}

/** Makes a mesh from `generateMesh` the one shown and exported (`current`): its design becomes the last valid one. */
export function adopt(mesh) {
  replaceCurrent(mesh);
  const { text, name } = designs.get(mesh);
  state.valid = text;
  state.name = name;
}

/**
 * A drag's preview (see `previewDesign` in detail.js): the wasm mesh of the
 * design (JSON text) with its guides sampled at most `faces` + 1 times;
 * throws the CLI's message, which is of that design.
 */
export const previewMesh = (faces, name) => generateAt(JSON.stringify(previewDesign(state.design, faces)), name);

/** The design's guides and admissible θ (the header `monge info` reports); throws when the guides are invalid. */
export const designInfo = () => JSON.parse(info(JSON.stringify(state.design), '<input>', MAX_VERTICES));

/**
 * The metrics and the cyclidic net's arcs are measured in a Web Worker
 * (src/worker.js, its own copy of the module), so that the main thread only
 * generates and draws: at 300 × 300 faces the metrics take ~45 ms.
 */
const worker = new Worker(new URL('worker.js', import.meta.url), { type: 'module' });
let measureId = 0;         // the latest request to the worker
let measuring = false;     // its answer has not come yet

/** Asks the worker for the metrics (and arcs) of the design shown. */
export function measure() {
  measureId += 1;
  measuring = true;
  $('metrics').classList.add('pending');
  worker.postMessage({
    id: measureId, text: JSON.stringify(state.design), name: state.name, offset: state.offset,
    maxVertices: MAX_VERTICES, arcs: $('show-arcs').checked,
  });
}

/** The design was refused: an answer for its predecessor is stale. */
export function forgetMeasure() {
  measureId += 1;
  measuring = false;
}

/** Whether the worker's answer to the latest request has not come yet. */
export const measurePending = () => measuring;

/**
 * Shows the worker's answers to the latest request, with `show(header,
 * measured)` (the header of the mesh shown, the worker's answer).
 */
export function onMeasured(show) {
  worker.onmessage = ({ data }) => {
    if (data.id !== measureId) return; // a newer design is being measured
    measuring = false;
    if (data.error) return; // the main thread shows monge's message for this design
    show(state.mesh, data);
    $('metrics').classList.remove('pending');
    redraw();
  };
}
