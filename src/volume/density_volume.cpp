// SPDX-License-Identifier: MIT
#include "volume/density_volume.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace occu {

namespace {

bool finite(const glm::vec3 &v)
{
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// A hash of a lattice point to [0, 1): value noise's random values.
double lattice_value(int i, int j, int k, std::uint32_t seed)
{
    std::uint32_t h = seed * 0x9e3779b9u;
    for (std::uint32_t v : {std::uint32_t(i), std::uint32_t(j), std::uint32_t(k)}) {
        h ^= v + 0x7f4a7c15u + (h << 6) + (h >> 2);
        h *= 0x85ebca6bu;
        h ^= h >> 13;
    }
    h *= 0xc2b2ae35u;
    h ^= h >> 16;
    return double(h >> 8) / double(1u << 24);
}

// Value noise: trilinear between lattice points `cell` metres apart, smoothed.
double value_noise(const glm::dvec3 &p, double cell, std::uint32_t seed)
{
    const glm::dvec3 u = p / cell;
    const glm::dvec3 f = glm::floor(u);
    glm::dvec3 t = u - f;
    t = t * t * (3.0 - 2.0 * t);
    const int i = int(f.x), j = int(f.y), k = int(f.z);
    double v = 0.0;
    for (int c = 0; c < 8; ++c) {
        const int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
        const double w = (di ? t.x : 1.0 - t.x) * (dj ? t.y : 1.0 - t.y) * (dk ? t.z : 1.0 - t.z);
        v += w * lattice_value(i + di, j + dj, k + dk, seed);
    }
    return v;
}

}  // namespace

DensityVolume::DensityVolume(const Aabb &box, glm::ivec3 points) : box_(box), points_(points)
{
    if (box.empty() || !finite(box.min) || !finite(box.max) || box.min.x == box.max.x || box.min.y == box.max.y ||
        box.min.z == box.max.z)
        throw std::invalid_argument("a density volume needs a finite box of positive size");
    if (points.x < 2 || points.y < 2 || points.z < 2)
        throw std::invalid_argument("a density volume needs at least 2 grid points per axis");
    if (double(points.x) * double(points.y) * double(points.z) > double(1u << 30))
        throw std::invalid_argument("a density volume of more than 2^30 grid points");
    min_ = glm::dvec3(box.min);
    cell_ = (glm::dvec3(box.max) - min_) / glm::dvec3(cells());
    values_.assign(std::size_t(points.x) * std::size_t(points.y) * std::size_t(points.z), 0.0f);
}

void DensityVolume::set(int i, int j, int k, float density)
{
    if (!(density >= 0.0f) || !std::isfinite(density))
        throw std::invalid_argument("density " + std::to_string(density) + " at grid point (" + std::to_string(i) +
                                    ", " + std::to_string(j) + ", " + std::to_string(k) +
                                    "): densities are finite and >= 0");
    values_[index(i, j, k)] = density;
}

double DensityVolume::sample(const glm::dvec3 &p) const
{
    const glm::dvec3 u = (p - min_) / cell_;
    const glm::ivec3 n = cells();
    if (!(u.x >= 0.0 && u.y >= 0.0 && u.z >= 0.0 && u.x <= n.x && u.y <= n.y && u.z <= n.z))
        return 0.0;
    // The cell holding p (on the far faces, the last cell).
    const glm::ivec3 c = glm::min(glm::ivec3(glm::floor(u)), n - 1);
    const glm::dvec3 t = u - glm::dvec3(c);
    double v = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
        const int di = corner & 1, dj = (corner >> 1) & 1, dk = (corner >> 2) & 1;
        const float d = at(c.x + di, c.y + dj, c.z + dk);
        if (d == 0.0f)
            continue;
        v += double(d) * (di ? t.x : 1.0 - t.x) * (dj ? t.y : 1.0 - t.y) * (dk ? t.z : 1.0 - t.z);
    }
    return v;
}

Aabb DensityVolume::cell_box(glm::ivec3 first, glm::ivec3 count) const
{
    const glm::ivec3 last = glm::min(first + count, cells());
    Aabb b;
    for (int a = 0; a < 3; ++a) {
        b.min[a] = float(min_[a] + double(first[a]) * cell_[a]);
        // The grid's last points are the box's own faces, not a rounded product.
        b.max[a] = last[a] == cells()[a] ? box_.max[a] : float(min_[a] + double(last[a]) * cell_[a]);
    }
    return b;
}

