// SPDX-License-Identifier: MIT
#include "strategies/wonka_view_cells/cull_map.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include "gl/state.h"

namespace occu {

namespace {

constexpr double depth_steps = 16777215.0;   // 2^24 - 1: the map's depth buffer is 24-bit

// A counter-clockwise polygon turning left (or straight) at every corner.
bool is_convex(const std::vector<glm::dvec2> &poly)
{
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const glm::dvec2 a = poly[i], b = poly[(i + 1) % poly.size()], c = poly[(i + 2) % poly.size()];
        if ((b.x - a.x) * (c.y - b.y) - (b.y - a.y) * (c.x - b.x) < 0.0)
            return false;
    }
    return true;
}

}  // namespace

PixelRect CullMapRegion::pixels_of(const glm::dvec2 &lo, const glm::dvec2 &hi) const
{
    const glm::dvec2 a = (lo - min) / pixel, b = (hi - min) / pixel;
    PixelRect r{int(std::max(-1.0, std::floor(a.x))), int(std::max(-1.0, std::floor(a.y))),
                int(std::min(double(width) + 1.0, std::floor(b.x) + 1.0)),
                int(std::min(double(height) + 1.0, std::floor(b.y) + 1.0))};
    r = r.clamped({0, 0, width, height});
    return r;
}

CullMap::CullMap(double bottom, double top) : bottom_(bottom), top_(top), target_(1, 1)
{
    if (!(bottom < top) || !std::isfinite(bottom) || !std::isfinite(top))
        throw std::invalid_argument("a cull map's heights need bottom < top, both finite");
}

std::uint32_t CullMap::depth_of(double height) const
{
    const double d = std::clamp((top_ - height) / (top_ - bottom_), 0.0, 1.0);
    return std::uint32_t(std::lround(d * depth_steps));
}

double CullMap::height_of(std::uint32_t depth) const
{
    return top_ - double(depth) / depth_steps * (top_ - bottom_);
}

