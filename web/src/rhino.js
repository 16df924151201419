// The Rhino file (.3dm) of the mesh shown, written in the page by rhino3dm
// (OpenNURBS compiled to WebAssembly, npm `rhino3dm`). The library is a few
// MB, so it is loaded on the first export only, from the page's own folder
// (build.mjs copies rhino3dm.js and rhino3dm.wasm next to app.js).

/** The layers, what each holds, and its colour (the view's, src/view.js: surface, guides, wireframe). */
const LAYERS = [
  { name: 'mesh', color: { r: 0xb0, g: 0xc4, b: 0xde, a: 255 } },     // the quad mesh, double-precision vertices
  { name: 'guide_u', color: { r: 0xd0, g: 0x20, b: 0x20, a: 255 } },  // guide_u's samples, a polyline
  { name: 'guide_v', color: { r: 0x20, g: 0x40, b: 0xd0, a: 255 } },  // guide_v's samples, a polyline
  { name: 'panels', color: { r: 0x3a, g: 0x4a, b: 0x5a, a: 255 } },   // each face, a closed polyline `panel i j`
];

let loading = null;

/** rhino3dm, loaded once (and again after a failed load). */
function loadRhino() {
  loading ??= import(new URL('rhino3dm.js', import.meta.url).href)
    .then((module) => module.default())
    .catch((error) => {
      loading = null;
      throw new Error(`cannot load rhino3dm (rhino3dm.js, rhino3dm.wasm beside the page) to write the .3dm: ${error.message}`);
    });
  return loading;
}

/** Point `k` of the flat `x, y, z, …` array `flat`, as [x, y, z]. */
const point = (flat, k) => [flat[3 * k], flat[3 * k + 1], flat[3 * k + 2]];

/**
 * The .3dm bytes of a quad mesh: `vertices` (f64, flat), `faces` (four
 * indices each, flat, wound as the exported files), `cols` (vertices per
 * row: face k is panel i j, i = ⌊k / (cols − 1)⌋), `guides` ({ u, v }: f64
 * flat samples). Each part on its layer of LAYERS.
 */
export async function rhinoFile({ vertices, faces, cols, guides }) {
  const rhino = await loadRhino();
  const doc = new rhino.File3dm();
  const [layers, objects, attributes, mesh] = [doc.layers(), doc.objects(), new rhino.ObjectAttributes(), new rhino.Mesh()];
  const [list, quads] = [mesh.vertices(), mesh.faces()];
  try {
    const layer = Object.fromEntries(LAYERS.map(({ name, color }) => [name, layers.addLayer(name, color)]));
    list.useDoublePrecisionVertices = true;
    for (let k = 0; k < vertices.length / 3; k += 1) list.addPoint3d(vertices[3 * k], vertices[3 * k + 1], vertices[3 * k + 2]);
    for (let f = 0; f < faces.length; f += 4) quads.addQuadFace(faces[f], faces[f + 1], faces[f + 2], faces[f + 3]);
    /** Sets the attributes of the next object: its name and layer. */
    const on = (name, layerName) => {
      attributes.name = name;
      attributes.layerIndex = layer[layerName];
      return attributes;
    };
    objects.addMesh(mesh, on('mesh', 'mesh'));
    for (const g of ['u', 'v']) {
      const samples = Array.from({ length: guides[g].length / 3 }, (_, k) => point(guides[g], k));
      objects.addPolyline(samples, on(`guide_${g}`, `guide_${g}`));
    }
    for (let f = 0; f < faces.length; f += 4) {
      const k = f / 4;
      const corners = [0, 1, 2, 3, 0].map((c) => point(vertices, faces[f + c]));
      objects.addPolyline(corners, on(`panel ${Math.floor(k / (cols - 1))} ${k % (cols - 1)}`, 'panels'));
    }
    return doc.toByteArray();
  } finally {
    // The tables (layers, objects, vertices, faces) are views into doc and mesh (and have a `delete(id)` of their own).
    for (const owned of [mesh, attributes, doc]) owned.delete();
  }
}
