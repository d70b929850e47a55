// The page of `overflight web`: the core compiled to WebAssembly
// (overflight_engine.js/.wasm) runs the hovercraft and casts the terrain's
// color and OpenGL window depth each frame; this shell uploads both into a
// WebGL2 framebuffer and draws the scene's objects over them with the
// Z-buffer, the composite of the native compositor (Szenberg, Gattass,
// Carvalho, "An Algorithm for the Visualization of a Terrain with Objects",
// SIBGRAPI 1997, sec. 5, Fig. 5): the ray caster's depth goes straight into
// the depth attachment, the objects are depth-tested against it, the color is
// blitted to the canvas. Tab switches to the engine's `roam` method (Duchaineau
// et al., "ROAMing Terrain: Real-time Optimally Adapting Meshes", 1997,
// split-only within a triangle budget): the mesh it builds in WebAssembly for
// the same camera is uploaded into WebGL2 buffers and drawn, for comparison.
//
// Plain JavaScript, no build step, one thread (no server headers needed).
// `?size=WxH` fixes the drawing buffer's size; `?test=1` stops the frame loop
// after the first frame and exposes window.overflight for tests/web;
// `?profile=1` times each stage of a frame (Profiler below).
'use strict';

// sim/KeyState.h's Key values.
const Key = {
    Accelerate: 0, Brake: 1, Left: 2, Right: 3, Fog: 4, Lighting: 5, Wireframe: 6, DetailUp: 7, DetailDown: 8,
    NextMethod: 9, Screenshot: 10, Hud: 11, Quit: 12, Shadows: 13, SunLater: 14, SunEarlier: 15, Water: 16,
};
// The arrows are held (sampled by the 100 Hz physics); the rest act on press.
const kArrowKeys = { ArrowUp: Key.Accelerate, ArrowDown: Key.Brake, ArrowLeft: Key.Left, ArrowRight: Key.Right };

// ---------------------------------------------------------------- loading

// The bytes of `url`, reporting progress(received, total) while they arrive;
// `total` is the size site.json gives (a server may send no Content-Length).
async function fetchBytes(url, total, progress) {
    const response = await fetch(url);
    if (!response.ok) throw new Error(`${url}: ${response.status} ${response.statusText}`);
    if (!response.body) return new Uint8Array(await response.arrayBuffer());
    const out = new Uint8Array(total);
    const reader = response.body.getReader();
    let received = 0;
    for (;;) {
        const { done, value } = await reader.read();
        if (done) break;
        if (received + value.length > total) throw new Error(`${url}: larger than site.json says`);
        out.set(value, received);
        received += value.length;
        progress(received, total);
    }
    if (received !== total) throw new Error(`${url}: ${received} bytes, site.json says ${total}`);
    return out;
}

// objects.bin or vehicle.bin (apps/WebSite.h): typed views of the solids,
// the lines and the boxes bounding them.
function parseObjects(bytes, file) {
    const buffer = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
    const magic = new TextDecoder().decode(new Uint8Array(buffer, 0, 7));
    if (magic !== 'OFOBJ01') throw new Error(`${file}: not an Overflight objects file`);
    const [v, i, l, b] = new Uint32Array(buffer, 8, 4);
    let at = 24;
    const take = (Type, n, padTo4 = false) => {
        const a = new Type(buffer, at, n);
        at += n * Type.BYTES_PER_ELEMENT;
        if (padTo4) at = (at + 3) & ~3;
        return a;
    };
    return {
        positions: take(Float32Array, 3 * v), normals: take(Float32Array, 3 * v), colors: take(Uint8Array, 3 * v, true),
        indices: take(Uint32Array, i), linePoints: take(Float32Array, 3 * l), lineColors: take(Uint8Array, 3 * l, true),
        boxes: take(Float32Array, 6 * b),
    };
}

// ---------------------------------------------------------------- the engine

// The smallest module using a SIMD128 instruction (the probe of the
// wasm-feature-detect project): the browser validates it if it runs SIMD.
const kSimdProbe = new Uint8Array([0, 97, 115, 109, 1, 0, 0, 0, 1, 5, 1, 96, 0, 1, 123, 3, 2, 1, 0, 10, 10, 1, 8, 0,
                                   65, 0, 253, 15, 253, 98, 11]);

// The engine's factory (Emscripten, MODULARIZE): the SIMD128 build where the
// browser has SIMD, else the scalar one; `name` says which.
function loadEngineScript() {
    const name = WebAssembly.validate(kSimdProbe) ? 'overflight_engine' : 'overflight_engine_scalar';
    return new Promise((resolve, reject) => {
        const script = document.createElement('script');
        script.src = `${name}.js`;
        script.onload = () => resolve({ name, factory: OverflightEngine }); // eslint-disable-line no-undef
        script.onerror = () => reject(new Error(`${name}.js: cannot load it`));
        document.head.appendChild(script);
    });
}

// The C API of the WebAssembly engine (web/WebEngine.h), with views into its
// heap taken afresh after every call (memory growth may move it).
class Engine {
    constructor(module) {
        this.m = module;
        this.width = 0;
        this.height = 0;
    }

    check(code, what) {
        if (code >= 0) return code;
        const p = this.m._of_error(), heap = this.m.HEAPU8;
        let end = p;
        while (heap[end] !== 0) ++end;
        throw new Error(`${what}: ${new TextDecoder().decode(heap.subarray(p, end))}`);
    }

    loadTerrain(bytes) {
        const p = this.m._malloc(bytes.length);
        if (!p) throw new Error('terrain.bin: not enough memory for it');
        this.m.HEAPU8.set(bytes, p);
        const code = this.m._of_load_terrain(p, bytes.length);
        this.m._free(p);
        this.check(code, 'terrain.bin');
    }

    setSize(w, h) {
        this.check(this.m._of_set_size(w, h), `image size ${w}x${h}`);
        this.width = w;
        this.height = h;
    }

    key(key, down) {
        this.m._of_key(key, down ? 1 : 0);
    }

    frame(seconds) {
        this.check(this.m._of_frame(seconds), 'frame');
    }

