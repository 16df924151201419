// The layers drawn over or instead of the surface, from the mesh shown: the
// faces coloured by panel area or by fold with their legend, the pencil axes
// in the Gauss map, the planes of the curvature lines, the marks where the
// mesh folds or nearly pinches with their warnings, and the cyclidic net's arcs.
import * as THREE from 'three';
import { $, fmt, setText, state } from './page.js';
import { arcLines, axesGroup, coloured, dotGeometry, empty, markers, meshSize, planesGroup, surface } from './view.js';

/** Below this smallest crossing sine the page warns that the mesh nearly pinches (§5.2). */
const LOW_CROSSING_SINE = 1e-3;

/** Colour of `t` in [0, 1] on the panel-area scale: blue (smallest) to red (largest). */
const ramp = (t) => new THREE.Color().setHSL(0.66 * (1 - t), 0.85, 0.5);
const FOLDED = new THREE.Color(0xff2020);
const UNFOLDED = new THREE.Color(0xb0c4de);

/**
 * Colours the faces of the wasm `mesh` as the `colour` control asks: by panel
 * area (§4.8) or by fold (§5.2), both measured in the module, with a legend;
 * `state.legend` holds the legend's numbers.
 */
export function showColours(mesh) {
  const mode = $('colour').value;
  coloured.visible = mode !== 'none';
  surface.visible = !coloured.visible;
  const legend = $('legend');
  legend.hidden = !coloured.visible;
  coloured.material.color.set(0xffffff);
  if (!coloured.visible) {
    state.legend = null;
    return;
  }
  const values = mode === 'area' ? mesh.faceAreas() : mesh.foldedFaces();
  let [min, max, folded] = [Infinity, -Infinity, 0];
  for (const x of values) {
    min = Math.min(min, x);
    max = Math.max(max, x);
    folded += x;
  }
  // Two triangles, six corners, a face, in the order of the faces (gridTriangles in view.js).
  const geometry = surface.geometry.toNonIndexed();
  const colours = new Float32Array(3 * geometry.getAttribute('position').count);
  values.forEach((x, k) => {
    const c = mode === 'fold' ? (x ? FOLDED : UNFOLDED) : ramp(max > min ? (x - min) / (max - min) : 0.5);
    for (let v = 6 * k; v < 6 * k + 6; v++) c.toArray(colours, 3 * v);
  });
  geometry.setAttribute('color', new THREE.BufferAttribute(colours, 3));
  coloured.geometry.dispose();
  coloured.geometry = geometry;
  if (mode === 'area') {
    state.legend = { mode, min, max };
    const stops = [0, 0.25, 0.5, 0.75, 1].map((t) => `${ramp(t).getStyle()} ${100 * t}%`).join(', ');
    legend.innerHTML = '<div>panel area</div><div class="bar"></div><div class="ends"><span class="min"></span><span class="max"></span></div>';
    legend.querySelector('.bar').style.background = `linear-gradient(to right, ${stops})`;
    legend.querySelector('.min').textContent = fmt(min, 4);
    legend.querySelector('.max').textContent = fmt(max, 4);
  } else {
    state.legend = { mode, folded, faces: values.length };
    legend.innerHTML = '<div>fold (§5.2)</div><div><span class="swatch folded"></span><span class="folded-count"></span>'
      + '<span class="swatch unfolded"></span><span class="unfolded-count"></span></div>';
    legend.querySelector('.swatch.folded').style.background = FOLDED.getStyle();
    legend.querySelector('.swatch.unfolded').style.background = UNFOLDED.getStyle();
    legend.querySelector('.folded-count').textContent = `folded: ${folded}`;
    legend.querySelector('.unfolded-count').textContent = `not folded: ${values.length - folded}`;
  }
}

/** Radius of the ball (the Gauss sphere's radius is 1) to which the pencil axes are clipped. */
const AXIS_CLIP = 3;

/** The pencil axes L1 (of the v-lines) and L2 (of the u-lines) of the header's Gauss map (§2.1.2). */
export function showAxes(header) {
  empty(axesGroup);
  const notes = [];
  for (const [name, color] of [['l1', 0x109010], ['l2', 0x9020b0]]) {
    const axis = header.axes[name];
    const label = name.toUpperCase();
    if (!axis) {
      notes.push(`${label} is at infinity (not drawn)`);
      continue;
    }
    const point = new THREE.Vector3().fromArray(axis.point);
    const distance = point.length();
    if (distance >= AXIS_CLIP) {
      notes.push(`${label} is ${fmt(distance)} from the centre, beyond the drawn ball of radius ${AXIS_CLIP}`);
      continue;
    }
    notes.push(`${label} at ${fmt(distance)} from the centre`);
    const half = Math.sqrt(AXIS_CLIP ** 2 - distance ** 2);
    const dir = new THREE.Vector3().fromArray(axis.dir);
    const line = new THREE.Line(new THREE.BufferGeometry().setFromPoints([
      point.clone().addScaledVector(dir, -half), point.clone().addScaledVector(dir, half),
    ]), new THREE.LineBasicMaterial({ color, depthTest: false }));
    line.renderOrder = 2;
    line.userData = { axis: name };
    axesGroup.add(line);
  }
  setText($('axes-note'), axesGroup.visible ? `pencil axes: ${notes.join('; ')}` : '');
}

