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

#include <algorithm>
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

// Produces and composites one frame of `method` into `target`, reporting the
// method's CPU steps and the compositor's steps through `timer`.
CompositeCounts draw_frame(TerrainMethod& method, MethodStats& stats, Compositor& compositor, const Camera& camera,
                           const Environment& env, RenderTarget& target, StepTimer& timer,
                           const CompositeOptions& options, const HovercraftState& vehicle) {
    const MethodOutput out = method.produce(MethodView{camera, env, glm::dvec2(vehicle.x, vehicle.z)}, stats);
    for (const MethodStep& s : stats.steps) timer.cpu_step(s.name, s.ms);
    return compositor.draw(out, camera, env, target, timer, options);
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
    MethodSet methods(context, options.method);
    std::size_t current = 0;

    WindowContext window("Overflight - " + data.info.source, options.width, options.height, options.visible);
    glfwSwapInterval(session.unattended() ? 0 : 1); // scripted runs go as fast as the GL allows
    glfwSetWindowUserPointer(window.window(), &session);
    glfwSetKeyCallback(window.window(), on_key);
    Hud hud(window.window()); // after our callback: ImGui chains to it
    methods.get(current);
    Compositor compositor(data.terrain, data.scene);

    FlightResult result;
    ColorImage shot;
    int shots = 0;
    double fps = 0, frame_ms = 0;
    CompositeCounts counts;
    MethodStats method_stats;
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
    auto last = Clock::now();

    while (!session.finished()) {
        const auto frame_start = Clock::now();
        glfwPollEvents();
        if (window.should_close()) break;
        bool quit = false, take_shot = false;
        for (Key k : session.begin_frame()) {
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
        session.advance(seconds_since(last));
        last = Clock::now();

        int fb_w = 0, fb_h = 0;
        window.framebuffer_size(fb_w, fb_h);
        const HovercraftState& s = session.vehicle();
        if (fb_w > 0 && fb_h > 0) { // minimised: keep simulating, draw nothing
            Camera& cam = session.camera();
            cam.width = fb_w;
            cam.height = fb_h;
            // Kept between frames: its full-screen copy pass is built once.
            if (window_target.width() != fb_w || window_target.height() != fb_h)
                window_target = RenderTarget::default_framebuffer(fb_w, fb_h);
            const ViewToggles& t = session.toggles();
            timer.begin_frame(int(current));
            counts = draw_frame(methods.get(current), method_stats, compositor, cam, session.environment(),
                                window_target, timer, {true, false, t.wireframe, VehiclePose{s.x, s.z, s.heading}}, s);
            // Screenshots are taken before the HUD so they match a replay.
            if ((take_shot || session.last_frame()) && screenshot) {
                window_target.read_color(shot);
                if (take_shot) screenshot(shot, cam, shots++);
                if (session.last_frame()) screenshot(shot, cam, -1);
            }
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
            glViewport(0, 0, fb_w, fb_h);
            hud.visible = t.hud;
            hud.draw(HudInfo{fps, frame_ms, session.ms_per_physics_step(), latest_steps, counts.terrain_primitives,
                             counts.object_triangles, methods.name(current), methods.get(current).detail(),
                             glm::dvec3(s.x, s.y, s.z), s.velocity, s.heading, to_string(t.fog), t.lighting,
                             t.wireframe, t.shadows, session.environment().sun_dir, t.water,
                             float(session.water_level().value_or(0.0))});
            window.swap_buffers();
        }
        session.end_frame();

        const double frame_s = seconds_since(frame_start);
        frame_ms = 1e3 * frame_s;
        fps = fps > 0 ? 0.9 * fps + 0.1 / std::max(frame_s, 1e-6) : 1.0 / std::max(frame_s, 1e-6);
        FlightMethodStats& st = stats_for(result.per_method, methods.name(current));
        ++st.frames;
        st.seconds += frame_s;
        st.triangles += counts.terrain_primitives;
        st.object_triangles += counts.object_triangles;
    }
    timer.flush();
    result.record = session.record();
    result.physics_steps = session.physics_steps();
    return result;
}

FlightMethodStats render_flight_record(const DataSet& data, const FlightRecord& record, long long frames,
                                       const MethodEntry& entry, const MethodContext& context, int width, int height,
                                       double fov, const std::function<void(const ColorImage&, long long frame)>& sink) {
    HeadlessRenderer renderer(data.terrain, data.scene);
    std::unique_ptr<TerrainMethod> method = entry.create(context);
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
