// SPDX-License-Identifier: MIT
// The small cities the integration tests draw whole frames of: a city of
// blocks x blocks (scene/city.h) in leaves of at most `leaf_triangles`,
// made by the one scene setup of the programs (evaluation/scene_setup.h),
// and a size x size context to draw it in, with depth test, back-face
// culling and a black clear colour.
#pragma once

#include <cstdint>

#include "culling/registry.h"
#include "evaluation/scene_setup.h"
#include "gl/gl_headers.h"
#include "gl/offscreen_context.h"
#include "render/scene_renderer.h"

namespace occu::integration {

inline SceneChoice small_city_choice(int blocks, std::uint32_t leaf_triangles)
{
    SceneChoice choice;
    choice.city.blocks_x = choice.city.blocks_z = blocks;
    choice.hierarchy.max_leaf_triangles = leaf_triangles;
    return choice;
}

struct SmallCity {
    SmallCity(int blocks, std::uint32_t leaf_triangles, int size)
        : ctx(size, size), setup(small_city_choice(blocks, leaf_triangles)), scene(setup.scene()),
          h(setup.hierarchy()), renderer(scene, h)
    {
        glViewport(0, 0, size, size);
        glEnable(GL_DEPTH_TEST);
        glEnable(GL_CULL_FACE);
        glClearColor(0, 0, 0, 0);
    }
    StrategyContext context() const { return {scene, h, renderer}; }

    gl::OffscreenContext ctx;   // first: the renderer needs it current
    SceneSetup setup;
    const Scene &scene;
    const Hierarchy &h;
    SceneRenderer renderer;
};

}  // namespace occu::integration
