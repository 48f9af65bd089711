// SPDX-License-Identifier: MIT
#include "strategies/poon_wang_opacity_maps/occluder_stacks.h"

#include <algorithm>

#include "camera/footprint.h"
#include "gl/framebuffer.h"
#include "gl/occlusion_unit.h"
#include "gl/state.h"
#include "render/id_buffer.h"

namespace occu {

namespace {

constexpr std::size_t group_limit = 64;

// Each occludee's nearest depth over its footprint, drawn as a window-aligned
// quad (identity matrices: NDC in, window depth out); 0 elsewhere.
void draw_occludee_depths(const std::vector<Occludee> &occludees, const std::vector<std::size_t> &group,
                          int resolution)
{
    glClearDepth(0.0);
    glClear(GL_DEPTH_BUFFER_BIT);
    glClearDepth(1.0);
    glDepthFunc(GL_ALWAYS);
    glDepthMask(GL_TRUE);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    auto ndc = [resolution](int p) { return 2.0f * float(p) / float(resolution) - 1.0f; };
    glBegin(GL_QUADS);
    for (std::size_t i : group) {
        const PixelRect &r = occludees[i].rect;
        const float z = 2.0f * occludees[i].z_near - 1.0f;
        glVertex3f(ndc(r.x0), ndc(r.y0), z);
        glVertex3f(ndc(r.x1), ndc(r.y0), z);
        glVertex3f(ndc(r.x1), ndc(r.y1), z);
        glVertex3f(ndc(r.x0), ndc(r.y1), z);
    }
    glEnd();
}

}  // namespace

ViewOccluders build_occluder_stacks(const SceneRenderer &renderer, const Hierarchy &hierarchy, const Camera &camera,
                                    const StackOptions &options)
{
    const gl::OcclusionUnit unit;
    ViewOccluders view;
    const int res = options.resolution, frame_size = options.resolution * options.map_divisor;
    const auto &nodes = hierarchy.nodes();
    const glm::mat4 vp = camera.view_projection();
    const Frustum frustum(vp);
    // A box's footprint in map pixels, as the run-time test takes it.
    auto map_footprint = [&](const Aabb &box) -> std::optional<Footprint> {
        auto f = box_footprint(vp, camera.position, box, frame_size, frame_size);
        if (f)
            f->rect = f->rect.to_map(options.map_divisor).clamped({0, 0, res, res});
        return f;
    };

    // What the view sees: an ID buffer at the maps' resolution.
    const std::vector<std::uint32_t> leaves = leaves_in_frustum(hierarchy, frustum);
    IdBuffer ids(renderer);
    view.pixels = pixels_per_leaf(ids.render(camera, leaves, res, res), nodes.size());

    // Occludees: nodes with enough triangles and no visible leaf. Children
    // follow their parents in the node array, so visibility sums bottom-up.
    std::vector<bool> visible(nodes.size(), false);
    for (std::size_t i = nodes.size(); i-- > 0;) {
        visible[i] = nodes[i].leaf() && view.pixels[i] > 0;
        for (std::uint32_t c = 0; c < nodes[i].child_count; ++c)
            visible[i] = visible[i] || visible[nodes[i].first_child + c];
    }
    for (std::uint32_t n = 0; n < nodes.size(); ++n) {
        if (visible[n] || nodes[n].subtree_triangles <= options.min_occludee_triangles ||
            frustum.classify(nodes[n].bounds) == Frustum::Side::outside)
            continue;
        const auto f = map_footprint(nodes[n].bounds);
        if (!f || f->rect.empty())
            continue;
        view.occludees.push_back({n, f->rect, f->window_z_near, {}});
        view.occludees.back().stack.resize(std::size_t(f->rect.area()));
    }

    // Candidates, with their footprints and nearest depth; a box without a
    // footprint is in front of everything, anywhere on screen.
    std::vector<float> near_z(nodes.size(), 0.0f);
    std::vector<PixelRect> footprint(nodes.size(), PixelRect{0, 0, res, res});
    for (std::uint32_t n : leaves)
        if (view.pixels[n] >= options.min_occluder_pixels) {
            view.candidates.push_back(n);
            if (const auto f = map_footprint(nodes[n].bounds)) {
                footprint[n] = f->rect;
                near_z[n] = f->window_z_near;
            }
        }

    gl::Framebuffer target(res, res);
    gl::Framebuffer::Bind bind(target);
    gl::AttribScope state(GL_ENABLE_BIT | GL_DEPTH_BUFFER_BIT | GL_COLOR_BUFFER_BIT | GL_POLYGON_BIT);
    gl::MatrixScope matrices;
    glDisable(GL_CULL_FACE);   // the stack wants every covered pixel, back faces too
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glEnable(GL_DEPTH_TEST);
    // Groups of up to 64 occludees with pairwise disjoint footprints: one
    // verbose tile each, so no tile counts another's pixels.
    std::vector<PixelRect> rects;
    std::vector<std::size_t> all;
    for (const Occludee &o : view.occludees) {
        all.push_back(rects.size());
        rects.push_back(o.rect);
    }
    for (const std::vector<std::size_t> &group : disjoint_groups(rects, std::move(all), group_limit)) {
        draw_occludee_depths(view.occludees, group, res);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_FALSE);
        gl::load_camera(camera);
        std::vector<PixelRect> tiles;
        std::vector<std::size_t> list_pixels;
        float z_far_group = 0.0f;
        for (std::size_t i : group) {
            tiles.push_back(view.occludees[i].rect);
            // A leaf's front and back faces both cover a pixel: room for 4 each.
            list_pixels.push_back(4 * std::size_t(view.occludees[i].rect.area()));
            z_far_group = std::max(z_far_group, view.occludees[i].z_near);
        }
        for (std::uint32_t c : view.candidates) {
            const PixelRect &f = footprint[c];
            if (near_z[c] >= z_far_group ||
                std::none_of(group.begin(), group.end(), [&](std::size_t j) { return f.overlaps(view.occludees[j].rect); }))
                continue;   // behind every occludee of the group, or beside them all
            gl::OcclusionPass pass(unit, gl::OcclusionMode::verbose, tiles, list_pixels);
            renderer.draw_leaf_flat(c);
            const std::vector<gl::OcclusionRecord> &records = pass.end();
            ++view.passes;
            for (std::size_t k = 0; k < group.size(); ++k) {
                Occludee &o = view.occludees[group[k]];
                // An overflowed list misses some of c: fewer sets, never wrong ones.
                for (const gl::OcclusionRecord::Pixel &p : records[k].pixels) {
                    auto &s = o.stack[std::size_t(int(p.y) - o.rect.y0) * std::size_t(o.rect.width()) +
                                      std::size_t(int(p.x) - o.rect.x0)];
                    if (s.empty() || s.back() != c)
                        s.push_back(c);
                }
            }
        }
    }
    return view;
}

}  // namespace occu
