// embedding-host: loads a scene with the Acetate host library, renders it from every floor in
// turn (as a player walking up through a building would see it) and writes one frame per floor.
// With --day-cycle N it then runs the day on the top floor: N frames, each setting the `day`
// parameter of every acetate.lighting entry live (Scene::set_param), as a game's clock would.
// With --fly N it then flies a 640 x 360 window over the scene (Scene::set_camera): N frames
// panning from corner to corner at scale 1, then N zoomed in at scale 2 (the same window, a
// quarter of the scene in it), and prints what each camera move and frame cost and the frames
// per second at each scale.
//
//   embedding-host SCENE OUT_DIR [--time SECONDS] [--day-cycle N] [--fly N] [--registry FILE]
//                  [--allowed-signers FILE] [--allow-unvalidated]
//
// Writes OUT_DIR/floor<N>.png (and day<K>.png, fly-scale<S>.png: the last frame at scale S/100)
// and prints one line per frame.
// Exit status 1 with one line on standard error when anything fails: a bad scene, a plugin the
// registry does not hold VALIDATED (the same line `acetate render` prints), a device error.
#include <acetate/host/host.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

int fail(const acetate::host::Error& error) {
    std::fprintf(stderr, "embedding-host: %s\n", error.message.c_str());
    return 1;
}

