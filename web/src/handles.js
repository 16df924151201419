// The handles: dots on the guides' draggable points (a B-spline's control
// points, a `points` guide's points, an arc's end) and their control polygons,
// and the drag that moves a point in its guide's plane and changes the design.
import * as THREE from 'three';
import { state } from './page.js';
import { camera, handles, meshSize, orbit, renderer, setPolyline } from './view.js';

/** The points of a guide that can be dragged (a B-spline's control points, a `points` guide's points), or null. */
export function controlPoints(name) {
  const spec = state.design[`guide_${name}`];
  return spec.bspline ? spec.bspline.control_points : spec.points ?? null;
}

/** The end of an `arc` guide (its start turned by angle_deg about the normal through the centre), or null. */
export function arcEnd(name) {
  const arc = state.design[`guide_${name}`].arc;
  if (!arc) return null;
  const centre = new THREE.Vector3().fromArray(arc.center);
  const axis = new THREE.Vector3().fromArray(arc.normal).normalize();
  return new THREE.Vector3().fromArray(arc.start).sub(centre).applyAxisAngle(axis, THREE.MathUtils.degToRad(arc.angle_deg)).add(centre);
}

/** A handle: a dot at `p` that drags `index` of guide `name`. */
function handle(p, name, index, color, radius) {
  const dot = new THREE.Mesh(new THREE.SphereGeometry(radius, 16, 8), new THREE.MeshBasicMaterial({ color, depthTest: false }));
  dot.position.copy(p);
  dot.renderOrder = 3;
  dot.userData = { guide: name, index };
  return dot;
}

export function showHandles() {
  handles.clear();
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
let drag = null; // { guide, index, plane, origin, tangent } or, for an arc's end, { guide, index: 'end', plane, arc }

function pointerRay(event) {
  const rect = renderer.domElement.getBoundingClientRect();
  const ndc = new THREE.Vector2(((event.clientX - rect.left) / rect.width) * 2 - 1, -((event.clientY - rect.top) / rect.height) * 2 + 1);
  raycaster.setFromCamera(ndc, camera);
  return raycaster.ray;
}

/** A handle was grabbed: the pointer drags it, not the view. */
function startDrag(event) {
  orbit.enabled = false;
  renderer.domElement.setPointerCapture(event.pointerId);
  event.stopImmediatePropagation();
}

/**
 * The arc's swept angle (degrees) that puts its end nearest `p` (a point of its
 * plane): the angle from start to `p` about the normal, the turn nearest the
 * current angle, kept within (−360°, 360°) and away from 0.
 */
function arcAngle(arc, p) {
  const centre = new THREE.Vector3().fromArray(arc.center);
  const axis = new THREE.Vector3().fromArray(arc.normal).normalize();
  const from = new THREE.Vector3().fromArray(arc.start).sub(centre);
  const to = p.clone().sub(centre);
  const angle = THREE.MathUtils.radToDeg(Math.atan2(axis.dot(from.clone().cross(to)), from.dot(to)));
  const turned = angle + 360 * Math.round((arc.angle_deg - angle) / 360);
  const sign = Math.sign(turned) || Math.sign(arc.angle_deg);
  return sign * Math.min(Math.max(Math.abs(turned), 0.1), 359.9);
}

/**
 * Lets the pointer drag the handles; `change(t0, dragging)` is told of each
 * move, at the time `t0` of its event.
 */
export function installHandles(change) {
  renderer.domElement.addEventListener('pointerdown', (event) => {
    if (!state.mesh) return;
    pointerRay(event);
    const hit = raycaster.intersectObjects(handles.children.filter((c) => c.isMesh))[0];
    // The first point is shared by both guides: it stays.
    if (!hit || hit.object.userData.index === 0) return;
    const { guide, index } = hit.object.userData;
    if (index === 'end') {
      const arc = state.design[`guide_${guide}`].arc;
      const centre = new THREE.Vector3().fromArray(arc.center);
      drag = { guide, index, arc, plane: new THREE.Plane().setFromNormalAndCoplanarPoint(new THREE.Vector3().fromArray(arc.normal).normalize(), centre) };
      startDrag(event);
      return;
    }
    const points = controlPoints(guide);
    const origin = new THREE.Vector3().fromArray(points[0]);
    const normal = new THREE.Vector3().fromArray(state.mesh.guides[guide].plane_normal);
    drag = {
      guide, index, origin,
      plane: new THREE.Plane().setFromNormalAndCoplanarPoint(normal, origin),
      tangent: new THREE.Vector3().fromArray(points[1]).sub(origin).normalize(),
    };
    startDrag(event);
  }, { capture: true });

  renderer.domElement.addEventListener('pointermove', (event) => {
    if (!drag) return;
    const t0 = performance.now();
    const p = pointerRay(event).intersectPlane(drag.plane, new THREE.Vector3());
    if (!p) return;
    if (drag.index === 'end') {
      drag.arc.angle_deg = arcAngle(drag.arc, p);
      showHandles();
      change(t0, true);
      return;
    }
    if (drag.index === 1) {
      // P1 − P0 is the start tangent: slide along it so the guides still meet at 90°.
      const s = Math.max(p.clone().sub(drag.origin).dot(drag.tangent), 1e-3 * meshSize());
      p.copy(drag.origin).addScaledVector(drag.tangent, s);
    }
    controlPoints(drag.guide)[drag.index] = p.toArray();
    showHandles();
    change(t0, true);
  });

  for (const type of ['pointerup', 'pointercancel']) {
    renderer.domElement.addEventListener(type, () => {
      drag = null;
      orbit.enabled = true;
    });
  }
}

/** Where point `index` (or 'end') of guide `guide` is on the screen, in client pixels. */
export function handleOnScreen(guide, index) {
  const p = (index === 'end' ? arcEnd(guide) : new THREE.Vector3().fromArray(controlPoints(guide)[index])).project(camera);
  const rect = renderer.domElement.getBoundingClientRect();
  return { x: rect.left + ((p.x + 1) / 2) * rect.width, y: rect.top + ((1 - p.y) / 2) * rect.height };
}
