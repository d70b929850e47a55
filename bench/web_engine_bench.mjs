// The WebAssembly side of the page's frame in Node, without a browser: the
// engine of a site of `overflight web` (its overflight_engine.js or another
// build's) on the site's terrain.bin, at a fixed size, flying forward (UP held,
// 1/30 s of physics per frame, the chase camera) as bench/web_fps.sh does;
// prints the mean milliseconds per frame of of_frame and of its parts
// (of_frame_stats: physics, lighting, tables, cast, resolve, water), and of
// the page's reads of the color and depth (views of the wasm heap); then
// the same with the last camera pinned, and the `overflight bench` command
// that times the native ray caster on one thread at that camera. A
// benchmark, not a test: print the load beside it.
//
//   node bench/web_engine_bench.mjs SITE [ENGINE_JS] [WxH] [FRAMES]
import fs from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';

const [site, engineArg, size = '1280x720', framesArg = '60'] = process.argv.slice(2);
if (!site) {
  console.error('usage: web_engine_bench.mjs SITE [ENGINE_JS] [WxH] [FRAMES]');
  process.exit(2);
}
const enginePath = path.resolve(engineArg || path.join(site, 'overflight_engine.js'));
const [w, h] = size.split('x').map(Number);
const frames = Number(framesArg);

const require = createRequire(import.meta.url);
const M = await require(enginePath)({ wasmBinary: fs.readFileSync(enginePath.replace(/\.js$/, '.wasm')) });
const bytes = fs.readFileSync(path.join(site, 'terrain.bin'));
const p = M._malloc(bytes.length);
M.HEAPU8.set(bytes, p);
if (M._of_load_terrain(p, bytes.length) !== 0) throw new Error('the terrain does not load');
M._free(p);
M._of_set_size(w, h);
M._of_frame(0); // lights the terrain once
M._of_key(0, 1); // UP
// Warm-up: long enough for the WebAssembly tier-up (V8 compiles hot
// functions again, optimised, in the background).
for (let k = 0; k < 100; ++k) M._of_frame(1 / 30);

const names = ['frame', 'physics', 'light', 'tables', 'cast', 'resolve', 'water'];
const sums = new Array(names.length).fill(0);
let views = 0;
const t0 = performance.now();
for (let k = 0; k < frames; ++k) {
  if (M._of_frame(1 / 30) !== 0) throw new Error('frame failed');
  if (M._of_frame_stats) {
    const s = new Float64Array(M.HEAPU8.buffer, M._of_frame_stats(), names.length);
    for (let i = 0; i < names.length; ++i) sums[i] += s[i];
  }
  const tv = performance.now();
  const n = M._of_width() * M._of_height();
  const c = new Uint8Array(M.HEAPU8.buffer, M._of_color(), 3 * n);
  const d = new Float32Array(M.HEAPU8.buffer, M._of_depth(), n);
  views += performance.now() - tv + (c[0] + d[0]) * 0;
}
const wall = (performance.now() - t0) / frames;
const parts = M._of_frame_stats ? names.map((n, i) => `${n} ${(sums[i] / frames).toFixed(2)}`).join(', ') : 'no of_frame_stats';
console.log(`${path.basename(enginePath)} ${size}: ${wall.toFixed(2)} ms per frame (JS views ${(views / frames).toFixed(3)}); ${parts}`);

// The last frame's camera pinned, for the native ray caster at the same view.
const [x, y, z, heading, pitch, fov, near, far] = new Float64Array(M.HEAPU8.buffer, M._of_camera(), 8);
M._of_set_camera(x, y, z, heading, pitch, fov, near, far);
M._of_frame(0);
const pinnedSums = new Array(names.length).fill(0);
const tp = performance.now();
for (let k = 0; k < frames; ++k) {
  M._of_frame(0);
  if (M._of_frame_stats) {
    const s = new Float64Array(M.HEAPU8.buffer, M._of_frame_stats(), names.length);
    for (let i = 0; i < names.length; ++i) pinnedSums[i] += s[i];
  }
}
const pinnedParts = M._of_frame_stats ? ` (${names.map((n, i) => `${n} ${(pinnedSums[i] / frames).toFixed(2)}`).join(', ')})` : '';
console.log(`pinned: ${((performance.now() - tp) / frames).toFixed(2)} ms per frame${pinnedParts}; natively: overflight bench demo ` +
            `--size ${size} --threads 1 --methods voxel --eye ${x},${y},${z} --heading ${heading} --pitch ${pitch} ` +
            `--fov ${fov} --near ${near} --far ${far}`);
