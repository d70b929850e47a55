#include "gl/FlightWindow.h"

#include "core/Error.h"
#include "gl/FlightMethods.h"
#include "gl/FlightRenderer.h"
#include "gl/FlightTimer.h"
#include "gl/GlContext.h"
#include "gl/Hud.h"
#include "gl/RenderTarget.h"
#include "sim/ChaseCamera.h"
#include "sim/FixedStepClock.h"
#include "sim/Hovercraft.h"
#include "sim/KeyState.h"

#include <GLFW/glfw3.h>
#include <epoxy/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>

namespace overflight::gl {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Keys and one-shot commands gathered from GLFW events between frames.
struct InputState {
    KeyState keys;
    std::vector<Key> commands; // reserved up front: no allocation per frame
};

std::optional<Key> key_of(int glfw_key) {
    switch (glfw_key) {
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
    default: return std::nullopt;
    }
}

void on_key(GLFWwindow* window, int key, int /*scancode*/, int action, int /*mods*/) {
    auto* in = static_cast<InputState*>(glfwGetWindowUserPointer(window));
    if (!in || action == GLFW_REPEAT) return; // seed 003: key repeat is ignored
    const std::optional<Key> k = key_of(key);
    if (!k) return;
    if (is_vehicle_key(*k)) {
        if (action == GLFW_PRESS) in->keys.press(*k);
        else in->keys.release(*k);
    } else if (action == GLFW_PRESS && in->commands.size() < in->commands.capacity()) {
        in->commands.push_back(*k);
    }
}

// Camera far plane: the whole map from any point on it.
void setup_camera(Camera& cam, const Terrain& t, double fov) {
    cam.fov = fov;
    cam.near = 0.5;
    const double span = std::hypot(double(t.width()), double(t.depth()), double(t.max_height() - t.min_height()));
    cam.far = std::max(1000.0, 1.1 * span);
    cam.projection = Projection::Shear;
}

// Chase distances grow with the grid spacing: on a 10 m or 90 m grid the
// paper's few-metre offsets would fill the view with a single cell. The eye
// stays low enough (above / behind = 0.2, about 11 degrees down) that the
// vehicle is in the lower part of the view while the camera aims at the
// look-ahead point (60 degrees horizontal fov at 16:9 sees 18 degrees down).
ChaseParams chase_params(const Terrain& t) {
    ChaseParams p;
    const double hs = t.h_scale();
    p.behind = std::max(p.behind, 3.0 * hs);
    p.above = std::max(p.above, 0.6 * hs);
    p.look_ahead = std::max(p.look_ahead, 8.0 * hs);
    return p;
}

// Fog (f) and lighting (1) toggles applied to the data set's environment. A
// data set without fog gets a density that fades the far side of the map.
Environment view_environment(const Environment& env, const Terrain& t, bool fog, bool lighting) {
    Environment e = env;
    if (!fog) e.fog_density = 0;
    else if (!(e.fog_density > 0))
        e.fog_density = float(2.0 / std::max(1.0, std::hypot(double(t.width()), double(t.depth()))));
    if (!lighting) {
        e.sun_color = glm::vec3(0.0f);
        e.ambient = glm::vec3(1.0f);
    }
    return e;
}

class MethodSet {
public:
    MethodSet(const DataSet& data, const FlightMethodFactory& factory, std::vector<std::string> names)
        : data_(data), factory_(factory), names_(std::move(names)), methods_(names_.size()) {}

    // The method at `index`, created on first use; nullptr if the factory
    // does not know it.
    FlightMethod* get(std::size_t index) {
        if (!methods_[index])
            methods_[index] = factory_ ? factory_(names_[index], data_) : make_flight_method(names_[index], data_);
        return methods_[index].get();
    }
    std::size_t size() const { return names_.size(); }
    const std::string& name(std::size_t i) const { return names_[i]; }

private:
    const DataSet& data_;
    const FlightMethodFactory& factory_;
    std::vector<std::string> names_;
    std::vector<std::unique_ptr<FlightMethod>> methods_;
};

FlightMethodStats& stats_for(std::vector<FlightMethodStats>& all, const std::string& name) {
    for (FlightMethodStats& s : all)
        if (s.method == name) return s;
    all.push_back(FlightMethodStats{name});
    return all.back();
}

// Adds one frame's step times to a method's sums.
void add_steps(FlightMethodStats& stats, const FlightSteps& steps) {
    for (int i = 0; i < steps.count; ++i) {
        const FlightStep& step = steps.step[std::size_t(i)];
        auto it = std::find_if(stats.step_ms.begin(), stats.step_ms.end(),
                               [&](const auto& entry) { return entry.first == step.name; });
        if (it == stats.step_ms.end()) it = stats.step_ms.insert(stats.step_ms.end(), {step.name, 0.0});
        it->second += step.ms;
    }
    ++stats.timed_frames;
}

} // namespace

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

