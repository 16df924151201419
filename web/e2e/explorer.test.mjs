// End-to-end test of the explorer page in headless Debian Chromium (playwright-core).
//
//   MONGE_BIN=target/release/monge node web/e2e/explorer.test.mjs [--latency-steps N]
//
// Serves web/dist (as `npm run build` leaves it) from a plain static file
// server (and opens it from file://, where it must say how to serve it), opens
// the page, moves θ and a control point, compares the page's
// mesh and exports with `monge generate` on the page's design (bit for bit),
// saves and loads a design, loads bad designs (the page must show the CLI's
// messages), measures the latency from an input to the end of its frame's
// task at 100 × 100 and 300 × 300 faces, and the long tasks of a drag that
// rests (reported, not asserted; N pairs of θ steps at each size, 4 by default:
// 40 for a steadier figure, a minute more of software GL; asserted: a drag frame
// draws no more at 300 × 300 than at 100 × 100 but for the guides at the same
// detail, made slower than the budget the drag frames come down to the coarsest
// detail and the rest draws every face, each drag move has the module generate
// a preview of at most the finest level's vertices and the rest the design's own
// mesh, which is drawn and is monge generate's, a full frame is drawn in bounded
// steps; a θ step rewrites no label of the panel but θ's value; the record of
// the meshes generated stays bounded), exports OBJ while a drag's preview is
// drawn (the design's own mesh must be written), drags a handle of each kind with its plane
// seen at a grazing angle (the point must stay near the pointer's ray and move
// no more than the pointer's path allows), refuses an edit (the page must say
// where, and export the last valid design), undoes and redoes every kind of
// edit (the same design bytes back), exports GLB and 3DM (read back by a
// GLB parser of its own and by rhino3dm), checks that the console has no error and
// no request failed, and keeps a screenshot in target/explorer-screenshot.png.
// Then `monge explore DESIGN` must serve the embedded page with that design,
// with the same clean console, and `monge explore --web-dir web/dist` the
// .3dm writer's files with their types. Exits non-zero on failure.
import { spawn, spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, writeFileSync, mkdirSync } from 'node:fs';
import { createServer } from 'node:http';
import { tmpdir } from 'node:os';
import { dirname, extname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import assert from 'node:assert/strict';
import { chromium } from 'playwright-core';
import rhino3dm from 'rhino3dm';
import { DRAG_FACES, FRAME_BUDGET_MS } from '../src/detail.js';

const repo = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const monge = resolve(process.env.MONGE_BIN ?? join(repo, 'target/release/monge'));
const work = mkdtempSync(join(tmpdir(), 'monge-e2e-'));
const screenshot = join(repo, 'target/explorer-screenshot.png');
const latencyArg = process.argv.indexOf('--latency-steps');
const latencySteps = latencyArg > 0 ? Number(process.argv[latencyArg + 1]) : 4;

/** Serves web/dist on a free port, as any static file server; resolves to { server, url }. */
function startStatic() {
  const types = { '.html': 'text/html', '.js': 'text/javascript', '.css': 'text/css', '.json': 'application/json', '.wasm': 'application/wasm' };
  const server = createServer((request, response) => {
    const path = new URL(request.url, 'http://x').pathname.replace(/^\/$/, '/index.html');
    try {
      const body = readFileSync(join(repo, 'web/dist', path.replace(/\.\./g, '')));
      response.writeHead(200, { 'Content-Type': types[extname(path)] ?? 'application/octet-stream' }).end(body);
    } catch {
      response.writeHead(404, { 'Content-Type': 'text/plain' }).end('not found');
    }
  });
  return new Promise((ok) => server.listen(0, '127.0.0.1', () => ok({ server: { kill: () => server.close() }, url: `http://127.0.0.1:${server.address().port}/` })));
}

/** Starts `monge explore ARGS…` on a free port; resolves to { server, url }. */
function startServer(...args) {
  const server = spawn(monge, ['explore', '--port', '0', ...args], { stdio: ['ignore', 'pipe', 'inherit'] });
  return new Promise((ok, fail) => {
    let out = '';
    server.stdout.on('data', (chunk) => {
      out += chunk;
      const match = out.match(/http:\/\/[\d.]+:\d+\//);
      if (match) ok({ server, url: match[0] });
    });
    server.on('exit', (code) => fail(new Error(`monge explore exited with ${code}: ${out}`)));
  });
}

/** `monge generate DESIGN -o OUT.json` in `work`; { status, stderr, mesh }. */
function generate(name) {
  const run = spawnSync(monge, ['generate', name, '-o', 'out.json'], { cwd: work, encoding: 'utf8' });
  const mesh = run.status === 0 ? JSON.parse(readFileSync(join(work, 'out.json'), 'utf8')) : null;
  return { status: run.status, stderr: run.stderr, mesh };
}

const log = (...args) => console.log('e2e:', ...args);

/**
 * `explorer[name]()`, an array of numbers, read from the page as its f64
 * bytes (base64): bit for bit (-0 included), and in a fraction of the time a
 * 300 × 300 grid's numbers take one by one.
 */
async function numbers(page, name) {
  const text = await page.evaluate((n) => {
    const bytes = new Uint8Array(Float64Array.from(explorer[n]()).buffer);
    let binary = '';
    for (let i = 0; i < bytes.length; i += 0x8000) binary += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
    return btoa(binary);
  }, name);
  return Array.from(new Float64Array(Uint8Array.from(Buffer.from(text, 'base64')).buffer));
}

/** Area of the quad a, b, c, d: half the cross product of its diagonals. */
function quadArea([a, b, c, d]) {
  const [p, q] = [[0, 1, 2].map((k) => c[k] - a[k]), [0, 1, 2].map((k) => d[k] - b[k])];
  return 0.5 * Math.hypot(p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]);
}

/** `monge generate` of the design of the page's `snapshot` gives the page's vertices bit for bit; they are returned. */
function sameAsCli(snapshot) {
  writeFileSync(join(work, 'current.json'), JSON.stringify(snapshot.design));
  const cli = generate('current.json');
  assert.equal(cli.status, 0, cli.stderr);
  const flat = cli.mesh.vertices.flat();
  assert.equal(cli.mesh.rows, snapshot.rows);
  assert.equal(cli.mesh.cols, snapshot.cols);
  assert.equal(flat.length, snapshot.vertices.length);
  const differ = flat.filter((x, k) => !Object.is(x, snapshot.vertices[k])).length;
  assert.equal(differ, 0, `${differ} coordinates of the page differ from monge generate's`);
  return flat;
}

/** Collects the page's console errors and failed requests (`problems`) and the URLs it requested (`requests`). */
function watchConsole(page) {
  const noise = { problems: [], requests: [] };
  page.on('console', (m) => { if (m.type() === 'error') noise.problems.push(`console error: ${m.text()}`); });
  page.on('request', (r) => noise.requests.push(r.url()));
  page.on('requestfailed', (r) => noise.problems.push(`failed: ${r.url()} ${r.failure()?.errorText}`));
  page.on('response', (r) => { if (r.status() >= 400) noise.problems.push(`${r.status()}: ${r.url()}`); });
  return noise;
}

/** The pointer's ray at client pixel (x, y), from the camera's frame (not the page's raycaster): { origin, dir, forward, tan }. */
function rayAt(cam, x, y) {
  const w = cam.world;
  const tan = Math.tan((cam.fov * Math.PI) / 360);
  const nx = ((x - cam.rect.left) / cam.rect.width) * 2 - 1;
  const ny = -(((y - cam.rect.top) / cam.rect.height) * 2 - 1);
  const local = [nx * tan * (cam.rect.width / cam.rect.height), ny * tan, -1];
  const dir = [0, 1, 2].map((k) => w[k] * local[0] + w[4 + k] * local[1] + w[8 + k] * local[2]);
  const n = Math.hypot(...dir);
  return { origin: [w[12], w[13], w[14]], dir: dir.map((d) => d / n), forward: [-w[8], -w[9], -w[10]], tan, height: cam.rect.height };
}
const sub = (a, b) => a.map((x, k) => x - b[k]);
const dot = (a, b) => a.reduce((s, x, k) => s + x * b[k], 0);
const len = (a) => Math.hypot(...a);
/** Distance from point p to the ray. */
function distanceToRay(p, ray) {
  const d = sub(p, ray.origin);
  const t = Math.max(0, dot(d, ray.dir));
  return len(sub(d, ray.dir.map((x) => x * t)));
}
/** Pixels a unit length covers at p seen face on. */
const pixelsPerUnit = (p, ray) => ray.height / 2 / (dot(sub(p, ray.origin), ray.forward) * ray.tan);

/** The step bound of a drag: a direction seen more than 60° from face on moves as if seen at 60° (GRAZING_FLOOR = 0.5 in handles.js). */
const FLOOR = 0.5;

/**
 * The drag frames' detail follows their cost, whatever the machine's speed:
 * with every animation frame made slower than the budget (a busy wait in
 * requestAnimationFrame), a pointer drag of θ comes down one level a frame
 * to the coarsest, each drawing fewer primitives, sending WebGL less than
 * the grid's vertices each frame (the drawn ones are a copy), and once it
 * rests the full grid is drawn (every face of the mesh). (That fast frames keep the finest
 * detail and cheap ones climb back is web/test/detail.test.mjs.)
 */
async function adaptiveDetail(page, idle) {
  const delay = 2 * FRAME_BUDGET_MS;
  await page.evaluate((ms) => {
    explorer.resetDetail();
    // The bytes sent to WebGL's buffers in drag quality (a full frame that
    // began while the test was slow to move again is not counted).
    window.uploaded = 0;
    const proto = WebGL2RenderingContext.prototype;
    window.realBuffer = { data: proto.bufferData, subData: proto.bufferSubData };
    const bytes = (data, count) => (!explorer.state.fast ? 0 : typeof data === 'number' ? data : count ? count * data.BYTES_PER_ELEMENT : data.byteLength);
    proto.bufferData = function (target, data, ...rest) {
      window.uploaded += bytes(data, rest[2]);
      return window.realBuffer.data.call(this, target, data, ...rest);
    };
    proto.bufferSubData = function (target, offset, data, srcOffset, count) {
      window.uploaded += bytes(data, count);
      return window.realBuffer.subData.call(this, target, offset, data, ...[srcOffset, count].filter((x) => x !== undefined));
    };
    window.realAnimationFrame = window.requestAnimationFrame;
    window.requestAnimationFrame = (callback) => window.realAnimationFrame((t) => {
      const start = performance.now();
      while (performance.now() - start < ms); // a slow frame, on any machine
      callback(t);
    });
  }, delay);
  const box = await page.locator('#theta').boundingBox();
  let x = box.x + box.width * ((await page.evaluate(() => explorer.state.design.theta_deg)) + 180) / 360;
  const y = box.y + box.height / 2;
  await page.mouse.move(x, y);
  await page.mouse.down();
  const seen = [];
  const uploads = [];
  for (let k = 0; k < 40 && seen.at(-1) !== DRAG_FACES.at(-1); k++) {
    const measured = await page.evaluate(() => {
      window.uploaded = 0;
      return explorer.state.latencies.length;
    });
    x += k % 2 ? -3 : 4;
    await page.mouse.move(x, y);
    // This move's frame measured (so that the next is drawn at the detail it leads to).
    await page.waitForFunction((n) => explorer.state.latencies.length > n, measured, { timeout: 10000 }).catch(() => {});
    const [detail, uploaded] = await page.evaluate(() => [explorer.frames().detail, window.uploaded]);
    uploads.push(uploaded);
    if (seen.at(-1) !== detail) seen.push(detail);
  }
  await page.mouse.up();
  await idle();
  const after = await page.evaluate(() => {
    window.requestAnimationFrame = window.realAnimationFrame;
    Object.assign(WebGL2RenderingContext.prototype, { bufferData: window.realBuffer.data, bufferSubData: window.realBuffer.subData });
    return { frames: explorer.frames(), rows: explorer.state.mesh.rows, cols: explorer.state.mesh.cols, fast: explorer.state.fast };
  });
  const byDetail = Object.entries(after.frames.byDetail).map(([d, n]) => [Number(d), n]).sort((a, b) => b[0] - a[0]);
  log(`drag frames made ${delay} ms slow: the mesh drawn by at most ${seen.join(' → ')} faces a side, ${byDetail.map(([d, n]) => `${n} primitives at ${d}`).join(', ')}`);
  assert.deepEqual(byDetail.map(([d]) => d), DRAG_FACES, `the drag came down one level a frame to the coarsest: ${seen.join(' → ')}`);
  byDetail.slice(1).forEach(([d, n], k) => assert.ok(n < byDetail[k][1], `a drag frame at ${d} faces a side draws fewer primitives than at ${byDetail[k][0]}: ${n} vs ${byDetail[k][1]}`));
  // The mesh's vertices alone, as f32: a drag frame at the coarsest level
  // sends a quarter of that at most (it sent the mesh's and the Gauss map's
  // vertices and normals, four times that, when it drew the whole grids' buffers).
  const grid = 12 * after.rows * after.cols;
  log(`bytes sent to WebGL's buffers by each drag move: ${uploads.join(', ')} (the mesh's vertices: ${grid})`);
  assert.ok(uploads.at(-1) < grid / 4, `a drag frame at the coarsest level sends WebGL less than a quarter of the mesh's ${grid} bytes of vertices: ${uploads}`);
  // Once it rests: full quality, every face of the mesh drawn.
  assert.equal(after.fast, false, 'full quality once the drag rests');
  const total = after.frames.steps.reduce((a, b) => a + b, 0);
  assert.ok(total >= 6 * (after.rows - 1) * (after.cols - 1), `the full frame draws every face: ${total} indices`);
}

/**
 * Real pointer drags (page.mouse) of each handle kind with the guide's plane
 * seen at a grazing angle (about 2° from edge on): the point stays in its
 * plane, moves no more than the pointer's path allows at its depth (a path of
 * P pixels moves it at most P / (FLOOR × pixels per unit)), and ends within the
 * pointer's path (in units at its depth) of the pointer's ray.
 */
async function grazingDrags(page, snapshot, idle) {
  const cases = [
    // example, guide, handle, plane normal, the design's point of the handle
    ['default-design.json', 'v', 2, [1, 0, 0], (d) => d.guide_v.bspline.control_points[2]],
    ['contract.json', 'u', 2, [0, 1, 0], (d) => d.guide_u.points[2]],
    ['fig2-enneper.json', 'u', 2, [0, 1, 0], (d) => sumOf(d.guide_u.parabola.start, d.guide_u.parabola.tangent, d.guide_u.parabola.quadratic)],
    ['fig2-enneper.json', 'v', 1, [1, 0, 0], (d) => sumOf(d.guide_v.parabola.start, d.guide_v.parabola.tangent.map((x) => x / 2))],
    ['fig12-torus.json', 'v', 'end', [1, 0, 0], (d) => arcEndOf(d.guide_v.arc)],
  ];
  for (const [name, guide, index, normal, pointOf] of cases) {
    const n = (await snapshot()).generations;
    const file = name === 'default-design.json' ? join(repo, 'web/src', name) : join(repo, 'examples', name);
    await page.setInputFiles('#load', file);
    await page.waitForFunction((k) => explorer.state.generations > k && explorer.idle(), n);
    const before = await snapshot();
    const p0 = pointOf(before.design);
    // Look along the plane, about 2° off it, from a distance of 4 sizes of the mesh.
    const size = meshRadius(before.vertices);
    const along = normal[0] ? [0, -1, 0] : [-1, 0, 0];
    const eye = [0, 1, 2].map((k) => p0[k] + size * (4 * along[k] + 0.14 * normal[k]) + (k === 2 ? 0.3 * size : 0));
    await page.evaluate(([e, t]) => explorer.look(e, t), [eye, p0]);
    await idle();
    const from = await page.evaluate(([g, k]) => explorer.handleOnScreen(g, k), [guide, index]);
    const cam = await page.evaluate(() => explorer.camera());
    const f0 = pixelsPerUnit(p0, rayAt(cam, from.x, from.y));
    // Across the plane's line on the screen and along it: 60 px in 6 moves.
    const [dx, dy] = [8, -6];
    await page.mouse.move(from.x, from.y);
    await page.mouse.down();
    for (let k = 1; k <= 6; k++) await page.mouse.move(from.x + dx * k, from.y + dy * k);
    await page.mouse.up();
    await idle();
    const after = await snapshot();
    const p = pointOf(after.design);
    const path = 6 * Math.hypot(dx, dy);
    const moved = len(sub(p, p0));
    const bound = path / (FLOOR * f0);
    const ray = rayAt(cam, from.x + 6 * dx, from.y + 6 * dy);
    const offRay = distanceToRay(p, ray);
    const offBound = path / pixelsPerUnit(p, ray);
    // Where the pointer's ray meets the plane: where a drag by that intersection would have sent the point.
    const hit = (dot(sub(p0, ray.origin), normal) / dot(ray.dir, normal));
    const jump = hit > 0 ? len(sub(ray.origin.map((o, k) => o + hit * ray.dir[k]), p0)).toFixed(1) : '∞ (behind the eye)';
    log(`grazing drag of ${name}'s guide_${guide} ${index} by ${path} px (${f0.toFixed(1)} px per unit face on): moved ${moved.toFixed(3)} (bound ${bound.toFixed(3)}; to the ray's meeting with the plane: ${jump}), ${offRay.toFixed(3)} from the pointer's ray (bound ${offBound.toFixed(3)})`);
    assert.ok(moved > 0, 'the point moved');
    assert.ok(Math.abs(dot(sub(p, p0), normal)) < 1e-9, `the point stays in its plane: ${p}`);
    assert.ok(moved <= 1.2 * bound, `a drag of ${path} px moved the point ${moved}, beyond ${bound}`);
    if (index === 'end') {
      assert.equal(Math.sign(after.design.guide_v.arc.angle_deg), Math.sign(before.design.guide_v.arc.angle_deg), 'the arc keeps its direction');
    } else {
      assert.ok(index === 1 || offRay <= 1.2 * offBound, `the point ends ${offRay} from the pointer's ray, beyond ${offBound}`);
    }
    if (!after.error) sameAsCli(after);
  }
}
const sumOf = (...vs) => [0, 1, 2].map((k) => vs.reduce((s, v) => s + v[k], 0));
/** The end of an arc guide, by Rodrigues' formula. */
function arcEndOf({ center, start, normal, angle_deg: a }) {
  const k = normal.map((x) => x / len(normal));
  const v = sub(start, center);
  const [c, s] = [Math.cos((a * Math.PI) / 180), Math.sin((a * Math.PI) / 180)];
  const cross = [k[1] * v[2] - k[2] * v[1], k[2] * v[0] - k[0] * v[2], k[0] * v[1] - k[1] * v[0]];
  return [0, 1, 2].map((i) => center[i] + v[i] * c + cross[i] * s + k[i] * dot(k, v) * (1 - c));
}
/** Half the diagonal of the vertices' bounding box. */
function meshRadius(flat) {
  const lo = [Infinity, Infinity, Infinity];
  const hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < flat.length; i++) { lo[i % 3] = Math.min(lo[i % 3], flat[i]); hi[i % 3] = Math.max(hi[i % 3], flat[i]); }
  return len(sub(hi, lo)) / 2;
}