void CullMap::begin(const CullMapRegion &region)
{
    if (region.width < 1 || region.height < 1 || region.width > 16384 || region.height > 16384 ||
        !(region.pixel > 0.0) || !std::isfinite(region.pixel) || !std::isfinite(region.min.x) ||
        !std::isfinite(region.min.y))
        throw std::invalid_argument("a cull map of " + std::to_string(region.width) + "x" +
                                    std::to_string(region.height) + " pixels of " + std::to_string(region.pixel) +
                                    " m: want 1 to 16384 pixels a side of a finite, positive size");
    region_ = region;
    samples_ = 0;
    target_.resize(region.width, region.height);
    const gl::Framebuffer::Bind bind(target_);
    const gl::AttribScope state(GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    glDepthMask(GL_TRUE);
    glStencilMask(0xFF);
    glClearDepth(1.0);   // the bottom: nothing hidden
    glClearStencil(0);
    glClear(GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
}

std::vector<double> CullMap::shadow_quads(const glm::dvec3 &p, const std::vector<const PrismOccluder *> &occluders) const
{
    // Vertices (x, z, -(top - height)): glOrtho's depth range [0, top - bottom]
    // puts height h at window depth (top - h) / (top - bottom).
    std::vector<double> v;
    const glm::dvec2 eye(p.x, p.z);
    const double reach = glm::length(glm::dvec2(region_.width, region_.height)) * region_.pixel;
    auto vertex = [&](const glm::dvec2 &q, double h) { v.insert(v.end(), {q.x, q.y, -(top_ - h)}); };
    auto quad = [&](const glm::dvec2 &a, const glm::dvec2 &b, double t0, double t1, double h0, double h1) {
        // Points of the rays from the eye through a and b at parameters t0 and t1.
        vertex(eye + t0 * (a - eye), h0);
        vertex(eye + t0 * (b - eye), h0);
        vertex(eye + t1 * (b - eye), h1);
        vertex(eye + t1 * (a - eye), h1);
    };
    for (const PrismOccluder *o : occluders) {
        const double h = o->top;
        // A convex footprint: seen from below its top (h > p.y) the edges
        // facing the eye cast the higher shadow over the whole silhouette's
        // angle (a sight line over a front edge at distance d1 climbs
        // faster than over a back edge at d2 > d1), seen from above its top
        // the back edges do; so half the edges suffice. A concave one or
        // one with courtyards draws every edge (each is valid on its own).
        const bool convex = o->holes.empty() && is_convex(o->outline);
        // A ray through an edge point at distance d from the eye reaches
        // (t - 1) d beyond the edge at parameter t: the nearest edge point
        // (not the nearest corner) decides how far t must go.
        double nearest = std::numeric_limits<double>::infinity();
        auto nearest_in = [&](const std::vector<glm::dvec2> &poly) {
            for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
                const glm::dvec2 ab = poly[i] - poly[j];
                const double len2 = glm::dot(ab, ab);
                const double t = len2 > 0.0 ? std::clamp(glm::dot(eye - poly[j], ab) / len2, 0.0, 1.0) : 0.0;
                nearest = std::min(nearest, glm::length(eye - (poly[j] + t * ab)));
            }
        };
        nearest_in(o->outline);
        for (const auto &hole : o->holes)
            nearest_in(hole);
        const double occluder_t_far = 1.0 + reach / std::max(nearest, 1e-9);
        auto ring = [&](const std::vector<glm::dvec2> &poly) {
            for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
                const glm::dvec2 a = poly[j], b = poly[i];
                const glm::dvec2 ea = a - eye, eb = b - eye;
                if (convex && h != p.y) {
                    // Counter-clockwise outline: the eye is in front of edge a->b when it lies to its right.
                    const bool facing = (b.x - a.x) * (eye.y - a.y) - (b.y - a.y) * (eye.x - a.x) < 0.0;
                    if (facing != (h > p.y))
                        continue;
                }
                if (std::abs(ea.x * eb.y - ea.y * eb.x) <= 1e-12 * glm::dot(ea, ea) + 1e-18)
                    continue;   // the eye on the edge's line: no wedge
                // Along a ray from the eye, the shadow's height at parameter
                // t (t = 1 on the edge) is p.y + t (h - p.y). The wedge ends
                // beyond the map (t_far), or where its plane leaves
                // [bottom, top]: above top everything is hidden (a flat
                // part at top), below bottom nothing is.
                // One t_far for the whole occluder: neighbouring edges' wedges
                // then share their side rays' vertices exactly, and the
                // rasterizer's fill rule leaves no crack along them.
                const double t_far = occluder_t_far;
                double t_end = t_far;
                bool capped = false;
                if (h > p.y) {
                    const double t_top = (top_ - p.y) / (h - p.y);
                    if (t_top < t_far) {
                        t_end = std::max(1.0, t_top);
                        capped = true;
                    }
                } else if (h < p.y) {
                    t_end = std::clamp((bottom_ - p.y) / (h - p.y), 1.0, t_far);
                }
                quad(a, b, 1.0, t_end, h, p.y + t_end * (h - p.y));
                if (capped)
                    quad(a, b, t_end, t_far, top_, top_);
            }
        };
        ring(o->outline);
        for (const auto &hole : o->holes)
            ring(hole);
    }
    return v;
}

void CullMap::add_sample_point(const glm::dvec3 &p, const std::vector<const PrismOccluder *> &occluders)
{
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        throw std::invalid_argument("a sample point that is not finite");
    const gl::Framebuffer::Bind bind(target_);
    const gl::AttribScope state(GL_ENABLE_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT | GL_COLOR_BUFFER_BIT |
                                GL_POLYGON_BIT | GL_TRANSFORM_BIT);
    const gl::MatrixScope matrices;
    glPushClientAttrib(GL_CLIENT_VERTEX_ARRAY_BIT);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    const glm::dvec2 hi = region_.max();
    glOrtho(region_.min.x, hi.x, region_.min.y, hi.y, 0.0, top_ - bottom_);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glEnable(GL_DEPTH_CLAMP);
    glEnable(GL_DEPTH_TEST);
    glEnableClientState(GL_VERTEX_ARRAY);
    const std::vector<double> quads = shadow_quads(p, occluders);
    auto draw_shadows = [&quads] {
        if (quads.empty())
            return;
        glVertexPointer(3, GL_DOUBLE, 0, quads.data());
        glDrawArrays(GL_QUADS, 0, GLsizei(quads.size() / 3));
    };
    if (samples_ == 0) {
        // The first sample point's umbra: the union of its shadows.
        glDisable(GL_STENCIL_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        draw_shadows();
    } else {
        // Section 5's two passes: the intersection of the umbra so far with
        // this point's. First mark where a new shadow is higher than the
        // umbra so far (there the old value is the smaller, and stays).
        glEnable(GL_STENCIL_TEST);
        glStencilMask(0xFF);
        glClearStencil(0);
        glClear(GL_STENCIL_BUFFER_BIT);
        glStencilFunc(GL_ALWAYS, 1, 0xFF);
        glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_FALSE);
        draw_shadows();
        // Elsewhere the new union is the smaller: reset those pixels to the
        // bottom and draw it there.
        glStencilFunc(GL_EQUAL, 0, 0xFF);
        glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
        glDepthFunc(GL_ALWAYS);
        glDepthMask(GL_TRUE);
        const glm::dvec2 lo = region_.min;
        const double floor_z = -(top_ - bottom_);
        const double reset[] = {lo.x, lo.y, floor_z, hi.x, lo.y, floor_z, hi.x, hi.y, floor_z, lo.x, hi.y, floor_z};
        glVertexPointer(3, GL_DOUBLE, 0, reset);
        glDrawArrays(GL_QUADS, 0, 4);
        glDepthFunc(GL_LESS);
        draw_shadows();
    }
    glPopClientAttrib();
    ++samples_;
}

