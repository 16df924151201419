// Builds web/dist, a static page that works from any file server:
//
// 1. the module: crates/monge-wasm compiled to wasm32-unknown-unknown (release)
//    and bound with `wasm-bindgen --target web` (the version pinned in its
//    Cargo.toml) into web/wasm/; paths are remapped so the bytes do not depend
//    on where the repository or the cargo home is;
// 2. index.html, style.css, default-design.json from src/, the module's
//    monge_wasm_bg.wasm, and app.js (with the modules it imports from src/)
//    and worker.js bundled with the parts of three.js they use and the
//    module's glue, minified by esbuild;
// 3. the .3dm writer: rhino-worker.js (src/rhino.js) bundled likewise, and
//    rhino3dm's ES module and WebAssembly (npm `rhino3dm`, pinned in
//    package.json) copied beside it as rhino3dm.js and rhino3dm.wasm, which the
//    worker loads on the first .3dm export only.
//
// Deterministic: the same sources and toolchain give the same bytes.
// `npm run embed` copies dist/ into the `monge` binary's sources
// (crates/monge-cli/web-dist); the module's glue, web/wasm/monge_wasm.js, is
// committed with it.
//
// `node build.mjs --bundle-only` skips step 1: it bundles the committed glue
// and takes the embedded module, so that CI checks that the embedded page is
// the one its sources make without compiling the module (whose output the
// tests compare with the native build's instead).
import { buildSync } from 'esbuild';
import { execFileSync } from 'node:child_process';
import { cpSync, mkdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { homedir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const repo = resolve(here, '..');
const dist = join(here, 'dist');
const wasmOut = join(here, 'wasm');

const embedded = join(repo, 'crates', 'monge-cli', 'web-dist', 'monge_wasm_bg.wasm');
const bundleOnly = process.argv.includes('--bundle-only');
if (!bundleOnly) buildModule();

function buildModule() {
  const cargoHome = process.env.CARGO_HOME ?? join(homedir(), '.cargo');
  const target = JSON.parse(execFileSync('cargo', ['metadata', '--format-version', '1', '--no-deps'], { cwd: repo })).target_directory;
  execFileSync('cargo', ['build', '--release', '--locked', '-p', 'monge-wasm', '--target', 'wasm32-unknown-unknown'], {
    cwd: repo,
    stdio: 'inherit',
    env: {
      ...process.env,
      CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_RUSTFLAGS: `--remap-path-prefix=${repo}=monge --remap-path-prefix=${cargoHome}=cargo`,
      // The shipped binary is stripped (Cargo.toml); the module must not be:
      // stripping drops its `target_features` section, from which wasm-bindgen
      // learns that reference types are on, and it would bind the module the old way.
      CARGO_PROFILE_RELEASE_STRIP: 'false',
    },
  });
  rmSync(wasmOut, { recursive: true, force: true });
  execFileSync('wasm-bindgen', ['--target', 'web', '--no-typescript', '--out-dir', wasmOut,
    join(target, 'wasm32-unknown-unknown', 'release', 'monge_wasm.wasm')], { stdio: 'inherit' });
}

rmSync(dist, { recursive: true, force: true });
mkdirSync(dist, { recursive: true });
for (const file of ['index.html', 'style.css', 'default-design.json']) {
  cpSync(join(here, 'src', file), join(dist, file));
}
cpSync(bundleOnly ? embedded : join(wasmOut, 'monge_wasm_bg.wasm'), join(dist, 'monge_wasm_bg.wasm'));
// rhino3dm as npm ships it (MIT), with its notice.
const rhino = join(here, 'node_modules', 'rhino3dm');
const { version, license } = JSON.parse(readFileSync(join(rhino, 'package.json'), 'utf8'));
writeFileSync(join(dist, 'rhino3dm.js'), `/*! rhino3dm ${version} (npm), ${license} licence, Robert McNeel & Associates, https://github.com/mcneel/rhino3dm */\n${
  readFileSync(join(rhino, 'rhino3dm.module.min.js'), 'utf8')}`);
cpSync(join(rhino, 'rhino3dm.wasm'), join(dist, 'rhino3dm.wasm'));
buildSync({
  // The page, and its worker (metrics and arcs off the main thread), each with
  // the module's glue; the .3dm writer's worker.
  entryPoints: ['app.js', 'worker.js', 'rhino-worker.js'].map((file) => join(here, 'src', file)),
  outdir: dist,
  bundle: true,
  minify: true,
  format: 'esm',
  target: 'es2022',
  legalComments: 'eof',
  logLevel: 'warning',
});
console.log(`built ${dist}`);