/** A binary glTF read by hand (not by the writer): its JSON chunk and its BIN chunk. */
function readGlb(bytes) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  assert.equal(bytes.subarray(0, 4).toString('latin1'), 'glTF', 'GLB magic');
  assert.equal(view.getUint32(4, true), 2, 'glTF 2');
  assert.equal(view.getUint32(8, true), bytes.length, 'GLB length');
  const chunks = {};
  for (let at = 12; at < bytes.length;) {
    const length = view.getUint32(at, true);
    chunks[bytes.subarray(at + 4, at + 8).toString('latin1').replace(/\0/g, '')] = bytes.subarray(at + 8, at + 8 + length);
    at += 8 + length;
  }
  return { json: JSON.parse(chunks.JSON.toString('utf8')), bin: chunks.BIN };
}

/** The elements of glTF accessor `index` as numbers (float32 or unsigned ints), from its buffer view in `bin`. */
function accessor({ json, bin }, index) {
  const a = json.accessors[index];
  const view = json.bufferViews[a.bufferView];
  const [Type, width] = { 5126: [Float32Array, 4], 5125: [Uint32Array, 4], 5123: [Uint16Array, 2] }[a.componentType];
  const n = a.count * { SCALAR: 1, VEC3: 3 }[a.type];
  const start = bin.byteOffset + (view.byteOffset ?? 0) + (a.byteOffset ?? 0);
  return { count: a.count, values: new Type(bin.buffer.slice(start, start + n * width)) };
}

