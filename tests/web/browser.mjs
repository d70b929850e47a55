// Headless Chromium driven over the DevTools protocol with nothing but Node
// (18 as Debian 12 ships it, or later): launch a browser in a fresh profile,
// open pages, evaluate expressions in them. The protocol runs over the pipe
// pair Chromium offers with --remote-debugging-pipe (it reads commands on its
// fd 3 and writes replies and events on its fd 4, each message one JSON text
// ended by a NUL byte), so no WebSocket client and no npm package is needed.
// Shared by site_test.mjs and bench/web_fps.mjs.
//
// Based on: the Chrome DevTools Protocol (Target, Page, Runtime domains; one
// browser connection, pages attached as flat sessions).
import { spawn } from 'node:child_process';
import { existsSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

export const CHROMIUM = process.env.OVERFLIGHT_CHROMIUM || '/usr/bin/chromium';

export function chromiumPresent() {
    return existsSync(CHROMIUM);
}

export class Browser {
    // Starts Chromium headless with software WebGL (SwiftShader through ANGLE:
    // no GPU on the test machines) and connects to it.
    static async launch({ width = 1280, height = 720 } = {}) {
        const profile = mkdtempSync(join(tmpdir(), 'overflight-chromium-'));
        const args = [
            '--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
            '--disable-background-networking', '--disable-component-update', '--disable-sync',
            '--disable-default-apps', '--disable-extensions', '--mute-audio',
            '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
            // rAF and timers keep their pace although no one looks at the page.
            '--disable-background-timer-throttling', '--disable-renderer-backgrounding',
            '--disable-backgrounding-occluded-windows',
            `--window-size=${width},${height}`, `--user-data-dir=${profile}`,
            '--remote-debugging-pipe', 'about:blank',
        ];
        // Chromium's own scratch folders (org.chromium.Chromium.*) go under the
        // profile, which close() removes, not into the shared temporary folder.
        const proc = spawn(CHROMIUM, args, {
            stdio: ['ignore', 'ignore', 'pipe', 'pipe', 'pipe'],
            env: { ...process.env, TMPDIR: profile },
        });
        const b = new Browser(proc, profile);
        proc.stderr.on('data', (chunk) => { b.log += chunk; });
        proc.on('exit', (code) => {
            for (const p of b.pending.values()) p.reject(new Error(`chromium exited (${code}):\n${b.log}`));
            b.pending.clear();
        });
        b.connect();
        // The first reply says the browser is up.
        await Promise.race([
            b.send('Browser.getVersion'),
            new Promise((_, reject) => setTimeout(() => reject(new Error(`chromium did not start in 60 s:\n${b.log}`)), 60000)),
        ]);
        return b;
    }

    constructor(proc, profile) {
        this.proc = proc;
        this.profile = profile;
        this.next = 1;
        this.pending = new Map();
        this.listeners = [];
        this.log = '';
    }

    connect() {
        this.input = this.proc.stdio[3];
        let buffered = Buffer.alloc(0);
        this.proc.stdio[4].on('data', (chunk) => {
            buffered = Buffer.concat([buffered, chunk]);
            for (let end = buffered.indexOf(0); end >= 0; end = buffered.indexOf(0)) {
                this.receive(JSON.parse(buffered.subarray(0, end).toString('utf8')));
                buffered = buffered.subarray(end + 1);
            }
        });
    }

    receive(msg) {
        if (msg.id !== undefined) {
            const p = this.pending.get(msg.id);
            this.pending.delete(msg.id);
            if (msg.error) p.reject(new Error(`${p.method}: ${msg.error.message}`));
            else p.resolve(msg.result);
        } else {
            for (const l of this.listeners) l(msg);
        }
    }

    send(method, params = {}, sessionId = undefined) {
        const id = this.next++;
        this.input.write(JSON.stringify({ id, method, params, sessionId }) + '\0');
        return new Promise((resolve, reject) => this.pending.set(id, { resolve, reject, method }));
    }

    // A new tab of width x height CSS pixels showing `url`; resolves after its load event.
    async open(url, { width = 1280, height = 720 } = {}) {
        const { targetId } = await this.send('Target.createTarget', { url: 'about:blank' });
        const { sessionId } = await this.send('Target.attachToTarget', { targetId, flatten: true });
        const page = new Page(this, sessionId);
        this.listeners.push((msg) => {
            if (msg.sessionId === sessionId) page.event(msg);
        });
        await page.send('Runtime.enable');
        await page.send('Page.enable');
        await page.send('Emulation.setDeviceMetricsOverride', { width, height, deviceScaleFactor: 1, mobile: false });
        const loaded = page.waitFor('Page.loadEventFired');
        await page.send('Page.navigate', { url });
        await loaded;
        return page;
    }

    async close() {
        try {
            await Promise.race([this.send('Browser.close'), new Promise((r) => setTimeout(r, 5000))]);
        } catch {
            // Closed already.
        }
        this.input.end();
        // The profile is removed once Chromium has stopped writing into it.
        if (this.proc.exitCode === null && this.proc.signalCode === null) {
            const exited = new Promise((r) => this.proc.once('exit', r));
            this.proc.kill();
            const timer = setTimeout(() => this.proc.kill('SIGKILL'), 10000);
            await exited;
            clearTimeout(timer);
        }
        // Its helper processes can outlive the browser by a moment, still
        // writing into the profile: retry for a few seconds, then leave it.
        for (let attempt = 0; ; ++attempt) {
            try {
                rmSync(this.profile, { recursive: true, force: true });
                return;
            } catch (e) {
                if (attempt === 50) {
                    console.error(`could not remove ${this.profile}: ${e.message}`);
                    return;
                }
                await new Promise((r) => setTimeout(r, 100));
            }
        }
    }
}

class Page {
    constructor(browser, sessionId) {
        this.browser = browser;
        this.sessionId = sessionId;
        this.console = []; // the page's console lines and uncaught exceptions
        this.waiters = [];
    }

    send(method, params = {}) {
        return this.browser.send(method, params, this.sessionId);
    }

    event(msg) {
        if (msg.method === 'Runtime.consoleAPICalled')
            this.console.push(msg.params.args.map((a) => a.value ?? a.description ?? '').join(' '));
        if (msg.method === 'Runtime.exceptionThrown') {
            const d = msg.params.exceptionDetails;
            this.console.push(`uncaught: ${d.exception?.description ?? d.text}`);
        }
        this.waiters = this.waiters.filter((w) => !(w.method === msg.method && (w.resolve(msg.params), true)));
    }

    waitFor(method) {
        return new Promise((resolve) => this.waiters.push({ method, resolve }));
    }

    // The value of `expression` (a promise is awaited), as JSON; throws the page's exception.
    async evaluate(expression) {
        const r = await this.send('Runtime.evaluate', { expression, awaitPromise: true, returnByValue: true });
        if (r.exceptionDetails) {
            const d = r.exceptionDetails;
            throw new Error(`page: ${d.exception?.description ?? d.text}`);
        }
        return r.result.value;
    }
}
