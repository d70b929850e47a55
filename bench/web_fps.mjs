// The frame rate of a site of `overflight web` in headless Chromium
// (software WebGL2, one thread), at a fixed drawing-buffer size, flying
// forward: frames counted over a window after a warm-up, for the ray
// caster's view and for the ROAM view (Tab: the engine's ROAM mesh drawn by
// WebGL2). Run by bench/web_fps.sh.
//
//   node web_fps.mjs SITE [WxH] [SECONDS]
import { Browser } from '../tests/web/browser.mjs';
import { serve } from '../tests/web/serve.mjs';
import { resolve } from 'node:path';

const [site, size = '1280x720', seconds = '10'] = process.argv.slice(2);
const [w, h] = size.split('x').map(Number);
const server = await serve(resolve(site));
const browser = await Browser.launch({ width: w, height: h });
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
try {
    const t0 = Date.now();
    const page = await browser.open(`http://127.0.0.1:${server.port}/?size=${size}`, { width: w, height: h });
    const status = await page.evaluate(`new Promise((resolve) => {
        const poll = () => window.overflight ? resolve(window.overflight.error || 'ready') : setTimeout(poll, 50);
        poll();
    })`);
    if (status !== 'ready') throw new Error(`the page failed: ${status}\n${page.console.join('\n')}`);
    const firstFrame = (Date.now() - t0) / 1000;
    const load = await page.evaluate('overflight.loadSeconds');
    // Fly forward (UP held) so that the view changes every frame.
    await page.send('Input.dispatchKeyEvent', { type: 'rawKeyDown', key: 'ArrowUp', code: 'ArrowUp', windowsVirtualKeyCode: 38 });
    const measure = async (view) => {
        if (await page.evaluate('overflight.state.view') !== view)
            await page.send('Input.dispatchKeyEvent', { type: 'rawKeyDown', key: 'Tab', code: 'Tab', windowsVirtualKeyCode: 9 });
        await sleep(2000);
        const a = await page.evaluate('[overflight.state.frames, performance.now(), overflight.state.engineMs]');
        await sleep(1000 * Number(seconds));
        const b = await page.evaluate('[overflight.state.frames, performance.now(), overflight.state.engineMs]');
        return { fps: (1000 * (b[0] - a[0])) / (b[1] - a[1]), engine_ms: b[2] };
    };
    const voxel = await measure('voxel');
    const roam = { ...(await measure('roam')), ...(await page.evaluate('overflight.roam()')) };
    const vehicle = await page.evaluate('overflight.vehicle()');
    console.log(JSON.stringify({ size, page_load_s: load, first_frame_s: firstFrame, voxel, roam, vehicle }));
} finally {
    await browser.close();
    server.close();
}
