// The explorer's second thread: the metrics (§2.2, §2.3) and the cyclidic
// net's arcs (§4.4) of the design shown, measured in its own copy of the
// module so that the page's main thread only generates and draws. The page
// posts { id, text, name, offset, maxVertices, arcs } after each change that
// rests, and keeps only the answer to its latest id.
import init, { generate } from '../wasm/monge_wasm.js';

const ready = init({ module_or_path: new URL('monge_wasm_bg.wasm', import.meta.url) });

/** Chords drawn per circular arc. */
const CHORDS_PER_ARC = 8;

self.onmessage = async ({ data: { id, text, name, offset, maxVertices, arcs } }) => {
  await ready;
  let mesh = null;
  try {
    const start = performance.now();
    mesh = generate(text, name, offset, maxVertices);
    const generated = performance.now();
    const metrics = mesh.metrics();
    const metricsMs = performance.now() - generated;
    let net = null;
    if (arcs) {
      try {
        const n = mesh.smooth(CHORDS_PER_ARC);
        net = { lines: n.lines(), arcs: n.arcs(), segments: n.segments().slice() };
        n.free();
      } catch (error) {
        net = { error: error.message };
      }
    }
    const answer = { id, metrics, metricsMs, workerMs: performance.now() - start, net };
    self.postMessage(answer, net?.segments ? [net.segments.buffer] : []);
  } catch (error) {
    self.postMessage({ id, error: error.message });
  } finally {
    if (mesh) mesh.free();
  }
};
