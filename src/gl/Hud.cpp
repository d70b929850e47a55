#include "gl/Hud.h"

#include "core/SunLight.h"

#include <epoxy/gl.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

namespace overflight::gl {

Hud::Hud(GLFWwindow* window) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr; // nothing left behind in the working folder
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 450 core");
}

Hud::~Hud() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

void Hud::draw(const HudInfo& info) {
    // A frame is always started and ended so that ImGui's input state stays in
    // step with GLFW even while the HUD is hidden.
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (visible) {
        ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_Always);
        ImGui::SetNextWindowBgAlpha(0.55f);
        ImGui::Begin("Overflight", nullptr,
                     ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                         ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                         ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs);
        ImGui::Text("%.1f fps  %.2f ms/frame", info.fps, info.frame_ms);
        ImGui::Text("method %s%s%s", info.method.c_str(), info.detail.empty() ? "" : "  ", info.detail.c_str());
        for (int i = 0; i < info.steps.count; ++i) {
            const FlightStep& s = info.steps.step[std::size_t(i)];
            ImGui::Text("  %-10s %7.2f ms%s", s.name, s.ms, s.gl ? " (gl)" : "");
        }
        ImGui::Text("  %-10s %7.4f ms/step", "physics", info.step_ms);
        ImGui::Text("triangles %lld  objects %lld", info.triangles, info.object_triangles);
        ImGui::Text("position %.1f, %.1f, %.1f", info.position.x, info.position.y, info.position.z);
        ImGui::Text("speed %.2f m/s  heading %.1f", info.speed, info.heading);
        ImGui::Text("fog %s  light %s  shadows %s  wire %s", info.fog, info.lighting ? "sun" : "baked",
                    info.shadows ? "on" : "off", info.wireframe ? "on" : "off");
        const SunAngles sun = sun_angles(info.sun_dir);
        ImGui::Text("sun azimuth %.0f  elevation %.0f%s", sun.azimuth, sun.elevation,
                    sun.elevation <= 0 ? " (night)" : "");
        if (info.water) ImGui::Text("water on, level %.1f", double(info.water_level));
        else ImGui::Text("water off");
        ImGui::TextDisabled("arrows fly  f 1 s t T o W  + _  Tab P H q");
        ImGui::End();
    }
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

} // namespace overflight::gl