// The fly-over: a window of 640 x 360 output pixels moving across the scene, `frames` frames at
// each scale, the camera set before every frame as a program following a player would. The
// first frame at a scale builds the effects for it; the others must cost nothing but drawing.
int fly(acetate::host::Scene& scene, double time, int frames,
        const std::filesystem::path& out_dir) {
    constexpr double kWindowWidth = 640, kWindowHeight = 360;
    for (double scale : {1.0, 2.0}) {
        const double w = kWindowWidth / scale, h = kWindowHeight / scale;
        const double travel_x = std::max(0.0, scene.width() - w);
        const double travel_y = std::max(0.0, scene.height() - h);
        // Timed from the second frame on: what a program pays per frame once it flies at a scale.
        auto start = std::chrono::steady_clock::now();
        for (int k = 0; k < frames; ++k) {
            if (k == 1) start = std::chrono::steady_clock::now();
            const double along = frames > 1 ? double(k) / (frames - 1) : 0.0;
            const acetate::host::Camera camera{travel_x * along, travel_y * along, w, h, scale};
            auto moved = scene.set_camera(camera);
            if (!moved) return fail(moved.error());
            if (auto timed = scene.set_time(time + k / 60.0); !timed) return fail(timed.error());
            auto stats = scene.render();
            if (!stats) return fail(stats.error());
            std::printf(
                "fly scale %.2f at (%.1f, %.1f): camera %.2f ms (%s), frame %.2f ms, %llu "
                "allocations, %llu compiles\n",
                scale, camera.x, camera.y, moved->milliseconds,
                moved->resized   ? "resized"
                : moved->rebuilt ? "rebuilt"
                                 : "moved",
                stats->milliseconds,
                static_cast<unsigned long long>(moved->targets_allocated +
                                                stats->targets_allocated),
                static_cast<unsigned long long>(moved->shaders_compiled + stats->shaders_compiled));
        }
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const int timed = std::max(frames - 1, 1);
        std::printf(
            "fly scale %.2f: %d frames after the first in %.2f s, %.1f frames per second "
            "(a camera move and a frame each)\n",
            scale, timed, seconds, timed / seconds);
        const std::filesystem::path file =
            out_dir / ("fly-scale" + std::to_string(int(scale * 100)) + ".png");
        if (auto written = scene.write_frame(file); !written) return fail(written.error());
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr,
                     "usage: embedding-host SCENE OUT_DIR [--time SECONDS] [--day-cycle N] "
                     "[--fly N] [--registry FILE] [--allowed-signers FILE] "
                     "[--allow-unvalidated]\n");
        return 2;
    }
    const std::filesystem::path scene_file = argv[1], out_dir = argv[2];
    acetate::host::HostOptions options;
    double time = 1.0;
    int day_frames = 0, fly_frames = 0;
    for (int i = 3; i < argc; ++i) {
        const std::string arg = argv[i];
        const bool has_value = i + 1 < argc;
        if (arg == "--time" && has_value)
            time = std::strtod(argv[++i], nullptr);
        else if (arg == "--day-cycle" && has_value)
            day_frames = std::atoi(argv[++i]);
        else if (arg == "--fly" && has_value)
            fly_frames = std::atoi(argv[++i]);
        else if (arg == "--registry" && has_value)
            options.registry = argv[++i];
        else if (arg == "--allowed-signers" && has_value)
            options.allowed_signers = argv[++i];
        else if (arg == "--allow-unvalidated")
            options.allow_unvalidated = true;
        else {
            std::fprintf(stderr, "embedding-host: unknown argument %s\n", arg.c_str());
            return 2;
        }
    }

    auto host = acetate::host::Host::create(options);
    if (!host) return fail(host.error());
    std::printf("device: %s\n", (*host)->device_name().c_str());

    auto scene = (*host)->load_scene_file(scene_file);
    if (!scene) return fail(scene.error());
    const acetate::host::LoadStatistics& load = (*scene)->load_statistics();
    std::printf("loaded %s (%ux%u, %u floors) in %.1f ms: %llu shaders compiled\n",
                scene_file.string().c_str(), (*scene)->width(), (*scene)->height(),
                (*scene)->floor_count(), load.milliseconds,
                static_cast<unsigned long long>(load.shaders_compiled));
    if (auto timed = (*scene)->set_time(time); !timed) return fail(timed.error());

    std::error_code ec;
    std::filesystem::create_directories(out_dir, ec);
    for (uint32_t floor = 0; floor < (*scene)->floor_count(); ++floor) {
        if (auto moved = (*scene)->set_active_floor(floor); !moved) return fail(moved.error());
        auto stats = (*scene)->render();
        if (!stats) return fail(stats.error());
        const std::filesystem::path file = out_dir / ("floor" + std::to_string(floor) + ".png");
        if (auto written = (*scene)->write_frame(file); !written) return fail(written.error());
        // A frame after the load does no work but drawing: nothing loaded, allocated, compiled.
        std::printf("floor %u (%s): %.2f ms, %u passes, %llu allocations, %llu compiles -> %s\n",
                    floor, (*scene)->floor_name(floor).c_str(), stats->milliseconds, stats->passes,
                    static_cast<unsigned long long>(stats->targets_allocated),
                    static_cast<unsigned long long>(stats->shaders_compiled),
                    file.string().c_str());
    }

    // The day, live: every acetate.lighting entry (the scene lists them; inspecting the file
    // needs no device) gets `day` set before each frame, with the clock running.
    auto info = acetate::host::Host::inspect_scene_file(scene_file);
    if (!info) return fail(info.error());
    std::vector<acetate::host::EffectSlot> lights;
    for (uint32_t f = 0; f < info->floor_effects.size(); ++f)
        for (uint32_t e = 0; e < info->floor_effects[f].size(); ++e)
            if (info->floor_effects[f][e] == "acetate.lighting") lights.push_back({f, e});
    for (int k = 0; k < day_frames; ++k) {
        const float day = day_frames > 1 ? float(k) / float(day_frames - 1) : 1.0f;
        double set_ms = 0;
        bool reloaded = false;
        for (const acetate::host::EffectSlot& slot : lights) {
            auto changed = (*scene)->set_param(slot, "day", {day});
            if (!changed) return fail(changed.error());
            set_ms += changed->milliseconds;
            reloaded = reloaded || changed->reloaded;
        }
        if (auto timed = (*scene)->set_time(time + k / 30.0); !timed) return fail(timed.error());
        auto stats = (*scene)->render();
        if (!stats) return fail(stats.error());
        const std::filesystem::path file = out_dir / ("day" + std::to_string(k) + ".png");
        if (auto written = (*scene)->write_frame(file); !written) return fail(written.error());
        std::printf(
            "day %.2f: set on %zu effects in %.2f ms (%s), frame %.2f ms, %llu "
            "allocations, %llu compiles -> %s\n",
            day, lights.size(), set_ms, reloaded ? "reloaded" : "in place", stats->milliseconds,
            static_cast<unsigned long long>(stats->targets_allocated),
            static_cast<unsigned long long>(stats->shaders_compiled), file.string().c_str());
    }
    return fly_frames > 0 ? fly(**scene, time, fly_frames, out_dir) : 0;
}
