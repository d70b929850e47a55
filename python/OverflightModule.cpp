// The Python module `overflight` (DESIGN sec. 6.1): terrains loaded as the
// command line loads them, rendered into NumPy arrays by the same render
// session, with the keyword arguments of a view mapped onto the command
// line's own option parser (`look_at=...` is `--look-at ...`), so that a view
// means the same in Python and in a shell.
//
//   t = overflight.load("dem.tif")                  # or "demo", a tile directory
//   t = overflight.from_array(heights, cell_size)   # a NumPy height array
//   color, depth = overflight.render(t, "voxel", (W, H), eye="lonlat:...", look_at="lonlat:...")
//   overflight.camera(t, ...) -> dict               # the camera file of a view
//   t.heights(), t.colors(), t.info()
//   overflight.sim(t, steps=..., press=[...])       # the hovercraft simulator
//
// Errors are overflight.Error with the one line the command line prints after
// "overflight: ". The GIL is released while loading, rendering and
// simulating; one terrain renders one view at a time (its GL context and its
// cached method are shared), different terrains render in parallel.
//
// What a call adds to the render `bench` times (the render session's, the
// same code) is kept to a few microseconds: the view's keywords are parsed by
// the command line's parser once per distinct view (view_args), and the
// arrays are the frame's own buffers, swapped out of the session or the
// method (RenderSession::take_images) and given back for later frames when
// NumPy drops them (SpareImages), so no pixel is copied after the renderer's
// read-back.
//
// The GL rule: a view makes the terrain's EGL context current on the calling
// thread and releases it before it leaves the terrain's lock, so whichever
// Python thread renders next can take it (EGL lets a context be current on
// one thread only) and a thread that ends holds none. Keeping it current
// between calls saved nothing measurable (a 16x16 voxel+objects view, 1000
// calls: 0.57 ms per call releasing it, 0.60 ms keeping it, `bench` 0.55 to
// 0.58 ms, load average 12 on 2 cores), so the simple rule stays.
#include "CameraOptions.h"
#include "LookOptions.h"
#include "OptionErrors.h"
#include "RenderSession.h"
#include "SimulatorRun.h"
#include "TerrainOptions.h"
#include "core/Error.h"
#include "core/Shading.h"
#include "io/CameraFile.h"
#include "io/HeightMapping.h"
#include "io/TerrainReport.h"
#include "io/TileDirectory.h"

#include <epoxy/egl.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace py = pybind11;

namespace overflight::python {

namespace {

// Image buffers of a terrain's frames that NumPy no longer holds, handed to
// the session for its next frames: a loop of views then renders into warm
// memory instead of faulting in a fresh buffer each frame. At most kKeep of
// each kind are kept (a loop holding the previous frame while the next is
// drawn cycles through three buffers: the session's, the previous and the
// returned one).
struct SpareImages {
    static constexpr std::size_t kKeep = 2;
    std::mutex mutex;
    std::vector<ColorImage> color;
    std::vector<DepthImage> depth;

    template <class T>
    static Image2D<T> take(std::mutex& m, std::vector<Image2D<T>>& from) {
        std::lock_guard lock(m);
        if (from.empty()) return {};
        Image2D<T> image = std::move(from.back());
        from.pop_back();
        return image;
    }
    template <class T>
    static void give(std::mutex& m, std::vector<Image2D<T>>& to, Image2D<T>&& image) {
        std::lock_guard lock(m);
        if (to.size() < kKeep) to.push_back(std::move(image));
    }
    ColorImage take_color() { return take(mutex, color); }
    DepthImage take_depth() { return take(mutex, depth); }
    void give_back(ColorImage&& image) { give(mutex, color, std::move(image)); }
    void give_back(DepthImage&& image) { give(mutex, depth, std::move(image)); }
};

// A terrain with the session that renders it: the last method used stays
// built, so that a loop of views pays for it once (as `bench` does).
struct TerrainHandle {
    DataSet data;
    std::string tile_dir; // a tile directory's path (quadtree reads its tiles)
    std::mutex mutex;     // one view at a time: the session's GL context and method
    std::string session_method, session_options; // what the session was built for (ViewArgs::methods_key)
    std::unique_ptr<app::RenderSession> session;
    const MethodEntry* row = nullptr;
    std::unique_ptr<TerrainMethod> method;
    // The camera of the last view and its arguments: a loop over one view
    // skips make_camera, whose default view scans the terrain's heights.
    std::string camera_key;
    Camera camera;
    // Shared with the arrays lent to NumPy, which may outlive the terrain.
    std::shared_ptr<SpareImages> spares = std::make_shared<SpareImages>();

