// The site of `overflight web` in a real browser (headless Chromium over the
// DevTools protocol, software WebGL2): a site for the demo island with one
// extra object is written, served on 127.0.0.1 and opened, and
//   (a) its canvas at a pinned camera equals `overflight render --method
//       voxel` of the same camera (the same ray caster compiled twice; the
//       objects drawn by WebGL2 and by the native compositor),
//   (b) the objects cover the same pixels (IoU of the object masks),
//   (c) holding UP for 200 physics steps moves the vehicle as `overflight
//       sim --press accelerate:0-200` does (within 1 cm);
//   (d) the chase view draws the hovercraft where `overflight fly --replay`
//       draws it for the same camera and vehicle (IoU of the vehicle masks),
//       inside the rectangle the page loads depth for;
//   (e) Tab switches to the engine's ROAM mesh drawn by WebGL2 (the HUD
//       says roam and its triangle count, the frame changes, no GL error),
//       with the hovercraft drawn in it too;
//   (f) the time-of-day key T moves the sun: the ROAM view and the cast
//       change, and so do the objects' pixels.
// Exits 77 (CTest: Skipped) when Chromium or the WebAssembly engine
// (scripts/build_web.sh) is missing.
//
//   node site_test.mjs --exe build/release/apps/overflight --web build/web
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync, statSync, readdirSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { inflateSync } from 'node:zlib';
import { Browser, CHROMIUM, chromiumPresent } from './browser.mjs';
import { serve } from './serve.mjs';

const SKIP = 77;
const arg = (name) => {
    const k = process.argv.indexOf(name);
    return k > 0 ? process.argv[k + 1] : undefined;
};
const exe = arg('--exe');
const webBuild = arg('--web');
if (!exe || !webBuild) {
    console.error('usage: site_test.mjs --exe OVERFLIGHT --web WEB_BUILD_DIR');
    process.exit(2);
}
if (!chromiumPresent()) {
    console.log(`SKIP: ${CHROMIUM} is not installed`);
    process.exit(SKIP);
}
if (!existsSync(join(webBuild, 'overflight_engine.wasm'))) {
    console.log(`SKIP: ${webBuild}/overflight_engine.wasm is not built (scripts/build_web.sh)`);
    process.exit(SKIP);
}

// Thresholds. The terrain is the same ray caster compiled for x86-64 and for
// WebAssembly; only the math library's last bits may differ (glibc and
// Emscripten's musl), so nearly every pixel is equal and the rest differ by a
// unit or two. Objects are rasterised by two GL implementations (Mesa
// llvmpipe natively, SwiftShader in Chromium) from the same float geometry:
// their edges may differ by a pixel.
const kMaxChannelDiff = 2;      // a pixel "equals" when no channel differs by more
const kMinEqualShare = 0.995;   // share of equal pixels
const kMinObjectIoU = 0.95;
const kMinRoamVehicleIoU = 0.9; // the same hovercraft over another terrain model
const kMaxPositionError = 0.01; // world units (metres): 1 cm

const W = 640, H = 360;
const DEMO = ['demo', '--demo-size', '513'];
const scratch = mkdtempSync(join(tmpdir(), 'overflight-site-test-'));
let failures = 0;
const check = (ok, what) => {
    console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
    if (!ok) ++failures;
};
const overflight = (...args) =>
    execFileSync(exe, args, { encoding: 'utf8', env: { ...process.env, OVERFLIGHT_WEB_ENGINE_DIR: webBuild } });

