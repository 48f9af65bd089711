// SPDX-License-Identifier: MIT
// A volume for the mixed polygon/volume scenes of Bartz, Meissner and
// Huettner (1998), section 5, "Support for Ray Casting": a scalar density
// on a regular grid, its subdivision entities (bricks), and front-to-back
// ray marching with emission and absorption that stops at the polygons'
// depth.
//
// Conventions: world space as everywhere in occu (metres, y up). The grid
// holds density samples at its points: point (i, j, k) sits at
// box.min + (i, j, k) * cell, so a grid of n points per axis spans n - 1
// cells. Between points density is trilinear, so a cell's density is zero
// everywhere exactly when its eight corner points are zero; a brick (a
// block of cells) is empty when every point of its cells is zero, and a
// ray gains nothing from an empty brick. Densities are >= 0 and finite.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "camera/camera.h"
#include "geometry/aabb.h"

namespace occu {

class DensityVolume {
public:
    // `points` grid points per axis (>= 2 each), spanning `box` (finite, not
    // empty); densities all zero. Throws std::invalid_argument naming the
    // bad argument.
    DensityVolume(const Aabb &box, glm::ivec3 points);

    const Aabb &box() const { return box_; }
    glm::ivec3 points() const { return points_; }
    glm::ivec3 cells() const { return points_ - 1; }
    glm::dvec3 cell_size() const { return cell_; }

    float at(int i, int j, int k) const { return values_[index(i, j, k)]; }
    // Throws std::invalid_argument for a negative or non-finite density.
    void set(int i, int j, int k, float density);

    // Trilinear density at p; 0 outside the box.
    double sample(const glm::dvec3 &p) const;

    // The world box of cells [first, first + count) (count clipped to the grid).
    Aabb cell_box(glm::ivec3 first, glm::ivec3 count) const;

private:
    std::size_t index(int i, int j, int k) const
    {
        return (std::size_t(k) * std::size_t(points_.y) + std::size_t(j)) * std::size_t(points_.x) + std::size_t(i);
    }

    Aabb box_;
    glm::ivec3 points_;
    glm::dvec3 min_, cell_;
    std::vector<float> values_;
};

// Smoke rising from a point and drifting with the wind: a cone of density
// around a bent axis, broken up by value noise, fading at its top. Zero far
// from the plume, so most bricks of its box are empty.
struct SmokePlume {
    glm::vec3 source{0.0f};        // where it starts (the bottom of the axis)
    float height = 100.0f;         // metres of rise
    float base_radius = 5.0f;      // at the source
    float top_radius = 25.0f;      // at the top
    glm::vec3 wind{0.5f, 0.0f, 0.0f};  // drift of the axis per metre of rise, at the top
    float noise_cell = 6.0f;       // metres between noise lattice points
    std::uint32_t seed = 1998;
};
DensityVolume make_smoke(const SmokePlume &plume, const Aabb &box, glm::ivec3 points);

// occu's default mixed scene: a plume from the courtyard of the city block
// (bx, bz) (scene/city.h's layout: blocks of block_size metres from the
// origin, the courtyard at the block's centre), drifting east over the
// rooftops, in a box of 128 x 128 x 64 m on a grid of `cell` metres
// (128 / cell rounded).
DensityVolume smoke_above_block(int bx, int bz, float block_size = 80.0f, float cell = 1.0f);

// The subdivision entities of section 5: bricks of brick_cells^3 cells (the
// last ones along an axis may be smaller), in x-fastest order; `empty`
// where the brick's density is zero everywhere.
struct Brick {
    glm::ivec3 first_cell;
    glm::ivec3 cell_count;
    Aabb box;
    bool empty;
};
// Throws std::invalid_argument unless brick_cells >= 1.
std::vector<Brick> make_bricks(const DensityVolume &volume, int brick_cells);

// Front-to-back ray marching with emission and absorption (the classic
// volume rendering integral, discretised): a sample of density rho over a
// step dt has opacity a = 1 - exp(-absorption * rho * dt) and adds
// T * a * colour, then the transmittance T becomes T * (1 - a); the
// polygon behind contributes T * its colour.
struct RayMarchSettings {
    double step = 0.5;             // metres between samples along a ray
    double absorption = 0.25;      // per metre at density 1
    glm::dvec3 low_colour{0.10, 0.09, 0.09};    // smoke colour at the volume's bottom
    glm::dvec3 high_colour{0.62, 0.60, 0.57};   // and at its top
    double opaque = 1.0 / 1024.0;  // stop where T falls below this (early ray termination)
};

// Casts one ray through the centre of a pixel of a width x height view of
// `camera`: from the near plane, samples at k * step (k = 0, 1, ...) along
// the ray inside the volume's box and in front of `window_depth` (the
// polygons' depth at the pixel, window z in [0, 1]: 1 where nothing was
// drawn, so the ray ends at the far plane). Everything is double precision
// from the camera's float matrices (the ones the GL used), so that the same
// pixel always gets the same ray, whoever asks.
class VolumeRayCaster {
public:
    // Throws std::invalid_argument for a step or absorption that is not
    // finite and positive.
    VolumeRayCaster(const DensityVolume &volume, const RayMarchSettings &settings);

    // Sets the view the next cast() calls use.
    void set_view(const Camera &camera, int width, int height);

    // The composited colour of pixel (x, y) (bottom row 0) over
    // `polygon_rgb` (8-bit), and whether any sample had density > 0 (the
    // pixel's colour is polygon_rgb exactly when it had none).
    struct Result {
        std::uint8_t rgb[3];
        bool volume_contributes;
    };
    Result cast(int x, int y, const std::uint8_t polygon_rgb[3], double window_depth) const;

    // Does the ray of pixel (x, y) meet the volume's box between the near
    // plane and window_depth? (What a ray caster without occlusion
    // information tests before it marches.)
    bool meets_box(int x, int y, double window_depth) const;

    const DensityVolume &volume() const { return volume_; }
    const RayMarchSettings &settings() const { return settings_; }

private:
    struct Ray {
        glm::dvec3 origin, direction;   // origin on the near plane, direction unit length
        double t_end;                   // where the polygons (or the far plane) are
    };
    Ray ray(int x, int y, double window_depth) const;
    // The part [t0, t1) of the ray inside the box and before t_end; false if none.
    bool clip_to_box(const Ray &r, double &t0, double &t1) const;

    const DensityVolume &volume_;
    RayMarchSettings settings_;
    glm::dmat4 inverse_view_projection_{1.0};
    int width_ = 1, height_ = 1;
};

}  // namespace occu