/**
 * Export GLB and Export 3DM of the design shown (`shown`, a snapshot), each
 * downloaded by a click and read by what did not write it: the GLB's chunks
 * by hand, the .3dm by rhino3dm in node. Against `monge generate`: the .3dm's
 * mesh has its vertices bit for bit (f64) and its OBJ's quads, the guides are
 * the mesh's first column and row, each panel a closed polyline through its
 * face's corners; the GLB has the vertices in f32 and two triangles a quad,
 * and is `monge generate -o mesh.glb`'s file byte for byte. rhino3dm is
 * loaded on the first .3dm export, not before; its load is timed (reported).
 */
async function rhinoAndGlb(page, shown, noise) {
  const began = performance.now();
  const flat = sameAsCli(shown); // and out.json of its design, current.json
  const { rows, cols } = shown;
  const faces = (rows - 1) * (cols - 1);
  spawnSync(monge, ['generate', 'current.json', '-o', 'out.obj'], { cwd: work });
  spawnSync(monge, ['generate', 'current.json', '-o', 'out.glb'], { cwd: work });
  const quads = readFileSync(join(work, 'out.obj'), 'utf8').split('\n').filter((l) => l.startsWith('f '))
    .map((l) => l.split(' ').slice(1).map((c) => Number(c.split('/')[0]) - 1));
  assert.equal(quads.length, faces);
  const save = async (button, name) => {
    const start = performance.now();
    const [file] = await Promise.all([page.waitForEvent('download'), page.click(button)]);
    assert.equal(file.suggestedFilename(), name);
    await file.saveAs(join(work, name));
    return { bytes: readFileSync(join(work, name)), ms: performance.now() - start };
  };

  const glb = await save('#export-glb', 'mesh.glb');
  assert.ok(glb.bytes.equals(readFileSync(join(work, 'out.glb'))), 'Export GLB is monge generate -o mesh.glb byte for byte');
  const gltf = readGlb(glb.bytes);
  const [primitive] = gltf.json.meshes.flatMap((m) => m.primitives);
  const positions = accessor(gltf, primitive.attributes.POSITION);
  const indices = accessor(gltf, primitive.indices);
  assert.equal(positions.count, rows * cols, 'a GLB position per vertex');
  assert.equal(indices.count, 6 * faces, 'two triangles a quad');
  const off = flat.filter((x, k) => !Object.is(Math.fround(x), positions.values[k])).length;
  assert.equal(off, 0, `${off} GLB coordinates are not the f32 of monge generate's`);

  assert.ok(!noise.requests.some((r) => r.includes('rhino3dm')), 'rhino3dm is not loaded before the first .3dm export');
  const loads = {};
  const started = (r) => { if (r.url().includes('rhino3dm')) loads[r.url().split('/').pop()] = { start: performance.now() }; };
  const finished = (r) => { const l = loads[r.url().split('/').pop()]; if (l) l.ms = performance.now() - l.start; };
  page.on('request', started);
  page.on('requestfinished', finished);
  const rhinoFile = await save('#export-3dm', 'mesh.3dm');
  page.off('request', started);
  page.off('requestfinished', finished);
  const rhino = await rhino3dm();
  const doc = rhino.File3dm.fromByteArray(new Uint8Array(rhinoFile.bytes));
  const layers = doc.layers();
  const layerNames = Array.from({ length: layers.count }, (_, k) => layers.get(k).name);
  assert.deepEqual(layerNames, ['mesh', 'guide_u', 'guide_v', 'panels']);
  const objects = doc.objects();
  assert.equal(objects.count, 3 + faces, 'the mesh, two guides and a polyline a panel');
  const byName = {};
  const panels = [];
  for (let k = 0; k < objects.count; k++) {
    const object = objects.get(k);
    const { name, layerIndex } = object.attributes();
    const geometry = object.geometry();
    if (layerNames[layerIndex] === 'panels') panels.push({ name, points: Array.from({ length: geometry.pointCount }, (_, j) => geometry.point(j)) });
    else byName[name] = { layer: layerNames[layerIndex], geometry };
  }
  const mesh = byName.mesh.geometry;
  assert.equal(byName.mesh.layer, 'mesh');
  assert.ok(mesh.vertices().useDoublePrecisionVertices, 'double-precision vertices');
  assert.equal(mesh.vertices().count, rows * cols);
  const read = mesh.vertices().toPoint3dArray().flat();
  const differ = flat.filter((x, k) => !Object.is(x, read[k])).length;
  assert.equal(differ, 0, `${differ} of the .3dm's vertex coordinates differ from monge generate's`);
  assert.equal(mesh.faces().count, faces);
  for (let f = 0; f < faces; f++) assert.deepEqual(mesh.faces().get(f), quads[f], `quad ${f} of the .3dm`);
  const vertex = (k) => flat.slice(3 * k, 3 * k + 3);
  for (const [guide, along] of [['u', (i) => vertex(i * cols)], ['v', (j) => vertex(j)]]) {
    const { layer, geometry } = byName[`guide_${guide}`];
    assert.equal(layer, `guide_${guide}`);
    const n = guide === 'u' ? rows : cols;
    assert.equal(geometry.pointCount, n, `guide_${guide}: a polyline through its ${n} samples`);
    for (let i = 0; i < n; i++) assert.deepEqual(geometry.point(i), along(i), `guide_${guide} sample ${i} is the mesh's vertex`);
  }
  for (const [f, panel] of panels.entries()) {
    const [i, j] = [Math.floor(f / (cols - 1)), f % (cols - 1)];
    assert.equal(panel.name, `panel ${i} ${j}`);
    assert.deepEqual(panel.points, [...quads[f], quads[f][0]].map(vertex), `panel ${i} ${j}: a closed polyline through its corners`);
  }
  doc.delete();
  const second = await save('#export-3dm', 'mesh.3dm');
  assert.ok(second.bytes.length > 0, 'a second export writes again');
  assert.deepEqual(await page.evaluate(() => [document.getElementById('export-3dm').disabled, document.getElementById('export-3dm').ariaBusy]), [false, 'false'], 'the button is back');
  const mb = (n) => `${(n / 1e6).toFixed(2)} MB`;
  const wasm = readFileSync(join(repo, 'web/dist/rhino3dm.wasm')).length;
  log(`Export GLB (${mb(glb.bytes.length)}) = monge generate -o mesh.glb byte for byte; Export 3DM (${mb(rhinoFile.bytes.length)}, ${rows} × ${cols} vertices, ${faces} panels) read by rhino3dm: vertices bit for bit`);
  log(`rhino3dm loaded on the first 3DM export only (${mb(wasm)} wasm): requests ${Object.entries(loads).map(([f, l]) => `${f} ${l.ms?.toFixed(0)} ms`).join(', ')}; first export ${rhinoFile.ms.toFixed(0)} ms (load + write), second ${second.ms.toFixed(0)} ms; these checks took ${((performance.now() - began) / 1000).toFixed(1)} s`);
}

