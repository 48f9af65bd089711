// The occluder database (Poon and Wang, section 3): for grid points over
// the scene, each with representative view directions, the occluders
// (hierarchy leaves) chosen there by the minimum-occluder-set
// preprocessing, best first, so that a run-time limit of N occluders takes
// the first N. At run time the culler takes the list of the grid point
// nearest the eye and the direction nearest the view direction.
//
// Grid: nx * ny * nz points at origin + (i, j, k) * spacing; view
// directions: `directions` horizontal headings, heading d at angle
// 2 pi d / directions from +x towards +z. View v = point * directions + d.
//
// File format (text, one record per line, '#' comments):
//   occu-occluder-database 1
//   grid OX OY OZ SX SY SZ NX NY NZ DIRECTIONS
//   scene LEAVES TRIANGLES           the hierarchy it was made for
//   view V ID ID ...                 one line per view that was processed
// A shard holds some views; merge() joins shards of one grid and scene.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "camera/camera.h"

namespace occu {

struct OccluderGrid {
    glm::vec3 origin{0.0f};
    glm::vec3 spacing{1.0f};
    glm::ivec3 points{1};
    int directions = 4;

    std::uint32_t view_count() const { return std::uint32_t(points.x * points.y * points.z * directions); }
    // The camera of view v (same lens as `lens`: fov, aspect, planes).
    Camera view_camera(std::uint32_t view, const Camera &lens) const;
    // The view nearest `camera`: nearest point, nearest heading.
    std::uint32_t nearest_view(const Camera &camera) const;
    bool operator==(const OccluderGrid &o) const;
};

class OccluderDatabase {
public:
    OccluderGrid grid;
    std::uint32_t scene_leaves = 0, scene_triangles = 0;
    std::map<std::uint32_t, std::vector<std::uint32_t>> views;   // view -> occluders, best first

    // The occluders for `camera`: the nearest view's list (or, if that view
    // was never processed, the nearest processed point's view of that
    // heading), interleaved with the list of the next heading on the
    // camera's side at the same point, if processed: a frustum turned
    // between two headings sees what both were chosen for. The share of
    // the second list grows with the turn, from none on the nearest
    // heading to half midway between the two. Best first.
    std::vector<std::uint32_t> occluders_for(const Camera &camera) const;

    void save(const std::string &path) const;
    // Throws std::runtime_error naming the file and line of what is wrong.
    static OccluderDatabase load(const std::string &path);
    // Joins shards; throws if their grids or scenes differ or a view repeats.
    static OccluderDatabase merge(const std::vector<OccluderDatabase> &shards);
};

}  // namespace occu
