// Ray casts one view of the built-in demo island with the Floating Horizon
// (Szenberg, Gattass, Carvalho, "An Algorithm for the Visualization of a
// Terrain with Objects", Algorithms 1 and 2) and prints a summary of its
// OpenGL window depth: terrain and sky pixels, and the nearest and farthest
// view depth painted. Exits 1 when the view, which looks over the island
// towards the horizon, lacks either terrain or sky.
#include "core/DemoIsland.h"
#include "core/Error.h"
#include "raycast/FloatingHorizon.h"

#include <algorithm>
#include <cstdio>
#include <limits>

int main() {
    using namespace overflight;
    try {
        DemoOptions demo;
        demo.size = 257;
        const DataSet data = make_demo_island(demo);
        const Terrain& terrain = data.terrain;

        // Above the highest peak, from over one shore, looking down across the
        // island: terrain fills the lower rows, sky the rows above (the horizon
        // and past the terrain's far edge).
        Camera camera;
        camera.width = 320;
        camera.height = 200;
        camera.heading = 45;
        camera.pitch = -25;
        camera.eye = {0.2 * terrain.width(), terrain.max_height() + 200.0, 0.2 * terrain.depth()};
        camera.far = 2.0 * std::max(terrain.width(), terrain.depth());

        FloatingHorizon caster(terrain);
        ColorImage color;
        DepthImage depth;
        caster.render(camera, data.environment, RaycastOptions{}, color, depth);

        long long terrain_pixels = 0;
        double nearest = std::numeric_limits<double>::infinity(), farthest = 0;
        for (const float d : depth.pixels) {
            if (d >= 1.0f) continue; // sky
            ++terrain_pixels;
            const double view_depth = camera.view_depth_of_window(d);
            nearest = std::min(nearest, view_depth);
            farthest = std::max(farthest, view_depth);
        }
        const long long sky_pixels = (long long)depth.pixels.size() - terrain_pixels;
        std::printf("raycast_depth: %dx%d view of the %dx%d demo island: %lld terrain pixels, %lld sky pixels",
                    depth.width, depth.height, terrain.cols(), terrain.rows(), terrain_pixels, sky_pixels);
        if (terrain_pixels > 0) std::printf(", view depth %.1f to %.1f", nearest, farthest);
        std::printf("\n");
        if (terrain_pixels == 0 || sky_pixels == 0) {
            std::fprintf(stderr, "raycast_depth: the view should hold both terrain and sky\n");
            return 1;
        }
    } catch (const Error& e) {
        std::fprintf(stderr, "raycast_depth: %s\n", e.what());
        return 1;
    }
    return 0;
}