/**
 * A refused edit: the page says what and where (the field outlined), keeps
 * the last valid mesh and exports it (labelled so), clears its warnings; a
 * refusal mid-drag of θ ends in full quality.
 */
async function neverSilent(page, snapshot, idle) {
  const n = (await snapshot()).generations;
  await page.setInputFiles('#load', join(repo, 'examples', 'fig10-arbitrary.json'));
  await page.waitForFunction((k) => explorer.state.generations > k && explorer.idle(), n);
  const valid = await snapshot();
  // θ dragged by the pointer from the admissible band into the refused one.
  const slider = await page.locator('#theta').boundingBox();
  const x = (deg) => slider.x + 5 + ((deg + 180) / 360) * (slider.width - 10);
  await page.mouse.move(x(valid.design.theta_deg), slider.y + slider.height / 2);
  await page.mouse.down();
  for (let k = 1; k <= 8; k++) await page.mouse.move(x(valid.design.theta_deg) - (k * (valid.design.theta_deg - 20)) / 8, slider.y + slider.height / 2);
  await page.mouse.up();
  await idle();
  const refused = await page.evaluate(() => ({
    theta: explorer.state.design.theta_deg,
    fast: explorer.state.fast,
    error: document.getElementById('error').textContent,
    errorShown: !document.getElementById('error').hidden,
    where: document.getElementById('error-source').textContent,
    invalid: [...document.querySelectorAll('.invalid')].map((e) => e.id),
    note: document.getElementById('last-valid').hidden ? null : document.getElementById('last-valid').textContent,
    label: document.getElementById('export-obj').textContent,
    warnings: document.getElementById('warnings').children.length,
    obj: explorer.exported('obj'),
    valid: JSON.parse(explorer.state.valid),
  }));
  writeFileSync(join(work, 'refused.json'), JSON.stringify({ ...valid.design, theta_deg: refused.theta }));
  const cli = generate('refused.json');
  assert.equal(cli.status, 2, `monge generate refuses θ = ${refused.theta}°`);
  assert.ok(refused.errorShown && refused.error === cli.stderr.replace(/^error: /, '').trimEnd().replace('refused.json', '<input>'), refused.error);
  assert.deepEqual(refused.invalid, ['theta'], 'the θ slider is marked');
  assert.match(refused.where, /θ/);
  assert.ok(refused.note && refused.note.includes('last valid design'), 'the page says it shows the last valid design');
  assert.equal(refused.label, 'Export OBJ (last valid design)');
  assert.equal(refused.warnings, 0, 'no warnings of another design');
  assert.equal(refused.fast, false, 'a refusal mid-drag ends in full quality');
  // The export is the last valid design's mesh (the last θ of the drag monge
  // took), as monge generate writes it.
  assert.deepEqual({ ...refused.valid, theta_deg: 0 }, { ...valid.design, theta_deg: 0 }, 'the last valid design is the dragged one at another θ');
  writeFileSync(join(work, 'valid.json'), JSON.stringify(refused.valid));
  spawnSync(monge, ['generate', 'valid.json', '-o', 'valid.obj'], { cwd: work });
  assert.equal(refused.obj, readFileSync(join(work, 'valid.obj'), 'utf8'), 'Export OBJ writes the last valid design');
  log(`θ dragged to ${refused.theta}°: "${refused.error.split('\n')[0].slice(0, 70)}…", ${refused.where} Export OBJ = monge generate of the last valid design (θ = ${refused.valid.theta_deg}°)`);
  // Undo: back to the valid design, nothing marked.
  await page.keyboard.press('Control+z');
  await idle();
  const back = await page.evaluate(() => ({ theta: explorer.state.design.theta_deg, invalid: document.querySelectorAll('.invalid').length, error: !document.getElementById('error').hidden, label: document.getElementById('export-obj').textContent }));
  assert.deepEqual(back, { theta: valid.design.theta_deg, invalid: 0, error: false, label: 'Export OBJ' }, 'undo returns to the valid design');
}

/**
 * Undo and redo: every edit (θ, samples, mesh kind, offset, a handle drag, a
 * loaded file) is one step; Ctrl+Z and Ctrl+Shift+Z (focus on θ's slider, which
 * must not move) give back the very same design bytes, step by step.
 */
async function undoRedo(page, snapshot, idle) {
  const text = () => page.evaluate(() => JSON.stringify({ design: explorer.state.design, offset: explorer.state.offset }));
  const steps = [await text()];
  const edits = {
    'θ': async () => { await page.focus('#theta'); await page.keyboard.press('ArrowRight'); },
    samples: async () => { await page.fill('#samples-u', '31'); await page.dispatchEvent('#samples-u', 'change'); },
    kind: async () => { await page.selectOption('#kind', 'conical'); },
    offset: async () => { await page.fill('#offset', '0.1'); await page.dispatchEvent('#offset', 'change'); },
    drag: async () => {
      await page.click('#fit');
      await idle();
      const from = await page.evaluate(() => explorer.handleOnScreen('u', 2));
      const grabbed = await page.evaluate(([x, y]) => document.elementFromPoint(x, y)?.tagName, [from.x, from.y]);
      assert.equal(grabbed, 'CANVAS', `guide_u's point 2 is on the view at ${from.x}, ${from.y}`);
      await page.mouse.move(from.x, from.y);
      await page.mouse.down();
      for (let k = 1; k <= 3; k++) await page.mouse.move(from.x + 5 * k, from.y - 4 * k);
      await page.mouse.up();
    },
    file: async () => { await page.setInputFiles('#load', join(repo, 'examples', 'fig13-freeform.json')); },
  };
  for (const [what, edit] of Object.entries(edits)) {
    await edit();
    await idle();
    const now = await text();
    assert.notEqual(now, steps.at(-1), `the ${what} edit changed the design`);
    steps.push(now);
  }
  assert.deepEqual(await page.evaluate(() => explorer.history().redo), 0);
  await page.focus('#theta');
  for (let k = steps.length - 2; k >= 0; k--) {
    await page.keyboard.press('Control+z');
    await idle();
    assert.equal(await text(), steps[k], `undo gives back step ${k} byte for byte`);
    assert.equal(Number(await page.inputValue('#theta')), JSON.parse(steps[k]).design.theta_deg, 'the slider shows the design\'s θ');
  }
  sameAsCli(await snapshot());
  for (let k = 1; k < steps.length; k++) {
    await page.keyboard.press(k % 2 ? 'Control+Shift+z' : 'Control+y');
    await idle();
    assert.equal(await text(), steps[k], `redo gives back step ${k} byte for byte`);
  }
  await page.click('#undo');
  await idle();
  assert.equal(await text(), steps.at(-2), 'the Undo button');
  await page.click('#redo');
  await idle();
  assert.equal(await text(), steps.at(-1), 'the Redo button');
  log(`undo/redo: ${steps.length - 1} edits (${Object.keys(edits).join(', ')}) undone and redone with Ctrl+Z / Ctrl+Shift+Z, each design byte for byte`);
}

