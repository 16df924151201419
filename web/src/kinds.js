// A guide's kind changed from the panel: the guide redrawn as a `points`,
// `bspline`, `arc` or `parabola` guide with the same start point, start
// tangent direction, end point and plane, so that the design stays one monge
// takes (the guides still meet at 90° in their planes).
import * as THREE from 'three';

const v = (a) => new THREE.Vector3().fromArray(a);

/** The guide's start, unit start tangent, end and sample count, whatever its kind. */
function ends(spec) {
  if (spec.parabola) {
    const { start, tangent, quadratic, samples } = spec.parabola;
    return { start: v(start), tangent: v(tangent).normalize(), end: v(start).add(v(tangent)).add(v(quadratic)), samples };
  }
  if (spec.arc) {
    const { center, start, normal, angle_deg: angle, samples } = spec.arc;
    const axis = v(normal).normalize();
    const radial = v(start).sub(v(center));
    const tangent = new THREE.Vector3().crossVectors(axis, radial).normalize().multiplyScalar(Math.sign(angle));
    const end = radial.clone().applyAxisAngle(axis, THREE.MathUtils.degToRad(angle)).add(v(center));
    return { start: v(start), tangent, end, samples };
  }
  const points = spec.bspline ? spec.bspline.control_points : spec.points;
  const tangent = spec.tangent ? v(spec.tangent) : v(points[1]).sub(v(points[0]));
  return { start: v(points[0]), tangent: tangent.normalize(), end: v(points.at(-1)), samples: spec.bspline ? spec.bspline.samples : points.length };
}

/**
 * `spec` (a guide of the design file) as a guide of kind `kind`: the quadratic
 * from its start along its start tangent to its end (a parabola; as a cubic
 * B-spline; as `samples` points of it with the tangent given), or the circle's
 * arc through its start, tangent there, to its end. Throws when there is none
 * (an arc needs an end off the start tangent's line).
 */
export function convertGuide(spec, kind, name) {
  const { start, tangent, end, samples } = ends(spec);
  const chord = end.clone().sub(start);
  const T = tangent.clone().multiplyScalar(Math.max(chord.dot(tangent), 1e-6 * chord.length()));
  const Q = chord.clone().sub(T);
  const at = (t) => start.clone().addScaledVector(T, t).addScaledVector(Q, t * t);
  const xyz = (p) => p.toArray();
  switch (kind) {
    case 'parabola':
      return { parabola: { start: xyz(start), tangent: xyz(T), quadratic: xyz(Q), samples } };
    case 'bspline': {
      // The parabola's quadratic Bézier raised to degree 3.
      const middle = start.clone().addScaledVector(T, 0.5);
      const c1 = start.clone().lerp(middle, 2 / 3);
      const c2 = end.clone().lerp(middle, 2 / 3);
      return { bspline: { degree: 3, samples, control_points: [start, c1, c2, end].map(xyz) } };
    }
    case 'points':
      return { points: Array.from({ length: samples }, (_, k) => xyz(at(k / (samples - 1)))), tangent: xyz(tangent) };
    case 'arc': {
      const across = Q.clone().normalize(); // towards the end, in the plane, ⟂ tangent
      const off = chord.dot(across);
      if (!(Math.abs(off) > 1e-9 * chord.length())) {
        throw new Error(`guide_${name}: a straight guide is no arc: move its end off the line of its start tangent first (drag a point), then make it an arc.`);
      }
      const radius = chord.lengthSq() / (2 * off);
      const center = start.clone().addScaledVector(across, radius);
      const r0 = start.clone().sub(center);
      const axis = new THREE.Vector3().crossVectors(r0, tangent).normalize();
      const rE = end.clone().sub(center);
      let angle = THREE.MathUtils.radToDeg(Math.atan2(axis.dot(r0.clone().cross(rE)), r0.dot(rE)));
      if (angle <= 0) angle += 360;
      return { arc: { center: xyz(center), start: xyz(start), normal: xyz(axis), angle_deg: angle, samples } };
    }
    default:
      throw new Error(`unknown guide kind ${kind}`);
  }
}

/** The kind of a guide of the design file. */
export const kindOf = (spec) => ['points', 'bspline', 'arc', 'parabola'].find((k) => spec[k]);