    // The terrain method of the next frames: 'voxel' or 'roam'.
    setMethod(name) {
        this.check(this.m._of_set_method(name === 'roam' ? 1 : 0), `method ${name}`);
    }

    // The last ROAM mesh's arrays (views into the heap) and its version,
    // which changes whenever the engine rebuilt them.
    mesh() {
        const m = this.m, heap = m.HEAPU8.buffer, nv = m._of_mesh_vertex_count(), ni = m._of_mesh_index_count();
        return {
            version: m._of_mesh_version(), vertices: nv,
            positions: new Float32Array(heap, m._of_mesh_positions(), 3 * nv),
            normals: new Float32Array(heap, m._of_mesh_normals(), 3 * nv),
            colors: new Uint8Array(heap, m._of_mesh_colors(), 3 * nv),
            indices: new Uint32Array(heap, m._of_mesh_indices(), ni),
        };
    }

    // The last ROAM frame's triangles, budget and milliseconds (tessellation and arrays).
    roamStats() {
        const s = new Float64Array(this.m.HEAPU8.buffer, this.m._of_roam_stats(), 8);
        return { triangles: s[0], vertices: s[1], ms: s[7], budget: this.m._of_roam_budget() };
    }

    // The sun of the last frame: azimuth, elevation (degrees) and the unit direction towards it.
    sun() {
        const s = new Float64Array(this.m.HEAPU8.buffer, this.m._of_sun(), 5);
        return { azimuth: s[0], elevation: s[1], dir: [s[2], s[3], s[4]] };
    }

    // The last frame's color (RGB8) and window depth, rows from the top.
    color() {
        return new Uint8Array(this.m.HEAPU8.buffer, this.m._of_color(), this.width * this.height * 3);
    }

    depth() {
        return new Float32Array(this.m.HEAPU8.buffer, this.m._of_depth(), this.width * this.height);
    }

    // The last frame's camera: eye, heading, pitch, fov, near, far.
    camera() {
        const c = new Float64Array(this.m.HEAPU8.buffer, this.m._of_camera(), 8);
        return { eye: [c[0], c[1], c[2]], heading: c[3], pitch: c[4], fov: c[5], near: c[6], far: c[7] };
    }

    vehicle() {
        const v = new Float64Array(this.m.HEAPU8.buffer, this.m._of_vehicle(), 5);
        return { x: v[0], y: v[1], z: v[2], heading: v[3], velocity: v[4] };
    }

    // The hovercraft body's frame (origin, right, up, forward), into `out` (12 floats).
    vehicleFrame(out) {
        out.set(new Float64Array(this.m.HEAPU8.buffer, this.m._of_vehicle_frame(), 12));
        return out;
    }

    // The objects' world boxes (6 floats each), which bound of_depth_rect.
    setObjectBounds(boxes) {
        const p = this.m._malloc(Math.max(4, boxes.byteLength));
        if (!p) throw new Error('objects.bin: not enough memory for its boxes');
        new Float32Array(this.m.HEAPU8.buffer, p, boxes.length).set(boxes);
        const code = this.m._of_set_object_bounds(p, boxes.length / 6);
        this.m._free(p);
        this.check(code, 'objects.bin');
    }

    // The last frame's pixels objects can cover: [col0, row0, col1, row1], rows from the top.
    depthRect() {
        return new Int32Array(this.m.HEAPU8.buffer, this.m._of_depth_rect(), 4);
    }

    physicsSteps() {
        return this.m._of_physics_steps();
    }

    // The viewer's toggles: fog mode (0 off, 1 GL_EXP, 2 atmosphere), sun
    // lighting, the hovercraft drawn (the chase camera).
    toggles() {
        const t = this.m._of_toggles();
        return { lighting: (t & 2) !== 0, fog: (t >> 4) & 3, vehicle: (t & 64) !== 0 };
    }

    setCamera(c) {
        this.check(this.m._of_set_camera(c.eye[0], c.eye[1], c.eye[2], c.heading, c.pitch, c.fov, c.near, c.far),
                   'camera');
    }

    followVehicle() {
        this.m._of_follow_vehicle();
    }
}

// The eye-relative view-projection of DESIGN sec. 2's shear camera, as the
// native FrameUniforms builds it (core/Camera.h projection_matrix() *
// view_matrix() * translate(eye), in double, rounded once to float): the
// shaders transform (world - eye), so that float positions far from the
// origin lose no precision.
function viewProjection(camera, width, height) {
    const rad = Math.PI / 180;
    const h = camera.heading * rad;
    const f = [Math.sin(h), 0, Math.cos(h)];
    const s = [-Math.cos(h), 0, Math.sin(h)]; // right = forward x up
    const u = [0, 1, 0];
    const n = camera.near, far = camera.far;
    const t = Math.tan((camera.fov * rad) / 2), aspect = height / width, shift = Math.tan(camera.pitch * rad);
    const l = -n * t, r = n * t, b = n * (-aspect * t + shift), top = n * (aspect * t + shift);
    // Column-major projection (glm::frustum) and rotation (glm::lookAt without its translation).
    const P = [2 * n / (r - l), 0, 0, 0, 0, 2 * n / (top - b), 0, 0, (r + l) / (r - l), (top + b) / (top - b),
               -(far + n) / (far - n), -1, 0, 0, -2 * far * n / (far - n), 0];
    const V = [s[0], u[0], -f[0], 0, s[1], u[1], -f[1], 0, s[2], u[2], -f[2], 0, 0, 0, 0, 1];
    const out = new Float32Array(16);
    for (let c = 0; c < 4; ++c)
        for (let row = 0; row < 4; ++row) {
            let sum = 0;
            for (let k = 0; k < 4; ++k) sum += P[k * 4 + row] * V[c * 4 + k];
            out[c * 4 + row] = sum;
        }
    return out;
}

// ---------------------------------------------------------------- WebGL2

// `?profile=1`: each stage of a frame ended by reading one pixel back (so
// that the software WebGL's work lands in the stage that queued it: Chrome's
// gl.finish() returned before SwiftShader had drawn, measured) and timed; the
// milliseconds per stage averaged over the frames since the last report().
// Off, mark() does nothing: the read-backs stall the page.
class Profiler {
    constructor(on) {
        this.on = on;
        this.gl = null;
        this.pixel = new Uint8Array(4);
        this.sums = {};
        this.frames = 0;
        this.t = 0;
    }