/**
 * A guide's kind changed from the panel: each kind keeps the guide's start and
 * end (measured here from the design file's keys) and gives a design monge
 * takes, the page's mesh being monge generate's.
 */
async function guideKinds(page, snapshot, idle) {
  await page.fill('#offset', '0');
  await page.dispatchEvent('#offset', 'change');
  const n = (await snapshot()).generations;
  await page.setInputFiles('#load', join(repo, 'web/src/default-design.json'));
  await page.waitForFunction((k) => explorer.state.generations > k && explorer.idle(), n);
  const endsOf = (g) => {
    if (g.parabola) return [g.parabola.start, sumOf(g.parabola.start, g.parabola.tangent, g.parabola.quadratic)];
    if (g.arc) return [g.arc.start, arcEndOf(g.arc)];
    const points = g.points ?? g.bspline.control_points;
    return [points[0], points.at(-1)];
  };
  const original = endsOf((await snapshot()).design.guide_u);
  for (const kind of ['parabola', 'arc', 'points', 'bspline']) {
    await page.selectOption('#kind-u', kind);
    await idle();
    const now = await snapshot();
    assert.equal(now.error, null, `guide_u as ${kind}: ${now.error}`);
    assert.ok(now.design.guide_u[kind], `guide_u is a ${kind}`);
    const [a, b] = endsOf(now.design.guide_u);
    const off = Math.max(len(sub(a, original[0])), len(sub(b, original[1])));
    assert.ok(off < 1e-9, `guide_u as ${kind} keeps its start and end (off by ${off})`);
    sameAsCli(now);
  }
  log('guide kinds: guide_u as parabola, arc, points and bspline, start and end kept; monge generate = page bit for bit');
}

/**
 * The page opened from a file (file://) says how to serve it; served, the θ
 * slider's admissible band is drawn (green pixels on it).
 */
async function firstImpressions(context, url) {
  const page = await context.newPage();
  try {
    await page.goto(`file://${join(repo, 'web/dist/index.html')}`);
    const note = page.locator('#file-note');
    assert.ok(await note.isVisible(), 'the page opened from a file says so');
    assert.match(await note.textContent(), /python3 -m http\.server.*monge explore/s);
    log(`file://: ${(await note.textContent()).replace(/\s+/g, ' ').trim()}`);
    await page.goto(`${url}?x`);
    await page.waitForFunction(() => window.explorer && window.explorer.idle() && window.explorer.state.generations > 0);
    assert.ok(await note.isHidden(), 'no such note when served');
    const n = await page.evaluate(() => explorer.state.generations);
    await page.setInputFiles('#load', join(repo, 'examples', 'fig10-arbitrary.json'));
    await page.waitForFunction((k) => explorer.state.generations > k && explorer.idle(), n);
    const png = (await page.locator('#theta').screenshot()).toString('base64');
    const green = await page.evaluate(async (data) => {
      const image = new Image();
      image.src = `data:image/png;base64,${data}`;
      await image.decode();
      const canvas = Object.assign(document.createElement('canvas'), { width: image.width, height: image.height });
      const context2d = canvas.getContext('2d');
      context2d.drawImage(image, 0, 0);
      const { data: px } = context2d.getImageData(0, 0, image.width, image.height);
      let count = 0;
      for (let i = 0; i < px.length; i += 4) if (Math.abs(px[i] - 0xb5) < 12 && Math.abs(px[i + 1] - 0xe3) < 12 && Math.abs(px[i + 2] - 0xb5) < 12) count += 1;
      return { count, total: px.length / 4 };
    }, png);
    assert.ok(green.count > 0.05 * green.total, `the admissible band is drawn on the slider: ${green.count} of ${green.total} pixels green`);
    log(`θ slider: ${green.count} of ${green.total} pixels in the admissible band's green`);
  } finally {
    await page.close();
  }
}

