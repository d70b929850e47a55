// Headless Chromium driven over the DevTools protocol with nothing but Node 20
// (its WebSocket client, behind --experimental-websocket): launch a browser in
// a fresh profile, open pages, evaluate expressions in them. Shared by
// site_test.mjs and bench/web_fps.mjs.
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
            '--remote-debugging-port=0', 'about:blank',
        ];
        // Its own process group, so that close() stops its helper processes too.
        const proc = spawn(CHROMIUM, args, { stdio: ['ignore', 'ignore', 'pipe'], detached: true });
        let log = '';
        const url = await new Promise((resolve, reject) => {
            const timer = setTimeout(() => reject(new Error(`chromium did not start in 60 s:\n${log}`)), 60000);
            proc.stderr.on('data', (chunk) => {
                log += chunk;
                const m = /DevTools listening on (ws:\/\/\S+)/.exec(log);
                if (m) {
                    clearTimeout(timer);
                    resolve(m[1]);
                }
            });
            proc.on('exit', (code) => reject(new Error(`chromium exited (${code}):\n${log}`)));
        });
        const b = new Browser(proc, profile);
        await b.connect(url);
        return b;
    }

    constructor(proc, profile) {
        this.proc = proc;
        this.profile = profile;
        this.next = 1;
        this.pending = new Map();
        this.listeners = [];
    }

    connect(url) {
        this.ws = new WebSocket(url);
        this.ws.onmessage = (e) => {
            const msg = JSON.parse(e.data);
            if (msg.id !== undefined) {
                const p = this.pending.get(msg.id);
                this.pending.delete(msg.id);
                if (msg.error) p.reject(new Error(`${p.method}: ${msg.error.message}`));
                else p.resolve(msg.result);
            } else {
                for (const l of this.listeners) l(msg);
            }
        };
        return new Promise((resolve, reject) => {
            this.ws.onopen = resolve;
            this.ws.onerror = () => reject(new Error(`cannot connect to ${url}`));
        });
    }

    send(method, params = {}, sessionId = undefined) {
        const id = this.next++;
        this.ws.send(JSON.stringify({ id, method, params, sessionId }));
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
        this.ws.close();
        // The profile is removed once Chromium and its helpers have stopped
        // writing into it.
        const group = (signal) => {
            try {
                process.kill(-this.proc.pid, signal);
            } catch {
                // None left.
            }
        };
        if (this.proc.exitCode === null) {
            const exited = new Promise((r) => this.proc.once('exit', r));
            group('SIGTERM');
            const timer = setTimeout(() => group('SIGKILL'), 10000);
            await exited;
            clearTimeout(timer);
        }
        group('SIGKILL');
        for (let attempt = 0; ; ++attempt) {
            try {
                rmSync(this.profile, { recursive: true, force: true });
                break;
            } catch (e) {
                if (attempt === 20) throw e;
                await new Promise((r) => setTimeout(r, 250));
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