    // Destroys the session. Views release the GL context after drawing
    // (ReleaseGlContext): the GL objects are deleted in it, so it is made
    // current here first. Called with `mutex` held.
    void drop_session() {
        if (session) session->make_gl_current();
        method.reset();
        session.reset();
        session_method.clear();
    }

    ~TerrainHandle() {
        std::lock_guard lock(mutex);
        drop_session();
    }
};
using Handle = std::shared_ptr<TerrainHandle>;

// "--name=value" arguments of keyword arguments: `_` for `-`; True is a
// flag, False and None are left out; a sequence of numbers is joined with
// commas, a sequence of strings gives the option once per string.
std::vector<std::string> arguments_of(const py::dict& kwargs) {
    std::vector<std::string> args;
    for (const auto& [key, value] : kwargs) {
        std::string name = py::str(key);
        std::replace(name.begin(), name.end(), '_', '-');
        name = "--" + name;
        if (value.is_none()) continue;
        if (py::isinstance<py::bool_>(value)) {
            if (value.cast<bool>()) args.push_back(name);
            continue;
        }
        if (py::isinstance<py::str>(value)) {
            args.push_back(name + "=" + value.cast<std::string>());
            continue;
        }
        if (!py::isinstance<py::sequence>(value)) {
            args.push_back(name + "=" + py::str(value).cast<std::string>());
            continue;
        }
        // A sequence of strings repeats the option (press=["accelerate:0-9",
        // "left:0-5"]); of numbers, it is one value (eye=(x, y, z)).
        std::string text;
        for (const py::handle item : value.cast<py::sequence>()) {
            if (py::isinstance<py::str>(item)) {
                args.push_back(name + "=" + item.cast<std::string>());
                continue;
            }
            if (!text.empty()) text += ',';
            text += py::str(item).cast<std::string>();
        }
        if (text.empty()) continue;
        args.push_back(name + "=" + text);
    }
    return args;
}

// Parses `args` with `app` (CLI11 takes them last first).
void parse(CLI::App& app, std::vector<std::string> args) {
    std::reverse(args.begin(), args.end());
    app.parse(args);
}

std::string size_text(const py::object& size) {
    if (size.is_none()) return {};
    const auto wh = size.cast<std::pair<int, int>>();
    return std::to_string(wh.first) + "x" + std::to_string(wh.second);
}

// `camera=`: a camera file's path or its dict (io/CameraFile.h).
void set_camera_source(const py::object& camera, app::CameraArgs& args) {
    if (camera.is_none()) return;
    if (py::isinstance<py::dict>(camera)) {
        args.camera_text = py::module_::import("json").attr("dumps")(camera).cast<std::string>();
        return;
    }
    args.camera_file = py::str(py::module_::import("os").attr("fspath")(camera));
}

std::string methods_key(const app::MethodOptions& m) {
    return m.surface + "|" + m.tilt_method + "|" + std::to_string(m.lod) + "|" + std::to_string(m.near_step) + "|" +
           std::to_string(m.triangles) + "|" + std::to_string(m.error_px) + "|" + std::to_string(m.cache_mib) + "|" +
           m.scene;
}

// The options of a view, parsed as `render` parses them. Immutable once
// built: views are cached by their arguments (view_args) and shared.
struct ViewArgs {
    app::CameraArgs camera;
    app::MethodOptions methods;
    app::LookArgs looks;
    std::string save_camera;

    std::string key;         // the arguments as text; empty for a camera file (read each time)
    std::string methods_key; // what selects the session besides the method (methods_key())

    ViewArgs(const std::vector<std::string>& args, std::string size, app::CameraArgs source) : camera(std::move(source)) {
        CLI::App app{"overflight.render"};
        app::add_camera_options(app, camera);
        app::add_method_options(app, methods);
        app::add_look_options(app, looks);
        app.add_option("--save-camera", save_camera);
        parse(app, args);
        camera.size = std::move(size);
        if (camera.camera_file.empty()) {
            key = camera.size + "\n" + camera.camera_text;
            for (const std::string& a : args) key += "\n" + a;
        }
        methods_key = python::methods_key(methods);
    }

