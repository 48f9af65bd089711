// SPDX-License-Identifier: MIT
// A renderer of its own that embeds one of occu's culling strategies, the way
// an application would: it makes the GL context, the scene and the camera
// itself, and per frame asks the strategy's Culler which objects to draw.
//
// The scene is a walled courtyard with doorways, crates outside it, and the
// eye inside turning on the spot: most crates in the frustum are behind a
// wall. Every frame is drawn twice, unculled and culled, and the two images
// must be equal pixel for pixel (for a conservative strategy), while the
// culled frames leave out some objects; the exit status says whether they
// did. docs/library.md walks through this file.
//
// usage: occu-culled-renderer [STRATEGY [FRAMES]]   (default: ou-shared, 24)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "culling/registry.h"
#include "gl/offscreen_context.h"
#include "gl/state.h"
#include "render/scene_renderer.h"
#include "scene/scene.h"
#include "spatial/hierarchy.h"
#include "traversal/traversal.h"

using namespace occu;

namespace {

constexpr int frame_size = 256;     // pixels, each way
constexpr std::size_t batch = 16;   // objects tested together (one occlusion pass for `ou`)

void add_box(Scene &scene, const std::string &name, const Aabb &box, const glm::vec3 &colour)
{
    Mesh mesh;
    mesh.name = name;
    mesh.color = colour;
    append_box(mesh, box);
    mesh.update_bounds();
    scene.meshes.push_back(std::move(mesh));
}

// Four walls 4 m high around a 20 m square, each with a 2 m doorway in its
// middle and 0.5 m gaps at the corners; crates of three heights on a 4 m
// grid around it. No two boxes touch, so no two faces share a depth and the
// order objects are drawn in cannot change a pixel.
Scene courtyard()
{
    Scene scene;
    const glm::vec3 wall{0.75f, 0.7f, 0.6f};
    for (float side : {-1.0f, 1.0f}) {
        for (float half : {-1.0f, 1.0f}) {
            const float inner = 10.0f * side, outer = 10.5f * side;
            // A wall along x (at z = +-10) and one along z (at x = +-10), each one half of a side.
            add_box(scene, "wall", Aabb::of({half * 1.0f, 0.0f, inner}, {half * 10.5f, 4.0f, outer}), wall);
            add_box(scene, "wall", Aabb::of({inner, 0.0f, half * 1.0f}, {outer, 4.0f, half * 9.5f}), wall);
        }
    }
    for (int i = 0; i < 20; ++i) {
        for (int j = 0; j < 20; ++j) {
            const float x = -38.0f + 4.0f * i, z = -38.0f + 4.0f * j;
            if (std::abs(x) < 14.0f && std::abs(z) < 14.0f)
                continue;   // inside the courtyard or against its walls
            const float height = 1.0f + float((i + j) % 3);
            add_box(scene, "crate", Aabb::of({x - 0.6f, 0.0f, z - 0.6f}, {x + 0.6f, height, z + 0.6f}),
                    {0.3f + 0.03f * i, 0.45f, 0.3f + 0.03f * j});
        }
    }
    scene.update_bounds();
    return scene;
}

// The camera of frame `f` of `frames`: inside the courtyard, off its centre,
// turning once around.
Camera camera_at(int f, int frames)
{
    const float heading = 2.0f * 3.14159265f * float(f) / float(frames);
    Camera camera;
    camera.position = {2.0f, 1.7f, 3.0f};
    camera.target = camera.position + glm::vec3(std::sin(heading), 0.0f, -std::cos(heading));
    return camera;
}

// The distance from the eye to the nearest point of `box`: the order in
// which objects are tested and drawn, nearest first, so that what is drawn
// first can hide what follows.
float distance_to(const glm::vec3 &eye, const Aabb &box)
{
    return glm::length(glm::clamp(eye, box.min, box.max) - eye);
}

// One frame: clear, then either every leaf in the frustum, or the leaves a
// culler finds visible. Returns how many leaves it drew.
std::size_t draw_frame(const SceneRenderer &renderer, const Hierarchy &hierarchy, const Frame &frame, Culler *culler)
{
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl::load_camera(frame.camera);
    std::vector<std::uint32_t> leaves = leaves_in_frustum(hierarchy, frame.frustum);
    std::sort(leaves.begin(), leaves.end(), [&](std::uint32_t a, std::uint32_t b) {
        return distance_to(frame.camera.position, hierarchy.nodes()[a].bounds) <
               distance_to(frame.camera.position, hierarchy.nodes()[b].bounds);
    });
    if (!culler) {
        for (std::uint32_t leaf : leaves)
            renderer.draw_leaf(leaf);
        glFinish();
        return leaves.size();
    }
    // The strategy clears its occlusion state and renders its occluders
    // (into its own framebuffer or memory, never this one).
    culler->begin_frame(frame);
    std::size_t drawn = 0;
    for (std::size_t first = 0; first < leaves.size(); first += batch) {
        std::vector<NodeTest> tests;
        for (std::size_t i = first; i < std::min(first + batch, leaves.size()); ++i)
            tests.push_back({leaves[i], hierarchy.nodes()[leaves[i]].bounds, true});
        culler->test(tests);   // against what is drawn so far, for the strategies that read it
        for (const NodeTest &t : tests) {
            if (t.result != Visibility::visible)
                continue;
            renderer.draw_leaf(t.node);
            culler->rendered(t.node);
            ++drawn;
        }
    }
    glFinish();
    return drawn;
}

}   // namespace