// 8-bit RGB or RGBA PNG, not interlaced (what `overflight render` writes) -> {width, height, rgba}.
function readPng(path) {
    const b = readFileSync(path);
    let at = 8, width = 0, height = 0, channels = 0;
    const idat = [];
    while (at < b.length) {
        const len = b.readUInt32BE(at), type = b.toString('latin1', at + 4, at + 8), data = b.subarray(at + 8, at + 8 + len);
        if (type === 'IHDR') {
            width = data.readUInt32BE(0);
            height = data.readUInt32BE(4);
            if (data[8] !== 8 || data[12] !== 0 || (data[9] !== 2 && data[9] !== 6))
                throw new Error(`${path}: not an 8-bit RGB(A) PNG`);
            channels = data[9] === 2 ? 3 : 4;
        } else if (type === 'IDAT') {
            idat.push(data);
        }
        at += 12 + len;
    }
    const raw = inflateSync(Buffer.concat(idat));
    const stride = width * channels, out = new Uint8Array(width * height * 4);
    let prev = new Uint8Array(stride);
    for (let r = 0; r < height; ++r) {
        const filter = raw[r * (stride + 1)], line = raw.subarray(r * (stride + 1) + 1, (r + 1) * (stride + 1));
        const cur = new Uint8Array(stride);
        for (let k = 0; k < stride; ++k) {
            const a = k >= channels ? cur[k - channels] : 0, up = prev[k], c = k >= channels ? prev[k - channels] : 0;
            let p = 0;
            if (filter === 1) p = a;
            else if (filter === 2) p = up;
            else if (filter === 3) p = (a + up) >> 1;
            else if (filter === 4) {
                const pa = Math.abs(up - c), pb = Math.abs(a - c), pc = Math.abs(a + up - 2 * c);
                p = pa <= pb && pa <= pc ? a : pb <= pc ? up : c;
            }
            cur[k] = (line[k] + p) & 255;
        }
        for (let c = 0; c < width; ++c)
            for (let k = 0; k < 4; ++k) out[4 * (r * width + c) + k] = k < channels ? cur[c * channels + k] : 255;
        prev = cur;
    }
    return { width, height, rgba: out };
}

// Whether pixel k of two RGBA images differs by more than `tolerance` in a channel.
const differs = (a, b, k, tolerance) =>
    Math.max(Math.abs(a[4 * k] - b[4 * k]), Math.abs(a[4 * k + 1] - b[4 * k + 1]), Math.abs(a[4 * k + 2] - b[4 * k + 2])) > tolerance;

