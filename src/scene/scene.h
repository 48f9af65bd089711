// Scenes: triangle meshes with bounding boxes.
#pragma once

#include <cstdint>
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
    glm::vec3 color{0.8f};
    Aabb bounds;

    std::size_t triangle_count() const { return indices.size() / 3; }
    // Recomputes `bounds` from the positions.
    void update_bounds();
};

struct Scene {
    std::vector<Mesh> meshes;
    Aabb bounds;

    std::size_t triangle_count() const;
    void update_bounds();
};

// Appends an axis-aligned box (12 triangles, outward normals) to `mesh`.
void append_box(Mesh &mesh, const Aabb &box);

}  // namespace occu