    begin() {
        if (this.on) this.t = performance.now();
    }

    mark(stage) {
        if (!this.on) return;
        if (this.gl) this.gl.readPixels(0, 0, 1, 1, this.gl.RGBA, this.gl.UNSIGNED_BYTE, this.pixel);
        const now = performance.now();
        this.sums[stage] = (this.sums[stage] || 0) + now - this.t;
        this.t = now;
    }

    end() {
        if (this.on) ++this.frames;
    }

    report() {
        const out = {};
        for (const [k, v] of Object.entries(this.sums)) out[k] = +(v / Math.max(1, this.frames)).toFixed(2);
        this.sums = {};
        this.frames = 0;
        return out;
    }
}
const profiler = new Profiler(new URLSearchParams(location.search).has('profile'));

function compile(gl, vs, fs) {
    const program = gl.createProgram();
    for (const [type, src] of [[gl.VERTEX_SHADER, vs], [gl.FRAGMENT_SHADER, fs]]) {
        const s = gl.createShader(type);
        gl.shaderSource(s, '#version 300 es\nprecision highp float;\n' + src);
        gl.compileShader(s);
        if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(`shader: ${gl.getShaderInfoLog(s)}`);
        gl.attachShader(program, s);
    }
    gl.linkProgram(program);
    if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error(`program: ${gl.getProgramInfoLog(program)}`);
    const uniforms = {};
    for (let k = 0; k < gl.getProgramParameter(program, gl.ACTIVE_UNIFORMS); ++k) {
        const name = gl.getActiveUniform(program, k).name;
        uniforms[name] = gl.getUniformLocation(program, name);
    }
    return { program, uniforms };
}

// The lighting of the native compositor's shade() and fogged()
// (gl/GlProgram.cpp), term for term: lit = albedo (ambient + sun_color
// max(N.sun, 0)), no sun at or below the horizon; then GL_EXP fog,
// mix(fog_color, lit, exp(-density |P - eye|)), or with the atmosphere the
// aerial perspective of core/AerialPerspective.h (Hoffman, Preetham,
// "Rendering Outdoor Light Scattering in Real Time", GDC 2002) with the
// per-frame constants of aerialFrame(). `atmosphere` is the native shaders'
// own GLSL of that aerial perspective and sky (the site's atmosphere.glsl,
// gl/AtmosphereGlsl.h), so the formula is written once for every GPU.
// Each program is compiled twice, with AIR 1 (the atmosphere) and AIR 0 (the
// fog): a branch on a uniform instead made SwiftShader pay for the
// atmosphere on every pixel even with it off (a full-screen sky 4x slower,
// measured in headless Chromium).
const shadeGlsl = (atmosphere) => `
uniform mat4 view_proj; // eye-relative: multiplies (world - eye)
uniform vec3 eye, sun_dir, sun_color, ambient, fog_color;
uniform float fog_density, baked;
uniform vec4 air_beta, air_rayleigh, air_haze;
${atmosphere}
vec3 fogged(vec3 color, vec3 world) {
#if AIR
    return aerial(color, world);
#else
    return mix(fog_color, color, exp(-fog_density * length(world - eye)));
#endif
}
vec3 shade(vec3 albedo, vec3 n, vec3 world) {
    if (baked > 0.0) return fogged(albedo, world);
    float lambert = sun_dir.y > 0.0 ? max(dot(normalize(n), sun_dir), 0.0) : 0.0;
    return fogged(albedo * (ambient + sun_color * lambert), world);
}
`;

// The atmosphere's constants for an eye at height eyeY (core/AerialPerspective.cpp
// aerial_frame(), as gl/FrameUniforms.cpp puts them in its uniform block).
function aerialFrame(environment, eyeY) {
    const a = environment.air;
    const s = environment.sun_dir, n = Math.hypot(s[0], s[1], s[2]);
    const sunY = n > 0 ? s[1] / n : 1;
    const heightFactor = (x) => {
        x = Math.max(x, -40);
        return Math.abs(x) < 1e-3 ? 1 - x * (0.5 - x / 6) : (1 - Math.exp(-x)) / x;
    };
    const airMass = (sine) => {
        const v = Math.min(Math.max(sine, 0), 1);
        return 1 / (v + 0.50572 * Math.pow((Math.asin(v) * 180) / Math.PI + 6.07995, -1.6364));
    };
    const beta = a.rayleigh.map((r) => r + a.haze);
    const eyeDensity = Math.exp(-eyeY / a.scale_height);
    const twilight = Math.min(Math.max(1 + sunY / 0.1, 0), 1);
    const column = eyeDensity * a.scale_height * airMass(sunY);
    const light = beta.map((b, c) => a.exposure * a.sunlight[c] * heightFactor(b * column) * twilight);
    return {
        beta: [...beta.map((b) => b * eyeDensity), a.scale_height],
        rayleigh: [...light.map((l, c) => (l * a.rayleigh[c]) / beta[c]), a.haze_g],
        haze: [...light.map((l, c) => (l * a.haze) / beta[c]), 1],
    };
}

const kLitVs = `
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 color;
uniform float flip_y;
out vec3 v_world, v_normal, v_color;
void main() {
    v_world = position;
    v_normal = normal;
    v_color = color;
    gl_Position = view_proj * vec4(position - eye, 1.0);
    gl_Position.y *= flip_y;
}
`;

// The hovercraft (vehicle.bin, in its own frame: base centre at the origin,
// +Z forward) placed by the engine's body frame (sim/VehicleBody.h, as `fly`
// places it): world = origin + axes * p, its normals turned alike. The
// origin comes eye-relative (body_offset = origin - eye, in double).
const kVehicleVs = `
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 color;
uniform float flip_y;
uniform vec3 body_offset;
uniform mat3 body_axes; // columns: right, up, forward
out vec3 v_world, v_normal, v_color;
void main() {
    vec3 relative = body_offset + body_axes * position;
    v_world = eye + relative;
    v_normal = body_axes * normal;
    v_color = color;
    gl_Position = view_proj * vec4(relative, 1.0);
    gl_Position.y *= flip_y;
}
`;

