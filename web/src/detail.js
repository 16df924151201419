// The detail of a drag frame, adapted to what the page's own drag frames
// cost: each grid is drawn while dragging by at most DRAG_FACES[level] of its
// faces a side (every k-th curvature line and the last), the level going one
// step coarser after a drag frame over FRAME_BUDGET_MS (input to the end of
// the frame's task, as the latency readout measures it) and one step finer
// after CHEAP_FRAMES drag frames in a row under CHEAP_SHARE of the budget. A
// real GPU keeps the top level; software GL, which spends a drag frame mostly
// on its triangles, comes down to the level it can draw in time, never below
// the last one, which still shows the shape. A drag's mesh is generated at
// that detail too (`previewDesign`: its guides sampled as coarsely), so that
// a drag move costs the coarse grid, not the design's. The full-quality
// frame drawn once a drag rests, of the design's own mesh, does not depend
// on it. Pure: no page, no three.js.

/** Faces a side of each level, finest first; each divides 100 and 300 faces into whole strides alike. */
export const DRAG_FACES = [50, 34, 25, 20, 15];
/** A drag frame's budget, input to the end of its task: 60 frames a second. */
export const FRAME_BUDGET_MS = 16;
/** A drag frame under this share of the budget is cheap... */
export const CHEAP_SHARE = 0.6;
/** ...and this many cheap ones in a row go one level finer. */
export const CHEAP_FRAMES = 3;

/** The level a drag starts from before any frame has been measured: the finest. */
export const startDetail = () => ({ level: 0, cheap: 0 });

/** The detail after a drag frame of `ms` drawn at `detail` ({ level, cheap }); a new object. */
export function nextDetail({ level, cheap }, ms) {
  if (ms > FRAME_BUDGET_MS) return { level: Math.min(level + 1, DRAG_FACES.length - 1), cheap: 0 };
  if (ms >= CHEAP_SHARE * FRAME_BUDGET_MS) return { level, cheap: 0 };
  if (cheap + 1 < CHEAP_FRAMES || level === 0) return { level, cheap: Math.min(cheap + 1, CHEAP_FRAMES) };
  return { level: level - 1, cheap: 0 };
}

/** The guide kinds sampled at `samples` parameter values. */
const SAMPLED = ['bspline', 'arc', 'parabola'];

/**
 * At most `faces` + 1 of a `points` guide's `points` (`faces` ≥ 3): the first
 * three (the start tangent, when not given, is the circle's through them),
 * then every k-th, and the last; the points themselves when there are no more.
 */
function thinPoints(points, faces) {
  if (points.length - 1 <= faces) return points;
  const stride = Math.ceil((points.length - 3) / Math.max(faces - 2, 1));
  const kept = points.slice(0, 2);
  for (let i = 2; i < points.length - 1; i += stride) kept.push(points[i]);
  kept.push(points.at(-1));
  return kept;
}

/**
 * A drag's preview of `design`: the same design with each sampled guide
 * (B-spline, arc, parabola) sampled at most `faces` + 1 times, and each
 * `points` guide thinned to at most `faces` + 1 of its points (see
 * `thinPoints`), so that its mesh has at most `faces` faces a side: the
 * exact mesh of the same curves sampled more coarsely, and of a polyline
 * through some of the points with the same start and start tangent. A new
 * object; `design` is left as it is.
 */
export function previewDesign(design, faces) {
  const lower = (spec) => {
    if (Array.isArray(spec?.points)) {
      const points = thinPoints(spec.points, faces);
      return points === spec.points ? spec : { ...spec, points };
    }
    const kind = SAMPLED.find((k) => spec?.[k]);
    if (!kind || !(spec[kind].samples > faces + 1)) return spec;
    return { ...spec, [kind]: { ...spec[kind], samples: faces + 1 } };
  };
  return { ...design, guide_u: lower(design.guide_u), guide_v: lower(design.guide_v) };
}
