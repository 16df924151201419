// The side panel's controls: θ's slider and its admissible range, the grid
// and mesh fields, the views shown (Gauss map, pencil axes, planes, arcs, face
// colours), and the metrics table.
import { $, fmt, fullMesh, setText, state } from './page.js';
import { generateMs, measure } from './bridge.js';
import { showAxes, showColours, showPlanes } from './layers.js';
import { arcLines, axesGroup, gauss, planesGroup, redraw } from './view.js';
import { convertGuide, kindOf } from './kinds.js';

/** The first words of a long message. */
const brief = (text, n = 90) => (text.length > n ? `${text.slice(0, n)}…` : text);

/** The metrics table of the mesh with header `answer`, from the worker's `measured`. */
export function showMetrics(answer, measured) {
  const m = JSON.parse(measured.metrics);
  const net = state.net;
  const worst = (w) => (w ? `${fmt(w.value)} at (${w.at.join(', ')})` : '—');
  const rows = [
    ['grid', `${answer.rows} × ${answer.cols} vertices, ${m.faces} faces`],
    ['mesh', `${answer.kind}, ${answer.mode}${answer.offset ? `, offset ${answer.offset}` : ''}`],
    ['face planarity', worst(m.face_planarity)],
    answer.kind === 'circular' ? ['circularity', worst(m.circularity)] : ['conical error', worst(m.conical)],
    ['row / column planarity', `${fmt(m.row_planarity.value)} / ${fmt(m.column_planarity.value)}`],
    ['torsion', worst(m.torsion)],
    ['max error (relative)', fmt(m.max_error)],
    ['panel area', `${fmt(m.panel_area.min)} … ${fmt(m.panel_area.max)}`],
    ['edge length', `${fmt(m.edge_length.min)} … ${fmt(m.edge_length.max)}`],
    ...(net ? [['cyclidic net (§4.4)', net.error ? brief(net.error.slice(net.error.indexOf(': ') + 2)) : `${net.lines} curvature lines, ${net.arcs} circular arcs`]] : []),
    ['in the page (wasm)', `generate ${fmt(generateMs, 2)} ms; in the worker: metrics ${fmt(measured.metricsMs, 2)} ms`],
  ];
  $('metrics').replaceChildren(...rows.map(([k, v]) => {
    const tr = document.createElement('tr');
    tr.append(Object.assign(document.createElement('td'), { textContent: k }), Object.assign(document.createElement('td'), { textContent: v }));
    return tr;
  }));
}

/** The admissible θ in words and as green on the slider. */
export function showThetaRange({ theta_range: r, mode }) {
  const slider = $('theta');
  if (mode === 'characteristic') {
    setText($('theta-range'), 'admissible: every θ in (−180°, 180°] (singular at +90°)');
    slider.style.removeProperty('--band');
    return;
  }
  setText($('theta-range'), `admissible: |θ| in [${r.min_deg.toFixed(2)}°, ${r.max_deg.toFixed(2)}°]`);
  const pct = (deg) => `${((deg + 180) / 360) * 100}%`;
  const ok = '#b5e3b5';
  const no = '#f3c0c0';
  const band = `linear-gradient(to right, ${no} ${pct(-r.max_deg)}, ${ok} ${pct(-r.max_deg)} ${pct(-r.min_deg)}, ${no} ${pct(-r.min_deg)} ${pct(r.min_deg)}, ${ok} ${pct(r.min_deg)} ${pct(r.max_deg)}, ${no} ${pct(r.max_deg)})`;
  if (slider.style.getPropertyValue('--band') !== band) slider.style.setProperty('--band', band);
}

/** Puts the design's values into the controls. */
export function syncControls() {
  const d = state.design;
  $('theta').value = d.theta_deg;
  $('theta-value').textContent = Number(d.theta_deg).toFixed(1);
  $('kind').value = d.mesh === 'conical' ? 'conical' : 'circular';
  $('offset').value = state.offset;
  for (const g of ['u', 'v']) {
    const spec = d[`guide_${g}`];
    const sampled = spec.bspline || spec.arc || spec.parabola;
    $(`samples-${g}`).value = sampled ? sampled.samples : spec.points.length;
    $(`samples-${g}`).disabled = !sampled;
    $(`kind-${g}`).value = kindOf(spec);
  }
}

/**
 * Lets the controls change the design and the views; `change(t0, dragging,
 * name, source)` is told of each change to the design, at the time `t0` of its
 * event, with the field as source; `done()` when an edit is complete (one step
 * of the design's history: θ when it is let go, a field when it changes);
 * `refuse(error, source)` shows an edit the page itself cannot make.
 */
export function installControls(change, done, refuse) {
  const field = (id) => ({ field: id });
  $('theta').addEventListener('input', (event) => {
    const t0 = event.timeStamp;
    state.design.theta_deg = Number(event.target.value);
    $('theta-value').textContent = state.design.theta_deg.toFixed(1);
    change(t0, true, '<input>', field('theta'));
  });
  $('theta').addEventListener('change', done);
  for (const g of ['u', 'v']) {
    $(`samples-${g}`).addEventListener('change', (event) => {
      const spec = state.design[`guide_${g}`];
      (spec.bspline || spec.arc || spec.parabola).samples = Math.round(Number(event.target.value));
      change(event.timeStamp, false, '<input>', field(`samples-${g}`));
      done();
    });
  }
  for (const g of ['u', 'v']) {
    $(`kind-${g}`).addEventListener('change', (event) => {
      const key = `guide_${g}`;
      try {
        state.design[key] = convertGuide(state.design[key], event.target.value, g);
      } catch (error) {
        event.target.value = kindOf(state.design[key]);
        refuse(error, field(`kind-${g}`));
        return;
      }
      syncControls();
      change(event.timeStamp, false, '<input>', field(`kind-${g}`));
      done();
    });
  }
  $('kind').addEventListener('change', (event) => {
    if (event.target.value === 'conical') state.design.mesh = 'conical';
    else delete state.design.mesh;
    change(event.timeStamp, false, '<input>', field('kind'));
    done();
  });
  $('offset').addEventListener('change', (event) => {
    state.offset = Number(event.target.value) || 0;
    change(event.timeStamp, false, '<input>', field('offset'));
    done();
  });
  $('show-gauss').addEventListener('change', (event) => {
    gauss.visible = event.target.checked;
    redraw();
  });
  $('show-axes').addEventListener('change', (event) => {
    axesGroup.visible = event.target.checked;
    if (state.mesh) showAxes(state.mesh);
    redraw();
  });
  $('show-planes').addEventListener('change', (event) => {
    planesGroup.visible = event.target.checked;
    if (state.mesh) showPlanes(state.mesh);
    redraw();
  });
  $('show-arcs').addEventListener('change', () => {
    if (state.mesh && !state.stale) measure();
    else arcLines.visible = false;
    redraw();
  });
  $('colour').addEventListener('change', () => {
    const mesh = fullMesh();
    if (mesh) showColours(mesh);
    redraw();
  });
}