std::vector<std::uint32_t> CullMap::read_depths() const
{
    const gl::Framebuffer::Bind bind(target_);
    std::vector<std::uint32_t> depths(std::size_t(region_.width) * std::size_t(region_.height));
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, region_.width, region_.height, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, depths.data());
    // GL returns the 24-bit values scaled to 32 bits.
    for (std::uint32_t &d : depths)
        d >>= 8;
    return depths;
}

std::uint32_t CullMap::Horizon::at(int x, int y) const
{
    if (y == 0)
        return bottom_[std::size_t(x)];
    if (y == height_ - 1)
        return top_[std::size_t(x)];
    if (x == 0)
        return left_[std::size_t(y)];
    return right_[std::size_t(y)];
}

CullMap::Horizon CullMap::read_horizon() const
{
    const gl::Framebuffer::Bind bind(target_);
    Horizon h;
    h.width_ = region_.width;
    h.height_ = region_.height;
    h.bottom_.resize(std::size_t(h.width_));
    h.top_.resize(std::size_t(h.width_));
    h.left_.resize(std::size_t(h.height_));
    h.right_.resize(std::size_t(h.height_));
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, h.width_, 1, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, h.bottom_.data());
    glReadPixels(0, h.height_ - 1, h.width_, 1, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, h.top_.data());
    glReadPixels(0, 0, 1, h.height_, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, h.left_.data());
    glReadPixels(h.width_ - 1, 0, 1, h.height_, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, h.right_.data());
    for (auto *ring : {&h.bottom_, &h.top_, &h.left_, &h.right_})
        for (std::uint32_t &d : *ring)
            d >>= 8;
    return h;
}

CullMap::Horizon CullMap::horizon_of(const CullMapRegion &region, const std::vector<std::uint32_t> &depths)
{
    Horizon h;
    h.width_ = region.width;
    h.height_ = region.height;
    const std::size_t w = std::size_t(region.width);
    for (int x = 0; x < region.width; ++x) {
        h.bottom_.push_back(depths[std::size_t(x)]);
        h.top_.push_back(depths[std::size_t(region.height - 1) * w + std::size_t(x)]);
    }
    for (int y = 0; y < region.height; ++y) {
        h.left_.push_back(depths[std::size_t(y) * w]);
        h.right_.push_back(depths[std::size_t(y) * w + w - 1]);
    }
    return h;
}

PixelRect CullMap::box_pixels(const Aabb &box) const
{
    return region_.pixels_of({box.min.x, box.min.z}, {box.max.x, box.max.z});
}

std::optional<bool> CullMap::visible_by_readback(const Aabb &box, const std::vector<std::uint32_t> &depths) const
{
    const PixelRect r = box_pixels(box);
    if (r.empty())
        return std::nullopt;
    const std::uint32_t top = depth_of(box.max.y);
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x)
            if (top < depths[std::size_t(y) * std::size_t(region_.width) + std::size_t(x)])
                return true;
    return false;
}