DensityVolume make_smoke(const SmokePlume &plume, const Aabb &box, glm::ivec3 points)
{
    if (!(plume.height > 0.0f) || !(plume.base_radius > 0.0f) || !(plume.top_radius > 0.0f) ||
        !(plume.noise_cell > 0.0f) || !finite(plume.source) || !finite(plume.wind))
        throw std::invalid_argument("a smoke plume needs a finite source and wind and positive sizes");
    DensityVolume v(box, points);
    const glm::dvec3 source(plume.source), wind(plume.wind);
    for (int k = 0; k < points.z; ++k)
        for (int j = 0; j < points.y; ++j)
            for (int i = 0; i < points.x; ++i) {
                const glm::dvec3 p = glm::dvec3(box.min) + glm::dvec3(i, j, k) * v.cell_size();
                const double rise = p.y - source.y;
                if (rise < 0.0 || rise > plume.height)
                    continue;
                const double s = rise / plume.height;
                // The axis bends with the wind, more the higher it gets.
                const glm::dvec3 axis = source + wind * rise * s + glm::dvec3(0.0, rise, 0.0);
                const double radius = plume.base_radius + (plume.top_radius - plume.base_radius) * s;
                const double off = glm::length(glm::dvec2(p.x - axis.x, p.z - axis.z));
                const double core = 1.0 - off / radius;
                if (core <= 0.0)
                    continue;
                const double puffs = value_noise(p, plume.noise_cell, plume.seed);
                const double fade = std::min({1.0, 5.0 * (1.0 - s), rise / 3.0 + 0.2});
                const double density = core * std::sqrt(core) * (0.25 + 0.75 * puffs) * fade;
                if (density > 0.0)
                    v.set(i, j, k, float(density));
            }
    return v;
}

DensityVolume smoke_above_block(int bx, int bz, float block_size, float cell)
{
    if (!(cell > 0.0f) || !(cell <= 64.0f))
        throw std::invalid_argument("smoke grid cells of " + std::to_string(cell) + " m: want (0, 64]");
    const glm::vec3 courtyard{(float(bx) + 0.5f) * block_size, 0.0f, (float(bz) + 0.5f) * block_size};
    SmokePlume plume;
    plume.source = courtyard;
    plume.height = 120.0f;
    plume.base_radius = 7.0f;
    plume.top_radius = 28.0f;
    plume.wind = {0.45f, 0.0f, 0.0f};
    // From 32 m west of the source to 96 m east (the drift), 32 m either
    // side north and south, 128 m up.
    const Aabb box{courtyard + glm::vec3(-32.0f, 0.0f, -32.0f), courtyard + glm::vec3(96.0f, 128.0f, 32.0f)};
    const int across = std::max(1, int(std::lround(128.0f / cell))), deep = std::max(1, int(std::lround(64.0f / cell)));
    return make_smoke(plume, box, {across + 1, across + 1, deep + 1});
}

std::vector<Brick> make_bricks(const DensityVolume &volume, int brick_cells)
{
    if (brick_cells < 1)
        throw std::invalid_argument("a brick needs at least one cell per axis, got " + std::to_string(brick_cells));
    const glm::ivec3 cells = volume.cells();
    std::vector<Brick> bricks;
    for (int z = 0; z < cells.z; z += brick_cells)
        for (int y = 0; y < cells.y; y += brick_cells)
            for (int x = 0; x < cells.x; x += brick_cells) {
                Brick b;
                b.first_cell = {x, y, z};
                b.cell_count = glm::min(glm::ivec3(brick_cells), cells - b.first_cell);
                b.box = volume.cell_box(b.first_cell, b.cell_count);
                // Its cells' corner points, the faces it shares with its neighbours included.
                b.empty = true;
                for (int k = z; k <= z + b.cell_count.z && b.empty; ++k)
                    for (int j = y; j <= y + b.cell_count.y && b.empty; ++j)
                        for (int i = x; i <= x + b.cell_count.x; ++i)
                            if (volume.at(i, j, k) != 0.0f) {
                                b.empty = false;
                                break;
                            }
                bricks.push_back(b);
            }
    return bricks;
}