/** At most this many planes of each family are drawn (evenly spaced, the last line included). */
const PLANES_PER_FAMILY = 12;

/**
 * The planes of the curvature lines (§2.2) of the drawn mesh, when shown: each
 * of a few rows and columns closed by its chord and filled (a fan from its first
 * vertex), which lies in the line's plane as the line is planar.
 */
export function showPlanes(header) {
  empty(planesGroup);
  if (!planesGroup.visible) return;
  const drawn = surface.geometry.getAttribute('position').array;
  const { rows, cols } = header;
  const family = (count, length, at, color, name) => {
    const step = Math.max(1, Math.ceil((count - 1) / (PLANES_PER_FAMILY - 1)));
    const lines = [];
    for (let l = 0; l < count - 1; l += step) lines.push(l);
    lines.push(count - 1);
    const material = new THREE.MeshBasicMaterial({ color, transparent: true, opacity: 0.18, side: THREE.DoubleSide, depthWrite: false });
    for (const l of lines) {
      const flat = new Float32Array(3 * length);
      for (let k = 0; k < length; k++) flat.set(drawn.subarray(3 * at(l, k), 3 * at(l, k) + 3), 3 * k);
      const fan = [];
      for (let k = 1; k + 1 < length; k++) fan.push(0, k, k + 1);
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.BufferAttribute(flat, 3));
      geometry.setIndex(fan);
      const plane = new THREE.Mesh(geometry, material);
      plane.userData = { family: name, line: l };
      planesGroup.add(plane);
    }
  };
  family(rows, cols, (i, j) => i * cols + j, 0x3050c0, 'row'); // row 0 is guide_v (blue)
  family(cols, rows, (j, i) => i * cols + j, 0xc03030, 'column'); // column 0 is guide_u (red)
}

/** Red and orange marks where the wasm `mesh` (of `header`) folds or nearly pinches (§5.2), and the warnings. */
export function showMarkers(header, mesh) {
  empty(markers);
  const size = meshSize();
  const r = header.report;
  const warnings = [];
  const marks = [];
  if (Math.abs(header.theta_deg - 90) < 1) {
    warnings.push(`θ = ${header.theta_deg}° is at or near the singular θ = +90°, where every Gauss circle passes through the corner normal: expect a degenerate mesh.`);
  }
  if (r.first_fold) {
    warnings.push(`The mesh folds over itself / pinches (§5.2) in ${r.folded_faces} faces, first at face (${r.first_fold.join(', ')}) (marked in red).`);
    marks.push({ kind: 'fold', face: r.first_fold });
  }
  if (r.min_crossing_sine < LOW_CROSSING_SINE) {
    warnings.push(`Low crossing sine ${r.min_crossing_sine.toExponential(1)} at face (${r.min_crossing_face.join(', ')}): the mesh nearly pinches there (§5.2) (marked in orange).`);
    marks.push({ kind: 'pinch', face: r.min_crossing_face });
  }
  for (const m of marks) {
    const color = m.kind === 'fold' ? 0xff0000 : 0xff8800;
    const dot = new THREE.Mesh(dotGeometry, new THREE.MeshBasicMaterial({ color, depthTest: false }));
    dot.scale.setScalar(0.02 * size);
    dot.position.fromArray(mesh.faceCentre(...m.face));
    dot.renderOrder = 2;
    markers.add(dot);
    if (m.kind === 'fold' && header.kind === 'circular') markers.add(faceHighlight(header, m.face, color));
  }
  const list = $('warnings');
  if (Array.from(list.children, (li) => li.textContent).join('\n') === warnings.join('\n')) return;
  list.replaceChildren(...warnings.map((w) => Object.assign(document.createElement('li'), { textContent: w })));
}

/** Face (i, j) of the drawn grid, filled with `color` on top of the surface. */
function faceHighlight(header, [i, j], color) {
  const drawn = surface.geometry.getAttribute('position').array;
  const v = (a, b) => Array.from(drawn.subarray(3 * (a * header.cols + b), 3 * (a * header.cols + b) + 3));
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array([...v(i, j), ...v(i + 1, j), ...v(i + 1, j + 1), ...v(i, j + 1)]), 3));
  geometry.setIndex([0, 1, 2, 0, 2, 3]);
  return new THREE.Mesh(geometry, new THREE.MeshBasicMaterial({ color, side: THREE.DoubleSide, depthTest: false }));
}

/** Draws the net's arcs (`net.segments`: chord ends, f32), or says why there is no net. */
export function showArcs(net) {
  state.net = net && (net.error ? { error: net.error } : { lines: net.lines, arcs: net.arcs });
  arcLines.visible = Boolean(net && !net.error);
  if (arcLines.visible) {
    arcLines.geometry.dispose();
    arcLines.geometry = new THREE.BufferGeometry();
    arcLines.geometry.setAttribute('position', new THREE.BufferAttribute(net.segments, 3));
  }
}
