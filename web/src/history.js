// The design's history: every edit (θ, samples, mesh kind, offset, a handle
// drag, a loaded file) is one step, undone and redone with Ctrl+Z and
// Ctrl+Shift+Z (or Ctrl+Y) and the Undo and Redo buttons. A step is kept as
// the JSON text of the design and the offset, so that undo and redo give back
// the very bytes the design had.
import { $, state } from './page.js';

const past = [];   // the steps before the present one, oldest first
const future = []; // the steps undone, the next one last
let present = null; // the step shown, as recorded

const text = () => JSON.stringify({ design: state.design, offset: state.offset });

function showButtons() {
  $('undo').disabled = past.length === 0;
  $('redo').disabled = future.length === 0;
}

/** Records the design as it is now as a step, if it differs from the last one; a new step forgets the steps undone. */
export function record() {
  const now = text();
  if (now === present) return;
  if (present !== null) past.push(present);
  present = now;
  future.length = 0;
  showButtons();
}

/**
 * Goes one step back (`back`) or forward: puts that step's design and offset
 * into the page's state; false when there is none. An edit not yet recorded
 * (θ being dragged) is recorded first, so that undo goes back to before it.
 */
export function step(back) {
  record();
  const from = back ? past : future;
  if (from.length === 0) return false;
  (back ? future : past).push(present);
  present = from.pop();
  ({ design: state.design, offset: state.offset } = JSON.parse(present));
  showButtons();
  return true;
}

/** The steps before and after the one shown (for the e2e test). */
export const depth = () => ({ undo: past.length, redo: future.length });
