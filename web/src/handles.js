// The handles: dots on the guides' draggable points (a B-spline's control
// points, a `points` guide's points, a parabola's Bézier control points, an
// arc's end) and their control polygons, and the drag that moves a point in
// its guide's plane and changes the design.
import * as THREE from 'three';
import { state } from './page.js';
import { camera, dotGeometry, empty, handles, meshSize, orbit, renderer, setPolyline } from './view.js';

/**
 * The draggable points of a guide, as [x, y, z] arrays: a B-spline's control
 * points, a `points` guide's points, or a parabola's quadratic Bézier control
 * points (start, start + tangent / 2, start + tangent + quadratic); null for an arc.
 */
export function controlPoints(name) {
  const spec = state.design[`guide_${name}`];
  if (spec.parabola) {
    const { start, tangent, quadratic } = spec.parabola;
    return [start, start.map((s, k) => s + tangent[k] / 2), start.map((s, k) => s + tangent[k] + quadratic[k])];
  }
  return spec.bspline ? spec.bspline.control_points : spec.points ?? null;
}

/** Moves draggable point `index` of guide `name` (see `controlPoints`) to `p`. */
function setControlPoint(name, index, p) {
  const spec = state.design[`guide_${name}`];
  if (!spec.parabola) {
    controlPoints(name)[index] = p;
    return;
  }
  const parabola = spec.parabola;
  const [start, , end] = controlPoints(name);
  if (index === 1) parabola.tangent = p.map((x, k) => 2 * (x - start[k]));
  // The end stays where it is when the tangent changes; the quadratic term follows.
  const target = index === 2 ? p : end;
  parabola.quadratic = target.map((x, k) => x - start[k] - parabola.tangent[k]);
}

/** The end of an `arc` guide (its start turned by angle_deg about the normal through the centre), or null. */
export function arcEnd(name) {
  const arc = state.design[`guide_${name}`].arc;
  if (!arc) return null;
  const centre = new THREE.Vector3().fromArray(arc.center);
  const axis = new THREE.Vector3().fromArray(arc.normal).normalize();
  return new THREE.Vector3().fromArray(arc.start).sub(centre).applyAxisAngle(axis, THREE.MathUtils.degToRad(arc.angle_deg)).add(centre);
}

/** Colour of the handle whose edit monge refused. */
const REFUSED = 0xff00ff;

/** A handle: a dot at `p` that drags `index` of guide `name`. */
function handle(p, name, index, color, radius) {
  const refused = state.invalid?.handle;
  const bad = refused && refused.guide === name && refused.index === index;
  const dot = new THREE.Mesh(dotGeometry, new THREE.MeshBasicMaterial({ color: bad ? REFUSED : color, depthTest: false }));
  dot.scale.setScalar(bad ? 1.6 * radius : radius);
  dot.position.copy(p);
  dot.renderOrder = 3;
  dot.userData = { guide: name, index, refused: Boolean(bad) };
  return dot;
}

export function showHandles() {
  empty(handles);
  const radius = 0.018 * meshSize();
  for (const [name, color] of [['u', 0xd02020], ['v', 0x2040d0]]) {
    const end = arcEnd(name);
    if (end) handles.add(handle(end, name, 'end', color, radius));
    const points = controlPoints(name);
    if (!points) continue;
    const polygon = new THREE.Line(new THREE.BufferGeometry(), new THREE.LineDashedMaterial({ color, dashSize: radius, gapSize: radius, depthTest: false }));
    setPolyline(polygon, points.flat());
    polygon.computeLineDistances();
    handles.add(polygon);
    points.forEach((p, index) => handles.add(handle(new THREE.Vector3().fromArray(p), name, index, index === 0 ? 0x777777 : color, radius)));
  }
}

const raycaster = new THREE.Raycaster();
/**
 * The drag under way: { guide, index, last (the pointer's last position),
 * moved }, with `point` (where the pointer has moved the point, in its plane)
 * and `axes` (the directions it may move along: the plane's two, or the start
 * tangent alone) for a point, `arc` for an arc's end.
 */