async function main() {
  const { server, url } = await startStatic();
  const context = await chromium.launchPersistentContext(join(work, 'profile'), {
    executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
    headless: true,
    viewport: { width: 1280, height: 800 },
    acceptDownloads: true,
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
      '--disable-component-update', '--disable-sync'],
  });
  try {
    const page = context.pages()[0] ?? await context.newPage();
    const pageErrors = [];
    page.on('pageerror', (e) => pageErrors.push(e.message));
    const noise = watchConsole(page);
    page.setDefaultTimeout(60000); // a loaded 2-core machine renders WebGL in software
    // The main thread's long tasks (over 50 ms), as the browser reports them.
    await context.addInitScript(() => {
      window.longTasks = [];
      new PerformanceObserver((list) => window.longTasks.push(...list.getEntries())).observe({ type: 'longtask' });
    });
    await page.goto(url);
    const idle = () => page.waitForFunction(() => window.explorer && window.explorer.idle() && window.explorer.state.generations > 0);
    await firstImpressions(context, url);
    const snapshot = async () => ({ ...await page.evaluate(() => ({
      design: JSON.parse(JSON.stringify(explorer.state.design)),
      rows: explorer.state.mesh.rows,
      cols: explorer.state.mesh.cols,
      metrics: document.getElementById('metrics').textContent,
      error: document.getElementById('error').hidden ? null : document.getElementById('error').textContent,
      generations: explorer.state.generations,
      geometries: explorer.frames().geometries,
      // Once idle, a drag's answer (drawn in drag quality, without metrics) has
      // been followed by the full one.
      full: !explorer.state.fast && !document.getElementById('metrics').classList.contains('pending'),
    })), vertices: await numbers(page, 'vertices') });
    await idle();
    const first = await snapshot();
    assert.equal(first.rows, 101, 'the default design has 100 × 100 faces');
    assert.equal(first.cols, 101);
    log(`page up at ${url}: ${first.rows} × ${first.cols} vertices`);

    // θ: a click on the slider, then the keyboard.
    const slider = await page.locator('#theta').boundingBox();
    await page.mouse.click(slider.x + slider.width * 0.42, slider.y + slider.height / 2);
    await page.keyboard.press('ArrowRight');
    await idle();
    const turned = await snapshot();
    assert.notEqual(turned.design.theta_deg, first.design.theta_deg, 'θ moved');
    assert.notDeepEqual(turned.vertices.slice(-3), first.vertices.slice(-3), 'the mesh changed with θ');
    assert.notEqual(turned.metrics, first.metrics, 'the metrics changed with θ');
    assert.ok(turned.full, 'full quality and metrics once θ rests');
    log(`θ ${first.design.theta_deg}° → ${turned.design.theta_deg}°`);
    // A θ step rewrites only the page's labels that change: the others (the
    // admissible range, the export buttons, the warnings, …) cost no layout.
    const rewritten = await page.evaluate(() => {
      const watch = new MutationObserver(() => {});
      watch.observe(document.getElementById('panel'), { subtree: true, childList: true, characterData: true, attributes: true });
      const theta = document.getElementById('theta');
      theta.value = String(Number(theta.value) + 1);
      theta.dispatchEvent(new Event('input'));
      const records = watch.takeRecords();
      watch.disconnect();
      const named = (node) => (node.nodeType === Node.ELEMENT_NODE && node.id ? node.id : named(node.parentNode));
      return [...new Set(records.map((r) => (r.type === 'attributes' ? `${named(r.target)}[${r.attributeName}]` : named(r.target))))];
    });
    await page.evaluate(() => {
      const theta = document.getElementById('theta');
      theta.value = String(Number(theta.value) - 1);
      theta.dispatchEvent(new Event('input'));
    });
    await idle();
    assert.deepEqual(rewritten.filter((what) => what !== 'theta-value' && what !== 'metrics[class]'), [], `a θ step rewrites only θ's value (and marks the metrics pending): ${rewritten}`);

    // Drag guide_u's third control point.
    const from = await page.evaluate(() => explorer.handleOnScreen('u', 3));
    await page.mouse.move(from.x, from.y);
    await page.mouse.down();
    for (let k = 1; k <= 5; k++) await page.mouse.move(from.x + 6 * k, from.y - 8 * k);
    await page.mouse.up();
    await idle();
    const dragged = await snapshot();
    const [before, after] = [turned, dragged].map((s) => s.design.guide_u.bspline.control_points);
    assert.notDeepEqual(after[3], before[3], 'the control point moved');
    assert.deepEqual(after[0], before[0], 'the shared start point stays');
    assert.ok(Math.abs(after[3][1]) < 1e-9, `the point stays in guide_u's plane y = 0: ${after[3]}`);
    assert.notDeepEqual(dragged.vertices, turned.vertices, 'the mesh changed with the control point');
    assert.notEqual(dragged.metrics, turned.metrics, 'the metrics changed with the control point');
    assert.ok(dragged.full, 'full quality and metrics once the point rests');
    // Each move draws the handles again: what it replaces is freed.
    assert.equal(dragged.geometries, turned.geometries, 'a drag leaves WebGL holding the buffers of as many geometries as before');
    log(`dragged guide_u P3 ${before[3]} → ${after[3].map((x) => x.toFixed(3))}`);

    // The page's mesh is `monge generate`'s on the page's design, bit for bit,
    // and so are its exports.
    const flat = sameAsCli(dragged);
    assert.equal(await page.evaluate(() => explorer.exported('json')), readFileSync(join(work, 'out.json'), 'utf8'), 'JSON export');
    spawnSync(monge, ['generate', 'current.json', '-o', 'out.obj'], { cwd: work });
    assert.equal(await page.evaluate(() => explorer.exported('obj')), readFileSync(join(work, 'out.obj'), 'utf8'), 'OBJ export');
    assert.ok(dragged.metrics.includes(`${dragged.rows} × ${dragged.cols} vertices`), 'the page shows the grid size');
    log(`monge generate = page: ${flat.length} coordinates bit for bit, OBJ and JSON exports byte for byte`);
    // Export OBJ clicked while a drag's preview is drawn (θ moved in the same
    // task, whatever the machine's speed): the file is the design's own mesh.
    const [during] = await Promise.all([page.waitForEvent('download'), page.evaluate(() => {
      const theta = document.getElementById('theta');
      theta.value = String(Number(theta.value) + 1);
      theta.dispatchEvent(new Event('input'));
      window.previewed = { preview: explorer.state.preview, rows: explorer.state.mesh.rows };
      document.getElementById('export-obj').click();
    })]);
    await during.saveAs(join(work, 'during.obj'));
    await idle();
    const previewed = await page.evaluate(() => window.previewed);
    assert.ok(previewed.preview && previewed.rows < dragged.rows, `a preview was drawn: ${JSON.stringify(previewed)}`);
    sameAsCli(await snapshot());
    spawnSync(monge, ['generate', 'current.json', '-o', 'out.obj'], { cwd: work });
    assert.equal(readFileSync(join(work, 'during.obj'), 'utf8'), readFileSync(join(work, 'out.obj'), 'utf8'), 'Export OBJ during a drag writes the design\'s own mesh');
    log(`Export OBJ during a drag (a preview of ${previewed.rows} × ${previewed.rows} vertices drawn) = monge generate of the design, byte for byte`);
    await page.evaluate((deg) => {
      const theta = document.getElementById('theta');
      theta.value = String(deg);
      theta.dispatchEvent(new Event('input'));
    }, dragged.design.theta_deg);
    await idle();
    assert.deepEqual((await snapshot()).design, dragged.design, 'θ back where it was');

    // Save the design, change θ, load it back.
    const [saved] = await Promise.all([page.waitForEvent('download'), page.click('#save')]);
    const savedPath = join(work, 'saved.json');
    await saved.saveAs(savedPath);
    assert.deepEqual(JSON.parse(readFileSync(savedPath, 'utf8')), dragged.design, 'the saved file is the design');
    await page.focus('#theta');
    for (let k = 0; k < 5; k++) await page.keyboard.press('ArrowLeft');
    await idle();
    assert.notEqual((await snapshot()).design.theta_deg, dragged.design.theta_deg);
    const drawn = (await snapshot()).generations;
    await page.setInputFiles('#load', savedPath);
    await page.waitForFunction((n) => explorer.state.generations > n && explorer.idle(), drawn);
    const loaded = await snapshot();
    assert.deepEqual(loaded.design, dragged.design, 'the loaded design is the saved one');
    assert.deepEqual(loaded.vertices, dragged.vertices, 'and gives the same mesh');
    assert.equal(await page.inputValue('#theta'), String(dragged.design.theta_deg));
    log('saved and loaded the design');

    // Bad designs: the page shows the CLI's message and keeps working.
    const bad = {
      'syntax.json': '{ "theta_deg": 30,\n  "guide_u": { "points": [[0,0,0],[1,0,0]] \n',
      'unknown-key.json': JSON.stringify({ ...dragged.design, thetadeg: 3 }, null, 2),
      'not-orthogonal.json': JSON.stringify({ theta_deg: 30, guide_u: { points: [[0, 0, 0], [1, 0, 0], [2, 0, 0.5]] }, guide_v: { points: [[0, 0, 0], [1, 1, 0], [1, 2, 0.5]] } }),
      'inadmissible.json': readFileSync(join(repo, 'examples/fig10-arbitrary.json'), 'utf8').replace(/"theta_deg"\s*:\s*[-\d.]+/, '"theta_deg": 5'),
    };
    for (const [name, text] of Object.entries(bad)) {
      writeFileSync(join(work, name), text);
      const expected = generate(name);
      assert.equal(expected.status, 2, `monge generate refuses ${name}`);
      const message = expected.stderr.replace(/^error: /, '').trimEnd();
      const before = await page.locator('#error').textContent();
      await page.setInputFiles('#load', join(work, name));
      // Until the page shows a new message (however long the machine takes), then which.
      const changed = (b) => { const e = document.getElementById('error'); return !e.hidden && e.textContent !== b; };
      await page.waitForFunction(changed, before);
      const shown = await page.locator('#error').textContent();
      assert.equal(shown, message, `the page shows the CLI's message for ${name}`);
      log(`${name}: ${message.split('\n')[0]}`);
    }
    assert.deepEqual((await snapshot()).design, dragged.design, 'a refused file leaves the design as it was');

    // Latency of θ at 100 × 100 and 300 × 300 faces, from the input event to the
    // end of the task of the frame that draws it: keyboard steps, one at a time,
    // then a pointer drag of the slider's thumb (20 moves) that rests, during
    // which the long tasks (over 50 ms, PerformanceObserver) are counted.
    // Reported, not asserted: speed is measured, never checked by a timed test
    // (this machine draws WebGL in software and may be loaded). Asserted is how
    // the work is split, which the machine does not change: a drag frame draws
    // no more at 300 × 300 than at 100 × 100 (every k-th curvature line), and the
    // full-quality frame is drawn in steps of at most `stepIndices` indices each.
    const quantile = (values, q) => [...values].sort((x, y) => x - y)[Math.min(values.length - 1, Math.floor(q * values.length))];
    const latency = async () => {
      await page.evaluate(() => { explorer.state.latencies.length = 0; });
      await page.focus('#theta');
      // One press at a time, each timed from its own input to the frame that shows
      // it (two presses before a frame would share it, timed from the earlier).
      for (let k = 0; k < latencySteps; k++) {
        await page.keyboard.press(k % 2 ? 'ArrowLeft' : 'ArrowRight');
        await idle();
      }
      const keys = await page.evaluate(() => explorer.state.latencies);
      assert.ok(keys.length >= latencySteps, 'every step drew a frame');
      const box = await page.locator('#theta').boundingBox();
      let x = box.x + box.width * ((await page.evaluate(() => explorer.state.design.theta_deg)) + 180) / 360;
      const y = box.y + box.height / 2;
      const since = await page.evaluate(() => {
        explorer.state.latencies.length = 0;
        explorer.state.generated.length = 0;
        explorer.resetDetail(); // the drag's first frame at the finest detail
        return performance.now();
      });
      await page.mouse.move(x, y);
      await page.mouse.down();
      for (let k = 0; k < 20; k++) {
        x += k < 10 ? 2 : -2;
        await page.mouse.move(x, y);
      }
      await page.mouse.up();
      await idle();
      const cycle = await page.evaluate((t) => ({
        latencies: explorer.state.latencies,
        long: window.longTasks.filter((e) => e.startTime >= t).map((e) => e.duration),
        frames: explorer.frames(),
        faces: (explorer.state.mesh.rows - 1) * (explorer.state.mesh.cols - 1),
        generated: explorer.state.generated,
        vertices: explorer.state.mesh.rows * explorer.state.mesh.cols,
      }), since);
      const { frames } = cycle;
      const figures = (values) => `median ${quantile(values, 0.5).toFixed(1)} ms, p95 ${quantile(values, 0.95).toFixed(1)} ms`;
      const side = Math.round(Math.sqrt(cycle.faces));
      log(`θ at ${side} × ${side} faces, input → end of the frame's task: ${keys.length} keyboard steps ${figures(keys)}; ` +
        `a pointer drag of ${cycle.latencies.length} frames ${figures(cycle.latencies)}; long tasks (> 50 ms) during the drag and its rest: ` +
        `${cycle.long.length}${cycle.long.length ? `, the longest ${Math.max(...cycle.long).toFixed(0)} ms` : ''}; ` +
        `a drag frame draws ${frames.drag} primitives (the mesh by at most ${frames.detail} faces a side), the full-quality frame ${frames.steps.length} steps of at most ${Math.max(...frames.steps)} indices`);
      assert.ok(frames.steps.every((n) => n <= frames.stepIndices), `each step of the full frame draws at most ${frames.stepIndices} indices: ${frames.steps}`);
      // Each move's mesh was generated at the drag frames' detail (its guides
      // sampled as coarsely), at most the finest level's vertices, whatever the
      // grid: never the design's own mesh, which is generated once the drag
      // rests (or, on a machine slow enough, each time it rests on the way).
      const { generated, vertices } = cycle;
      const coarse = (DRAG_FACES[0] + 1) ** 2;
      const previews = generated.filter((n) => n <= coarse);
      log(`the module generated, during the drag and its rest: ${previews.length} meshes of at most ${Math.max(...previews)} vertices, ${generated.length - previews.length} of ${vertices} (the design's)`);
      assert.ok(generated.every((n) => n <= coarse || n === vertices), `each mesh generated is a drag's preview (at most ${coarse} vertices) or the design's: ${generated}`);
      assert.ok(previews.length >= cycle.latencies.length, `each drag frame shows a preview's mesh: ${previews.length} generated for ${cycle.latencies.length} frames`);
      assert.equal(generated.at(-1), vertices, 'once it rests, the design\'s own mesh is generated');
      // The mesh shown once the drag rests is monge generate's (f32, as drawn).
      const flat = sameAsCli(await snapshot());
      const shown = await numbers(page, 'drawnVertices');
      assert.equal(shown.length, flat.length);
      const off = flat.filter((c, k) => Math.fround(c) !== shown[k]).length;
      assert.equal(off, 0, `${off} drawn coordinates are not the f32 of monge generate's`);
      log(`the drag at ${side} × ${side} rests on monge generate's mesh: ${flat.length} coordinates drawn as its f32`);
      return { side, frames };
    };
    const at100 = await latency();
    await adaptiveDetail(page, idle);
    // Two inputs 200 ms apart in one task: the frame after is the first to
    // show either, and the readout counts from the earlier.
    const apart = await page.evaluate(() => {
      explorer.state.latencies.length = 0;
      const theta = document.getElementById('theta');
      const step = (d) => {
        theta.value = String(Number(theta.value) + d);
        const input = new Event('input');
        theta.dispatchEvent(input);
        return input.timeStamp;
      };
      const first = step(1);
      while (performance.now() - first < 200); // no frame in between
      return step(-1) - first;
    });
    await idle();
    const counted = await page.evaluate(() => explorer.state.latencies);
    assert.equal(counted.length, 1, `one frame shows both inputs: ${counted}`);
    assert.ok(counted[0] >= apart, `the readout counts from the earlier input: ${counted[0]} ms, the inputs ${apart} ms apart`);
    // A long drag (twice as many moves as the record keeps, in one task)
    // leaves the record of the meshes generated at its bound: the latest.
    const record = await page.evaluate(() => {
      explorer.state.generated.length = 0;
      const theta = document.getElementById('theta');
      for (let k = 0; k < 2 * explorer.generatedKept; k++) {
        theta.value = String(Number(theta.value) + (k % 2 ? -1 : 1));
        theta.dispatchEvent(new Event('input'));
      }
      return { kept: explorer.generatedKept, length: explorer.state.generated.length };
    });
    await idle();
    assert.equal(record.length, record.kept, `${2 * record.kept} drag moves leave the latest ${record.kept} meshes generated on record: ${record.length}`);
    for (const g of ['u', 'v']) {
      await page.fill(`#samples-${g}`, '301');
      await page.dispatchEvent(`#samples-${g}`, 'change');
    }
    await idle();
    assert.equal((await snapshot()).rows, 301, '300 × 300 faces');
    const at300 = await latency();
    // The guides are drawn whole, in all their samples: 200 more segments each at
    // 300 × 300. Compared at each detail both drags drew (the first frame of
    // each is at the finest).
    const guides = 2 * (at300.side - at100.side);
    const details = Object.keys(at300.frames.byDetail).filter((d) => d in at100.frames.byDetail);
    assert.ok(details.length > 0, `both drags drew a frame at the finest detail: ${Object.keys(at300.frames.byDetail)} and ${Object.keys(at100.frames.byDetail)}`);
    for (const d of details) {
      const [big, small] = [at300.frames.byDetail[d], at100.frames.byDetail[d]];
      assert.ok(big <= small + guides, `a drag frame at ${d} faces a side draws as much at 300 × 300 as at 100 × 100 but for the guides' ${guides} more segments: ${big} vs ${small} primitives`);
    }
    assert.ok(at300.frames.steps.length > 1, 'the full frame at 300 × 300 is drawn in several steps');
    for (const g of ['u', 'v']) {
      await page.fill(`#samples-${g}`, '101');
      await page.dispatchEvent(`#samples-${g}`, 'change');
    }
    await idle();

    // The hint, the colours by panel area and by fold with their legends, the
    // pencil axes, the planes of the curvature lines, and points and arc guides dragged.
    assert.match(await page.locator('#hint').textContent(), /orbit.*zoom.*pan.*drag/, 'the hint');
    assert.ok(await page.locator('#hint').isVisible(), 'the hint is on screen');
    await page.selectOption('#colour', 'area');
    await page.waitForFunction(() => explorer.state.legend?.mode === 'area');
    const shown = await snapshot();
    const legend = await page.evaluate(() => ({ ...explorer.state.legend, text: document.getElementById('legend').textContent, hidden: document.getElementById('legend').hidden }));
    const metrics = await page.evaluate(() => JSON.parse(explorer.metrics()).panel_area);
    assert.ok(!legend.hidden && legend.text.startsWith('panel area'), legend.text);
    assert.deepEqual([legend.min, legend.max], [metrics.min, metrics.max], 'the legend shows the metrics\' panel areas');
    // Measured again here, from the vertices, with the diagonals' formula.
    const at = (i, j) => shown.vertices.slice(3 * (i * shown.cols + j), 3 * (i * shown.cols + j) + 3);
    const areas = [];
    for (let i = 0; i + 1 < shown.rows; i++) for (let j = 0; j + 1 < shown.cols; j++) areas.push(quadArea([at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]));
    const [min, max] = [Math.min(...areas), Math.max(...areas)];
    assert.ok(Math.abs(min - legend.min) <= 1e-9 * max && Math.abs(max - legend.max) <= 1e-9 * max, `${min} … ${max} vs ${legend.min} … ${legend.max}`);
    log(`colour by panel area: legend ${legend.min} … ${legend.max} = metrics = measured from the vertices (to ${Math.max(Math.abs(min - legend.min), Math.abs(max - legend.max)) / max} of the largest)`);

    // Figure 14 at θ = 84° folds: coloured by fold, the legend counts the CLI's folded faces.
    const family = readFileSync(join(repo, 'examples/fig14-family.toml'), 'utf8').replace(/^theta_deg = .*$/m, 'theta_deg = 84');
    writeFileSync(join(work, 'folds.toml'), family);
    const warned = generate('folds.toml').stderr.match(/folds over itself .* in (\d+) faces/);
    assert.ok(warned, 'monge generate warns of folds');
    await page.selectOption('#colour', 'fold');
    const loads = (await snapshot()).generations;
    await page.setInputFiles('#load', join(work, 'folds.toml'));
    await page.waitForFunction((n) => explorer.state.generations > n && explorer.idle() && explorer.state.legend?.mode === 'fold', loads);
    const folds = await page.evaluate(() => ({ ...explorer.state.legend, text: document.getElementById('legend').textContent }));
    assert.equal(folds.folded, Number(warned[1]), 'the legend counts the folded faces monge generate reports');
    assert.ok(folds.text.includes(`folded: ${warned[1]}`), folds.text);
    log(`colour by fold: ${folds.folded} of ${folds.faces} faces folded, as monge generate says`);

    // The pencil axes: two polar reciprocal lines, drawn or named as out of the drawn ball.
    await page.check('#show-axes');
    const axes = await page.evaluate(() => ({ header: explorer.state.mesh.axes, drawn: explorer.drawn().axes, note: document.getElementById('axes-note').textContent }));
    const norm = (v) => Math.hypot(...v);
    const { l1, l2 } = axes.header;
    assert.ok(Math.abs(norm(l1.point) * norm(l2.point) - 1) < 1e-9, 'L2 is the polar of L1: distances a and 1/a');
    assert.ok(Math.abs(l1.dir.reduce((s, x, k) => s + x * l2.dir[k], 0)) < 1e-12, 'L1 ⟂ L2');
    assert.ok(axes.drawn.length >= 1 && axes.note.includes('L1') && axes.note.includes('L2'), JSON.stringify(axes));
    log(axes.note);
    await page.check('#show-planes');
    const planes = await page.evaluate(() => explorer.drawn().planes);
    const rowsShown = planes.filter((p) => p.family === 'row').map((p) => p.line);
    const colsShown = planes.filter((p) => p.family === 'column').map((p) => p.line);
    const header = await page.evaluate(() => explorer.state.mesh);
    assert.ok(rowsShown.includes(0) && rowsShown.includes(header.rows - 1) && colsShown.includes(header.cols - 1), JSON.stringify(planes));
    log(`planes of the curvature lines: ${rowsShown.length} rows and ${colsShown.length} columns drawn`);
    await page.screenshot({ path: join(repo, 'target/explorer-features.png') });
    await page.uncheck('#show-planes');
    await page.uncheck('#show-axes');
    assert.deepEqual(await page.evaluate(() => explorer.drawn()), { axes: [], planes: [] }, 'hidden on demand');

    /** Loads example `name` and drags handle `index` of guide `guide`; resolves to [before, after] snapshots. */
    const dragGuide = async (name, guide, index, dx, dy) => {
      const n = (await snapshot()).generations;
      await page.setInputFiles('#load', join(repo, 'examples', name));
      await page.waitForFunction((k) => explorer.state.generations > k && explorer.idle(), n);
      const before = await snapshot();
      const from = await page.evaluate(([g, k]) => explorer.handleOnScreen(g, k), [guide, index]);
      await page.mouse.move(from.x, from.y);
      await page.mouse.down();
      for (let k = 1; k <= 5; k++) await page.mouse.move(from.x + dx * k, from.y + dy * k);
      await page.mouse.up();
      await idle();
      const after = await snapshot();
      assert.notDeepEqual(after.vertices, before.vertices, `dragging ${name}'s guide_${guide} ${index} changed the mesh`);
      return [before, after];
    };
    const [pointsBefore, pointsAfter] = await dragGuide('contract.json', 'u', 2, 4, -6);
    const [p, q] = [pointsBefore, pointsAfter].map((s) => s.design.guide_u.points);
    assert.notDeepEqual(q[2], p[2], 'the point moved');
    assert.deepEqual(q.slice(0, 2), p.slice(0, 2), 'the others stay');
    assert.ok(Math.abs(q[2][1]) < 1e-9, `the point stays in guide_u's plane y = 0: ${q[2]}`);
    sameAsCli(pointsAfter);
    log(`dragged contract.json's points guide_u P2 ${p[2]} → ${q[2].map((x) => x.toFixed(3))}: monge generate = page bit for bit`);
    const [arcBefore, arcAfter] = await dragGuide('fig12-torus.json', 'v', 'end', -5, -3);
    const [a, b] = [arcBefore, arcAfter].map((s) => s.design.guide_v.arc);
    assert.notEqual(b.angle_deg, a.angle_deg, 'the arc\'s angle changed');
    assert.deepEqual([b.center, b.start, b.normal, b.samples], [a.center, a.start, a.normal, a.samples], 'centre, start, normal stay');
    sameAsCli(arcAfter);
    log(`dragged fig12-torus.json's arc guide_v end: angle ${a.angle_deg}° → ${b.angle_deg.toFixed(3)}°: monge generate = page bit for bit`);
    await page.selectOption('#colour', 'none');
    assert.ok(await page.locator('#legend').isHidden(), 'no legend for plain faces');

    // The smooth net (§4.4) of the dragged torus design, measured in the worker:
    // its arcs drawn, its JSON export = `monge smooth --samples 9` byte for byte.
    await page.check('#show-arcs');
    await idle();
    const net = await page.evaluate(() => ({ arcs: explorer.arcs(), json: explorer.netExport(), design: explorer.state.design, rows: explorer.state.mesh.rows, cols: explorer.state.mesh.cols, metrics: document.getElementById('metrics').textContent }));
    assert.equal(net.arcs.lines, net.rows + net.cols, JSON.stringify(net.arcs));
    assert.ok(net.arcs.segments === net.arcs.arcs * 8, `every arc drawn as 8 chords: ${JSON.stringify(net.arcs)}`);
    assert.ok(net.metrics.includes(`${net.arcs.arcs} circular arcs`), net.metrics);
    writeFileSync(join(work, 'torus.json'), JSON.stringify(net.design));
    const smooth = spawnSync(monge, ['smooth', 'torus.json', '-o', 'net.json', '--samples', '9'], { cwd: work, encoding: 'utf8' });
    assert.equal(smooth.status, 0, smooth.stderr);
    assert.equal(net.json, readFileSync(join(work, 'net.json'), 'utf8'), 'the page\'s net export is monge smooth\'s');
    log(`smooth net of the dragged torus: ${net.arcs.lines} curvature lines, ${net.arcs.arcs} arcs drawn; export = monge smooth bit for bit`);
    // The README's picture: Figure 13's free-form design, faces coloured by
    // panel area, with its smooth net's arcs.
    const shownBefore = (await snapshot()).generations;
    await page.setInputFiles('#load', join(repo, 'examples', 'fig13-freeform.json'));
    await page.waitForFunction((k) => explorer.state.generations > k && explorer.idle(), shownBefore);
    await rhinoAndGlb(page, await snapshot(), noise);
    await page.selectOption('#colour', 'area');
    await idle();
    await page.screenshot({ path: join(repo, 'target/explorer-arcs.png') });
    await page.selectOption('#colour', 'none');
    await page.uncheck('#show-arcs');
    await idle();

    await grazingDrags(page, snapshot, idle);
    await neverSilent(page, snapshot, idle);
    await undoRedo(page, snapshot, idle);
    await guideKinds(page, snapshot, idle);

    assert.deepEqual(pageErrors, [], 'no errors in the page');
    assert.deepEqual(noise.problems, [], 'no console error and no failed request from a plain static server');
    log(`static server: ${noise.requests.length} requests, none failed, no console error; none to api/design: ${!noise.requests.some((r) => r.includes('api/design'))}`);
    assert.ok(!noise.requests.some((r) => r.includes('api/design') || r.includes('favicon')), noise.requests.join(' '));
    assert.ok((await snapshot()).full, 'the screenshot is in full quality');
    mkdirSync(dirname(screenshot), { recursive: true });
    await page.screenshot({ path: screenshot });
    log(`screenshot: ${screenshot}`);
  } finally {
    await context.close();
    server.kill();
  }
}

