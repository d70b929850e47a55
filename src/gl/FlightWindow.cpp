// Based on: CMSC 23700 project 2a sec. 3 and 4; Szenberg et al. 1997 sec. 5 and 7 (Table 1 steps).
#include "gl/FlightWindow.h"

#include "core/Error.h"
#include "gl/Compositor.h"
#include "gl/FlightTimer.h"
#include "gl/GlContext.h"
#include "gl/HeadlessRenderer.h"
#include "gl/Hud.h"
#include "gl/RenderTarget.h"

#include <GLFW/glfw3.h>
#include <epoxy/gl.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

namespace overflight::gl {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::optional<Key> key_of(int glfw_key, int mods) {
    switch (glfw_key) {
    case GLFW_KEY_S: return Key::Shadows;
    case GLFW_KEY_T: return (mods & GLFW_MOD_SHIFT) ? Key::SunEarlier : Key::SunLater;
    case GLFW_KEY_UP: return Key::Accelerate;
    case GLFW_KEY_DOWN: return Key::Brake;
    case GLFW_KEY_LEFT: return Key::Left;
    case GLFW_KEY_RIGHT: return Key::Right;
    case GLFW_KEY_F: return Key::Fog;
    case GLFW_KEY_1: return Key::Lighting;
    case GLFW_KEY_W: return Key::Wireframe;
    case GLFW_KEY_KP_ADD: return Key::DetailUp;
    case GLFW_KEY_KP_SUBTRACT: return Key::DetailDown;
    // '+' is shift-'=' and '_' is shift-'-' on US keyboards; the unshifted
    // keys are accepted too so the level of detail works on any layout.
    case GLFW_KEY_EQUAL: return Key::DetailUp;
    case GLFW_KEY_MINUS: return Key::DetailDown;
    case GLFW_KEY_TAB: return Key::NextMethod;
    case GLFW_KEY_P: return Key::Screenshot;
    case GLFW_KEY_H: return Key::Hud;
    case GLFW_KEY_Q: return Key::Quit;
    case GLFW_KEY_O: return Key::Water;
    default: return std::nullopt;
    }
}

void on_key(GLFWwindow* window, int key, int /*scancode*/, int action, int mods) {
    auto* session = static_cast<FlightSession*>(glfwGetWindowUserPointer(window));
    if (!session || action == GLFW_REPEAT) return; // key repeat is ignored (sec. 3.1)
    const std::optional<Key> k = key_of(key, mods);
    if (!k) return;
    if (action == GLFW_PRESS) session->press(*k);
    else session->release(*k);
}

// The methods of the window, built from the table when first shown: the
// first one asked for, then the fly rows in table order (Tab).
class MethodSet {
public:
    MethodSet(const MethodContext& context, const std::string& first) : context_(context) {
        const MethodEntry* entry = find_terrain_method(first);
        if (!entry)
            throw Error("terrain method", "'" + first + "' is not one (known: " + terrain_method_names(", ") + ")");
        rows_.push_back(entry);
        for (const MethodEntry& m : terrain_methods())
            if (m.fly && &m != entry) rows_.push_back(&m);
        methods_.resize(rows_.size());
    }
    TerrainMethod& get(std::size_t i) {
        if (!methods_[i]) methods_[i] = rows_[i]->create(context_);
        return *methods_[i];
    }
    std::size_t size() const { return rows_.size(); }
    const char* name(std::size_t i) const { return rows_[i]->name; }

private:
    const MethodContext& context_;
    std::vector<const MethodEntry*> rows_;
    std::vector<std::unique_ptr<TerrainMethod>> methods_;
};

FlightMethodStats& stats_for(std::vector<FlightMethodStats>& all, const std::string& name) {
    for (FlightMethodStats& s : all)
        if (s.method == name) return s;
    all.push_back(FlightMethodStats{name});
    return all.back();
}

// One frame on its way to the screen: everything its composite needs, kept
// from the moment it was simulated, so that what is drawn (terrain, objects,
// vehicle, HUD) is the frame's own camera and state even when it is drawn
// while the next frame is being cast.
struct ShownFrame {
    std::size_t method = 0;
    std::string detail; // the method's level of detail when it was cast
    Camera camera;
    Environment environment;
    CompositeOptions options;
    HovercraftState vehicle;
    ViewToggles toggles;
    int slot = -1;       // the compositor's staged slot (an image method, cast ahead); -1: produce when drawn
    MethodStats stats;   // the method's steps (and the staging's)
    bool shot = false;   // P was pressed in this frame
    bool last = false;   // the last frame of an unattended run
};

// An image method's output is cast and staged ahead (Compositor::stage()
// copies it out of the method's buffers); a mesh method's arrays are read by
// the compositor while it draws, so it runs in step with the drawing.
bool casts_ahead(const TerrainMethod& method) { return method.output_kind() == MethodOutputKind::Images; }

// Produces frame `f` with `method` and, when it is drawn later, stages its
// images into f.slot. Runs on a oneTBB task beside the GL thread: it touches
// no GL, only the method and the compositor's slot (Compositor::stage()).
void cast_and_stage(TerrainMethod& method, Compositor& compositor, ShownFrame& f) {
    const MethodOutput out =
        method.produce(MethodView{f.camera, f.environment, glm::dvec2(f.vehicle.x, f.vehicle.z)}, f.stats);
    const auto t0 = Clock::now();
    compositor.stage(f.slot, out, f.camera, f.environment, f.options);
    f.stats.add_step_since("stage", t0);
}

} // namespace