    // The camera for `data` (render's default size 1280x720).
    Camera make(const DataSet& data) const { return app::make_camera(camera, data, 1280, 720); }
};
using View = std::shared_ptr<const ViewArgs>;

// The parsed view of render()'s arguments. Building the option parser and
// parsing costs more than a small frame, so a loop over a few views parses
// each once: the parsed views are kept by their arguments' text (at most
// kKeep of them; all dropped when full). A camera file is still read at
// every call (ViewArgs::make).
View view_args(const py::object& size, const py::object& camera_source, const py::dict& view) {
    static constexpr std::size_t kKeep = 64;
    static std::mutex mutex;
    static std::unordered_map<std::string, View> parsed;
    const std::vector<std::string> args = arguments_of(view);
    std::string size_arg = size_text(size);
    app::CameraArgs source;
    set_camera_source(camera_source, source);
    std::string key = size_arg + "\n" + source.camera_file + "\n" + source.camera_text;
    for (const std::string& a : args) key += "\n" + a;
    {
        std::lock_guard lock(mutex);
        if (const auto it = parsed.find(key); it != parsed.end()) return it->second;
    }
    auto v = std::make_shared<const ViewArgs>(args, std::move(size_arg), std::move(source));
    std::lock_guard lock(mutex);
    if (parsed.size() >= kKeep) parsed.clear();
    parsed.emplace(std::move(key), v);
    return v;
}

// A frame's images, handed to NumPy without a copy (array_of).
struct Frame {
    ColorImage color;
    DepthImage depth; // empty unless asked for
};

// An image lent to NumPy: its buffer is the array's memory; when the array
// dies, the buffer goes back to its terrain's spares.
template <class T>
struct LentImage {
    Image2D<T> image;
    std::shared_ptr<SpareImages> home;
    ~LentImage() { home->give_back(std::move(image)); }
};

template <class T>
py::array_t<T> array_of(std::vector<T>&& v, std::vector<py::ssize_t> shape) {
    auto* owned = new std::vector<T>(std::move(v));
    py::capsule free_when_done(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
    return py::array_t<T>(shape, owned->data(), free_when_done);
}

// `image` as an array of `shape` (rows, cols[, channels]) of its own memory.
template <class E, class T>
py::array_t<E> array_of(Image2D<T>&& image, const std::shared_ptr<SpareImages>& home, std::vector<py::ssize_t> shape) {
    static_assert(sizeof(T) % sizeof(E) == 0 && alignof(T) >= alignof(E));
    auto* lent = new LentImage<T>{std::move(image), home};
    py::capsule give_back(lent, [](void* p) { delete static_cast<LentImage<T>*>(p); });
    return py::array_t<E>(shape, reinterpret_cast<const E*>(lent->image.pixels.data()), give_back);
}

// Leaves no EGL context current on this thread when the scope ends, so that
// another Python thread can make the terrain's context current for its next view.
struct ReleaseGlContext {
    ~ReleaseGlContext() {
        if (eglGetCurrentContext() != EGL_NO_CONTEXT)
            eglMakeCurrent(eglGetCurrentDisplay(), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
};

Frame render_view(TerrainHandle& t, const std::string& method_name, const ViewArgs& view, bool want_depth) {
    // The spare buffers, taken before the lock (their own lock is short).
    Frame f{t.spares->take_color(), want_depth ? t.spares->take_depth() : DepthImage{}};
    std::lock_guard lock(t.mutex);
    const ReleaseGlContext release; // before the lock is left
    if (view.key.empty() || view.key != t.camera_key) {
        t.camera_key.clear();
        t.camera = view.make(t.data);
        t.camera_key = view.key;
    }
    const Camera camera = t.camera;
    if (!t.session || method_name != t.session_method || view.methods_key != t.session_options) {
        const MethodEntry* row = find_terrain_method(method_name);
        if (!row) throw Error("--method", "unknown method '" + method_name + "' (known: " + terrain_method_names() + ")");
        t.drop_session();
        t.session = std::make_unique<app::RenderSession>(t.data, view.methods, row->reads_tiles ? t.tile_dir : std::string());
        // A user's `voxel` view shows the objects: Szenberg's composite (as render).
        if (method_name == "voxel" && t.session->has_objects()) row = find_terrain_method("voxel+objects");
        t.row = row;
        t.method = t.session->create(*row);
        t.session_method = method_name;
        t.session_options = view.methods_key;
    }
    t.session->set_environment(app::with_looks(view.looks, t.data.environment));
    app::RenderedView rendered;
    t.session->render(*t.row, *t.method, camera, want_depth, rendered);
    if (!view.save_camera.empty())
        write_camera_file(view.save_camera, camera, app::camera_map_of(camera, t.data));
    // The frame's own buffers, swapped for the spares (no copy where the
    // session or the method can lend them).
    t.session->take_images(*t.method, rendered, f.color, want_depth ? &f.depth : nullptr);
    return f;
}

Handle load(const std::string& path, const py::object& color, const py::object& demo_size,
            const py::object& max_direct_size) {
    app::TerrainArgs args;
    {
        CLI::App app{"overflight.load"};
        app::add_terrain_options(app, args);
        app::add_max_direct_size_option(app, args);
        py::dict options;
        options["color"] = color;
        options["demo_size"] = demo_size;
        options["max_direct_size"] = max_direct_size;
        std::vector<std::string> argv = arguments_of(options);
        argv.insert(argv.begin(), path);
        parse(app, argv);
    }
    auto t = std::make_shared<TerrainHandle>();
    py::gil_scoped_release release;
    // A tile directory is opened as its overview; quadtree reads its tiles.
    if (is_tile_directory(path)) {
        t->data = app::load_terrain_lazily(args);
        t->tile_dir = path;
    } else {
        t->data = app::load_terrain(args);
    }
    return t;
}

// The 16-bit mapping of DESIGN sec. 4 for an array of elevations.
Handle from_array(const py::array_t<float, py::array::c_style | py::array::forcecast>& heights, double cell_size,
                  const py::object& colors) {
    if (heights.ndim() != 2 || heights.shape(0) < 2 || heights.shape(1) < 2)
        throw Error("heights", "must be a 2-D array of at least 2x2 elevations");
    if (!(cell_size > 0) || !std::isfinite(cell_size)) throw Error("cell_size", "must be a positive number");
    const int rows = int(heights.shape(0)), cols = int(heights.shape(1));
    std::vector<float> z(heights.data(), heights.data() + heights.size());
    float lo = z[0], hi = z[0];
    bool integral = true;
    for (float v : z) {
        if (!std::isfinite(v)) throw Error("heights", "holds a value that is not finite (NaN or infinity)");
        lo = std::min(lo, v);
        hi = std::max(hi, v);
        integral = integral && v == std::round(v);
    }
    const HeightMapping mapping = choose_height_mapping(lo, hi, integral);
    auto t = std::make_shared<TerrainHandle>();
    t->data.terrain = Terrain(rows, cols, float(cell_size), mapping.v_scale, mapping.y_offset);
    quantise_heights(z, mapping, t->data.terrain.heights());
    t->data.info.source = "array";
    t->data.info.kind = "array";
    if (colors.is_none()) {
        shade_by_elevation(t->data.terrain, 0.0f);
        t->data.info.color_source = "elevation ramp + hillshade";
    } else {
        const auto c = colors.cast<py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>>();
        if (c.ndim() != 3 || c.shape(0) != rows || c.shape(1) != cols || c.shape(2) != 3)
            throw Error("colors", "must be a uint8 array of shape (rows, cols, 3) like heights");
        std::memcpy(t->data.terrain.colors().data(), c.data(), c.size());
        t->data.info.color_source = "array";
    }
    return t;
}

py::tuple render(const Handle& t, const std::string& method, const py::object& size, const py::object& camera,
                 bool depth, const py::kwargs& view) {
    const View args = view_args(size, camera, view);
    Frame f;
    {
        py::gil_scoped_release release;
        f = render_view(*t, method, *args, depth);
    }
    const py::ssize_t h = f.color.height, w = f.color.width;
    py::object depth_array = py::none();
    if (depth) depth_array = array_of<float>(std::move(f.depth), t->spares, {h, w});
    return py::make_tuple(array_of<std::uint8_t>(std::move(f.color), t->spares, {h, w, 3}), depth_array);
}

py::dict camera_dict(const Handle& t, const py::object& size, const py::object& camera, const py::kwargs& view) {
    const View args = view_args(size, camera, view);
    std::string text;
    {
        py::gil_scoped_release release;
        const Camera c = args->make(t->data);
        text = camera_file_text(c, app::camera_map_of(c, t->data));
    }
    return py::module_::import("json").attr("loads")(text);
}

py::dict sim(const Handle& t, const py::kwargs& options) {
    app::SimArgs args;
    CLI::App app{"overflight.sim"};
    app::add_sim_options(app, args);
    parse(app, arguments_of(options));
    std::vector<double> columns[6];
    {
        py::gil_scoped_release release;
        run_simulator(args, t->data, [&](long long k, const HovercraftState& s) {
            const double row[6] = {double(k), s.x, s.z, s.y, s.velocity, s.heading};
            for (int i = 0; i < 6; ++i) columns[i].push_back(row[i]);
        });
    }
    py::dict out;
    const char* names[6] = {"step", "x", "z", "y", "velocity", "heading"};
    for (int i = 0; i < 6; ++i) {
        const py::ssize_t n = py::ssize_t(columns[i].size());
        out[names[i]] = array_of(std::move(columns[i]), {n});
    }
    return out;
}

py::array_t<float> heights(const Handle& t) {
    const Terrain& terrain = t->data.terrain;
    std::vector<float> h(terrain.heights().size());
    for (std::size_t i = 0; i < h.size(); ++i)
        h[i] = terrain.v_scale() * float(terrain.heights()[i]) + terrain.y_offset();
    return array_of(std::move(h), {terrain.rows(), terrain.cols()});
}

} // namespace

} // namespace overflight::python

PYBIND11_MODULE(overflight, m) {
    using namespace overflight;
    using namespace overflight::python;
    m.doc() = "Overflight: render height-field terrains into NumPy arrays (DESIGN sec. 6.1)";
    static py::exception<Error> error_type(m, "Error", PyExc_RuntimeError);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const Error& e) {
            PyErr_SetString(error_type.ptr(), app::in_option_terms(e).what());
        } catch (const CLI::ParseError& e) {
            PyErr_SetString(error_type.ptr(), e.what());
        }
    });

