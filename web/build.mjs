// Builds web/dist: the page's own files from src/ plus three.js from
// node_modules (no bundler: the page loads ES modules through an import map).
import { cpSync, mkdirSync, rmSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const dist = join(here, 'dist');
const three = join(here, 'node_modules', 'three');

rmSync(dist, { recursive: true, force: true });
mkdirSync(join(dist, 'vendor'), { recursive: true });
cpSync(join(here, 'src'), dist, { recursive: true });
for (const file of ['build/three.module.js', 'build/three.core.js', 'examples/jsm/controls/OrbitControls.js']) {
  cpSync(join(three, file), join(dist, 'vendor', file.split('/').pop()));
}
console.log(`built ${dist}`);