std::vector<std::optional<bool>> CullMap::visible_by_unit(const gl::OcclusionUnit &unit, const std::vector<Aabb> &boxes,
                                                          std::size_t *passes) const
{
    std::vector<std::optional<bool>> visible(boxes.size());
    std::vector<std::size_t> pending;
    std::vector<PixelRect> rects(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        rects[i] = box_pixels(boxes[i]);
        if (!rects[i].empty())
            pending.push_back(i);
    }
    const gl::Framebuffer::Bind bind(target_);
    const gl::AttribScope state(GL_ENABLE_BIT | GL_DEPTH_BUFFER_BIT | GL_COLOR_BUFFER_BIT | GL_POLYGON_BIT |
                                GL_TRANSFORM_BIT);
    const gl::MatrixScope matrices;
    glPushClientAttrib(GL_CLIENT_VERTEX_ARRAY_BIT);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    // Window pixels as coordinates, so that a box's top covers exactly its
    // pixels (their centres lie strictly inside it), and depth as the map's.
    glOrtho(0.0, region_.width, 0.0, region_.height, 0.0, top_ - bottom_);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glDisable(GL_CULL_FACE);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_SCISSOR_TEST);
    glEnable(GL_DEPTH_CLAMP);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glEnableClientState(GL_VERTEX_ARRAY);

    // Passes of boxes whose pixels do not overlap, one tile each, filled
    // first fit in the boxes' order: a box goes to the first pass that no
    // box before it overlaps and that has a tile left. Each pixel keeps a
    // mask of the passes holding it, 32 passes at a time (4 bytes a pixel,
    // as the read-back's copy of the map), so that a box's pass costs one
    // look at its pixels, not one for every pass tried.
    const std::size_t width = std::size_t(region_.width);
    const std::size_t max_tiles = std::size_t(unit.max_tiles());
    std::vector<std::vector<std::size_t>> pass_boxes;
    std::vector<std::uint32_t> holding(width * std::size_t(region_.height));
    for (std::size_t first_pass = 0; !pending.empty(); first_pass += 32) {
        std::fill(holding.begin(), holding.end(), 0);
        std::uint32_t full = 0;
        std::vector<std::size_t> later;
        for (std::size_t i : pending) {
            const PixelRect &r = rects[i];
            std::uint32_t taken = full;
            for (int y = r.y0; y < r.y1 && taken != ~std::uint32_t(0); ++y)
                for (int x = r.x0; x < r.x1; ++x)
                    taken |= holding[std::size_t(y) * width + std::size_t(x)];
            if (taken == ~std::uint32_t(0)) {
                later.push_back(i);
                continue;
            }
            const int bit = __builtin_ctz(~taken);
            for (int y = r.y0; y < r.y1; ++y)
                for (int x = r.x0; x < r.x1; ++x)
                    holding[std::size_t(y) * width + std::size_t(x)] |= std::uint32_t(1) << bit;
            const std::size_t pass = first_pass + std::size_t(bit);
            if (pass == pass_boxes.size())
                pass_boxes.emplace_back();
            pass_boxes[pass].push_back(i);
            if (pass_boxes[pass].size() == max_tiles)
                full |= std::uint32_t(1) << bit;
        }
        pending.swap(later);
    }

    // Nothing writes the map between the passes, so every pass is begun and
    // ended without waiting and all are read at the end: the rasterizer
    // answers them together (on llvmpipe, in the scene of the map's own
    // drawing) rather than one hand-over per pass.
    std::vector<std::unique_ptr<gl::AsyncOcclusionPass>> issued;
    for (const std::vector<std::size_t> &in_pass : pass_boxes) {
        std::vector<PixelRect> tiles;
        std::vector<double> v;
        for (std::size_t i : in_pass) {
            const PixelRect &r = rects[i];
            tiles.push_back(r);
            const double z = -(top_ - std::clamp(double(boxes[i].max.y), bottom_, top_));
            v.insert(v.end(), {double(r.x0), double(r.y0), z, double(r.x1), double(r.y0), z, double(r.x1),
                               double(r.y1), z, double(r.x0), double(r.y1), z});
        }
        glVertexPointer(3, GL_DOUBLE, 0, v.data());
        issued.push_back(std::make_unique<gl::AsyncOcclusionPass>(unit));
        issued.back()->begin(gl::OcclusionMode::conservative, tiles);   // only nohc > 0 is read
        glDrawArrays(GL_QUADS, 0, GLsizei(v.size() / 3));   // the vertices are copied here
        issued.back()->end();
    }
    glPopClientAttrib();
    for (std::size_t p = 0; p < issued.size(); ++p) {
        const std::vector<gl::OcclusionRecord> &records = issued[p]->records();
        for (std::size_t k = 0; k < pass_boxes[p].size(); ++k)
            visible[pass_boxes[p][k]] = records[k].nohc > 0;
    }
    if (passes)
        *passes = issued.size();
    return visible;
}

}  // namespace occu