const kLitFs = `
in vec3 v_world, v_normal, v_color;
out vec4 frag;
void main() { frag = vec4(shade(v_color, v_normal, v_world), 1.0); }
`;

// The ROAM view's terrain: shade() per vertex (Gouraud), interpolated. The
// software rasteriser of headless Chromium (SwiftShader) fills 1280x720 with
// the per-fragment shade() three times slower than with a plain color
// (measured), and the mesh covers the screen; ROAM's triangles are a few
// pixels across, so lighting and fog interpolated over them differ little.
const kTerrainVs = `
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 color;
out vec3 v_color;
void main() {
    v_color = shade(color, normal, position);
    gl_Position = view_proj * vec4(position - eye, 1.0);
}
`;

const kColorFs = `
in vec3 v_color;
out vec4 frag;
void main() { frag = vec4(v_color, 1.0); }
`;

const kLineFs = `
in vec3 v_world, v_normal, v_color;
out vec4 frag;
void main() { frag = vec4(fogged(v_color, v_world), 1.0); }
`;

// The sky of the mesh view (gl/SkyPass.cpp): the horizon color blended to the
// zenith's by the height of the view ray through the pixel, or the
// atmosphere's sky.
const kSkyVs = `
out vec2 ndc;
void main() {
    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2) * 2.0 - 1.0;
    ndc = p;
    gl_Position = vec4(p, 1.0, 1.0);
}
`;
const kSkyFs = `
in vec2 ndc;
uniform mat4 inverse_view_proj;
uniform vec3 sky_horizon, sky_zenith;
out vec4 frag;
void main() {
    vec4 near = inverse_view_proj * vec4(ndc, -1.0, 1.0), far = inverse_view_proj * vec4(ndc, 1.0, 1.0);
    vec3 dir = far.xyz / far.w - near.xyz / near.w;
#if AIR
    frag = vec4(air_sky(dir), 1.0);
#else
    frag = vec4(mix(sky_horizon, sky_zenith, max(normalize(dir).y, 0.0)), 1.0);
#endif
}
`;

// The composite to the canvas, rows turned over (texture row 0 is the
// image's top) by the full-screen triangle's texture coordinates: the
// interpolated coordinate lands mid-texel at each pixel centre, so the
// nearest texel is exactly the pixel's. SwiftShader fills 1280x720 with this
// plain texture() in half the time of a texelFetch at integer
// coordinates computed per fragment (measured in headless Chromium).
const kPresentVs = `
out vec2 uv;
void main() {
    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2) * 2.0 - 1.0;
    uv = vec2(0.5 * p.x + 0.5, 0.5 - 0.5 * p.y);
    gl_Position = vec4(p, 1.0, 1.0);
}
`;
const kPresentFs = `
uniform highp sampler2D image;
in vec2 uv;
out vec4 frag;
void main() { frag = texture(image, uv); }
`;

// A triangle mesh (or line list) in GL buffers, attributes as kLitVs reads them.
class GlMesh {
    constructor(gl, positions, normals, colors, indices) {
        this.gl = gl;
        this.vao = gl.createVertexArray();
        gl.bindVertexArray(this.vao);
        const attribute = (location, data, size, type, normalized) => {
            const b = gl.createBuffer();
            gl.bindBuffer(gl.ARRAY_BUFFER, b);
            gl.bufferData(gl.ARRAY_BUFFER, data, gl.STATIC_DRAW);
            gl.enableVertexAttribArray(location);
            gl.vertexAttribPointer(location, size, type, normalized, 0, 0);
        };
        attribute(0, positions, 3, gl.FLOAT, false);
        if (normals) attribute(1, normals, 3, gl.FLOAT, false);
        else gl.vertexAttrib3f(1, 0, 1, 0);
        attribute(2, colors, 3, gl.UNSIGNED_BYTE, true);
        this.count = indices ? indices.length : positions.length / 3;
        if (indices) {
            gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, gl.createBuffer());
            gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, indices, gl.STATIC_DRAW);
        }
        this.indexed = !!indices;
        gl.bindVertexArray(null);
    }

    draw(mode) {
        if (this.count === 0) return;
        const gl = this.gl;
        gl.bindVertexArray(this.vao);
        if (this.indexed) gl.drawElements(mode, this.count, gl.UNSIGNED_INT, 0);
        else gl.drawArrays(mode, 0, this.count);
        gl.bindVertexArray(null);
    }
}

// The inverse of a column-major 4x4 matrix (Gauss-Jordan in double).
function invert4(m) {
    const a = [];
    for (let r = 0; r < 4; ++r) a.push([m[r], m[4 + r], m[8 + r], m[12 + r], r === 0 ? 1 : 0, r === 1 ? 1 : 0, r === 2 ? 1 : 0, r === 3 ? 1 : 0]);
    for (let c = 0; c < 4; ++c) {
        let p = c;
        for (let r = c + 1; r < 4; ++r) if (Math.abs(a[r][c]) > Math.abs(a[p][c])) p = r;
        [a[c], a[p]] = [a[p], a[c]];
        const pivot = a[c][c];
        for (let k = 0; k < 8; ++k) a[c][k] /= pivot;
        for (let r = 0; r < 4; ++r) {
            if (r === c) continue;
            const f = a[r][c];
            for (let k = 0; k < 8; ++k) a[r][k] -= f * a[c][k];
        }
    }
    const out = new Float32Array(16);
    for (let r = 0; r < 4; ++r) for (let c = 0; c < 4; ++c) out[c * 4 + r] = a[r][4 + c];
    return out;
}