    py::class_<TerrainHandle, Handle>(m, "Terrain", "A loaded terrain (DESIGN sec. 4) and the session that renders it")
        .def_property_readonly("rows", [](const Handle& t) { return t->data.terrain.rows(); })
        .def_property_readonly("cols", [](const Handle& t) { return t->data.terrain.cols(); })
        .def_property_readonly("cell_size", [](const Handle& t) { return t->data.terrain.h_scale(); },
                               "horizontal scale: world units between samples")
        .def("heights", &heights, "world heights Y (rows x cols float32; row 0 north, DESIGN sec. 1)")
        .def(
            "colors",
            [](const Handle& t) {
                Terrain& terrain = t->data.terrain;
                return py::array_t<std::uint8_t>({terrain.rows(), terrain.cols(), 3},
                                                 reinterpret_cast<std::uint8_t*>(terrain.colors().data()),
                                                 py::cast(t));
            },
            "the color map (rows x cols x 3 uint8), a view of the terrain's own memory")
        .def(
            "info",
            [](const Handle& t) {
                return py::module_::import("json").attr("loads")(terrain_report_json(describe(t->data)));
            },
            "what `overflight info --json` reports, as a dict")
        .def("__repr__", [](const Handle& t) {
            return "<overflight.Terrain " + t->data.info.source + " " + std::to_string(t->data.terrain.cols()) + "x" +
                   std::to_string(t->data.terrain.rows()) + ">";
        });

