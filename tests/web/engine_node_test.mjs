// The WebAssembly engine (web/WebEngine.h) in Node, without a browser, against
// the native code it is built from:
//   - the demo island written as OFTERR01 by the native writer (web_fixture)
//     loads, and the voxel cast of a fixed camera equals the native method's
//     color and depth for that camera (the numbers are printed; the bounds
//     are the test's);
//   - holding UP for 200 physics steps moves the vehicle as
//     `overflight sim --press accelerate:0-200` does, within 1 cm;
//   - a broken file is refused with a one-line error.
// With --bench, also prints the cast's ms per frame at 1280x720.
//
//   node engine_node_test.mjs --engine build/web/overflight_engine.js
//        --fixture BUILD/tests/web_fixture --overflight BUILD/apps/overflight [--bench]
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import { createRequire } from 'node:module';
import os from 'node:os';
import path from 'node:path';

const args = process.argv.slice(2);
const opt = (name) => {
  const i = args.indexOf(name);
  return i >= 0 ? args[i + 1] : undefined;
};
const enginePath = path.resolve(opt('--engine') ?? 'build/web/overflight_engine.js');
const fixture = opt('--fixture');
const overflight = opt('--overflight');
const bench = args.includes('--bench');
if (!fixture || !overflight) {
  console.error('usage: engine_node_test.mjs --engine JS --fixture EXE --overflight EXE [--bench]');
  process.exit(2);
}

let failures = 0;
const check = (ok, what) => {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures++;
};

// The factory reads its .wasm beside the .js; Node's fetch cannot read a
// file path, so the bytes are handed over.
const require = createRequire(import.meta.url);
const factory = require(enginePath);
const wasmBinary = fs.readFileSync(enginePath.replace(/\.js$/, '.wasm'));
const M = await factory({ wasmBinary });
const errorText = () => M.UTF8ToString ? M.UTF8ToString(M._of_error()) : readCString(M._of_error());
function readCString(ptr) {
  let s = '';
  for (let p = ptr; M.HEAPU8[p]; ++p) s += String.fromCharCode(M.HEAPU8[p]);
  return s;
}

function loadTerrain(bytes) {
  const p = M._malloc(bytes.length);
  M.HEAPU8.set(bytes, p);
  const rc = M._of_load_terrain(p, bytes.length);
  M._free(p);
  return rc;
}

