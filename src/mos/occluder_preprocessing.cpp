#include "mos/occluder_preprocessing.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "GL/mesax_occlusion_unit.h"
#include "culling/occluder_selection.h"
#include "culling/traversal.h"
#include "gl/extensions.h"
#include "mos/minimum_occluder_set.h"
#include "render/id_buffer.h"

namespace occu {

namespace {

struct Rect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;   // pixels x0 <= x < x1
    int area() const { return (x1 - x0) * (y1 - y0); }
};

struct Occludee {
    std::uint32_t node;
    Rect rect;
    float z_near;
    std::vector<std::vector<std::uint32_t>> stack;   // per rect pixel, occluders covering it
};

// The box's rectangle in a resolution x resolution map, as the run-time
// test widens it (opacity_map_culler.cpp), and its nearest window depth.
bool occludee_rect(const glm::mat4 &vp, const Camera &camera, const Aabb &box, int resolution, Rect &r, float &z)
{
    const auto p = project_box(vp, camera.position, box);
    if (!p)
        return false;
    auto to_map = [&](float ndc) { return (ndc + 1.0f) * 0.5f * float(resolution); };
    r.x0 = std::clamp(int(std::floor(to_map(p->ndc_min.x))), 0, resolution);
    r.x1 = std::clamp(int(std::ceil(to_map(p->ndc_max.x))), 0, resolution);
    r.y0 = std::clamp(int(std::floor(to_map(p->ndc_min.y))), 0, resolution);
    r.y1 = std::clamp(int(std::ceil(to_map(p->ndc_max.y))), 0, resolution);
    z = p->window_z_near;
    return r.x0 < r.x1 && r.y0 < r.y1;
}

}  // namespace

std::vector<std::size_t> order_by_marginal_score(const std::vector<std::vector<std::uint32_t>> &sets,
                                                 const std::vector<std::vector<std::vector<std::uint32_t>>> &sets_of,
                                                 const std::vector<double> &cost)
{
    const std::size_t count = sets.size();
    auto is_subset = [](const std::vector<std::uint32_t> &t, const std::vector<std::uint32_t> &s) {
        return t.size() <= s.size() && std::includes(s.begin(), s.end(), t.begin(), t.end());
    };
    // covers[i]: occludees one of whose sets is a subset of set i.
    std::vector<std::vector<std::uint32_t>> covers(count);
    for (std::uint32_t o = 0; o < sets_of.size(); ++o)
        for (std::size_t i = 0; i < count; ++i)
            if (std::any_of(sets_of[o].begin(), sets_of[o].end(), [&](const auto &t) { return is_subset(t, sets[i]); }))
                covers[i].push_back(o);
    std::vector<bool> hidden(sets_of.size(), false), used(count, false), chosen;
    auto is_chosen = [&chosen](std::uint32_t id) { return id < chosen.size() && chosen[id]; };
    auto cost_of = [&cost](std::uint32_t id) { return id < cost.size() ? cost[id] : 1.0; };
    std::vector<std::size_t> order;
    for (;;) {
        std::size_t best = count;
        double best_score = 0.0;
        for (std::size_t i = 0; i < count; ++i) {
            if (used[i])
                continue;
            double g = 0.0, c = 0.0;
            for (std::uint32_t o : covers[i])
                g += !hidden[o];
            for (std::uint32_t id : sets[i])
                c += is_chosen(id) ? 0.0 : cost_of(id);
            const double score = g / std::max(c, 1e-9);
            if (g > 0.0 && score > best_score) {
                best_score = score;
                best = i;
            }
        }
        if (best == count)
            break;
        used[best] = true;
        order.push_back(best);
        for (std::uint32_t id : sets[best]) {
            if (id >= chosen.size())
                chosen.resize(std::size_t(id) + 1, false);
            chosen[id] = true;
        }
        for (std::uint32_t o = 0; o < sets_of.size(); ++o)
            hidden[o] = hidden[o] || std::any_of(sets_of[o].begin(), sets_of[o].end(), [&](const auto &t) {
                            return std::all_of(t.begin(), t.end(), is_chosen);
                        });
    }
    for (std::size_t i = 0; i < count; ++i)
        if (!used[i])
            order.push_back(i);
    return order;
}