    m.def("load", &load, py::arg("path"), py::arg("color") = py::none(), py::arg("demo_size") = py::none(),
          py::arg("max_direct_size") = py::none(),
          "Load a terrain as the command line does: \"demo\", a hovercraft data set directory, a tile directory or "
          "any raster GDAL reads (color: an orthophoto or color raster).");
    m.def("from_array", &from_array, py::arg("heights"), py::arg("cell_size"), py::arg("colors") = py::none(),
          "A terrain from a 2-D array of elevations (row 0 north) with cell_size world units between samples; "
          "colors: (rows, cols, 3) uint8, else an elevation ramp with hill shading.");
    m.def("render", &render, py::arg("terrain"), py::arg("method") = "voxel", py::arg("size") = py::none(),
          py::arg("camera") = py::none(), py::arg("depth") = true,
          "Render one view: (color HxWx3 uint8, depth HxW float32 OpenGL window depth, 1.0 = sky; None with "
          "depth=False, which spares reading it back). size=(W, H) (default 1280x720); camera: a camera file's path or dict; the keyword arguments are render's options "
          "with _ for - (eye, at, agl, look_at, crs, heading, pitch, fov, projection, near, far, scene, surface, "
          "lighting, sun, shadows, atmosphere, save_camera, ...).");
    m.def("camera", &camera_dict, py::arg("terrain"), py::arg("size") = py::none(), py::arg("camera") = py::none(),
          "The camera file (as a dict) of the view render would draw for the same arguments.");
    m.def("sim", &sim, py::arg("terrain"),
          "Run the hovercraft simulator as `overflight sim` (steps=N, at=..., heading=..., press=[\"accelerate:0-100\"], "
          "slope=...): a dict of arrays step, x, z, y, velocity, heading, one entry per 10 ms step.");
}

