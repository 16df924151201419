// The drag frames' detail (web/src/detail.js) fed with frame times: the
// levels' stride at 100 and 300 faces, and how the level follows the frames.
import assert from 'node:assert/strict';
import test from 'node:test';
import { CHEAP_FRAMES, CHEAP_SHARE, DRAG_FACES, FRAME_BUDGET_MS, nextDetail, startDetail } from '../src/detail.js';

/** The level after drag frames of `times` ms each, from `from`. */
const after = (times, from = startDetail()) => times.reduce(nextDetail, from);
const floor = DRAG_FACES.length - 1;
const slow = 3 * FRAME_BUDGET_MS;
const fast = CHEAP_SHARE * FRAME_BUDGET_MS / 2;

test('fast frames keep the finest level', () => {
  assert.equal(after(Array(100).fill(fast)).level, 0);
  // Within the budget but not cheap: no change either way.
  assert.equal(after(Array(100).fill(0.9 * FRAME_BUDGET_MS)).level, 0);
  assert.equal(after(Array(100).fill(FRAME_BUDGET_MS)).level, 0);
});

test('each frame over the budget is one level coarser, down to the floor and no further', () => {
  for (let n = 0; n <= floor; n++) assert.equal(after(Array(n).fill(slow)).level, n);
  assert.equal(after(Array(50).fill(slow)).level, floor);
  assert.equal(after(Array(50).fill(FRAME_BUDGET_MS + 0.01)).level, floor);
});

test('cheap frames in a row go one level finer, back to the finest', () => {
  const coarse = after(Array(floor).fill(slow));
  assert.equal(after(Array(CHEAP_FRAMES - 1).fill(fast), coarse).level, floor, 'not before enough cheap frames');
  assert.equal(after(Array(CHEAP_FRAMES).fill(fast), coarse).level, floor - 1);
  assert.equal(after(Array(floor * CHEAP_FRAMES).fill(fast), coarse).level, 0);
  // A frame that is not cheap starts the count again.
  const broken = [...Array(CHEAP_FRAMES - 1).fill(fast), 0.9 * FRAME_BUDGET_MS, ...Array(CHEAP_FRAMES - 1).fill(fast)];
  assert.equal(after(broken, coarse).level, floor);
});

test('alternating slow and cheap frames never climb above where the slow ones put it', () => {
  const times = Array.from({ length: 60 }, (_, k) => (k % 2 ? fast : slow));
  assert.equal(after(times).level, floor);
});

/** Faces a side drawn of a grid of `faces` a side by every `step`-th line and the last (everyStep in view.js). */
const drawnFaces = (faces, most) => {
  const step = Math.ceil(faces / most);
  return Math.ceil(faces / step);
};

test('each level draws as many faces a side of 100 and of 300 faces, and the Gauss map at 0.4 of them too', () => {
  let previous = Infinity;
  for (const most of DRAG_FACES) {
    assert.ok(most < previous, 'levels from finest to coarsest');
    previous = most;
    for (const m of [most, Math.floor(0.4 * most)]) {
      assert.equal(drawnFaces(300, m), drawnFaces(100, m), `at most ${m} faces a side`);
      assert.ok(drawnFaces(100, m) <= m);
    }
  }
});