FlightResult run_flight_window(const DataSet& data, const FlightWindowOptions& options,
                               const FlightMethodFactory& factory, const ScreenshotSink& screenshot) {
    const Terrain& terrain = data.terrain;
    std::vector<std::string> names = options.methods;
    if (std::find(names.begin(), names.end(), options.method) == names.end())
        names.insert(names.begin(), options.method);
    std::size_t current = std::size_t(std::find(names.begin(), names.end(), options.method) - names.begin());

    // The vehicle first, so a bad start fails before a window flashes up.
    const double x0 = options.start.given ? options.start.x : terrain.width() * 0.5;
    const double z0 = options.start.given ? options.start.z : terrain.depth() * 0.5;
    Hovercraft hc(terrain, x0, z0, options.start.given ? options.start.heading : 0.0);

    WindowContext window("Overflight - " + data.info.source, options.width, options.height, options.visible);
    const bool unattended = options.frames > 0;
    glfwSwapInterval(unattended ? 0 : 1); // scripted runs go as fast as the GL allows
    InputState input;
    input.commands.reserve(64);
    glfwSetWindowUserPointer(window.window(), &input);
    glfwSetKeyCallback(window.window(), on_key);
    Hud hud(window.window()); // after our callback: ImGui chains to it
    hud.visible = options.hud;

    MethodSet methods(data, factory, names);
    if (!methods.get(current)) throw Error("--method", "'" + names[current] + "' is not available in this build");
    FlightRenderer renderer(data);

    ChaseCamera chase(chase_params(terrain));
    Camera cam;
    setup_camera(cam, terrain, options.fov);
    chase.reset(terrain, hc.state(), cam);
    FixedStepClock clock(hc.params().step);

    bool fog = data.environment.fog_density > 0, lighting = true, wireframe = false;
    FlightResult result;
    result.record.frames.reserve(unattended ? std::size_t(options.frames) : 4096);
    unsigned scripted_held = 0; // vehicle keys the script holds (bit per key)
    ColorImage shot;
    int shots = 0;
    double sim_time = 0, fps = 0, frame_ms = 0, step_ms = 0;
    FlightFrameCounts counts;
    // Step timings arrive a few frames late (GL queries); the HUD shows the
    // latest, the per-method statistics sum them.
    FlightSteps latest_steps;
    FlightStepTimer timer([&](int tag, const FlightSteps& steps) {
        latest_steps = steps;
        add_steps(stats_for(result.per_method, methods.name(std::size_t(tag))), steps);
    });
    RenderTarget window_target = RenderTarget::default_framebuffer(options.width, options.height);
    auto last = Clock::now();

    for (long long frame = 0; !unattended || frame < options.frames; ++frame) {
        const auto frame_start = Clock::now();
        glfwPollEvents();
        if (window.should_close()) break;

        // Scripted keys act exactly like events arriving before this frame.
        for (int k = 0; k < 4; ++k) {
            const bool held = options.script.held_at(Key(k), frame);
            const bool was = (scripted_held >> k) & 1u;
            if (held && !was) input.keys.press(Key(k));
            if (!held && was) input.keys.release(Key(k));
            scripted_held = held ? scripted_held | (1u << k) : scripted_held & ~(1u << k);
        }
        for (int k = 4; k < kKeyCount; ++k)
            if (options.script.starts_at(Key(k), frame) && input.commands.size() < input.commands.capacity())
                input.commands.push_back(Key(k));

        bool quit = false, take_shot = false;
        for (Key k : input.commands) {
            switch (k) {
            case Key::Fog: fog = !fog; break;
            case Key::Lighting: lighting = !lighting; break;
            case Key::Wireframe: wireframe = !wireframe; break;
            case Key::DetailUp: methods.get(current)->scale_detail(std::sqrt(2.0)); break;
            case Key::DetailDown: methods.get(current)->scale_detail(1.0 / std::sqrt(2.0)); break;
            case Key::NextMethod:
                // Tab: the next method that can be built, same camera.
                for (std::size_t i = 1; i <= methods.size(); ++i) {
                    const std::size_t next = (current + i) % methods.size();
                    if (methods.get(next)) {
                        current = next;
                        break;
                    }
                }
                break;
            case Key::Screenshot: take_shot = true; break;
            case Key::Hud: hud.visible = !hud.visible; break;
            case Key::Quit: quit = true; break;
            default: break;
            }
        }
        input.commands.clear();
        if (quit) break;

        // Physics: fixed 10 ms steps for the time this frame stands for.
        const double dt = unattended ? options.frame_time : std::min(0.25, seconds_since(last));
        last = Clock::now();
        sim_time += dt;
        const int steps = clock.advance(dt);
        Controls seen;
        const auto physics_start = Clock::now();
        for (int i = 0; i < steps; ++i) {
            const Controls c = input.keys.sample();
            hc.step(c);
            seen.accelerate |= c.accelerate;
            seen.brake |= c.brake;
            seen.left |= c.left;
            seen.right |= c.right;
        }
        if (steps > 0) step_ms = 1e3 * seconds_since(physics_start) / steps;
        result.physics_steps += steps;
        chase.update(terrain, hc.state(), dt, cam);

        int fb_w = 0, fb_h = 0;
        window.framebuffer_size(fb_w, fb_h);
        if (fb_w > 0 && fb_h > 0) { // minimised: keep simulating, draw nothing
            cam.width = fb_w;
            cam.height = fb_h;
            // Kept between frames: its full-screen copy pass is built once.
            if (window_target.width() != fb_w || window_target.height() != fb_h)
                window_target = RenderTarget::default_framebuffer(fb_w, fb_h);
            const Environment env = view_environment(data.environment, terrain, fog, lighting);
            FlightMethod* method = methods.get(current);
            const HovercraftState& s = hc.state();
            timer.begin_frame(int(current));
            counts = renderer.draw(*method, cam, env, window_target, timer, VehiclePose{s.x, s.z, s.heading},
                                   wireframe);
            // Screenshots are taken before the HUD so they match a replay.
            const bool last_frame = unattended && frame + 1 == options.frames;
            if ((take_shot || last_frame) && screenshot) {
                window_target.read_color(shot);
                if (take_shot) screenshot(shot, shots++);
                if (last_frame) screenshot(shot, -1);
            }
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
            glViewport(0, 0, fb_w, fb_h);
            hud.draw(HudInfo{fps, frame_ms, step_ms, latest_steps, counts.terrain_triangles, counts.object_triangles,
                             method->name(), method->detail(), glm::dvec3(s.x, s.y, s.z), s.velocity, s.heading, fog,
                             lighting, wireframe});
            window.swap_buffers();
        }

        const HovercraftState& s = hc.state();
        FlightFrame rec;
        rec.frame = frame;
        rec.time = sim_time;
        rec.eye = cam.eye;
        rec.heading = cam.heading;
        rec.pitch = cam.pitch;
        rec.x = s.x;
        rec.z = s.z;
        rec.velocity = s.velocity;
        rec.vehicle_heading = s.heading;
        rec.keys = seen;
        result.record.frames.push_back(rec);

        const double frame_s = seconds_since(frame_start);
        frame_ms = 1e3 * frame_s;
        fps = fps > 0 ? 0.9 * fps + 0.1 / std::max(frame_s, 1e-6) : 1.0 / std::max(frame_s, 1e-6);
        FlightMethodStats& st = stats_for(result.per_method, methods.name(current));
        ++st.frames;
        st.seconds += frame_s;
        st.triangles += counts.terrain_triangles;
        st.object_triangles += counts.object_triangles;
    }
    timer.flush();
    return result;
}