const work = fs.mkdtempSync(path.join(os.tmpdir(), 'overflight-web-'));
try {
  execFileSync(fixture, [work, '513', '320x240'], { stdio: 'inherit' });
  const cam = JSON.parse(fs.readFileSync(path.join(work, 'camera.json'), 'utf8'));
  const terrain = fs.readFileSync(path.join(work, 'terrain.ofterr'));

  // A broken file: refused, one line, the terrain loaded before kept.
  const broken = Uint8Array.from(terrain.subarray(0, 1000));
  const rcBroken = loadTerrain(broken);
  check(rcBroken === -1 && !errorText().includes('\n') && errorText().length > 0,
        `truncated file refused (${rcBroken}: ${errorText()})`);
  check(M._of_frame(0) === -2, 'no frame without a terrain');

  // The cast of a fixed camera against the native one.
  check(loadTerrain(terrain) === 0, `demo ${cam.demo_size} loads (${terrain.length} bytes)`);
  check(M._of_set_size(cam.width, cam.height) === 0, 'size set');
  check(M._of_set_camera(cam.eye[0], cam.eye[1], cam.eye[2], cam.heading, cam.pitch, cam.fov, cam.near, cam.far) === 0,
        'camera pinned');
  check(M._of_frame(0) === 0, `frame cast (${errorText()})`);
  const n = cam.width * cam.height;
  const color = M.HEAPU8.slice(M._of_color(), M._of_color() + 3 * n);
  const depth = new Float32Array(M.HEAPU8.slice(M._of_depth(), M._of_depth() + 4 * n).buffer);
  const nativeColor = fs.readFileSync(path.join(work, 'native_color.rgb'));
  const nativeDepth = new Float32Array(Uint8Array.from(fs.readFileSync(path.join(work, 'native_depth.f32'))).buffer);
  let sameColor = 0, maxChannel = 0, sameDepth = 0, maxDepth = 0, sky = 0;
  for (let i = 0; i < n; ++i) {
    let d = 0;
    for (let k = 0; k < 3; ++k) d = Math.max(d, Math.abs(color[3 * i + k] - nativeColor[3 * i + k]));
    if (d === 0) sameColor++;
    maxChannel = Math.max(maxChannel, d);
    const dz = Math.abs(depth[i] - nativeDepth[i]);
    if (dz === 0) sameDepth++;
    maxDepth = Math.max(maxDepth, dz);
    if (nativeDepth[i] === 1) sky++;
  }
  const pct = (k) => (100 * k / n).toFixed(3);
  console.log(`cast ${cam.width}x${cam.height}: color identical ${pct(sameColor)} % (max channel difference ` +
              `${maxChannel}), depth identical ${pct(sameDepth)} % (max difference ${maxDepth.toExponential(2)}), ` +
              `sky ${pct(sky)} %`);
  check(sky > 0 && sky < n, 'the view holds terrain and sky');
  check(maxChannel <= 1 && sameColor >= 0.999 * n, 'color equals the native cast (<= 1 level, >= 99.9 % identical)');
  check(maxDepth <= 1e-6 && sameDepth >= 0.999 * n, 'depth equals the native cast (<= 1e-6, >= 99.9 % identical)');
  const vp = new Float32Array(M.HEAPU8.slice(M._of_view_proj(), M._of_view_proj() + 64).buffer);
  // Its last row gives clip w = view depth along F = (sin h, 0, cos h) (shear): F . (p - eye).
  const h = cam.heading * Math.PI / 180, F = [Math.sin(h), 0, Math.cos(h)];
  const wOfEye = vp[3] * cam.eye[0] + vp[7] * cam.eye[1] + vp[11] * cam.eye[2] + vp[15];
  check(Math.abs(vp[3] - F[0]) < 1e-6 && Math.abs(vp[7]) < 1e-6 && Math.abs(vp[11] - F[2]) < 1e-6 &&
        Math.abs(wOfEye) < 1e-2, 'view-projection: clip w is the view depth along the heading');

  // The flight: UP held for 200 steps of 10 ms, against `overflight sim`.
  check(loadTerrain(terrain) === 0, 'terrain reloaded (a fresh flight)');
  M._of_set_size(64, 48);
  M._of_key(0, 1);
  const web = [];
  for (let k = 0; k < 200; ++k) {
    if (M._of_frame(0.01) !== 0) throw new Error(errorText());
    const v = new Float64Array(M.HEAPU8.slice(M._of_vehicle(), M._of_vehicle() + 40).buffer);
    web.push({ steps: M._of_physics_steps(), x: v[0], y: v[1], z: v[2], heading: v[3], velocity: v[4] });
  }
  check(web.every((w, k) => w.steps === k + 1), 'one physics step per 10 ms frame');
  const csv = execFileSync(overflight, ['sim', 'demo', '--demo-size', String(cam.demo_size), '--steps', '200',
                                        '--press', 'accelerate:0-200'], { encoding: 'utf8' });
  const rows = csv.trim().split('\n').slice(1).map((l) => l.split(',').map(Number));
  let worst = 0;
  for (const [step, x, z, y] of rows) {
    const w = web[step];
    worst = Math.max(worst, Math.hypot(w.x - x, w.y - y, w.z - z));
  }
  const last = rows[rows.length - 1];
  console.log(`sim: 200 steps, native end (${last[1]}, ${last[3]}, ${last[2]}) at ${last[4]} u/s; ` +
              `largest distance to the wasm vehicle ${worst.toExponential(2)} world units`);
  check(rows.length === 200 && worst <= 0.01, 'vehicle positions equal `overflight sim` within 1 cm');

  if (bench) {
    loadTerrain(terrain);
    M._of_set_size(1280, 720);
    M._of_set_camera(cam.eye[0], cam.eye[1], cam.eye[2], cam.heading, cam.pitch, cam.fov, cam.near, cam.far);
    M._of_frame(0); // lights the terrain once
    const frames = 20;
    const t0 = performance.now();
    for (let k = 0; k < frames; ++k) M._of_frame(0);
    console.log(`bench: 1280x720 cast ${((performance.now() - t0) / frames).toFixed(1)} ms per frame ` +
                `(${path.basename(enginePath)}, one thread)`);
  }
} finally {
  fs.rmSync(work, { recursive: true, force: true });
}
if (failures) {
  console.error(`${failures} check(s) failed`);
  process.exit(1);
}
