// The WebAssembly module (crates/monge-wasm) against the native `monge` binary
// on every example design: the same vertices bit for bit, and the same OBJ,
// JSON and GLB files byte for byte. The module is the one `npm run build` left
// in web/wasm/ if there is one, else the one embedded in the binary
// (crates/monge-cli/web-dist), with its glue (web/wasm/monge_wasm.js).
//
//   MONGE_BIN=target/release/monge node --test web/test/
import { spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, readdirSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import assert from 'node:assert/strict';
import test from 'node:test';
import init, { generate, info, parseDesign } from '../wasm/monge_wasm.js';

const repo = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const monge = resolve(process.env.MONGE_BIN ?? join(repo, 'target/release/monge'));
const work = mkdtempSync(join(tmpdir(), 'monge-wasm-'));
const built = join(repo, 'web/wasm/monge_wasm_bg.wasm');
const module = existsSync(built) ? built : join(repo, 'crates/monge-cli/web-dist/monge_wasm_bg.wasm');
console.log(`the module: ${module}`);
await init({ module_or_path: readFileSync(module) });

/** Surface designs: every example but the developable, multi-patch and planes files. */
const examples = readdirSync(join(repo, 'examples'))
  .filter((f) => /\.(json|toml)$/.test(f) && !/\.(developable|patches|planes)\.json$/.test(f));

/** `monge generate DESIGN -o OUT [--offset D]` → the bytes of OUT (and of the offset file). */
function native(design, out, offset) {
  const args = ['generate', join(repo, 'examples', design), '-o', join(work, out)];
  if (offset) args.push('--offset', String(offset));
  const run = spawnSync(monge, args, { encoding: 'utf8' });
  assert.equal(run.status, 0, run.stderr);
  const stem = out.replace(/\.[^.]+$/, '');
  const file = offset ? `${stem}.offset+${offset}${out.slice(stem.length)}` : out;
  return readFileSync(join(work, file));
}

test('there are example designs', () => assert.ok(examples.length >= 10, examples.join(' ')));

for (const name of examples) {
  test(`${name}: the same vertices and files as the native build`, () => {
    const text = parseDesign(readFileSync(join(repo, 'examples', name), 'utf8'), name, name.endsWith('.toml'));
    for (const offset of [0, 0.125]) {
      const mesh = generate(text, name, offset, 25_000_000);
      try {
        const json = native(name, 'mesh.json', offset);
        const expected = JSON.parse(json).vertices.flat();
        const vertices = Float64Array.from(mesh.vertices());
        assert.equal(vertices.length, expected.length);
        const differ = expected.filter((x, k) => !Object.is(x, vertices[k])).length;
        assert.equal(differ, 0, `${differ} of ${expected.length} coordinates differ at offset ${offset}`);
        assert.ok(Buffer.from(mesh.export('json')).equals(json), `JSON export at offset ${offset}`);
        assert.ok(Buffer.from(mesh.export('obj')).equals(native(name, 'mesh.obj', offset)), `OBJ export at offset ${offset}`);
        assert.ok(Buffer.from(mesh.export('glb')).equals(native(name, 'mesh.glb', offset)), `GLB export at offset ${offset}`);
      } finally {
        mesh.free();
      }
    }
  });
}

for (const name of examples) {
  test(`${name}: the cyclidic net is monge smooth's, byte for byte`, () => {
    const text = parseDesign(readFileSync(join(repo, 'examples', name), 'utf8'), name, name.endsWith('.toml'));
    const out = join(work, 'net.json');
    const run = spawnSync(monge, ['smooth', join(repo, 'examples', name), '-o', out, '--samples', '5'], { encoding: 'utf8' });
    const mesh = generate(text, name, 0, 25_000_000);
    try {
      if (run.status !== 0) {
        // A conical design or a folded face: the same refusal, naming the file.
        assert.throws(() => mesh.smooth(4), (e) => {
          const why = e.message.slice(e.message.indexOf(': ') + 2);
          return e.message.startsWith(`${name}: `) && run.stderr.includes(why.split('\n')[0]);
        }, run.stderr);
        return;
      }
      const net = mesh.smooth(4);
      try {
        assert.ok(Buffer.from(net.export(5)).equals(readFileSync(out)), 'net JSON');
        const lines = JSON.parse(readFileSync(out, 'utf8')).lines;
        assert.equal(net.lines(), lines.length);
        assert.equal(net.arcs(), lines.reduce((n, l) => n + l.arcs.length, 0));
        assert.equal(net.segments().length, net.arcs() * 4 * 6);
      } finally {
        net.free();
      }
    } finally {
      mesh.free();
    }
  });
}

test('refusals carry the CLI\'s messages', () => {
  const name = 'fig10-arbitrary.json';
  const design = JSON.parse(readFileSync(join(repo, 'examples', name), 'utf8'));
  const text = JSON.stringify({ ...design, theta_deg: 5 });
  assert.throws(() => generate(text, 'bad.json', 0, 1000000), /^Error: bad\.json: .*θ/s);
  const range = JSON.parse(info(text, 'bad.json', 1000000)).theta_range;
  assert.ok(range.min_deg > 5 && range.max_deg <= 180, JSON.stringify(range));
  assert.throws(() => parseDesign('{ "theta_deg": 30,\n', 'syntax.json', false), /^Error: syntax\.json:2/);
  assert.throws(() => generate(text, 'big.json', 0, 10), /^Error: big\.json: .*10/s);
});