FlightMethodStats render_flight_record(const DataSet& data, const FlightRecord& record, long long frames,
                                       const std::string& method_name, int width, int height, double fov,
                                       const FlightMethodFactory& factory,
                                       const std::function<void(const ColorImage&, long long frame)>& sink) {
    HeadlessContext context;
    RenderTarget target(width, height);
    std::unique_ptr<FlightMethod> method = factory ? factory(method_name, data) : make_flight_method(method_name, data);
    if (!method) throw Error("--method", "'" + method_name + "' is not available in this build");
    FlightRenderer renderer(data);
    FlightMethodStats stats{method_name};
    FlightStepTimer timer([&](int, const FlightSteps& steps) { add_steps(stats, steps); });

    Camera cam;
    setup_camera(cam, data.terrain, fov);
    cam.width = width;
    cam.height = height;
    const Environment env = view_environment(data.environment, data.terrain, data.environment.fog_density > 0, true);
    const std::size_t n = frames > 0 ? std::min<std::size_t>(std::size_t(frames), record.frames.size())
                                     : record.frames.size();
    ColorImage image;
    for (std::size_t i = 0; i < n; ++i) {
        const FlightFrame& f = record.frames[i];
        const auto t0 = Clock::now();
        cam.eye = f.eye;
        cam.heading = f.heading;
        cam.pitch = f.pitch;
        timer.begin_frame(0);
        const FlightFrameCounts counts =
            renderer.draw(*method, cam, env, target, timer, VehiclePose{f.x, f.z, f.vehicle_heading}, false);
        target.read_color(image);
        stats.seconds += seconds_since(t0);
        stats.triangles += counts.terrain_triangles;
        stats.object_triangles += counts.object_triangles;
        ++stats.frames;
        sink(image, f.frame);
    }
    timer.flush();
    return stats;
}

} // namespace overflight::gl