VolumeRayCaster::VolumeRayCaster(const DensityVolume &volume, const RayMarchSettings &settings)
    : volume_(volume), settings_(settings)
{
    if (!(settings.step > 0.0) || !std::isfinite(settings.step))
        throw std::invalid_argument("ray marching step must be finite and positive");
    if (!(settings.absorption > 0.0) || !std::isfinite(settings.absorption))
        throw std::invalid_argument("ray marching absorption must be finite and positive");
}

void VolumeRayCaster::set_view(const Camera &camera, int width, int height)
{
    if (width < 1 || height < 1)
        throw std::invalid_argument("a view of " + std::to_string(width) + "x" + std::to_string(height) + " pixels");
    inverse_view_projection_ = glm::inverse(glm::dmat4(camera.projection()) * glm::dmat4(camera.view()));
    width_ = width;
    height_ = height;
}

VolumeRayCaster::Ray VolumeRayCaster::ray(int x, int y, double window_depth) const
{
    const double nx = 2.0 * (double(x) + 0.5) / double(width_) - 1.0;
    const double ny = 2.0 * (double(y) + 0.5) / double(height_) - 1.0;
    auto unproject = [&](double ndc_z) {
        const glm::dvec4 p = inverse_view_projection_ * glm::dvec4(nx, ny, ndc_z, 1.0);
        return glm::dvec3(p) / p.w;
    };
    const glm::dvec3 near_point = unproject(-1.0), far_point = unproject(1.0);
    const glm::dvec3 surface = unproject(2.0 * std::clamp(window_depth, 0.0, 1.0) - 1.0);
    Ray r;
    r.origin = near_point;
    r.direction = glm::normalize(far_point - near_point);
    r.t_end = glm::dot(surface - near_point, r.direction);
    return r;
}

bool VolumeRayCaster::clip_to_box(const Ray &r, double &t0, double &t1) const
{
    const glm::dvec3 lo(volume_.box().min), hi(volume_.box().max);
    t0 = 0.0;
    t1 = r.t_end;
    for (int a = 0; a < 3; ++a) {
        if (r.direction[a] == 0.0) {
            if (r.origin[a] < lo[a] || r.origin[a] > hi[a])
                return false;
            continue;
        }
        double ta = (lo[a] - r.origin[a]) / r.direction[a], tb = (hi[a] - r.origin[a]) / r.direction[a];
        if (ta > tb)
            std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    return t0 < t1;
}

bool VolumeRayCaster::meets_box(int x, int y, double window_depth) const
{
    double t0, t1;
    return clip_to_box(ray(x, y, window_depth), t0, t1);
}

VolumeRayCaster::Result VolumeRayCaster::cast(int x, int y, const std::uint8_t polygon_rgb[3], double window_depth) const
{
    Result out{{polygon_rgb[0], polygon_rgb[1], polygon_rgb[2]}, false};
    const Ray r = ray(x, y, window_depth);
    double t0, t1;
    if (!clip_to_box(r, t0, t1))
        return out;
    const double step = settings_.step;
    const double bottom = double(volume_.box().min.y), height = double(volume_.box().extent().y);
    glm::dvec3 colour(0.0);
    double transmittance = 1.0;
    for (double k = std::ceil(t0 / step); k * step < t1; k += 1.0) {
        const glm::dvec3 p = r.origin + (k * step) * r.direction;
        const double rho = volume_.sample(p);
        if (rho <= 0.0)
            continue;
        out.volume_contributes = true;
        const double alpha = 1.0 - std::exp(-settings_.absorption * rho * step);
        const double h = std::clamp((p.y - bottom) / height, 0.0, 1.0);
        colour += transmittance * alpha * glm::mix(settings_.low_colour, settings_.high_colour, h);
        transmittance *= 1.0 - alpha;
        if (transmittance < settings_.opaque)
            break;
    }
    if (!out.volume_contributes)
        return out;
    for (int c = 0; c < 3; ++c) {
        const double v = colour[c] + transmittance * double(polygon_rgb[c]) / 255.0;
        out.rgb[c] = std::uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
    }
    return out;
}

}  // namespace occu