// The composite: an offscreen framebuffer whose color and depth attachments
// receive the engine's images, the objects drawn into it, and a blit to the
// canvas (gl/Compositor.h, "Images"); or, in the mesh view, the sky, the
// terrain mesh and the objects (its "Mesh").
//
// A view is { viewProj (eye-relative, viewProjection()), eye, sunDir (unit,
// towards the sun: the engine's, which the time-of-day keys move),
// fogDensity, air (aerialFrame(), or null: no atmosphere), baked (the
// terrain's colors unlit), vehicle (the hovercraft's body frame,
// Engine.vehicleFrame(), or null: none drawn) }.
class Renderer {
    constructor(canvas, site, objects, vehicle) {
        const gl = canvas.getContext('webgl2', { antialias: false, depth: true, alpha: false, preserveDrawingBuffer: false });
        if (!gl) throw new Error('this browser has no WebGL2');
        this.gl = gl;
        this.environment = site.environment;
        const shade = shadeGlsl(site.atmosphere);
        // The fog's program, its atmosphere variant as .air (use() picks).
        const shaded = (vs, fs) => {
            const air = (on) => `#define AIR ${on}\n`;
            return { ...compile(gl, air(0) + vs, air(0) + fs), air: compile(gl, air(1) + vs, air(1) + fs) };
        };
        this.lit = shaded(shade + kLitVs, shade + kLitFs);
        this.line = shaded(shade + kLitVs, shade + kLineFs);
        this.sky = shaded(kSkyVs, shade + kSkyFs);
        this.terrain = shaded(shade + kTerrainVs, kColorFs);
        this.present = compile(gl, kPresentVs, kPresentFs);
        this.solids = new GlMesh(gl, objects.positions, objects.normals, objects.colors, objects.indices);
        this.lines = new GlMesh(gl, objects.linePoints, null, objects.lineColors, null);
        this.vehicleProgram = shaded(shade + kVehicleVs, shade + kLitFs);
        this.vehicle = new GlMesh(gl, vehicle.positions, vehicle.normals, vehicle.colors, vehicle.indices);
        this.bodyOffset = new Float32Array(3);
        this.bodyAxes = new Float32Array(9);
        this.fbo = gl.createFramebuffer();
        this.width = 0;
        this.height = 0;
    }

    resize(w, h) {
        const gl = this.gl;
        if (w === this.width && h === this.height) return;
        this.width = w;
        this.height = h;
        if (this.color) gl.deleteTexture(this.color);
        if (this.depth) gl.deleteTexture(this.depth);
        const texture = (format) => {
            const t = gl.createTexture();
            gl.bindTexture(gl.TEXTURE_2D, t);
            gl.texStorage2D(gl.TEXTURE_2D, 1, format, w, h);
            gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
            gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
            return t;
        };
        this.color = texture(gl.RGB8);
        this.depth = texture(gl.DEPTH_COMPONENT32F);
        gl.bindFramebuffer(gl.FRAMEBUFFER, this.fbo);
        gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, this.color, 0);
        gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.DEPTH_ATTACHMENT, gl.TEXTURE_2D, this.depth, 0);
        if (gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE) throw new Error('framebuffer incomplete');
        gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    }

    // Makes `program` (its atmosphere variant if the view has the
    // atmosphere) current with the view's uniforms; returns the one in use.
    use(program, view, flipY, baked) {
        if (program.air && view.air) program = program.air;
        const gl = this.gl;
        const e = this.environment;
        const u = program.uniforms;
        gl.useProgram(program.program);
        gl.uniformMatrix4fv(u.view_proj, false, view.viewProj);
        gl.uniform3fv(u.eye, view.eye);
        gl.uniform3fv(u.sun_dir, view.sunDir);
        gl.uniform3fv(u.sun_color, e.sun_color);
        gl.uniform3fv(u.ambient, e.ambient);
        gl.uniform3fv(u.fog_color, e.fog_color);
        gl.uniform1f(u.fog_density, view.fogDensity);
        const air = view.air || { beta: [0, 0, 0, 1], rayleigh: [0, 0, 0, 0], haze: [0, 0, 0, 0] };
        gl.uniform4fv(u.air_beta, air.beta);
        gl.uniform4fv(u.air_rayleigh, air.rayleigh);
        gl.uniform4fv(u.air_haze, air.haze);
        gl.uniform1f(u.baked, baked ? 1 : 0);
        if (u.flip_y) gl.uniform1f(u.flip_y, flipY);
        return program;
    }

    // The objects and the hovercraft, lit by the engine's sun (never baked:
    // the native compositor lights them whatever the terrain's lighting),
    // depth-tested, no culling.
    drawObjects(view, flipY) {
        const gl = this.gl;
        gl.enable(gl.DEPTH_TEST);
        gl.depthFunc(gl.LESS);
        gl.depthMask(true);
        // The solids are closed and wound counter-clockwise seen from
        // outside (gl/ObjectGeometry.h): their back faces are hidden, and
        // culling them halves SwiftShader's fragments. Drawn upside down
        // (flipY -1) the winding turns over.
        gl.enable(gl.CULL_FACE);
        gl.frontFace(flipY < 0 ? gl.CW : gl.CCW);
        this.use(this.lit, view, flipY, false);
        this.solids.draw(gl.TRIANGLES);
        this.use(this.line, view, flipY, false);
        this.lines.draw(gl.LINES);
        if (view.vehicle) {
            const f = view.vehicle;
            for (let c = 0; c < 3; ++c) this.bodyOffset[c] = f[c] - view.eye[c];
            this.bodyAxes.set(f.subarray(3, 12));
            const p = this.use(this.vehicleProgram, view, flipY, false);
            gl.uniform3fv(p.uniforms.body_offset, this.bodyOffset);
            gl.uniformMatrix3fv(p.uniforms.body_axes, false, this.bodyAxes);
            this.vehicle.draw(gl.TRIANGLES);
        }
        gl.disable(gl.CULL_FACE);
        gl.frontFace(gl.CCW);
    }

    // The ray caster's frame: its color and depth (rows from the top) loaded
    // as they are, so that the framebuffer holds the image upside down; the
    // objects are drawn upside down to match (clip y negated: pixel centres
    // mirror onto pixel centres), and a full-screen pass copies the whole to
    // the canvas the right way up (a blit instead showed black in Chromium's
    // SwiftShader when nothing had been drawn into the framebuffer).
    drawCast(engine, view, objects) {
        const gl = this.gl;
        const w = engine.width, h = engine.height;
        this.resize(w, h);
        gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
        gl.bindTexture(gl.TEXTURE_2D, this.color);
        gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, w, h, gl.RGB, gl.UNSIGNED_BYTE, engine.color());
        profiler.mark('color');
        gl.bindFramebuffer(gl.FRAMEBUFFER, this.fbo);
        gl.viewport(0, 0, w, h);
        const [c0, r0, c1, r1] = engine.depthRect();
        if (objects && c1 > c0 && r1 > r0) {
            // The window depth goes straight into the depth attachment
            // (Szenberg eq. 7), only inside the rectangle objects can cover:
            // no fragment is drawn outside it, so the stale depth there is
            // never tested.
            gl.pixelStorei(gl.UNPACK_ALIGNMENT, 4);
            gl.pixelStorei(gl.UNPACK_ROW_LENGTH, w);
            gl.bindTexture(gl.TEXTURE_2D, this.depth);
            gl.texSubImage2D(gl.TEXTURE_2D, 0, c0, r0, c1 - c0, r1 - r0, gl.DEPTH_COMPONENT, gl.FLOAT,
                             engine.depth().subarray(r0 * w + c0, (r1 - 1) * w + c1));
            gl.pixelStorei(gl.UNPACK_ROW_LENGTH, 0);
            profiler.mark('depth');
            this.drawObjects(view, -1);
            profiler.mark('objects');
        }
        gl.bindFramebuffer(gl.FRAMEBUFFER, null);
        gl.disable(gl.DEPTH_TEST);
        gl.useProgram(this.present.program);
        gl.activeTexture(gl.TEXTURE0);
        gl.bindTexture(gl.TEXTURE_2D, this.color);
        gl.uniform1i(this.present.uniforms.image, 0);
        gl.drawArrays(gl.TRIANGLES, 0, 3);
        profiler.mark('present');
    }

    // The comparison view: the terrain as a WebGL2 mesh (RoamMeshView), the
    // objects, and the sky behind them: drawn last at the far plane where the
    // depth buffer still holds it, so that the fill-bound software rasteriser
    // shades each pixel once.
    drawMesh(w, h, view, mesh, wireframe) {
        const gl = this.gl;
        const e = this.environment;
        gl.bindFramebuffer(gl.FRAMEBUFFER, null);
        gl.viewport(0, 0, w, h);
        gl.depthMask(true);
        gl.clearDepth(1);
        gl.clear(gl.DEPTH_BUFFER_BIT);
        gl.enable(gl.DEPTH_TEST);
        gl.depthFunc(gl.LESS);
        this.use(this.terrain, view, 1, view.baked);
        if (wireframe) mesh.drawWireframe();
        else mesh.draw();
        this.drawObjects(view, 1);
        gl.depthFunc(gl.LEQUAL);
        gl.depthMask(false);
        const sky = this.use(this.sky, view, 1, false);
        gl.uniformMatrix4fv(sky.uniforms.inverse_view_proj, false, invert4(view.viewProj));
        gl.uniform3fv(sky.uniforms.sky_horizon, e.sky_horizon);
        gl.uniform3fv(sky.uniforms.sky_zenith, e.sky_zenith);
        gl.drawArrays(gl.TRIANGLES, 0, 3);
        gl.depthMask(true);
        gl.depthFunc(gl.LESS);
    }

    // The canvas as RGBA rows from the top (tests).
    readPixels() {
        const gl = this.gl;
        const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
        const up = new Uint8Array(w * h * 4);
        gl.bindFramebuffer(gl.FRAMEBUFFER, null);
        gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, up);
        const out = new Uint8Array(w * h * 4);
        for (let r = 0; r < h; ++r) out.set(up.subarray((h - 1 - r) * w * 4, (h - r) * w * 4), r * w * 4);
        return out;
    }
}