let browser, server;
try {
    // The site: the demo island (513 samples: its village, the vehicle start
    // at about (1571, 3788) facing 141 degrees, lies where this test looks)
    // with its own objects (houses, the parked vehicle, a water tower, a
    // transmission line) and one blue box beyond the village.
    const scene = join(scratch, 'scene.toml');
    writeFileSync(scene, '[[object]]\nkind = "box"\nx = 1665.0\nz = 3671.0\nwidth = 20.0\nheight = 30.0\n' +
                         'depth = 20.0\nheading = 30.0\ncolor = [40, 60, 200]\n');
    const site = join(scratch, 'site');
    const t0 = Date.now();
    overflight('web', ...DEMO, '--scene', scene, '-o', site);
    const writeSeconds = (Date.now() - t0) / 1000;
    const siteBytes = readdirSync(site).reduce((sum, f) => sum + statSync(join(site, f)).size, 0);
    check(['atmosphere.glsl', 'index.html', 'objects.bin', 'overflight.js', 'overflight_engine.js', 'overflight_engine.wasm', 'site.json',
           'terrain.bin', 'vehicle.bin'].every((f) => existsSync(join(site, f))), 'the site holds the page, the engine, terrain and objects');

    // The native view, whose camera the page then pins.
    const native = join(scratch, 'native.png'), cameraFile = join(scratch, 'camera.json');
    overflight('render', ...DEMO, '--scene', scene, '--method', 'voxel', '--size', `${W}x${H}`, '--at', '1476,3904',
               '--agl', '60', '--look-at', '1640,3700', '--save-camera', cameraFile, '-o', native);
    const cam = JSON.parse(readFileSync(cameraFile, 'utf8'));
    const camera = { eye: cam.eye, heading: cam.heading, pitch: cam.pitch, fov: cam.fov, near: cam.near, far: cam.far };

    server = await serve(site);
    browser = await Browser.launch({ width: W, height: H });
    const opened = Date.now();
    const page = await browser.open(`http://127.0.0.1:${server.port}/?test=1&size=${W}x${H}`, { width: W, height: H });
    const ready = await page.evaluate(`new Promise((resolve) => {
        const poll = () => window.overflight ? resolve(window.overflight.error || 'ready') : setTimeout(poll, 50);
        poll();
    })`);
    const firstFrameSeconds = (Date.now() - opened) / 1000;
    if (ready !== 'ready') throw new Error(`the page failed: ${ready}\n${page.console.join('\n')}`);
    const loadSeconds = await page.evaluate('overflight.loadSeconds');

    // (a) the composite at the pinned camera against the native one.
    const pixels = async (objects) =>
        new Uint8Array(Buffer.from(await page.evaluate(`overflight.view(${JSON.stringify(camera)}, ${objects})`), 'base64'));
    const web = await pixels(true), webCast = await pixels(false);
    const ref = readPng(native);
    check(ref.width === W && ref.height === H, `native image is ${W}x${H}`);
    let equal = 0, maxDiff = 0;
    for (let k = 0; k < W * H; ++k) {
        if (!differs(web, ref.rgba, k, kMaxChannelDiff)) ++equal;
        for (let c = 0; c < 3; ++c) maxDiff = Math.max(maxDiff, Math.abs(web[4 * k + c] - ref.rgba[4 * k + c]));
    }
    const exact = Array.from({ length: W * H }, (_, k) => !differs(web, ref.rgba, k, 0)).filter(Boolean).length;
    const equalShare = equal / (W * H);
    check(equalShare >= kMinEqualShare,
          `canvas equals native render: ${(100 * equalShare).toFixed(3)}% of pixels within ${kMaxChannelDiff} ` +
          `(${(100 * exact / (W * H)).toFixed(3)}% exact, max difference ${maxDiff}; need ${100 * kMinEqualShare}%)`);

    // (b) the objects' pixels: where each composite differs from the page's
    // cast without objects (the cast is the native one, by (a)).
    let both = 0, either = 0, webObjects = 0, nativeObjects = 0;
    const objectMask = new Uint8Array(W * H);
    for (let k = 0; k < W * H; ++k) {
        const w = differs(web, webCast, k, 0), n = differs(ref.rgba, webCast, k, kMaxChannelDiff);
        objectMask[k] = w;
        both += w && n;
        either += w || n;
        webObjects += w;
        nativeObjects += n;
    }
    const iou = either ? both / either : 0;
    check(webObjects > 500, `the objects cover ${webObjects} pixels in the page (${nativeObjects} natively)`);
    check(iou >= kMinObjectIoU, `object IoU ${iou.toFixed(4)} (need ${kMinObjectIoU})`);

    // (c) UP held for 200 steps of 10 ms, one physics step per frame.
    const flown = await page.evaluate(`overflight.fly(['Accelerate'], 200, 0.01)`);
    const csv = overflight('sim', ...DEMO, '--steps', '200', '--press', 'accelerate:0-200').trim().split('\n');
    const [, x, z, y, velocity, heading] = csv[csv.length - 1].split(',').map(Number);
    const error = Math.max(Math.abs(flown.vehicle.x - x), Math.abs(flown.vehicle.z - z), Math.abs(flown.vehicle.y - y));
    check(flown.steps === 200, `the page ran ${flown.steps} physics steps for 200 frames of 10 ms`);
    check(error <= kMaxPositionError,
          `vehicle after 2 s of UP: page (${flown.vehicle.x.toFixed(4)}, ${flown.vehicle.z.toFixed(4)}, ` +
          `${flown.vehicle.y.toFixed(4)}) vs sim (${x.toFixed(4)}, ${z.toFixed(4)}, ${y.toFixed(4)}): ` +
          `${(100 * error).toFixed(4)} cm apart; velocity ${flown.vehicle.velocity.toFixed(4)} vs ${velocity.toFixed(4)}, ` +
          `heading ${flown.vehicle.heading.toFixed(4)} vs ${heading.toFixed(4)}`);

    // (d) the chase view after (c), stopped and turned left by 75 degrees
    // (where the 513² demo's blocky voxel ground, natively too, leaves the
    // hovercraft in sight), with and without the hovercraft, against the
    // native replay of that frame (camera and vehicle from the page).
    await page.evaluate(`overflight.fly(['Brake'], 300, 0.01), overflight.fly(['Left'], 100, 0.01)`);
    const chase = async (vehicle) => {
        const r = await page.evaluate(`overflight.chase(${vehicle})`);
        return { ...r, pixels: new Uint8Array(Buffer.from(r.pixels, 'base64')) };
    };
    const withVehicle = await chase(true), without = await chase(false);
    const c = withVehicle.camera, v = withVehicle.vehicle;
    const record = join(scratch, 'chase.csv'), replayDir = join(scratch, 'replay');
    writeFileSync(record, 'frame,time,eye_x,eye_y,eye_z,heading,pitch,x,z,velocity,vehicle_heading,accelerate,brake,left,right\n' +
                          `0,0,${c.eye.join(',')},${c.heading},${c.pitch},${v.x},${v.z},${v.velocity},${v.heading},0,0,0,0\n`);
    overflight('fly', ...DEMO, '--scene', scene, '--method', 'voxel', '--size', `${W}x${H}`, '--replay', record,
               '--out', replayDir);
    const replayed = readPng(join(replayDir, 'frame_00000.png'));
    const [c0, r0, c1, r1] = withVehicle.depthRect;
    let vBoth = 0, vEither = 0, vWeb = 0, vNative = 0, outside = 0;
    const vehicleMask = new Uint8Array(W * H);
    for (let k = 0; k < W * H; ++k) {
        const w = differs(withVehicle.pixels, without.pixels, k, 0);
        vehicleMask[k] = w;
        const n = differs(replayed.rgba, without.pixels, k, kMaxChannelDiff);
        vBoth += w && n;
        vEither += w || n;
        vWeb += w;
        vNative += n;
        const col = k % W, row = Math.floor(k / W);
        if (w && (col < c0 || col >= c1 || row < r0 || row >= r1)) ++outside;
    }
    const vehicleIoU = vEither ? vBoth / vEither : 0;
    check(vWeb > 200, `the hovercraft covers ${vWeb} pixels in the page's chase view (${vNative} natively)`);
    check(vehicleIoU >= kMinObjectIoU, `hovercraft IoU against fly --replay ${vehicleIoU.toFixed(4)} (need ${kMinObjectIoU})`);
    check(outside === 0, `the hovercraft lies inside the depth upload's rectangle (${outside} pixels outside)`);

    // (e) Tab: the ROAM view of the same camera, keys as a user presses them.
    const press = async (key, code, keyCode, modifiers = 0) => {
        for (const type of ['rawKeyDown', 'keyUp'])
            await page.send('Input.dispatchKeyEvent', { type, key, code, windowsVirtualKeyCode: keyCode, modifiers });
    };
    const share = (a, b) => Array.from({ length: W * H }, (_, k) => differs(a, b, k, 0)).filter(Boolean).length / (W * H);
    const voxelView = await pixels(true);
    await press('Tab', 'Tab', 9);
    const roamView = await pixels(true);
    const hud = await page.evaluate('overflight.hud()');
    const roam = await page.evaluate('overflight.roam()');
    const glError = await page.evaluate('overflight.glError()');
    check(await page.evaluate('overflight.state.view') === 'roam' && hud.includes(`roam (WebGL2, ${roam.triangles} triangles`),
          `Tab shows the ROAM view: HUD "${hud}"`);
    check(roam.triangles > 1000 && roam.triangles <= roam.budget, `${roam.triangles} triangles within the budget ${roam.budget}`);
    const roamShare = share(roamView, voxelView);
    check(roamShare > 0.01, `the ROAM frame differs from the cast in ${(100 * roamShare).toFixed(1)}% of pixels`);
    check(glError === 0, `no WebGL error (${glError})`);
    // The hovercraft in the ROAM view: where the cast's chase view has it
    // (the mesh may hide an edge the voxels leave in sight).
    const roamWith = await chase(true), roamWithout = await chase(false);
    let rBoth = 0, rEither = 0, rPixels = 0;
    for (let k = 0; k < W * H; ++k) {
        const r = differs(roamWith.pixels, roamWithout.pixels, k, 0);
        rBoth += r && vehicleMask[k];
        rEither += r || vehicleMask[k];
        rPixels += r;
    }
    const roamVehicleIoU = rEither ? rBoth / rEither : 0;
    check(rPixels > 200 && roamVehicleIoU >= kMinRoamVehicleIoU,
          `the hovercraft in the ROAM view covers ${rPixels} pixels, IoU ${roamVehicleIoU.toFixed(4)} with the ` +
          `cast's (need ${kMinRoamVehicleIoU})`);

    // (f) T four times (two hours earlier): ROAM view, then the cast.
    const sunBefore = await page.evaluate('overflight.sun()');
    for (let k = 0; k < 4; ++k) await press('T', 'KeyT', 84, 8);
    const roamEarlier = await pixels(true);
    const sunAfter = await page.evaluate('overflight.sun()');
    check(sunAfter.elevation !== sunBefore.elevation,
          `T moved the sun from ${sunBefore.azimuth.toFixed(1)}/${sunBefore.elevation.toFixed(1)} to ` +
          `${sunAfter.azimuth.toFixed(1)}/${sunAfter.elevation.toFixed(1)} degrees (azimuth/elevation)`);
    check(share(roamEarlier, roamView) > 0.1, `the ROAM view is relit (${(100 * share(roamEarlier, roamView)).toFixed(1)}% of pixels)`);
    await press('Tab', 'Tab', 9);
    const castEarlier = await pixels(true);
    let objectPixels = 0, objectChanged = 0;
    for (let k = 0; k < W * H; ++k) {
        objectPixels += objectMask[k];
        objectChanged += objectMask[k] && differs(castEarlier, voxelView, k, 0);
    }
    check(share(castEarlier, voxelView) > 0.1 && objectChanged > 0.5 * objectPixels,
          `the cast is relit (${(100 * share(castEarlier, voxelView)).toFixed(1)}% of pixels) and so are the objects ` +
          `(${objectChanged} of ${objectPixels} pixels)`);
    check(await page.evaluate('overflight.glError()') === 0, 'still no WebGL error');

    check(page.console.every((l) => !/uncaught|error/i.test(l)), `no errors in the page's console${
        page.console.length ? `: ${page.console.join(' | ')}` : ''}`);
    console.log(JSON.stringify({
        site_bytes: siteBytes, site_write_s: writeSeconds, page_load_s: loadSeconds, first_frame_s: firstFrameSeconds,
        equal_share: equalShare, exact_share: exact / (W * H), max_channel_diff: maxDiff, object_iou: iou,
        object_pixels_web: webObjects, object_pixels_native: nativeObjects, position_error_m: error,
        vehicle_iou: vehicleIoU, vehicle_pixels_web: vWeb, vehicle_pixels_native: vNative,
    }));
} catch (e) {
    console.log(`FAIL ${e.stack || e}`);
    ++failures;
} finally {
    if (browser) await browser.close();
    if (server) server.close();
    rmSync(scratch, { recursive: true, force: true });
}
process.exit(failures ? 1 : 0);
