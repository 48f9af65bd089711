// SPDX-License-Identifier: MIT
// View cells over a city's free space: Wonka, Wimmer and Schmalstieg,
// "Visibility Preprocessing with Occluder Fusion for Urban Walkthroughs"
// (2000), section 3, "Subdivision into View Cells".
//
// "We chose to use a constrained Delaunay triangulation of free space,
// modified to guarantee that the maximum length of view cell edges does
// not exceed a user specified threshold. The actual view cells are found
// by erecting a prism above each triangle of the triangulation. [...]
// because of the 2.5D property of occluders, any object found visible from
// one particular point is also visible from all locations above this
// point. This implies that sample points need only be placed on the 3
// edges bounding the top triangle of the view cell."
//
// Free space is the ground rectangle less the footprints (scene.h) grown by
// the clearance and merged, whose outlines are the triangulation's
// constraints; CGAL's Delaunay mesher bounds the
// edges. A cell is the prism from `bottom` to `top` over its triangle; an
// eye belongs to a cell when it lies over the triangle (boundary included,
// the first cell in index order on a shared edge) at a height in
// [bottom, top]. The triangles are plain data, so the run time needs no
// CGAL: locate() walks a uniform grid of them.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace occu {

struct ViewCellOptions {
    double max_edge = 24.0;   // metres: no cell edge longer (the paper's threshold)
    // Metres kept free between the cells and every footprint. A frame is
    // drawn with a near plane: an eye nearer a wall than the plane's reach
    // (the distance to its farthest corner) has the wall clipped away and
    // sees through the building, which no occluder shadow allows for. Eyes
    // in that band belong to no cell (renderers fall back to their own
    // culling), and narrow gaps between buildings close.
    double clearance = 1.0;
    // Free space narrower than this between the footprints grown by the
    // clearance (the slits between neighbouring buildings) holds no cells:
    // a conforming triangulation would fill it with slivers.
    double close_gaps = 4.0;
    double bottom = 0.0;      // the prisms' height range: street level
    double top = 2.0;         // to the highest eye the cells serve
};

class ViewCells {
public:
    // Triangulates the free space of `ground` (x in [min.x, max.x], z in
    // [min.y, max.y]) outside the footprints. Throws std::invalid_argument
    // for a non-finite or empty ground, a max_edge not finite and positive
    // (or so small that the ground would need more than 2^22 cells), or
    // bottom >= top, or a clearance that is negative or not finite.
    ViewCells(const glm::dvec2 &ground_min, const glm::dvec2 &ground_max, const std::vector<PrismOccluder> &footprints,
              const ViewCellOptions &options);
    // Cells given as data (a database's): checked for finite, non-degenerate triangles.
    ViewCells(std::vector<std::array<glm::dvec2, 3>> triangles, const ViewCellOptions &options);

    std::size_t size() const { return triangles_.size(); }
    // Counter-clockwise in (x, z).
    const std::array<glm::dvec2, 3> &triangle(std::size_t cell) const { return triangles_[cell]; }
    const ViewCellOptions &options() const { return options_; }

    // The cell holding `eye`, or none (inside a footprint, outside the
    // ground, below bottom or above top).
    std::optional<std::uint32_t> locate(const glm::vec3 &eye) const;

    // Sample points on the cell's top edges (height `top`): the three
    // corners and points between them so that no point of an edge is
    // farther than epsilon from one (spacing at most 2 epsilon). Throws
    // std::invalid_argument unless epsilon is finite and positive.
    std::vector<glm::dvec3> sample_points(std::size_t cell, double epsilon) const;

    // The cell's box: its triangle's bounds from bottom to top.
    struct Bounds {
        glm::dvec2 min, max;
    };
    Bounds bounds(std::size_t cell) const;

private:
    void build_grid();

    std::vector<std::array<glm::dvec2, 3>> triangles_;
    ViewCellOptions options_;
    // locate(): cells by the grid squares their bounds touch.
    glm::dvec2 grid_min_{0.0}, grid_cell_{1.0};
    glm::ivec2 grid_size_{0};
    std::vector<std::vector<std::uint32_t>> grid_;
};

}  // namespace occu