// The engine's ROAM mesh in WebGL2 buffers, attributes as kTerrainVs reads them.
// The buffers are sized once for the mesh (and grown by half again when a
// larger one comes); each new mesh is copied into them with bufferSubData,
// the plain-array upload of the native renderer. The wireframe's line list
// is made from the triangles only while it is shown.
class RoamMeshView {
    constructor(gl) {
        this.gl = gl;
        this.vao = gl.createVertexArray();
        this.buffers = [gl.createBuffer(), gl.createBuffer(), gl.createBuffer()];
        this.indexBuffer = gl.createBuffer();
        this.edgeBuffer = gl.createBuffer();
        this.bytes = new Map(); // the size of each buffer's store
        this.version = -1;
        this.edgeVersion = -1;
        this.count = 0;
        this.indices = null;
        gl.bindVertexArray(this.vao);
        [[3, gl.FLOAT, false], [3, gl.FLOAT, false], [3, gl.UNSIGNED_BYTE, true]].forEach(([size, type, norm], k) => {
            gl.bindBuffer(gl.ARRAY_BUFFER, this.buffers[k]);
            gl.enableVertexAttribArray(k);
            gl.vertexAttribPointer(k, size, type, norm, 0, 0);
        });
        gl.bindVertexArray(null);
    }

    // Copies `data` into `buffer` (bound to `target`), growing its store when
    // it is too small.
    upload(target, buffer, data) {
        const gl = this.gl;
        gl.bindBuffer(target, buffer);
        if (data.byteLength > (this.bytes.get(buffer) || 0)) {
            const bytes = Math.ceil(data.byteLength * 1.5);
            gl.bufferData(target, bytes, gl.DYNAMIC_DRAW);
            this.bytes.set(buffer, bytes);
        }
        gl.bufferSubData(target, 0, data);
    }

    // Uploads the engine's mesh (Engine.mesh()) unless it is the one uploaded last.
    update(mesh) {
        if (mesh.version === this.version) return;
        const gl = this.gl;
        gl.bindVertexArray(null); // the element buffer is bound to the VAO when drawing
        [mesh.positions, mesh.normals, mesh.colors].forEach((a, k) => this.upload(gl.ARRAY_BUFFER, this.buffers[k], a));
        this.upload(gl.ELEMENT_ARRAY_BUFFER, this.indexBuffer, mesh.indices);
        this.count = mesh.indices.length;
        this.indices = mesh.indices.slice(); // the heap's view goes stale at the next engine call
        this.version = mesh.version;
    }