void FlightMethodStats::add_steps(const std::vector<std::pair<const char*, double>>& steps) {
    for (const auto& [name, ms] : steps) {
        auto it = std::find_if(step_ms.begin(), step_ms.end(), [&](const auto& entry) { return entry.first == name; });
        if (it == step_ms.end()) it = step_ms.insert(step_ms.end(), {name, 0.0});
        it->second += ms;
    }
    ++timed_frames;
}

std::string FlightMethodStats::steps_text() const {
    std::string text;
    for (const auto& [name, sum] : step_ms) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%s%s:%.2f", text.empty() ? "" : ";", name.c_str(),
                      timed_frames ? sum / double(timed_frames) : 0.0);
        text += buf;
    }
    return text;
}

FlightResult run_flight_window(const DataSet& data, const FlightWindowOptions& options, const MethodContext& context,
                               const ScreenshotSink& screenshot) {
    // The vehicle and the first method's name first, so bad input fails before a window flashes up.
    FlightSession session(data.terrain, data.environment, options.session);
    // One horizon sweep per sun direction for the ray casters' lighting and
    // the compositor's shadow ceiling.
    SharedSunShadow sun_shadow(data.terrain);
    MethodContext shared_context = context;
    shared_context.sun_shadow = &sun_shadow;
    MethodSet methods(shared_context, options.method);
    std::size_t current = 0;

    WindowContext window("Overflight - " + data.info.source, options.width, options.height, options.visible);
    glfwSwapInterval(session.unattended() ? 0 : 1); // scripted runs go as fast as the GL allows
    glfwSetWindowUserPointer(window.window(), &session);
    glfwSetKeyCallback(window.window(), on_key);
    Hud hud(window.window()); // after our callback: ImGui chains to it
    methods.get(current);
    Compositor compositor(data.terrain, data.scene);
    compositor.share_sun_shadow(&sun_shadow);

    FlightResult result;
    ColorImage shot;
    int shots = 0;
    double fps = 0, frame_ms = 0;
    // Step timings arrive a few frames late (GL queries); the HUD shows the
    // latest, the per-method statistics sum them.
    FlightSteps latest_steps;
    std::vector<std::pair<const char*, double>> steps;
    FlightStepTimer timer([&](int tag, const FlightSteps& s) {
        latest_steps = s;
        steps.clear();
        for (int i = 0; i < s.count; ++i) steps.emplace_back(s.step[std::size_t(i)].name, s.step[std::size_t(i)].ms);
        stats_for(result.per_method, methods.name(std::size_t(tag))).add_steps(steps);
    });
    RenderTarget window_target = RenderTarget::default_framebuffer(options.width, options.height);

    // Draws frame `f` (produced now unless it was cast ahead), the HUD over
    // it, and shows it. The statistics count a frame when it is shown, with
    // the wall-clock time since the previous one was.
    auto shown_at = Clock::now();
    auto show = [&](ShownFrame& f) {
        // Isolated: while the cast of the next frame runs on a oneTBB task,
        // parallel work here (the shadow sweep of a moved sun) must not pick
        // that task up and keep the frame waiting for it.
        tbb::this_task_arena::isolate([&] {
            if (window_target.width() != f.camera.width || window_target.height() != f.camera.height)
                window_target = RenderTarget::default_framebuffer(f.camera.width, f.camera.height);
            timer.begin_frame(int(f.method));
            CompositeCounts counts;
            if (f.slot >= 0) {
                for (const MethodStep& s : f.stats.steps) timer.cpu_step(s.name, s.ms);
                counts = compositor.draw_staged(f.slot, f.camera, f.environment, window_target, timer, f.options);
            } else {
                const MethodOutput out = methods.get(f.method).produce(
                    MethodView{f.camera, f.environment, glm::dvec2(f.vehicle.x, f.vehicle.z)}, f.stats);
                for (const MethodStep& s : f.stats.steps) timer.cpu_step(s.name, s.ms);
                counts = compositor.draw(out, f.camera, f.environment, window_target, timer, f.options);
            }
            // Screenshots are taken before the HUD so they match a replay.
            if ((f.shot || f.last) && screenshot) {
                window_target.read_color(shot);
                if (f.shot) screenshot(shot, f.camera, shots++);
                if (f.last) screenshot(shot, f.camera, -1);
            }
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
            glViewport(0, 0, f.camera.width, f.camera.height);
            const HovercraftState& s = f.vehicle;
            const ViewToggles& t = f.toggles;
            hud.visible = t.hud;
            hud.draw(HudInfo{fps, frame_ms, session.ms_per_physics_step(), latest_steps, counts.terrain_primitives,
                             counts.object_triangles, methods.name(f.method), f.detail, glm::dvec3(s.x, s.y, s.z),
                             s.velocity, s.heading, to_string(t.fog), t.lighting, t.wireframe, t.shadows,
                             f.environment.sun_dir, t.water, float(session.water_level().value_or(0.0))});
            window.swap_buffers();

            const auto now = Clock::now();
            const double frame_s = std::chrono::duration<double>(now - shown_at).count();
            shown_at = now;
            frame_ms = 1e3 * frame_s;
            fps = fps > 0 ? 0.9 * fps + 0.1 / std::max(frame_s, 1e-6) : 1.0 / std::max(frame_s, 1e-6);
            FlightMethodStats& st = stats_for(result.per_method, methods.name(f.method));
            ++st.frames;
            st.seconds += frame_s;
            st.triangles += counts.terrain_primitives;
            st.object_triangles += counts.object_triangles;
        });
    };

    // Frame N+1 is cast (and staged) on a oneTBB task while frame N is
    // drawn: `ahead` is the frame in flight, `waiting` the one cast and not
    // yet shown. The two swap roles every frame, so a task never writes the
    // frame being drawn. The task group is declared after everything the
    // task uses and is waited for before any of it goes away.
    std::array<ShownFrame, 2> frames;
    ShownFrame* ahead = nullptr;   // being cast
    ShownFrame* waiting = nullptr; // cast, not shown yet
    tbb::task_group casting;
    struct Join {
        tbb::task_group& group;
        ~Join() {
            try {
                group.wait();
            } catch (...) {
            }
        }
    } join{casting};
    auto finish_cast = [&] {
        if (!ahead) return;
        casting.wait(); // rethrows what the cast threw
        waiting = ahead;
        ahead = nullptr;
    };
    auto show_waiting = [&] {
        if (!waiting) return;
        show(*waiting);
        waiting = nullptr;
    };
    auto last = Clock::now();

    while (!session.finished()) {
        glfwPollEvents();
        if (window.should_close()) break;
        const std::vector<Key>& commands = session.begin_frame();
        session.advance(seconds_since(last));
        last = Clock::now();
        // The commands act on the methods: the frame in flight is cast first.
        finish_cast();
        bool quit = false, take_shot = false;
        for (Key k : commands) {
            if (k == Key::DetailUp) methods.get(current).scale_detail(std::sqrt(2.0));
            if (k == Key::DetailDown) methods.get(current).scale_detail(1.0 / std::sqrt(2.0));
            if (k == Key::NextMethod) {
                current = (current + 1) % methods.size();
                methods.get(current);
            }
            take_shot |= k == Key::Screenshot;
            quit |= k == Key::Quit;
        }
        if (quit) break;

        int fb_w = 0, fb_h = 0;
        window.framebuffer_size(fb_w, fb_h);
        if (fb_w <= 0 || fb_h <= 0) { // minimised: keep simulating, draw nothing
            waiting = nullptr;
            session.end_frame();
            continue;
        }
        ShownFrame& f = frames[waiting == &frames[0] ? 1 : 0];
        Camera& cam = session.camera();
        cam.width = fb_w;
        cam.height = fb_h;
        const HovercraftState& s = session.vehicle();
        const ViewToggles& t = session.toggles();
        f.method = current;
        f.detail = methods.get(current).detail();
        f.camera = cam;
        f.environment = session.environment();
        f.options = {true, false, t.wireframe, VehiclePose{s.x, s.z, s.heading}};
        f.vehicle = s;
        f.toggles = t;
        f.shot = take_shot;
        f.last = session.last_frame();
        f.slot = -1;
        TerrainMethod& method = methods.get(current);
        if (casts_ahead(method)) {
            // The stream's slots are sized for the new frame: a frame cast at
            // another size is shown first.
            if (waiting && (waiting->camera.width != fb_w || waiting->camera.height != fb_h)) show_waiting();
            f.slot = compositor.acquire_slot(f.camera);
            ahead = &f;
            casting.run([&method, &compositor, &f] { cast_and_stage(method, compositor, f); });
            show_waiting();
        } else {
            show_waiting();
            show(f);
        }
        session.end_frame();
    }
    // The frame still in flight is shown too: every recorded frame is drawn.
    finish_cast();
    show_waiting();
    timer.flush();
    result.record = session.record();
    result.physics_steps = session.physics_steps();
    return result;
}

