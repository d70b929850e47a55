#pragma once
// The heads-up display of the `fly` window: fps, ms per frame, per
// rendering step (ray cast or tessellate, uploads, objects: FlightStepTimer)
// and per physics step, triangles, method and level of detail, vehicle
// position, speed and heading, and the fog (off, GL_EXP, atmosphere) /
// lighting / wireframe toggles of CMSC 23700 project 2a sec. 3.1. Drawn with Dear ImGui (Debian's libimgui + its GLFW and
// OpenGL 3 backends).
#include "gl/FlightTimer.h"

#include <glm/vec3.hpp>

#include <string>

struct GLFWwindow;

namespace overflight::gl {

struct HudInfo {
    double fps = 0;
    double frame_ms = 0;        // wall-clock ms of the last frame
    double step_ms = 0;         // ms per 10 ms physics step (CPU time of the simulation)
    FlightSteps steps;          // rendering steps of the latest timed frame
    long long triangles = 0;    // terrain
    long long object_triangles = 0;
    std::string method;
    std::string detail;         // method's level of detail, may be empty
    glm::dvec3 position{0.0};   // vehicle, world
    double speed = 0;           // world units per second
    double heading = 0;         // degrees
    const char* fog = "off";    // the fog mode: off, GL_EXP, atmosphere
    bool lighting = true, wireframe = false;
    bool shadows = false;
    glm::vec3 sun_dir{0.0f, 1.0f, 0.0f}; // towards the sun
    bool water = false;
    float water_level = 0.0f;
};

class Hud {
public:
    // Creates the ImGui context for `window` (its context must be current) and
    // chains ImGui's GLFW callbacks after the ones already installed, so the
    // window's own key handling keeps working. Does not write imgui.ini.
    explicit Hud(GLFWwindow* window);
    ~Hud();
    Hud(const Hud&) = delete;
    Hud& operator=(const Hud&) = delete;

    // Draws the HUD over the bound default framebuffer (no-op when hidden).
    void draw(const HudInfo& info);
    bool visible = true;
};

} // namespace overflight::gl