let drag = null;

function pointerRay(event) {
  const rect = renderer.domElement.getBoundingClientRect();
  const ndc = new THREE.Vector2(((event.clientX - rect.left) / rect.width) * 2 - 1, -((event.clientY - rect.top) / rect.height) * 2 + 1);
  raycaster.setFromCamera(ndc, camera);
  return raycaster.ray;
}

/** Where `p` is on the screen, in client pixels. */
function toScreen(p) {
  const q = p.clone().project(camera);
  const rect = renderer.domElement.getBoundingClientRect();
  return new THREE.Vector2(rect.left + ((q.x + 1) / 2) * rect.width, rect.top + ((1 - q.y) / 2) * rect.height);
}

/**
 * Pixels a unit length covers at `p` when seen face on: a direction seen at a
 * grazing angle covers fewer.
 */
function pixelsPerUnit(p) {
  const depth = p.clone().applyMatrix4(camera.matrixWorldInverse).z;
  const height = renderer.domElement.getBoundingClientRect().height;
  return height / 2 / (Math.max(-depth, camera.near) * Math.tan(THREE.MathUtils.degToRad(camera.fov / 2)));
}

/**
 * A direction that covers less than this share of the pixels it would cover
 * face on (seen more than 60° away from face on) moves no faster than if it
 * were seen at 60°: the point never runs away along a line seen end on.
 */
export const GRAZING_FLOOR = 0.5;

/**
 * The step, along `axes` (unit vectors), that moves the point at `p` by the
 * pointer's move `delta` (client pixels) on the screen: the least-squares step
 * through the screen's Jacobian, each singular value floored at GRAZING_FLOOR
 * of the pixels per unit seen face on, so that a step is at most
 * |delta| / (GRAZING_FLOOR × pixels per unit) long however the plane is seen.
 */
function followStep(p, axes, delta) {
  const h = 1e-3 * meshSize();
  const at = toScreen(p);
  const columns = axes.map((a) => toScreen(p.clone().addScaledVector(a, h)).sub(at).divideScalar(h));
  const floor = GRAZING_FLOOR * pixelsPerUnit(p);
  const step = new THREE.Vector3();
  if (columns.length === 1) {
    const [c] = columns;
    const s = c.length();
    if (s > 0) step.addScaledVector(axes[0], c.dot(delta) / (s * Math.max(s, floor)));
    return step;
  }
  // The 2 × 2 Jacobian J = [c0 c1]: its singular vectors are the eigenvectors of JᵀJ.
  const [c0, c1] = columns;
  const a = c0.dot(c0);
  const b = c0.dot(c1);
  const d = c1.dot(c1);
  const angle = 0.5 * Math.atan2(2 * b, a - d);
  for (const phi of [angle, angle + Math.PI / 2]) {
    const v = [Math.cos(phi), Math.sin(phi)]; // right singular vector, in the plane's axes
    const jv = c0.clone().multiplyScalar(v[0]).addScaledVector(c1, v[1]); // = s u
    const s = jv.length();
    if (s === 0) continue;
    const amount = jv.dot(delta) / (s * Math.max(s, floor)); // (u · delta) / max(s, floor)
    step.addScaledVector(axes[0], amount * v[0]).addScaledVector(axes[1], amount * v[1]);
  }
  return step;
}

/** Two orthonormal directions of the plane with unit `normal`. */
function planeAxes(normal) {
  const e1 = new THREE.Vector3().crossVectors(normal, Math.abs(normal.x) < 0.9 ? new THREE.Vector3(1, 0, 0) : new THREE.Vector3(0, 1, 0)).normalize();
  return [e1, new THREE.Vector3().crossVectors(normal, e1)];
}

/** A handle was grabbed: the pointer drags it, not the view. */
function startDrag(event) {
  orbit.enabled = false;
  renderer.domElement.setPointerCapture(event.pointerId);
  event.stopImmediatePropagation();
}