    draw() {
        if (this.count === 0) return;
        const gl = this.gl;
        gl.bindVertexArray(this.vao);
        gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, this.indexBuffer);
        gl.drawElements(gl.TRIANGLES, this.count, gl.UNSIGNED_INT, 0);
        gl.bindVertexArray(null);
    }

    drawWireframe() {
        if (this.count === 0) return;
        const gl = this.gl;
        gl.bindVertexArray(this.vao);
        if (this.edgeVersion !== this.version) {
            const t = this.indices, edges = new Uint32Array(2 * t.length);
            for (let k = 0; k < t.length; k += 3)
                edges.set([t[k], t[k + 1], t[k + 1], t[k + 2], t[k + 2], t[k]], 2 * k);
            this.upload(gl.ELEMENT_ARRAY_BUFFER, this.edgeBuffer, edges);
            this.edgeVersion = this.version;
        }
        gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, this.edgeBuffer);
        gl.drawElements(gl.LINES, 2 * this.count, gl.UNSIGNED_INT, 0);
        gl.bindVertexArray(null);
    }
}

// ---------------------------------------------------------------- the page

// terrain.bin (core/WebTerrainFormat.h, "OFTERR01"): what the shell needs of
// it besides the engine, i.e. the grid's extent for the fog and the lighting
// the objects are shaded with.
function parseTerrain(bytes) {
    const d = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    const f32 = (at) => d.getFloat32(at, true);
    const vec3 = (at) => [f32(at), f32(at + 4), f32(at + 8)];
    const rows = d.getInt32(8, true), cols = d.getInt32(12, true);
    return {
        rows, cols, hScale: f32(16),
        environment: {
            sun_dir: vec3(36), sun_color: vec3(48), ambient: vec3(60), fog_density: f32(72), fog_color: vec3(76),
            sky_zenith: vec3(88), sky_horizon: vec3(100),
            air: {
                rayleigh: vec3(116), haze: f32(128), scale_height: f32(132), haze_g: f32(136), exposure: f32(140),
                sunlight: vec3(144),
            },
        },
    };
}

// The GL_EXP fog of the flight's current fog mode (sim/FlightSession.h
// view_environment): the data set's density, or one that fades the far
// side of the map when it has none; nothing with the fog off.
function fogDensity(terrain, fogMode) {
    if (fogMode !== 1) return 0;
    const e = terrain.environment.fog_density;
    if (e > 0) return e;
    const w = terrain.hScale * (terrain.cols - 1), d = terrain.hScale * (terrain.rows - 1);
    return Math.fround(2 / Math.max(1, Math.hypot(w, d)));
}

function toBase64(bytes) {
    let s = '';
    for (let k = 0; k < bytes.length; k += 0x8000) s += String.fromCharCode.apply(null, bytes.subarray(k, k + 0x8000));
    return btoa(s);
}

