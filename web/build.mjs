// Builds web/dist: index.html and style.css from src/, and app.js bundled with
// the parts of three.js it uses (from node_modules) and minified by esbuild
// (deterministic: the same sources give the same bytes, which .ci/run checks
// against the copy embedded in the `monge` binary, crates/monge-cli/web-dist).
import { buildSync } from 'esbuild';
import { cpSync, mkdirSync, rmSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const dist = join(here, 'dist');

rmSync(dist, { recursive: true, force: true });
mkdirSync(dist, { recursive: true });
for (const file of ['index.html', 'style.css']) {
  cpSync(join(here, 'src', file), join(dist, file));
}
buildSync({
  entryPoints: [join(here, 'src', 'app.js')],
  outfile: join(dist, 'app.js'),
  bundle: true,
  minify: true,
  format: 'esm',
  target: 'es2022',
  legalComments: 'eof',
  logLevel: 'warning',
});
console.log(`built ${dist}`);