/**
 * Turns the arc's end by the pointer's move `delta` (client pixels): the end
 * slides along the circle's tangent there (see `followStep`), by at most the
 * step the floor allows, so the swept angle changes smoothly. It keeps its sign
 * (the arc's direction) and stays within (0°, 360°) in size.
 */
function turnArc(arc, delta) {
  const centre = new THREE.Vector3().fromArray(arc.center);
  const axis = new THREE.Vector3().fromArray(arc.normal).normalize();
  const end = arcEnd(drag.guide);
  const radial = end.clone().sub(centre);
  const tangent = new THREE.Vector3().crossVectors(axis, radial).normalize(); // the direction of growing angle
  const along = followStep(end, [tangent], delta).dot(tangent);
  const turned = arc.angle_deg + THREE.MathUtils.radToDeg(along / radial.length());
  const sign = Math.sign(arc.angle_deg);
  arc.angle_deg = sign * Math.min(Math.max(sign * turned, 0.1), 359.9);
}

/**
 * Lets the pointer drag the handles; `change(t0, dragging, name, source)` is
 * told of each move, at the time `t0` of its event, with the handle as
 * source; `done()` when a drag that moved a point ends (one step of the
 * design's history).
 */
export function installHandles(change, done) {
  renderer.domElement.addEventListener('pointerdown', (event) => {
    if (!state.mesh) return;
    pointerRay(event);
    const hit = raycaster.intersectObjects(handles.children.filter((c) => c.isMesh))[0];
    // The first point is shared by both guides: it stays.
    if (!hit || hit.object.userData.index === 0) return;
    const { guide, index } = hit.object.userData;
    const last = new THREE.Vector2(event.clientX, event.clientY);
    if (index === 'end') {
      drag = { guide, index, arc: state.design[`guide_${guide}`].arc, last, moved: false };
      startDrag(event);
      return;
    }
    const points = controlPoints(guide);
    const origin = new THREE.Vector3().fromArray(points[0]);
    // P1 − P0 is the start tangent: P1 slides along it so the guides still meet at 90°.
    const axes = index === 1
      ? [new THREE.Vector3().fromArray(points[1]).sub(origin).normalize()]
      : planeAxes(new THREE.Vector3().fromArray(state.mesh.guides[guide].plane_normal).normalize());
    drag = { guide, index, origin, axes, last, moved: false, point: new THREE.Vector3().fromArray(points[index]) };
    startDrag(event);
  }, { capture: true });

  renderer.domElement.addEventListener('pointermove', (event) => {
    if (!drag) return;
    const t0 = event.timeStamp;
    const now = new THREE.Vector2(event.clientX, event.clientY);
    const delta = now.clone().sub(drag.last);
    drag.last = now;
    if (delta.lengthSq() === 0) return;
    drag.moved = true;
    const source = { handle: { guide: drag.guide, index: drag.index } };
    if (drag.index === 'end') {
      turnArc(drag.arc, delta);
    } else {
      const p = drag.point.add(followStep(drag.point, drag.axes, delta));
      if (drag.index === 1) {
        // Not through the start, nor past it.
        const s = Math.max(p.clone().sub(drag.origin).dot(drag.axes[0]), 1e-3 * meshSize());
        p.copy(drag.origin).addScaledVector(drag.axes[0], s);
      }
      setControlPoint(drag.guide, drag.index, p.toArray());
    }
    showHandles();
    change(t0, true, '<input>', source);
  });

  for (const type of ['pointerup', 'pointercancel']) {
    renderer.domElement.addEventListener(type, () => {
      if (drag?.moved) done();
      drag = null;
      orbit.enabled = true;
    });
  }
}

/** Where point `index` (or 'end') of guide `guide` is on the screen, in client pixels. */
export function handleOnScreen(guide, index) {
  camera.updateMatrixWorld(); // the camera may have moved since the last frame drew
  const p = toScreen(index === 'end' ? arcEnd(guide) : new THREE.Vector3().fromArray(controlPoints(guide)[index]));
  return { x: p.x, y: p.y };
}