std::vector<std::uint32_t> select_occluders_for_view(const SceneRenderer &renderer, const Hierarchy &hierarchy,
                                                     const Camera &camera, const PreprocessOptions &options,
                                                     PreprocessStats *stats)
{
    auto ScissorsMESAX = reinterpret_cast<PFNGLSCISSORSMESAXPROC>(gl::get_proc_address("glScissorsMESAX"));
    auto OcclusionBuffersMESAX =
        reinterpret_cast<PFNGLOCCLUSIONBUFFERSMESAXPROC>(gl::get_proc_address("glOcclusionBuffersMESAX"));
    if (!ScissorsMESAX || !OcclusionBuffersMESAX)
        throw std::runtime_error("preprocessing needs GL_MESAX_occlusion_unit");
    PreprocessStats local;
    PreprocessStats &st = stats ? *stats : local;
    const int res = options.resolution;
    const auto &nodes = hierarchy.nodes();
    const glm::mat4 vp = camera.view_projection();
    const Frustum frustum(vp);

    // 1. What the view sees.
    std::vector<std::uint32_t> leaves;
    for (std::uint32_t n = 0; n < nodes.size(); ++n)
        if (nodes[n].leaf() && frustum.classify(nodes[n].bounds) != Frustum::Side::outside)
            leaves.push_back(n);
    const auto pixels = pixels_per_leaf(render_leaf_ids(renderer, camera, leaves, res, res), nodes.size());

    // 2. Occludees: nodes with enough triangles and no visible leaf. Parents
    // precede children in the node array, so visibility sums bottom-up.
    std::vector<bool> visible(nodes.size(), false);
    for (std::size_t i = nodes.size(); i-- > 0;) {
        const auto &n = nodes[i];
        visible[i] = n.leaf() ? pixels[i] > 0 : false;
        for (std::uint32_t c = n.first_child; c < n.first_child + n.child_count; ++c)
            visible[i] = visible[i] || visible[c];
    }
    std::vector<Occludee> occludees;
    for (std::uint32_t n = 0; n < nodes.size(); ++n) {
        if (visible[n] || nodes[n].subtree_triangles <= options.min_occludee_triangles ||
            frustum.classify(nodes[n].bounds) == Frustum::Side::outside)
            continue;
        Occludee o{n, {}, 0.0f, {}};
        if (!occludee_rect(vp, camera, nodes[n].bounds, res, o.rect, o.z_near))
            continue;
        o.stack.resize(std::size_t(o.rect.area()));
        occludees.push_back(std::move(o));
    }
    st.occludees = std::uint32_t(occludees.size());

    // 3. Occluder stacks. Occludees go in groups of up to 64 with disjoint
    // rectangles; the depth buffer gets each one's nearest depth over its
    // rectangle (0 elsewhere), then one verbose pass per candidate, depth
    // tested (LESS) without depth writes, lists exactly the pixels where the
    // candidate lies in front of the occludee: the paper's depth sorting,
    // per pixel.
    std::vector<std::uint32_t> candidates;
    std::vector<float> near_z(nodes.size(), 0.0f);
    std::vector<Rect> footprint(nodes.size(), Rect{0, 0, res, res});
    for (std::uint32_t n : leaves)
        if (pixels[n] >= options.min_occluder_pixels) {
            candidates.push_back(n);
            float z = 0.0f;   // a box that crosses the near plane: in front, anywhere on screen
            if (occludee_rect(vp, camera, nodes[n].bounds, res, footprint[n], z))
                near_z[n] = z;
        }
    st.candidates = std::uint32_t(candidates.size());
    GLint viewport[4];
    glGetIntegerv(GL_VIEWPORT, viewport);
    glViewport(0, 0, res, res);
    glPushAttrib(GL_ENABLE_BIT | GL_DEPTH_BUFFER_BIT | GL_COLOR_BUFFER_BIT | GL_POLYGON_BIT);
    glDisable(GL_CULL_FACE);   // the stack wants every covered pixel, back faces too
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glEnable(GL_DEPTH_TEST);
    constexpr std::size_t group_limit = 64;
    std::vector<std::vector<GLuint>> lists(group_limit);
    std::vector<std::size_t> pending(occludees.size());
    for (std::size_t i = 0; i < pending.size(); ++i)
        pending[i] = i;
    while (!pending.empty()) {
        std::vector<std::size_t> group, later;
        for (std::size_t i : pending) {
            const Rect &r = occludees[i].rect;
            const bool disjoint = group.size() < group_limit && std::all_of(group.begin(), group.end(), [&](std::size_t j) {
                const Rect &q = occludees[j].rect;
                return r.x1 <= q.x0 || q.x1 <= r.x0 || r.y1 <= q.y0 || q.y1 <= r.y0;
            });
            (disjoint ? group : later).push_back(i);
        }
        pending.swap(later);

        // Each occludee's nearest depth over its rectangle, drawn as a
        // window-aligned quad (identity matrices: NDC in, window depth out).
        glClearDepth(0.0);
        glClear(GL_DEPTH_BUFFER_BIT);
        glClearDepth(1.0);
        glDepthFunc(GL_ALWAYS);
        glDepthMask(GL_TRUE);
        glMatrixMode(GL_PROJECTION);
        glLoadIdentity();
        glMatrixMode(GL_MODELVIEW);
        glLoadIdentity();
        glBegin(GL_QUADS);
        for (std::size_t i : group) {
            const Rect &r = occludees[i].rect;
            auto ndc = [res](int p) { return 2.0f * float(p) / float(res) - 1.0f; };
            const float z = 2.0f * occludees[i].z_near - 1.0f;
            glVertex3f(ndc(r.x0), ndc(r.y0), z);
            glVertex3f(ndc(r.x1), ndc(r.y0), z);
            glVertex3f(ndc(r.x1), ndc(r.y1), z);
            glVertex3f(ndc(r.x0), ndc(r.y1), z);
        }
        glEnd();
        glDepthFunc(GL_LESS);
        glDepthMask(GL_FALSE);
        load_camera(camera);

        const std::size_t count = group.size();
        std::vector<GLint> tiles(4 * count);
        std::vector<GLsizei> sizes(count);
        std::vector<GLuint *> buffers(count);
        float z_far_group = 0.0f;
        for (std::size_t k = 0; k < count; ++k) {
            const Occludee &o = occludees[group[k]];
            tiles[4 * k] = o.rect.x0;
            tiles[4 * k + 1] = o.rect.y0;
            tiles[4 * k + 2] = o.rect.x1 - o.rect.x0;
            tiles[4 * k + 3] = o.rect.y1 - o.rect.y0;
            // A leaf's front and back faces both cover a pixel: room for 4 each.
            lists[k].resize(8 + 2 * 4 * std::size_t(o.rect.area()));
            sizes[k] = GLsizei(lists[k].size());
            buffers[k] = lists[k].data();
            z_far_group = std::max(z_far_group, o.z_near);
        }
        for (std::uint32_t c : candidates) {
            const Rect &f = footprint[c];
            if (near_z[c] >= z_far_group || std::none_of(group.begin(), group.end(), [&](std::size_t j) {
                    const Rect &q = occludees[j].rect;
                    return f.x0 < q.x1 && q.x0 < f.x1 && f.y0 < q.y1 && q.y0 < f.y1;
                }))
                continue;   // behind every occludee of the group, or beside them all
            OcclusionBuffersMESAX(GLsizei(count), sizes.data(), buffers.data());
            ScissorsMESAX(GLsizei(count), tiles.data());
            glRenderMode(GL_VERBOSE_OCCLUSION_MESAX);
            renderer.draw_leaf_flat(c);
            glRenderMode(GL_RENDER);
            ++st.passes;
            for (std::size_t k = 0; k < count; ++k) {
                Occludee &o = occludees[group[k]];
                const GLuint n = lists[k][0];
                const std::size_t listed = std::min<std::size_t>(n, (lists[k].size() - 8) / 2);
                const int w = o.rect.x1 - o.rect.x0;
                for (std::size_t i = 0; i < listed; ++i) {
                    const GLuint x = lists[k][8 + 2 * i], y = lists[k][9 + 2 * i];
                    if (x == 0xffffffffu)
                        break;   // overflow terminator: the stack misses some of c (fewer sets, never wrong ones)
                    auto &s = o.stack[std::size_t(int(y) - o.rect.y0) * std::size_t(w) + std::size_t(int(x) - o.rect.x0)];
                    if (s.empty() || s.back() != c)
                        s.push_back(c);
                }
            }
        }
    }
    ScissorsMESAX(0, nullptr);
    glPopAttrib();
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);

    // 4. Minimum occluder sets per occludee.
    MosSearchOptions search;
    search.cost.assign(nodes.size(), 1.0);
    for (std::uint32_t c : candidates)
        search.cost[c] = 1.0 + double(pixels[c]) / options.pixels_per_occluder;
    search.keep_cheapest = options.sets_per_occludee;
    search.step_budget = options.step_budget;
    std::map<std::vector<std::uint32_t>, double> gain;
    std::vector<std::vector<std::vector<std::uint32_t>>> sets_of;   // per coverable occludee
    for (Occludee &o : occludees) {
        std::vector<std::vector<std::uint32_t>> slots;
        bool covered = true;
        for (auto &s : o.stack) {
            if (s.empty()) {
                covered = false;
                break;
            }
            std::sort(s.begin(), s.end());
            slots.push_back(std::move(s));
        }
        o.stack.clear();
        if (!covered)
            continue;
        std::sort(slots.begin(), slots.end());
        slots.erase(std::unique(slots.begin(), slots.end()), slots.end());
        std::stable_sort(slots.begin(), slots.end(), [](const auto &a, const auto &b) { return a.size() < b.size(); });
        const MosSearchResult r = minimum_occluder_sets(slots, search);
        st.searches_cut += !r.complete;
        if (r.sets.empty())
            continue;
        ++st.coverable;
        for (const auto &set : r.sets)
            gain[set] += 1.0;
        sets_of.push_back(r.sets);
    }
    st.sets = std::uint32_t(gain.size());

    // 5. Scores, with the superset rule: a set also occludes what its subsets do.
    struct Scored {
        double score;
        const std::vector<std::uint32_t> *set;
    };
    std::vector<Scored> scored;
    for (const auto &[set, g] : gain) {
        double total = g, cost = 0.0;
        for (const auto &[other, og] : gain)
            if (other.size() < set.size() && std::includes(set.begin(), set.end(), other.begin(), other.end()))
                total += og;
        for (std::uint32_t c : set)
            cost += search.cost[c];
        scored.push_back({total / cost, &set});
    }
    std::stable_sort(scored.begin(), scored.end(), [](const Scored &a, const Scored &b) { return a.score > b.score; });
    if (options.marginal_scores) {
        std::vector<std::vector<std::uint32_t>> sets;
        for (const Scored &x : scored)
            sets.push_back(*x.set);
        std::vector<Scored> reordered;
        for (std::size_t i : order_by_marginal_score(sets, sets_of, search.cost))
            reordered.push_back(scored[i]);
        scored.swap(reordered);
    }

    // 6. Selection with redundancy removal by ID rendering.
    std::vector<std::uint32_t> selected;
    std::vector<bool> in_selection(nodes.size(), false);
    const std::size_t batch = 16;
    std::size_t next = 0;
    while (next < scored.size() && selected.size() < options.max_occluders) {
        const std::size_t before = selected.size();
        for (; next < scored.size() && selected.size() < before + batch; ++next)
            for (std::uint32_t c : *scored[next].set)
                if (!in_selection[c]) {
                    in_selection[c] = true;
                    selected.push_back(c);
                }
        const auto shown = pixels_per_leaf(render_leaf_ids(renderer, camera, selected, res, res), nodes.size());
        std::vector<std::uint32_t> kept;
        for (std::uint32_t c : selected)
            if (shown[c])
                kept.push_back(c);
            // hidden or redundant: stays marked, so later sets do not bring it back
        selected = std::move(kept);
    }
    if (selected.size() > options.max_occluders)
        selected.resize(options.max_occluders);
    return selected;
}

}  // namespace occu
