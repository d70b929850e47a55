// A static file server on 127.0.0.1 for the tests and the benchmark: what
// `python3 -m http.server -d SITE` does for a user, with the content types a
// browser wants (application/wasm lets it compile the engine while it
// downloads). No server headers beyond those: the page needs none.
import { createServer } from 'node:http';
import { createReadStream, statSync } from 'node:fs';
import { extname, join, normalize } from 'node:path';

const kTypes = {
    '.html': 'text/html; charset=utf-8', '.js': 'text/javascript', '.wasm': 'application/wasm',
    '.json': 'application/json', '.bin': 'application/octet-stream',
};

// Serves `root` on a free port; resolves to { port, close() }.
export function serve(root) {
    const server = createServer((req, res) => {
        let path = decodeURIComponent(new URL(req.url, 'http://x').pathname);
        if (path.endsWith('/')) path += 'index.html';
        const file = join(root, normalize(path));
        let size;
        try {
            if (!file.startsWith(root)) throw new Error('outside');
            size = statSync(file).size;
        } catch {
            res.writeHead(404);
            res.end();
            return;
        }
        res.writeHead(200, { 'Content-Type': kTypes[extname(file)] || 'application/octet-stream', 'Content-Length': size });
        createReadStream(file).pipe(res);
    });
    return new Promise((resolve) => {
        server.listen(0, '127.0.0.1', () => resolve({ port: server.address().port, close: () => server.close() }));
    });
}