int main(int argc, char **argv)
{
    const std::string spec = argc > 1 ? argv[1] : "ou-shared";
    const int frames = argc > 2 ? std::atoi(argv[2]) : 24;
    if (argc > 3 || frames < 1 || spec == "-h" || spec == "--help") {
        std::fprintf(stderr, "usage: occu-culled-renderer [STRATEGY [FRAMES]]   (default: ou-shared 24)\n");
        return 2;
    }
    try {
        // The GL context: OSMesa on the patched Mesa (GALLIUM_DRIVER picks
        // softpipe or llvmpipe), with its colour buffer in this process.
        gl::OffscreenContext context(frame_size, frame_size);
        glViewport(0, 0, frame_size, frame_size);
        glEnable(GL_DEPTH_TEST);
        glEnable(GL_CULL_FACE);
        glClearColor(0.55f, 0.7f, 0.9f, 1.0f);

        // The scene, the hierarchy whose leaves are the objects a culler
        // answers for (a crate or two each), and the renderer that draws them.
        const Scene scene = courtyard();
        const Hierarchy hierarchy = Hierarchy::build(scene, {/*max_leaf_triangles=*/24});
        const SceneRenderer renderer(scene, hierarchy);

        // The strategy, by the name the programs take (e.g. "ou-shared",
        // "skins", "hzb", "om-ps:occluders=16").
        const StrategyContext strategy_context{scene, hierarchy, renderer};
        Strategy strategy = make_strategy(spec, strategy_context);
        if (own_traversal(*strategy.culler) || strategy.choice.family->needs_truth) {
            std::fprintf(stderr,
                         "occu-culled-renderer: %s walks the hierarchy itself or needs the oracle; "
                         "this renderer only asks for tests\n",
                         spec.c_str());
            return 2;
        }

        const std::size_t pixels = std::size_t(frame_size) * frame_size * 4;
        std::size_t in_frustum = 0, drawn = 0, differing_frames = 0;
        for (int f = 0; f < frames; ++f) {
            const Frame frame(camera_at(f, frames), frame_size, frame_size);
            const std::size_t all = draw_frame(renderer, hierarchy, frame, nullptr);
            const std::vector<std::uint8_t> unculled(context.pixels(), context.pixels() + pixels);
            const std::size_t visible = draw_frame(renderer, hierarchy, frame, strategy.culler.get());
            std::size_t differing = 0;
            for (std::size_t i = 0; i < pixels; i += 4)
                differing += !std::equal(&unculled[i], &unculled[i] + 4, context.pixels() + i);
            std::printf("frame %2d: %3zu objects in the frustum, %3zu drawn, %3zu culled, %zu pixels differ\n", f, all,
                        visible, all - visible, differing);
            in_frustum += all;
            drawn += visible;
            differing_frames += differing > 0;
        }
        std::printf("%s: %zu of %zu objects in the frustum culled over %d frames; %zu frames differ from the "
                    "unculled ones\n",
                    spec.c_str(), in_frustum - drawn, in_frustum, frames, differing_frames);
        if (strategy.choice.conservative() && differing_frames > 0) {
            std::fprintf(stderr, "occu-culled-renderer: %s is conservative but changed %zu frames\n", spec.c_str(),
                         differing_frames);
            return 1;
        }
        if (drawn == in_frustum) {
            std::fprintf(stderr, "occu-culled-renderer: %s culled nothing behind the walls\n", spec.c_str());
            return 1;
        }
        return 0;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "occu-culled-renderer: %s\n", e.what());
        return 2;
    }
}