/** `monge explore DESIGN` serves the embedded page, which opens DESIGN. */
async function embedded() {
  const design = 'examples/fig13-freeform.json';
  const { server, url } = await startServer(join(repo, design));
  const browser = await chromium.launch({ executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium', headless: true, args: ['--no-sandbox', '--disable-gpu'] });
  try {
    const page = await browser.newPage();
    page.setDefaultTimeout(60000);
    const noise = watchConsole(page);
    await page.goto(url);
    await page.waitForFunction(() => window.explorer && window.explorer.idle() && window.explorer.state.generations > 0);
    assert.deepEqual(noise.problems, [], 'no console error and no failed request from monge explore');
    assert.ok(noise.requests.some((r) => r.endsWith('/api/design')), 'the page served by monge explore asks it for its design');
    const cli = generate(join(repo, design));
    const shown = await numbers(page, 'vertices');
    assert.deepEqual(shown, cli.mesh.vertices.flat(), `the page served by monge explore shows ${design}`);
    log(`monge explore ${design}: the embedded page shows it (${cli.mesh.rows} × ${cli.mesh.cols} vertices); ${noise.requests.length} requests, none failed, no console error`);
  } finally {
    await browser.close();
    server.kill();
  }
}

/** `monge explore --web-dir web/dist` serves the .3dm writer's files with the types a browser runs them by. */
async function servedTypes() {
  const { server, url } = await startServer('--web-dir', join(repo, 'web/dist'));
  try {
    const types = { 'rhino-worker.js': 'text/javascript; charset=utf-8', 'rhino3dm.js': 'text/javascript; charset=utf-8', 'rhino3dm.wasm': 'application/wasm' };
    for (const [file, type] of Object.entries(types)) {
      const response = await fetch(new URL(file, url));
      const body = Buffer.from(await response.arrayBuffer());
      assert.equal(response.status, 200, file);
      assert.equal(response.headers.get('content-type'), type, file);
      assert.ok(body.equals(readFileSync(join(repo, 'web/dist', file))), `${file} served whole`);
    }
    log(`monge explore --web-dir web/dist serves ${Object.entries(types).map(([f, t]) => `${f} as ${t}`).join(', ')}`);
  } finally {
    server.kill();
  }
}

main().then(embedded).then(servedTypes).then(() => log('passed'), (error) => {
  console.error(error);
  process.exit(1);
});
