// SPDX-License-Identifier: MIT
// Scenes: triangle meshes with bounding boxes.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "geometry/aabb.h"

namespace occu {

struct Mesh {
    std::string name;
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;       // one per position
    std::vector<std::uint32_t> indices;   // three per triangle, counter-clockwise seen from outside
    glm::vec3 color{0.8f};              // RGB in [0, 1], before lighting
    std::vector<glm::vec3> colors;       // one per position, or empty: `color` for every vertex
    // False for a surface that gives its own light (a level's sky): drawn
    // in its colours as they are, without the renderer's light (render/shading.h).
    bool shaded = true;
    Aabb bounds;
    // False for a see-through mesh (glass, grates, water, foliage: a
    // Quake III level's translucent shaders, scene/quake3_bsp.h): drawn,
    // but hiding nothing behind it, so no strategy or preprocessing step
    // may take it as an occluder.
    bool occluder = true;

    // The look the scene calls for (render/scene_renderer.h, Look::scene),
    // read only where a reader was asked for it; empty otherwise. Per
    // position, or empty: the texture's coordinates, the coordinates in the
    // scene's lightmap atlas (Scene::lightmap_atlas; `lightmapped` meshes
    // only) and the light baked into the vertices (RGBA8: Quake III's vertex
    // colours, the light of faces without a lightmap).
    std::vector<glm::vec2> texcoords, lightmap_coords;
    std::vector<std::uint32_t> vertex_light;   // RGBA8, R in the low byte
    std::int32_t image = -1;                   // Scene::images: the mesh's texture; -1: none
    bool lightmapped = false;

    std::size_t triangle_count() const { return indices.size() / 3; }
    // Recomputes `bounds` from the positions.
    void update_bounds();
};

// A 2.5D occluder (Wonka, Wimmer and Schmalstieg 2000, section 4.1): a
// solid prism between heights `bottom` and `top` over a simple polygon in
// the ground plane (world x and z), wholly inside the scene's geometry, so
// that whatever it hides the scene hides: inside occluder meshes, never
// see-through ones (Mesh::occluder), which hide nothing. The view cells'
// visibility (strategies/wonka_view_cells/) takes these prisms, declared by
// the scene's generator, as its only occluders, never the meshes. Points are (x, z); the outline
// runs counter-clockwise in those coordinates (positive signed area), holes
// clockwise.
struct PrismOccluder {
    std::vector<glm::dvec2> outline;                // (x, z)
    std::vector<std::vector<glm::dvec2>> holes;     // courtyards
    double bottom = 0.0, top = 0.0;
};

struct Level;

// A decoded picture: RGBA8 rows, the top row first.
struct Image {
    std::string name;
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;
};

struct Scene {
    std::vector<Mesh> meshes;
    Aabb bounds;
    // The 2.5D occluders a generator knows (the city's buildings); empty
    // for a loaded scene, whose solids nothing tells apart.
    std::vector<PrismOccluder> prism_occluders;
    // A level's BSP tree, leaves, clusters, visibility, brushes and spawn
    // points (scene/level.h: a Quake III level's, scene/quake3_bsp.h), where
    // the scene is one; null otherwise.
    std::shared_ptr<const Level> level;
    // The look's pictures (Mesh::image) and the lightmap atlas among them
    // (-1: none), where the reader was asked for the look.
    std::vector<Image> images;
    std::int32_t lightmap_atlas = -1;

    std::size_t triangle_count() const;
    void update_bounds();
};

// Throws std::runtime_error when a vertex coordinate of `scene` is not
// finite (NaN or infinite): boxes, projections and the hierarchy's splits
// of such a scene mean nothing. The message begins with `source` (what the
// scene came from, e.g. its file) and names the first such vertex, its mesh
// (by name, or by `mesh_number` when it has none) and how many of the
// mesh's vertices are not finite.
void require_finite_vertices(const Mesh &mesh, std::size_t mesh_number, const std::string &source);
void require_finite_vertices(const Scene &scene, const std::string &source);

// Whether a triangle's corners are collinear to float precision: the third
// lies within a float step at their largest coordinate (the rounding the
// stored corners carry) of the line through the other two. Such a triangle
// has no surface to draw or to hide anything, yet a driver may rasterize
// its edge through a pixel centre with depth and colour interpolated over
// an area that is rounding noise (Debian's unpatched llvmpipe drew one of a
// level's floor at depth 0, in black, in front of everything;
// tests/spec/gl-1.0/degenerate-triangle-depth-within-corners.c): the scene
// readers leave them out.
bool collinear_corners(const glm::vec3 &a, const glm::vec3 &b, const glm::vec3 &c);
// Removes the triangles of `mesh` whose corners are collinear (above), the
// others kept in order; returns how many it removed.
std::size_t remove_collinear_triangles(Mesh &mesh);

// Appends an axis-aligned box (12 triangles, outward normals) to `mesh`.
void append_box(Mesh &mesh, const Aabb &box);

}  // namespace occu
