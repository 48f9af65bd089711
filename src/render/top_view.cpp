// SPDX-License-Identifier: MIT
#include "render/top_view.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gl/gl_headers.h"

namespace occu {

Rgba8 TopViewColour::rgba8() const
{
    auto byte = [](float v) { return std::uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
    return {byte(r), byte(g), byte(b), 255};
}

namespace {

// The top view's layout: a title of two lines, the map, a legend of three.
struct Layout {
    int scale, pad, line;
    int title_height, legend_top;   // rows from the top
    PixelRect map;                  // GL window coordinates
    int map_top;                    // rows from the top
};

Layout layout_of(int width, int height)
{
    Layout l;
    l.scale = std::clamp(std::min(width, height) / 256, 1, 4);
    l.pad = 3 * l.scale;
    l.line = line_height * l.scale;
    l.title_height = l.pad + 2 * l.line;
    const int legend_height = 3 * l.line + l.pad;
    l.legend_top = height - legend_height;
    const int room = std::max(0, height - l.title_height - legend_height);
    const int side = std::max(0, std::min(width - 2 * l.pad, room));
    const int x0 = (width - side) / 2;
    l.map_top = l.title_height + (room - side) / 2;
    const int y0 = height - l.map_top - side;
    l.map = {x0, y0, x0 + side, y0 + side};
    return l;
}

void colour(const TopViewColour &c, float k = 1.0f)
{
    glColor3f(c.r * k, c.g * k, c.b * k);
}

void footprint(const Aabb &a, GLenum mode)
{
    glBegin(mode);
    glVertex2f(a.min.x, a.min.z);
    glVertex2f(a.max.x, a.min.z);
    glVertex2f(a.max.x, a.max.z);
    glVertex2f(a.min.x, a.max.z);
    glEnd();
}

}  // namespace

PixelRect top_view_map_area(int width, int height)
{
    return layout_of(width, height).map;
}

void render_top_view(const Hierarchy &hierarchy, const Camera &camera, const std::vector<std::uint32_t> &drawn_in,
                     const std::vector<std::uint32_t> &wrongly_culled_in, const PixelRect &area)
{
    std::vector<std::uint32_t> drawn = drawn_in, wrongly_culled = wrongly_culled_in;
    std::sort(drawn.begin(), drawn.end());
    std::sort(wrongly_culled.begin(), wrongly_culled.end());
    const Aabb &b = hierarchy.root().bounds;
    const float margin = std::max(1.0f, 0.05f * std::max(b.extent().x, b.extent().z));

    glPushAttrib(GL_ENABLE_BIT | GL_COLOR_BUFFER_BIT | GL_VIEWPORT_BIT | GL_CURRENT_BIT | GL_LINE_BIT | GL_POINT_BIT |
                 GL_SCISSOR_BIT);
    glMatrixMode(GL_PROJECTION);
    glPushMatrix();
    glMatrixMode(GL_MODELVIEW);
    glPushMatrix();
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    glClearColor(1, 1, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (!area.empty())
        glViewport(area.x0, area.y0, area.width(), area.height());
    GLint viewport[4];
    glGetIntegerv(GL_VIEWPORT, viewport);

    // x to the right, z downwards, as a map of the xz plane; the ground
    // rectangle and its margin, widened along one axis to the viewport's
    // proportions.
    // The camera too, where it stands outside the scene.
    const glm::vec3 &eye = camera.position;
    float x0 = std::min(b.min.x, eye.x) - margin, x1 = std::max(b.max.x, eye.x) + margin;
    float z0 = std::min(b.min.z, eye.z) - margin, z1 = std::max(b.max.z, eye.z) + margin;
    const float aspect = float(std::max(1, viewport[2])) / float(std::max(1, viewport[3]));
    if ((x1 - x0) / (z1 - z0) < aspect) {
        const float grow = 0.5f * ((z1 - z0) * aspect - (x1 - x0));
        x0 -= grow;
        x1 += grow;
    } else {
        const float grow = 0.5f * ((x1 - x0) / aspect - (z1 - z0));
        z0 -= grow;
        z1 += grow;
    }
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(x0, x1, z1, z0, -1, 1);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();

    // Each leaf's category, then the categories in order, so that what was
    // drawn (or wrongly culled) at any height lies on top.
    enum Category { outside, culled, drawn_leaf, wrong, categories };
    const TopViewColour fills[categories] = {top_view_colours::outside, top_view_colours::culled,
                                             top_view_colours::drawn, top_view_colours::wrongly_culled};
    const Frustum frustum(camera.view_projection());
    const auto &nodes = hierarchy.nodes();
    std::vector<std::uint32_t> of[categories];
    for (std::uint32_t n = 0; n < nodes.size(); ++n) {
        if (!nodes[n].leaf() || nodes[n].bounds.extent().x > 0.5f * b.extent().x)
            continue;   // the ground would cover everything
        if (std::binary_search(wrongly_culled.begin(), wrongly_culled.end(), n))
            of[wrong].push_back(n);
        else if (std::binary_search(drawn.begin(), drawn.end(), n))
            of[drawn_leaf].push_back(n);
        else if (frustum.classify(nodes[n].bounds) == Frustum::Side::outside)
            of[outside].push_back(n);
        else
            of[culled].push_back(n);
    }
    glLineWidth(1.0f);
    for (int c = 0; c < categories; ++c) {
        colour(fills[c]);
        for (std::uint32_t n : of[c])
            footprint(nodes[n].bounds, GL_QUADS);
        colour(fills[c], 0.7f);   // edges a shade darker, so that neighbours part
        for (std::uint32_t n : of[c])
            footprint(nodes[n].bounds, GL_LINE_LOOP);
    }

    // The camera: a dot, its view direction across the ground and, unless
    // it looks nearly straight down, the sides of its horizontal field of view.
    const glm::vec3 p = camera.position, d = camera.target - camera.position;
    const float len = 0.12f * std::max(b.extent().x, b.extent().z), flat = std::hypot(d.x, d.z);
    colour(top_view_colours::camera);
    if (flat > 0.2f * glm::length(d)) {
        const float heading = std::atan2(d.z, d.x);
        const float half = std::atan(std::tan(glm::radians(camera.fovy_degrees) * 0.5f) * camera.aspect);
        glLineWidth(1.0f);
        glBegin(GL_LINES);
        for (float s : {-1.0f, 1.0f}) {
            glVertex2f(p.x, p.z);
            glVertex2f(p.x + std::cos(heading + s * half) * len, p.z + std::sin(heading + s * half) * len);
        }
        glEnd();
        glLineWidth(2.5f);
        glBegin(GL_LINES);
        glVertex2f(p.x, p.z);
        glVertex2f(p.x + std::cos(heading) * len, p.z + std::sin(heading) * len);
        glEnd();
    }
    glPointSize(7.0f);
    glBegin(GL_POINTS);
    glVertex2f(p.x, p.z);
    glEnd();

    glMatrixMode(GL_PROJECTION);
    glPopMatrix();
    glMatrixMode(GL_MODELVIEW);
    glPopMatrix();
    glPopAttrib();
}

void caption_top_view(ImageRef image, const TopViewCaption &caption)
{
    const Layout l = layout_of(image.width, image.height);
    const Rgba8 ink{25, 25, 30, 255}, faint{90, 90, 100, 255};
    const int s = l.scale;
    char text[160];

    // The title: the strategy and the frame; the frame's time and what it culled.
    int x = draw_text(image, l.pad, l.pad, caption.strategy, ink, s);
    std::snprintf(text, sizeof(text), "   frame %zu", caption.frame);
    draw_text(image, x, l.pad, text, faint, s);
    std::snprintf(text, sizeof(text), "%.2f ms   culled %.1f%% of triangles", caption.ms, caption.culled_percent);
    draw_text(image, l.pad, l.pad + l.line, text, ink, s);

    // The legend: two columns of three rows, a swatch before each entry.
    const int swatch = cap_height * s, column = image.width / 2;
    auto entry = [&](int col, int row, const TopViewColour *c, const std::string &label) {
        const int ex = l.pad + col * column, ey = l.legend_top + row * l.line;
        if (c) {
            fill_rect(image, ex, ey, swatch, swatch, c->rgba8());
            fill_rect(image, ex + swatch, ey, s, swatch, ink);   // a hairline, so that pale swatches show
        }
        draw_text(image, ex + swatch + 3 * s, ey, label, ink, s);
    };
    entry(0, 0, &top_view_colours::drawn, "drawn");
    entry(0, 1, &top_view_colours::culled, "culled (occluded)");
    entry(1, 0, &top_view_colours::outside, "outside the frustum");
    if (caption.wrongly_culled) {
        std::snprintf(text, sizeof(text), "wrongly culled: %zu", *caption.wrongly_culled);
        entry(1, 1, &top_view_colours::wrongly_culled, text);
    }
    // The camera's sign: a dot and a stroke.
    const int cy = l.legend_top + 2 * l.line;
    fill_rect(image, l.pad + swatch / 2 - 2 * s, cy + swatch / 2 - 2 * s, 4 * s, 4 * s, top_view_colours::camera.rgba8());
    fill_rect(image, l.pad + swatch / 2, cy + swatch / 2 - s / 2, swatch / 2 + s, std::max(1, s), top_view_colours::camera.rgba8());
    entry(0, 2, nullptr, "camera, view");
    if (caption.efficiency_percent) {
        std::snprintf(text, sizeof(text), "efficiency %.1f%%", *caption.efficiency_percent);
        entry(1, 2, nullptr, text);
    }
}

}  // namespace occu
