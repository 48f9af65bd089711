// SPDX-License-Identifier: MIT
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
// File format: occu's database format (culling/database_file.h), kind
// occluder-sets version 1, algorithm minimum-occluder-set; its settings
// are those of the preprocessing (PreprocessOptions::describe(), among
// them resolution=R, the run-time maps it serves, R x R), the grid
//   grid-origin=OX,OY,OZ grid-spacing=SX,SY,SZ grid-points=NX,NY,NZ headings=D
// and the lens of its views; its scene, scene_provenance(hierarchy). The payload:
//   view V ID ID ...                      one line per view that was processed
// A shard holds some views; merge() joins shards of one provenance.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "camera/camera.h"
#include "culling/database_file.h"
#include "spatial/hierarchy.h"

namespace occu {

struct OccluderGrid {
    glm::vec3 origin{0.0f};
    glm::vec3 spacing{1.0f};
    glm::ivec3 points{1};
    int directions = 4;

    // The grid of occu-preprocess build and of databases made on demand:
    // points.x x points.z points across the scene's ground, corner to
    // corner (one point across an axis: at its middle), at `eye_height`
    // above its floor, and points.y such layers up to that height above its
    // top, each with `directions` headings.
    static OccluderGrid over_scene(const Aabb &bounds, const glm::ivec3 &points, int directions, float eye_height);

    std::uint32_t view_count() const { return std::uint32_t(points.x * points.y * points.z * directions); }
    // The camera of view v (same lens as `lens`: fov, aspect, planes).
    Camera view_camera(std::uint32_t view, const Camera &lens) const;
    // The view nearest `camera`: nearest point, nearest heading.
    std::uint32_t nearest_view(const Camera &camera) const;
    bool operator==(const OccluderGrid &o) const;
};

// The grid as a database's settings record it
// ("grid-origin=... grid-spacing=... grid-points=... headings=D").
std::string grid_settings(const OccluderGrid &grid);

class OccluderDatabase {
public:
    DatabaseProvenance provenance;
    // Of its settings: the grid, and the run-time maps' resolution (R x R).
    OccluderGrid grid;
    int resolution = 0;
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
    // Throws std::runtime_error naming the file and line of what is wrong
    // (a grid number that is not a finite float among it), or another
    // algorithm's database.
    static OccluderDatabase load(const std::string &path);
    // Joins shards; throws if their provenance differs (naming the
    // difference) or a view repeats.
    static OccluderDatabase merge(const std::vector<OccluderDatabase> &shards);
};

}  // namespace occu