FlightMethodStats render_flight_record(const DataSet& data, const FlightRecord& record, long long frames,
                                       const MethodEntry& entry, const MethodContext& context, int width, int height,
                                       double fov, const std::function<void(const ColorImage&, long long frame)>& sink) {
    HeadlessRenderer renderer(data.terrain, data.scene);
    // One horizon sweep for the method's lighting and the compositor, as in the window.
    SharedSunShadow sun_shadow(data.terrain);
    MethodContext shared_context = context;
    shared_context.sun_shadow = &sun_shadow;
    renderer.compositor().share_sun_shadow(&sun_shadow);
    std::unique_ptr<TerrainMethod> method = entry.create(shared_context);
    FlightMethodStats stats{entry.name};
    MethodStats method_stats;
    FrameTimings timings;
    std::vector<std::pair<const char*, double>> steps;

    Camera cam = flight_camera(data.terrain, fov);
    cam.width = width;
    cam.height = height;
    const Environment env = view_environment(data.environment, data.terrain, fog_mode_of(data.environment), true);
    const std::size_t n = frames > 0 ? std::min<std::size_t>(std::size_t(frames), record.frames.size())
                                     : record.frames.size();
    ColorImage image;
    for (std::size_t i = 0; i < n; ++i) {
        const FlightFrame& f = record.frames[i];
        const auto t0 = Clock::now();
        cam.eye = f.eye;
        cam.heading = f.heading;
        cam.pitch = f.pitch;
        const MethodOutput out = method->produce(MethodView{cam, env, glm::dvec2(f.x, f.z)}, method_stats);
        renderer.render(out, cam, env, {true, false, false, VehiclePose{f.x, f.z, f.vehicle_heading}}, image, nullptr,
                        &timings);
        stats.seconds += seconds_since(t0);
        steps.clear();
        for (const MethodStep& s : method_stats.steps) steps.emplace_back(s.name, s.ms);
        steps.insert(steps.end(), timings.steps_ms.begin(), timings.steps_ms.end());
        stats.add_steps(steps);
        stats.triangles += timings.counts.terrain_primitives;
        stats.object_triangles += timings.counts.object_triangles;
        ++stats.frames;
        sink(image, f.frame);
    }
    return stats;
}

} // namespace overflight::gl