async function main() {
    const params = new URLSearchParams(location.search);
    const testing = params.has('test');
    const canvas = document.getElementById('view');
    const hud = document.getElementById('hud');
    const help = document.getElementById('help');
    const status = document.getElementById('status');
    const fill = document.getElementById('fill');
    const t0 = performance.now();

    const siteResponse = await fetch('site.json');
    if (!siteResponse.ok) throw new Error(`site.json: ${siteResponse.status} ${siteResponse.statusText}`);
    const site = await siteResponse.json();
    const enginePromise = loadEngineScript().then(async ({ name, factory }) => ({ name, module: await factory() }));
    const [terrainBytes, objectBytes, vehicleBytes, atmosphere] = await Promise.all([
        fetchBytes(site.terrain.file, site.terrain.bytes, (got, total) => {
            fill.style.width = `${(100 * got) / total}%`;
            status.textContent = `loading the terrain: ${(got / 1e6).toFixed(1)} of ${(total / 1e6).toFixed(1)} MB`;
        }),
        fetchBytes(site.objects.file, site.objects.bytes, () => {}),
        fetchBytes(site.vehicle.file, site.vehicle.bytes, () => {}),
        fetch('atmosphere.glsl').then((r) => {
            if (!r.ok) throw new Error(`atmosphere.glsl: ${r.status} ${r.statusText}`);
            return r.text();
        }),
    ]);
    status.textContent = 'starting the engine';
    const loaded = await enginePromise;
    const engine = new Engine(loaded.module);
    engine.loadTerrain(terrainBytes);
    const terrain = parseTerrain(terrainBytes);
    const objects = parseObjects(objectBytes, site.objects.file);
    engine.setObjectBounds(objects.boxes);
    const renderer = new Renderer(canvas, { environment: terrain.environment, atmosphere }, objects,
                                  parseObjects(vehicleBytes, site.vehicle.file));
    const vehicleFrame = new Float64Array(12);
    let showVehicle = true; // tests hide it
    const roam = new RoamMeshView(renderer.gl); // the comparison view's mesh
    profiler.gl = renderer.gl;

    const fixed = /^(\d+)x(\d+)$/.exec(params.get('size') || '');
    const resize = () => {
        const w = fixed ? +fixed[1] : Math.max(16, canvas.clientWidth);
        const h = fixed ? +fixed[2] : Math.max(16, canvas.clientHeight);
        if (canvas.width !== w || canvas.height !== h || engine.width !== w || engine.height !== h) {
            canvas.width = w;
            canvas.height = h;
            engine.setSize(w, h);
        }
    };

    const state = { view: 'voxel', wireframe: false, hud: true, objects: true, frames: 0, fps: 0, engineMs: 0 };
    // Draws the engine's last frame.
    const draw = () => {
        const toggles = engine.toggles();
        const camera = engine.camera();
        const sunDir = engine.sun().dir;
        const view = {
            viewProj: viewProjection(camera, engine.width, engine.height),
            eye: new Float32Array(camera.eye),
            sunDir: new Float32Array(sunDir),
            fogDensity: fogDensity(terrain, toggles.fog),
            air: toggles.fog === 2 ? aerialFrame({ ...terrain.environment, sun_dir: sunDir }, camera.eye[1]) : null,
            baked: !toggles.lighting,
            vehicle: toggles.vehicle && showVehicle ? engine.vehicleFrame(vehicleFrame) : null,
        };
        if (state.view === 'voxel') {
            renderer.drawCast(engine, view, state.objects);
        } else {
            roam.update(engine.mesh());
            profiler.mark('mesh upload');
            renderer.drawMesh(engine.width, engine.height, view, roam, state.wireframe);
            profiler.mark('mesh draw');
        }
    };

    // The HUD: fps over the last second, the method, the vehicle.
    let windowStart = performance.now(), windowFrames = 0;
    const showHud = () => {
        const now = performance.now();
        ++windowFrames;
        if (now - windowStart >= 1000) {
            state.fps = (1000 * windowFrames) / (now - windowStart);
            windowStart = now;
            windowFrames = 0;
        }
        help.hidden = !state.hud;
        if (!state.hud) {
            hud.textContent = '';
            return;
        }
        const v = engine.vehicle();
        const fog = ['fog off', 'GL_EXP fog', 'atmosphere'][engine.toggles().fog];
        const roamStats = engine.roamStats();
        const method = state.view === 'voxel'
            ? `voxel (floating horizon, WebAssembly${loaded.name.endsWith('scalar') ? '' : ' SIMD128'})`
            : `roam (WebGL2, ${roamStats.triangles} triangles, budget ${roamStats.budget})`;
        const sun = engine.sun();
        hud.textContent = `${state.fps.toFixed(1)} fps  ${method}  ${engine.width}x${engine.height}  ${fog}  ` +
            `x ${v.x.toFixed(1)} z ${v.z.toFixed(1)} y ${v.y.toFixed(1)}  ${v.velocity.toFixed(1)}/s  ` +
            `heading ${v.heading.toFixed(0)}°  sun ${sun.azimuth.toFixed(0)}°/${sun.elevation.toFixed(0)}°`;
    };

    let last = performance.now();
    let running = false;
    const tick = (now) => {
        if (!running) return;
        resize();
        const t = performance.now();
        profiler.mark('browser'); // since the last frame's end: compositing, events, idle
        engine.frame(Math.max(0, (now - last) / 1000));
        profiler.mark('engine');
        // The engine's share of a frame (physics, camera, cast), smoothed.
        state.engineMs += 0.05 * (performance.now() - t - state.engineMs);
        last = now;
        draw();
        ++state.frames;
        showHud();
        profiler.mark('hud');
        profiler.end();
        requestAnimationFrame(tick);
    };
    const start = () => {
        if (running) return;
        running = true;
        last = performance.now();
        requestAnimationFrame(tick);
    };

    // Keys as in `fly`: the arrows fly; f fog, 1 lighting, s shadows, t / T
    // the sun half an hour later / earlier, o water and + / _ (or = / -) the
    // ROAM budget go to the engine; Tab, W and H are the page's own.
    const engineKeys = {
        f: Key.Fog, '1': Key.Lighting, s: Key.Shadows, t: Key.SunLater, T: Key.SunEarlier, o: Key.Water,
        '+': Key.DetailUp, '=': Key.DetailUp, _: Key.DetailDown, '-': Key.DetailDown,
    };
    canvas.addEventListener('keydown', (e) => {
        if (e.key in kArrowKeys) {
            if (!e.repeat) engine.key(kArrowKeys[e.key], true);
        } else if (e.key === 'Tab') {
            state.view = state.view === 'voxel' ? 'roam' : 'voxel';
            engine.setMethod(state.view);
        } else if (e.key === 'W') {
            state.wireframe = !state.wireframe;
        } else if (e.key === 'H' || e.key === 'h') {
            state.hud = !state.hud;
        } else if (e.key in engineKeys) {
            if (!e.repeat) {
                engine.key(engineKeys[e.key], true);
                engine.key(engineKeys[e.key], false);
            }
        } else {
            return;
        }
        e.preventDefault();
    });
    canvas.addEventListener('keyup', (e) => {
        if (e.key in kArrowKeys) engine.key(kArrowKeys[e.key], false);
    });
    // A key released while the page had no focus would stay held.
    window.addEventListener('blur', () => Object.values(kArrowKeys).forEach((k) => engine.key(k, false)));

    // The first frame, then the loop (unless a test drives the page).
    resize();
    engine.frame(0);
    draw();
    showHud();
    const loadSeconds = (performance.now() - t0) / 1000;
    document.getElementById('loading').remove();
    canvas.focus();
    if (!testing) start();

    // The hooks of tests/web/site_test.mjs and bench/web_fps.sh.
    window.overflight = {
        site, state, loadSeconds, start,
        stop() { running = false; },
        // One frame of the pinned camera `c` (eye, heading, pitch, fov, near,
        // far; shear), with or without the objects; the canvas as base64 RGBA.
        view(c, objects) {
            engine.setCamera(c);
            engine.frame(0);
            state.objects = objects;
            draw();
            showHud();
            state.objects = true;
            return toBase64(renderer.readPixels());
        },
        hud: () => hud.textContent,
        glError: () => renderer.gl.getError(),
        sun: () => engine.sun(),
        roam: () => engine.roamStats(),
        // `frames` frames of exactly `seconds` each with the arrows in `keys`
        // held from the first: the vehicle and the physics steps run.
        fly(keys, frames, seconds) {
            engine.followVehicle();
            const before = engine.physicsSteps();
            for (const k of keys) engine.key(Key[k], true);
            for (let k = 0; k < frames; ++k) engine.frame(seconds);
            for (const k of keys) engine.key(Key[k], false);
            return { vehicle: engine.vehicle(), steps: engine.physicsSteps() - before };
        },
        vehicle: () => engine.vehicle(),
        profile: () => profiler.report(),
        // One frame of the chase camera, with or without the hovercraft: the
        // canvas as base64 RGBA, the frame's camera and vehicle, and the
        // rectangle objects can cover.
        chase(vehicle) {
            engine.followVehicle();
            engine.frame(0);
            showVehicle = vehicle;
            draw();
            showVehicle = true;
            return {
                pixels: toBase64(renderer.readPixels()), camera: engine.camera(), vehicle: engine.vehicle(),
                depthRect: Array.from(engine.depthRect()),
            };
        },
    };
}

main().catch((e) => {
    console.error(e);
    const status = document.getElementById('status');
    if (status) status.textContent = `error: ${e.message}`;
    window.overflight = { error: e.message };
});
