// SPDX-License-Identifier: MIT
// Occluder skins: Leone et al., section 4 (the steps are in the header).
#include "occluders/occluder_skins.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>

#include <glm/glm.hpp>

namespace occu {

namespace {

using Vec = glm::dvec3;

// Per-voxel flags.
constexpr std::uint8_t surface_bit = 1;   // a triangle overlaps the voxel
constexpr std::uint8_t flooded_bit = 2;   // reached by a flood from a candidate inner voxel
constexpr std::uint8_t inner_bit = 4;     // in a flooded region confirmed inside (winding number)
constexpr std::uint8_t taken_bit = 8;     // in a box already made

std::string format_number(double x)
{
    char text[32];
    std::snprintf(text, sizeof(text), "%.9g", x);
    return text;
}

std::string format_point(const Vec &p)
{
    char text[96];
    std::snprintf(text, sizeof(text), "(%.3f, %.3f, %.3f)", p.x, p.y, p.z);
    return text;
}

// The voxel grid over a mesh's bounding box: n voxels per axis, the outer
// layer of which is padding the mesh never reaches; voxel (x, y, z) spans
// origin + (x, y, z) * voxel to origin + (x + 1, y + 1, z + 1) * voxel.
// Index x + n.x * (y + n.y * z): "scan order" is x fastest, then y, then z.
// Kept in double: the same numbers give the surface test its voxel bounds
// and the skins their corners, so rounding cannot move one against the other.
struct Grid {
    glm::ivec3 n{0};
    Vec origin{0.0};
    double voxel = 1.0;

    std::size_t count() const { return std::size_t(n.x) * std::size_t(n.y) * std::size_t(n.z); }
    std::size_t index(int x, int y, int z) const
    {
        return std::size_t(x) + std::size_t(n.x) * (std::size_t(y) + std::size_t(n.y) * std::size_t(z));
    }
    std::size_t index(const glm::ivec3 &c) const { return index(c.x, c.y, c.z); }
    glm::ivec3 coords(std::size_t i) const
    {
        const int x = int(i % std::size_t(n.x));
        i /= std::size_t(n.x);
        return {x, int(i % std::size_t(n.y)), int(i / std::size_t(n.y))};
    }
    bool on_border(const glm::ivec3 &c) const
    {
        return c.x == 0 || c.y == 0 || c.z == 0 || c.x == n.x - 1 || c.y == n.y - 1 || c.z == n.z - 1;
    }
    Vec corner(const glm::ivec3 &c) const { return origin + Vec(c) * voxel; }
    Vec center(const glm::ivec3 &c) const { return origin + (Vec(c) + 0.5) * voxel; }
};

// A triangle prepared for the separating-axis test against many voxels
// (Akenine-Möller, "Fast 3D triangle-box overlap testing", the paper's ref.
// [12]; written here from the theorem, not from his code). A triangle and a
// box, both convex, are disjoint exactly when their projections onto some
// axis do not overlap, and for this pair the axes to try are 13: the box's
// three face normals, the triangle's normal, and the nine cross products of
// a box edge direction with a triangle edge. The triangle's projections do
// not depend on the voxel, so they are computed once; a voxel (centre c,
// half-size h on each axis) projects onto axis a as the interval
// a.c +- (h |a.x| + h |a.y| + h |a.z|).
class TriangleAxes {
public:
    TriangleAxes(const Vec &p0, const Vec &p1, const Vec &p2, double half)
    {
        const Vec e[3] = {p1 - p0, p2 - p1, p0 - p2};
        // The normal first: for a slanted triangle it rejects most voxels of its box.
        add(glm::cross(e[0], e[1]), p0, p1, p2, half);
        for (int i = 0; i < 3; ++i) {
            Vec u(0.0);
            u[i] = 1.0;
            add(u, p0, p1, p2, half);
            for (const Vec &edge : e)
                add(glm::cross(u, edge), p0, p1, p2, half);
        }
    }

    // Touching counts as overlap (only a strict gap separates): with the
    // tolerance in `half`, a voxel the triangle passes near is a surface voxel.
    bool overlaps(const Vec &center) const
    {
        for (int k = 0; k < count_; ++k) {
            const double c = glm::dot(axis_[k], center);
            if (lo_[k] - c > radius_[k] || hi_[k] - c < -radius_[k])
                return false;
        }
        return true;
    }

private:
    void add(const Vec &a, const Vec &p0, const Vec &p1, const Vec &p2, double half)
    {
        if (glm::dot(a, a) == 0.0)
            return;   // a degenerate edge or triangle: this axis separates nothing
        const double d0 = glm::dot(a, p0), d1 = glm::dot(a, p1), d2 = glm::dot(a, p2);
        axis_[count_] = a;
        lo_[count_] = std::min({d0, d1, d2});
        hi_[count_] = std::max({d0, d1, d2});
        radius_[count_] = half * (std::fabs(a.x) + std::fabs(a.y) + std::fabs(a.z));
        ++count_;
    }

    std::array<Vec, 13> axis_{};
    std::array<double, 13> lo_{}, hi_{}, radius_{};
    int count_ = 0;
};

// The generalized winding number of the mesh's triangles about p: the sum
// of the solid angles they subtend, over 4 pi (the solid angle of a
// triangle by Van Oosterom and Strackee's formula, tan(omega / 2) =
// a.(b x c) / (|a||b||c| + (a.b)|c| + (a.c)|b| + (b.c)|a|) with a, b, c
// the corners seen from p). For a closed surface with faces counter-
// clockwise from outside it counts how many times the surface wraps p:
// 1 inside, 0 outside, 2 inside two overlapping closed parts; for an open
// surface it is not a whole number near the hole.
double winding_number(const Mesh &mesh, const Vec &p)
{
    double sum = 0.0;
    const std::size_t triangles = mesh.triangle_count();
    for (std::size_t t = 0; t < triangles; ++t) {
        const Vec a = Vec(mesh.positions[mesh.indices[3 * t]]) - p;
        const Vec b = Vec(mesh.positions[mesh.indices[3 * t + 1]]) - p;
        const Vec c = Vec(mesh.positions[mesh.indices[3 * t + 2]]) - p;
        const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
        const double det = glm::dot(a, glm::cross(b, c));
        const double den = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
        sum += 2.0 * std::atan2(det, den);
    }
    return sum / (4.0 * 3.14159265358979323846);
}

// How far a winding number may be from a whole number on a closed surface.
// The sum's rounding in double over thousands of triangles is about 1e-12;
// a hole that subtends more than 4 pi 1e-5 sr (1.3e-4 sr: a 0.25 m square
// 20 m away) is seen. Smaller gaps, such as seams of float rounding between
// parts, count as closed: nothing of a skin can be seen through them.
constexpr double winding_tolerance = 1e-5;

bool fail(std::string *why, const std::string &text)
{
    if (why)
        *why = text;
    return false;
}

// Step 1: the grid and its surface voxels.
bool voxelize(const Mesh &mesh, double voxel, Grid &grid, std::vector<std::uint8_t> &flags, std::string *why)
{
    Aabb bounds;
    for (std::uint32_t i : mesh.indices)
        bounds.expand(mesh.positions[i]);
    const Vec lo(bounds.min), hi(bounds.max);
    double magnitude = 0.0;
    for (int a = 0; a < 3; ++a)
        magnitude = std::max({magnitude, std::fabs(lo[a]), std::fabs(hi[a])});
    // The tolerance: voxels are tested enlarged by this much on every side,
    // so an inner voxel is at least this far from every triangle. It dwarfs
    // the rounding of the skins' corners to float (half a float ulp, at most
    // 6e-8 of the coordinates' magnitude) and of the test in double.
    auto tolerance = [&](double v) { return 1e-3 * v + 1e-6 * magnitude; };
    // Centred on the box, with room for half a voxel (and the tolerance) more
    // than its extent: the box's faces lie a quarter to three quarters of a
    // voxel inside the first (or last) voxel that is not padding, never on a
    // voxel's boundary, so a side loses at most 3/4 of a voxel (a face on a
    // boundary would mark the voxels on both sides), and the padding stays
    // clear of the surface (the flood's way round the mesh) by more than
    // the tolerance.
    auto cells = [&](int a, double v) { return std::ceil((hi[a] - lo[a] + 4.0 * tolerance(v)) / v + 0.5) + 2.0; };
    auto voxels = [&](double v) { return cells(0, v) * cells(1, v) * cells(2, v); };
    if (voxels(voxel) > double(max_skin_voxels)) {
        double enough = voxel;
        while (voxels(enough) > double(max_skin_voxels))
            enough *= 1.01;
        const double digits = std::pow(10.0, std::floor(std::log10(enough)) - 1.0);   // two significant, up
        return fail(why, "voxel grid too large: " + format_number(cells(0, voxel)) + " x " +
                             format_number(cells(1, voxel)) + " x " + format_number(cells(2, voxel)) +
                             " voxels at voxel size " + format_number(voxel) + " m, more than " +
                             std::to_string(max_skin_voxels) + "; a voxel size of " +
                             format_number(std::ceil(enough / digits) * digits) + " m or more would do");
    }
    for (int a = 0; a < 3; ++a) {
        grid.n[a] = int(cells(a, voxel));
        grid.origin[a] = 0.5 * (lo[a] + hi[a]) - 0.5 * double(grid.n[a]) * voxel;
    }
    grid.voxel = voxel;
    flags.assign(grid.count(), 0);

    const double eps = tolerance(voxel);
    const double half = 0.5 * voxel + eps;
    const std::size_t triangles = mesh.triangle_count();
    for (std::size_t t = 0; t < triangles; ++t) {
        const Vec p0(mesh.positions[mesh.indices[3 * t]]), p1(mesh.positions[mesh.indices[3 * t + 1]]),
            p2(mesh.positions[mesh.indices[3 * t + 2]]);
        const TriangleAxes axes(p0, p1, p2, half);
        // Only the voxels of the triangle's own box (grown by the tolerance).
        glm::ivec3 first, last;
        for (int a = 0; a < 3; ++a) {
            const double tmin = std::min({p0[a], p1[a], p2[a]}) - eps, tmax = std::max({p0[a], p1[a], p2[a]}) + eps;
            first[a] = std::clamp(int(std::floor((tmin - grid.origin[a]) / voxel)), 0, grid.n[a] - 1);
            last[a] = std::clamp(int(std::floor((tmax - grid.origin[a]) / voxel)), 0, grid.n[a] - 1);
        }
        for (int z = first.z; z <= last.z; ++z)
            for (int y = first.y; y <= last.y; ++y)
                for (int x = first.x; x <= last.x; ++x) {
                    std::uint8_t &f = flags[grid.index(x, y, z)];
                    if (!(f & surface_bit) && axes.overlaps(grid.center({x, y, z})))
                        f |= surface_bit;
                }
    }
    return true;
}

// Steps 2 and 3: flood the interiors from the candidate inner voxels and
// keep the regions inside. False (with why) when the surface leaks.
bool find_inner_voxels(const Mesh &mesh, const Grid &grid, std::vector<std::uint8_t> &flags, std::string *why)
{
    // The paper's rule needs, for each voxel, a surface voxel somewhere
    // before and after it on each axis: it lies strictly between the first
    // and the last surface voxel of its row along x, along y and along z.
    struct Span {
        int first = std::numeric_limits<int>::max(), last = -1;
        void add(int i) { first = std::min(first, i), last = std::max(last, i); }
        bool inside(int i) const { return first < i && i < last; }
    };
    const glm::ivec3 n = grid.n;
    std::vector<Span> along_x(std::size_t(n.y) * n.z), along_y(std::size_t(n.x) * n.z), along_z(std::size_t(n.x) * n.y);
    for (int z = 0; z < n.z; ++z)
        for (int y = 0; y < n.y; ++y)
            for (int x = 0; x < n.x; ++x)
                if (flags[grid.index(x, y, z)] & surface_bit) {
                    along_x[std::size_t(y) + std::size_t(n.y) * z].add(x);
                    along_y[std::size_t(x) + std::size_t(n.x) * z].add(y);
                    along_z[std::size_t(x) + std::size_t(n.x) * y].add(z);
                }
    const std::ptrdiff_t step[6] = {-1, 1, -std::ptrdiff_t(n.x), std::ptrdiff_t(n.x),
                                    -std::ptrdiff_t(n.x) * n.y, std::ptrdiff_t(n.x) * n.y};
    std::vector<std::size_t> stack, region;
    bool any_inner = false;
    for (int z = 1; z < n.z - 1; ++z)
        for (int y = 1; y < n.y - 1; ++y)
            for (int x = 1; x < n.x - 1; ++x) {
                const std::size_t start = grid.index(x, y, z);
                if ((flags[start] & (surface_bit | flooded_bit)) || !along_x[std::size_t(y) + std::size_t(n.y) * z].inside(x) ||
                    !along_y[std::size_t(x) + std::size_t(n.x) * z].inside(y) ||
                    !along_z[std::size_t(x) + std::size_t(n.x) * y].inside(z))
                    continue;
                // A candidate inner voxel: flood its region through voxels
                // that are not surface (section 4, fig. 3).
                region.clear();
                stack.assign(1, start);
                flags[start] |= flooded_bit;
                bool border = false;
                while (!stack.empty()) {
                    const std::size_t i = stack.back();
                    stack.pop_back();
                    region.push_back(i);
                    const glm::ivec3 c = grid.coords(i);
                    border = border || grid.on_border(c);
                    for (int k = 0; k < 6; ++k) {
                        const int axis = k / 2, to = c[axis] + (k % 2 ? 1 : -1);
                        if (to < 0 || to >= n[axis])
                            continue;
                        const std::size_t j = std::size_t(std::ptrdiff_t(i) + step[k]);
                        if (!(flags[j] & (surface_bit | flooded_bit))) {
                            flags[j] |= flooded_bit;
                            stack.push_back(j);
                        }
                    }
                }
                if (border) {
                    // The flood got out: "leak through one of the holes",
                    // the case the paper leaves open. Unless the candidate
                    // was outside to begin with (winding number 0: a room
                    // whose door is not in line with it sees walls in all
                    // six directions), the surface has a hole.
                    const Vec p = grid.center({x, y, z});
                    if (std::fabs(winding_number(mesh, p)) <= winding_tolerance)
                        continue;
                    return fail(why, "not watertight: the flood from the inner voxel at " + format_point(p) +
                                         " reaches the voxel grid's border (a hole about a voxel, " +
                                         format_number(grid.voxel) + " m, wide or more)");
                }
                // The region is connected and clear of the surface: one
                // winding number holds for all of it. Taken at the region's
                // voxel nearest its centroid, on average nearest a hole.
                Vec centroid(0.0);
                for (std::size_t i : region)
                    centroid += Vec(grid.coords(i));
                centroid /= double(region.size());
                glm::ivec3 middle = grid.coords(start);
                double nearest = std::numeric_limits<double>::max();
                for (std::size_t i : region) {
                    const glm::ivec3 c = grid.coords(i);
                    const Vec d = Vec(c) - centroid;
                    if (glm::dot(d, d) < nearest) {
                        nearest = glm::dot(d, d);
                        middle = c;
                    }
                }
                const Vec p = grid.center(middle);
                const double w = winding_number(mesh, p);
                if (std::fabs(w - std::round(w)) > winding_tolerance) {
                    char text[32];
                    std::snprintf(text, sizeof(text), "%.6f", w);
                    return fail(why, std::string("not watertight: the winding number about the inner voxel at ") +
                                         format_point(p) + " is " + text +
                                         ", not a whole number (the surface is open; a hole narrower than a voxel)");
                }
                if (std::lround(w) == 0)
                    continue;   // a pocket of outside: a cavity, or sealed off at this voxel size
                for (std::size_t i : region)
                    flags[i] |= inner_bit;
                any_inner = true;
            }
    if (any_inner)
        return true;
    // No interior. An open surface often has no candidate at all (a box
    // without one side: no voxel sees surface in all six directions); its
    // winding number, fractional in the middle, tells it from a closed mesh
    // too thin for this voxel size.
    const glm::ivec3 middle = n / 2;
    std::size_t best = flags.size();
    long best_d2 = std::numeric_limits<long>::max();
    for (int z = 1; z < n.z - 1; ++z)
        for (int y = 1; y < n.y - 1; ++y)
            for (int x = 1; x < n.x - 1; ++x) {
                const glm::ivec3 d = glm::ivec3(x, y, z) - middle;
                const long d2 = long(d.x) * d.x + long(d.y) * d.y + long(d.z) * d.z;
                if (!(flags[grid.index(x, y, z)] & surface_bit) && d2 < best_d2) {
                    best_d2 = d2;
                    best = grid.index(x, y, z);
                }
            }
    if (best != flags.size()) {
        const Vec p = grid.center(grid.coords(best));
        const double w = winding_number(mesh, p);
        if (std::fabs(w - std::round(w)) > winding_tolerance) {
            char text[32];
            std::snprintf(text, sizeof(text), "%.6f", w);
            return fail(why, std::string("not watertight: no inner voxel, and the winding number at ") +
                                 format_point(p) + " is " + text + ", not a whole number (the surface is open)");
        }
    }
    return fail(why, "no interior: no voxel of " + format_number(grid.voxel) +
                         " m fits inside the closed surface without touching it (thinner than about two voxels)");
}

// Danell's densest voxel, as SkinOptions::Start::densest documents: the
// free voxel (inner, not taken) of largest chessboard distance to a voxel
// that is not free, by the classic two raster passes over the 26-neighbours
// (each pass takes the minimum over the 13 neighbours it has already seen,
// plus one), exact for the chessboard metric. The padding is never free, so
// the passes run over the voxels inside it with no bounds checks.
// Returns flags.size() when no voxel is free.
std::size_t densest_free_voxel(const Grid &grid, const std::vector<std::uint8_t> &flags, std::vector<std::uint16_t> &d)
{
    const glm::ivec3 n = grid.n;
    const auto sx = std::ptrdiff_t(1), sy = std::ptrdiff_t(n.x), sz = std::ptrdiff_t(n.x) * n.y;
    std::array<std::ptrdiff_t, 13> before{};
    int k = 0;
    for (int dz = -1; dz <= 0; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
                if (dz < 0 || dy < 0 || (dy == 0 && dx < 0))   // before in scan order
                    before[std::size_t(k++)] = dz * sz + dy * sy + dx * sx;
    auto free = [&](std::size_t i) { return (flags[i] & (inner_bit | taken_bit)) == inner_bit; };
    d.assign(flags.size(), 0);
    bool any = false;
    for (int z = 1; z < n.z - 1; ++z)
        for (int y = 1; y < n.y - 1; ++y)
            for (int x = 1; x < n.x - 1; ++x) {
                const std::size_t i = grid.index(x, y, z);
                if (!free(i))
                    continue;
                any = true;
                std::uint16_t m = std::numeric_limits<std::uint16_t>::max();
                for (std::ptrdiff_t o : before)
                    m = std::min(m, d[std::size_t(std::ptrdiff_t(i) + o)]);
                d[i] = std::uint16_t(std::min<int>(m + 1, std::numeric_limits<std::uint16_t>::max()));
            }
    if (!any)
        return flags.size();
    for (int z = n.z - 2; z >= 1; --z)
        for (int y = n.y - 2; y >= 1; --y)
            for (int x = n.x - 2; x >= 1; --x) {
                const std::size_t i = grid.index(x, y, z);
                if (!free(i))
                    continue;
                std::uint16_t m = d[i];
                for (std::ptrdiff_t o : before)
                    m = std::min<std::uint16_t>(m, std::uint16_t(std::min<int>(d[std::size_t(std::ptrdiff_t(i) - o)] + 1,
                                                                             std::numeric_limits<std::uint16_t>::max())));
                d[i] = m;
            }
    std::size_t best = flags.size();
    std::uint16_t best_d = 0;
    for (std::size_t i = 0; i < d.size(); ++i)
        if (d[i] > best_d) {   // strictly: ties go to the first in scan order
            best_d = d[i];
            best = i;
        }
    return best;
}

// Step 4: boxes one after another.
std::vector<Aabb> extract_boxes(const Grid &grid, std::vector<std::uint8_t> &flags, const SkinOptions &options)
{
    auto free = [&](std::size_t i) { return (flags[i] & (inner_bit | taken_bit)) == inner_bit; };
    // Whether the voxels of the box lo..hi with axis `axis` set to `at` are
    // all free. The padding is never free, so `at` never leaves the grid.
    auto layer_free = [&](glm::ivec3 lo, glm::ivec3 hi, int axis, int at) {
        lo[axis] = hi[axis] = at;
        for (int z = lo.z; z <= hi.z; ++z)
            for (int y = lo.y; y <= hi.y; ++y)
                for (int x = lo.x; x <= hi.x; ++x)
                    if (!free(grid.index(x, y, z)))
                        return false;
        return true;
    };
    const double voxel_volume = grid.voxel * grid.voxel * grid.voxel;
    std::vector<Aabb> boxes;
    std::vector<std::uint16_t> distances;
    std::size_t cursor = 0;   // first start: no voxel before it is free, nor ever becomes so
    while (int(boxes.size()) < options.max_boxes) {
        std::size_t seed = flags.size();
        if (options.start == SkinOptions::Start::densest) {
            seed = densest_free_voxel(grid, flags, distances);
        } else {
            while (cursor < flags.size() && !free(cursor))
                ++cursor;
            seed = cursor;
        }
        if (seed == flags.size())
            break;   // every inner voxel taken
        // Grow by one layer in each of the six directions in turn while the
        // new layer is all inner and not taken (section 4: "we expand this
        // AABB by a voxel length in every one of the six directions").
        glm::ivec3 lo = grid.coords(seed), hi = lo;
        for (bool grew = true; grew;) {
            grew = false;
            for (int direction = 0; direction < 6; ++direction) {
                const int axis = direction / 2;
                const int at = direction % 2 ? hi[axis] + 1 : lo[axis] - 1;
                if (layer_free(lo, hi, axis, at)) {
                    (direction % 2 ? hi : lo)[axis] = at;
                    grew = true;
                }
            }
        }
        const glm::ivec3 size = hi - lo + 1;
        if (double(size.x) * size.y * size.z * voxel_volume < double(options.min_volume))
            break;   // threshold 2: this box is rejected and the search stops
        for (int z = lo.z; z <= hi.z; ++z)
            for (int y = lo.y; y <= hi.y; ++y)
                for (int x = lo.x; x <= hi.x; ++x)
                    flags[grid.index(x, y, z)] |= taken_bit;
        boxes.push_back(Aabb{glm::vec3(grid.corner(lo)), glm::vec3(grid.corner(hi + 1))});
    }
    return boxes;
}

// FNV-1a: stable across runs and machines.
struct Fnv1a {
    std::uint64_t h = 1469598103934665603ull;
    void bytes(const void *data, std::size_t size)
    {
        for (std::size_t i = 0; i < size; ++i) {
            h ^= static_cast<const unsigned char *>(data)[i];
            h *= 1099511628211ull;
        }
    }
    template <typename T> void add(const T &value) { bytes(&value, sizeof(value)); }
};

std::string hex16(std::uint64_t h)
{
    char hex[17];
    std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(h));
    return hex;
}

}  // namespace

std::string SkinOptions::describe() const
{
    return "voxel=" + format_number(voxel_size) + " max-boxes=" + std::to_string(max_boxes) +
           " min-volume=" + format_number(min_volume) + " start=" + (start == Start::densest ? "densest" : "first");
}

std::string SkinOptions::problem() const
{
    if (!(std::isfinite(voxel_size) && voxel_size > 0.0f))
        return "voxel size wants a positive finite number of metres, not " + format_number(voxel_size);
    if (max_boxes < 1)
        return "max boxes wants at least 1, not " + std::to_string(max_boxes);
    if (!(std::isfinite(min_volume) && min_volume >= 0.0f))
        return "min volume wants a finite number of m^3, at least 0, not " + format_number(min_volume);
    return {};
}

std::optional<std::vector<Aabb>> occluder_skins(const Mesh &mesh, const SkinOptions &options, std::string *why)
{
    if (const std::string problem = options.problem(); !problem.empty())
        throw std::invalid_argument("occluder skins: " + problem);
    if (!mesh.occluder) {
        fail(why, "see-through (not an occluder): it hides nothing behind it");
        return std::nullopt;
    }
    if (mesh.triangle_count() == 0) {
        fail(why, "no triangles");
        return std::nullopt;
    }
    for (std::size_t i = 0; i < 3 * mesh.triangle_count(); ++i)
        if (mesh.indices[i] >= mesh.positions.size()) {
            fail(why, "index " + std::to_string(i) + " is " + std::to_string(mesh.indices[i]) + ", beyond its " +
                          std::to_string(mesh.positions.size()) + " vertices");
            return std::nullopt;
        }
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const glm::vec3 &p = mesh.positions[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            fail(why, "vertex " + std::to_string(i) + " is not finite");
            return std::nullopt;
        }
    }
    Grid grid;
    std::vector<std::uint8_t> flags;
    if (!voxelize(mesh, double(options.voxel_size), grid, flags, why) || !find_inner_voxels(mesh, grid, flags, why))
        return std::nullopt;
    return extract_boxes(grid, flags, options);
}

std::string SkinReport::message() const
{
    return "mesh " + std::to_string(mesh) + (name.empty() ? std::string(" (unnamed)") : " '" + name + "'") + ": " +
           problem;
}

std::size_t SceneSkins::box_count() const
{
    std::size_t n = 0;
    for (const MeshSkins &s : skins)
        n += s.boxes.size();
    return n;
}

namespace {

// A mesh that is another moved without turning (the copies of a scene,
// such as the city's --city-copies) has that mesh's skins moved with it:
// a skin box lies clear of the first mesh's surface by the voxel test's
// tolerance, and inside it; moved by t, it lies as far from the first
// mesh moved by t, and the second mesh's vertices lie within `off` of
// those (each coordinate), so its surface, every point a convex
// combination of its vertices, lies within `off` too: the box stays clear
// of it and inside it (its winding number cannot change while no surface
// crosses the box) as long as `off` is below the tolerance. Half of it is
// allowed, the other half left for the corners' rounding to float, which
// rounds inwards here.
struct Translation {
    std::uint32_t of = 0;   // the first mesh of the shape
    Vec by{0.0};
};

std::optional<Vec> translation(const Mesh &from, const Mesh &to, double voxel)
{
    if (from.occluder != to.occluder || from.indices != to.indices || from.positions.size() != to.positions.size() ||
        from.positions.empty())
        return std::nullopt;
    for (std::uint32_t i : from.indices)
        if (i >= from.positions.size())
            return std::nullopt;
    const Vec by = Vec(to.positions[0]) - Vec(from.positions[0]);
    // The vertices the triangles use, as voxelize measures them.
    double magnitude = 0.0;
    for (std::uint32_t i : from.indices) {
        const Vec p = glm::abs(Vec(from.positions[i]));
        magnitude = std::max({magnitude, p.x, p.y, p.z});
    }
    // voxelize's tolerance for `from`, halved.
    const double allowed = 0.5 * (1e-3 * voxel + 1e-6 * magnitude);
    for (std::uint32_t i : from.indices) {
        const Vec off = glm::abs(Vec(to.positions[i]) - Vec(from.positions[i]) - by);
        if (!(std::max({off.x, off.y, off.z}) <= allowed))
            return std::nullopt;
    }
    return by;
}

// Each mesh that some earlier mesh of the scene moves onto, the earliest
// such: found over the whole scene, so that every shard gives a mesh the
// same skins.
std::vector<std::optional<Translation>> translated_copies(const Scene &scene, double voxel)
{
    // Candidates share indices and the shape about their first vertex to a
    // centimetre: a key that rounds two copies apart only loses the sharing.
    std::map<std::uint64_t, std::vector<std::uint32_t>> shapes;
    std::vector<std::optional<Translation>> out(scene.meshes.size());
    for (std::uint32_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh &mesh = scene.meshes[m];
        if (mesh.positions.empty())
            continue;
        std::uint64_t h = 1469598103934665603ull;
        auto add = [&](std::uint64_t v) { h = (h ^ v) * 1099511628211ull; };
        add(mesh.positions.size());
        for (std::uint32_t i : mesh.indices)
            add(i);
        const Vec first(mesh.positions[0]);
        for (const glm::vec3 &p : mesh.positions) {
            const glm::dvec3 r = glm::round((Vec(p) - first) * 100.0);
            add(std::uint64_t(std::int64_t(r.x))), add(std::uint64_t(std::int64_t(r.y))), add(std::uint64_t(std::int64_t(r.z)));
        }
        auto &same = shapes[h];
        for (std::uint32_t earlier : same)
            if (const auto by = translation(scene.meshes[earlier], mesh, voxel)) {
                out[m] = Translation{earlier, *by};
                break;
            }
        if (!out[m])
            same.push_back(m);
    }
    return out;
}

Aabb translated_inwards(const Aabb &box, const Vec &by)
{
    const Vec lo = Vec(box.min) + by, hi = Vec(box.max) + by;
    glm::vec3 min, max;
    for (int a = 0; a < 3; ++a) {
        min[a] = float(lo[a]);
        if (double(min[a]) < lo[a])
            min[a] = std::nextafter(min[a], std::numeric_limits<float>::infinity());
        max[a] = float(hi[a]);
        if (double(max[a]) > hi[a])
            max[a] = std::nextafter(max[a], -std::numeric_limits<float>::infinity());
    }
    return Aabb::of(min, max);
}

}  // namespace

SceneSkins scene_skins(const Scene &scene, const SkinOptions &options, int shard, int shards,
                       const std::function<void(std::size_t, std::size_t)> &progress)
{
    if (shards < 1 || shard < 1 || shard > shards)
        throw std::invalid_argument("scene skins: shard " + std::to_string(shard) + " of " + std::to_string(shards) +
                                    " (wants 1 <= I <= N)");
    if (const std::string problem = options.problem(); !problem.empty())
        throw std::invalid_argument("occluder skins: " + problem);
    std::vector<std::uint32_t> meshes;
    for (std::size_t m = 0; m < scene.meshes.size(); ++m)
        if (int(m % std::size_t(shards)) == shard - 1)
            meshes.push_back(std::uint32_t(m));
    const auto copies = translated_copies(scene, double(options.voxel_size));
    // The skins of the first mesh of each shape this shard needs: made once.
    std::map<std::uint32_t, std::optional<std::vector<Aabb>>> made;
    std::map<std::uint32_t, std::string> made_why;
    auto skins_of = [&](std::uint32_t m) -> const std::optional<std::vector<Aabb>> & {
        auto it = made.find(m);
        if (it == made.end())
            it = made.emplace(m, occluder_skins(scene.meshes[m], options, &made_why[m])).first;
        return it->second;
    };
    SceneSkins out;
    for (std::size_t k = 0; k < meshes.size(); ++k) {
        const std::uint32_t m = meshes[k];
        const Mesh &mesh = scene.meshes[m];
        std::optional<std::vector<Aabb>> boxes;
        std::string why;
        // A copy of a mesh without skins is made on its own: the reason
        // names places of the mesh it is about.
        if (copies[m] && skins_of(copies[m]->of)) {
            boxes.emplace();
            for (const Aabb &b : *skins_of(copies[m]->of)) {
                const Aabb moved = translated_inwards(b, copies[m]->by);
                if (moved.min.x < moved.max.x && moved.min.y < moved.max.y && moved.min.z < moved.max.z)
                    boxes->push_back(moved);
            }
        } else {
            boxes = occluder_skins(mesh, options, &why);
        }
        if (boxes)
            out.skins.push_back({m, std::move(*boxes)});
        else
            out.skipped.push_back({m, mesh.name, why});
        if (progress)
            progress(k + 1, meshes.size());
    }
    return out;
}

std::string scene_geometry_fingerprint(const Scene &scene)
{
    Fnv1a f;
    f.add(std::uint64_t(scene.meshes.size()));
    for (const Mesh &mesh : scene.meshes) {
        // A see-through mesh gets no skins: marked in the hash (only then,
        // so that scenes without one keep their fingerprints).
        if (!mesh.occluder)
            f.add(std::uint64_t(0x7365652d7468726full));
        f.add(std::uint64_t(mesh.positions.size()));
        for (const glm::vec3 &p : mesh.positions)
            f.add(p);
        f.add(std::uint64_t(mesh.indices.size()));
        for (std::uint32_t i : mesh.indices)
            f.add(i);
    }
    return hex16(f.h);
}

std::string skin_scene_provenance(const Scene &scene)
{
    return scene_geometry_fingerprint(scene) + " meshes=" + std::to_string(scene.meshes.size()) +
           " triangles=" + std::to_string(scene.triangle_count());
}

DatabaseProvenance OccluderSkinDatabase::provenance_for(const Scene &scene, const SkinOptions &options)
{
    // Pure geometry: no Mesa takes part.
    return DatabaseProvenance::current("occluder-skins", options.describe(), skin_scene_provenance(scene), false);
}

OccluderSkinDatabase OccluderSkinDatabase::make(const Scene &scene, const SkinOptions &options, int shard, int shards,
                                                const std::function<void(std::size_t, std::size_t)> &progress)
{
    OccluderSkinDatabase db;
    db.provenance = provenance_for(scene, options);
    db.meshes = std::uint32_t(scene.meshes.size());
    SceneSkins s = scene_skins(scene, options, shard, shards, progress);
    for (MeshSkins &m : s.skins)
        db.skins[m.mesh] = std::move(m.boxes);
    for (const SkinReport &r : s.skipped)
        db.skipped[r.mesh] = r.problem;
    return db;
}

const std::vector<Aabb> &OccluderSkinDatabase::boxes(std::uint32_t mesh) const
{
    static const std::vector<Aabb> none;
    const auto it = skins.find(mesh);
    return it == skins.end() ? none : it->second;
}

std::size_t OccluderSkinDatabase::box_count() const
{
    std::size_t n = 0;
    for (const auto &[mesh, list] : skins)
        n += list.size();
    return n;
}

bool OccluderSkinDatabase::operator==(const OccluderSkinDatabase &o) const
{
    if (!(provenance == o.provenance) || meshes != o.meshes || skipped != o.skipped || skins.size() != o.skins.size())
        return false;
    for (const auto &[mesh, list] : skins) {
        const auto it = o.skins.find(mesh);
        if (it == o.skins.end() || it->second.size() != list.size())
            return false;
        for (std::size_t b = 0; b < list.size(); ++b)
            if (list[b].min != it->second[b].min || list[b].max != it->second[b].max)
                return false;
    }
    return true;
}

void OccluderSkinDatabase::save(const std::string &path) const
{
    DatabaseWriter writer(path, "occluder-skins", 1, provenance);
    std::ostream &out = writer.out();
    auto skins_it = skins.begin();
    auto skipped_it = skipped.begin();
    // By mesh index, skins and skipped lines interleaved.
    while (skins_it != skins.end() || skipped_it != skipped.end()) {
        if (skipped_it == skipped.end() || (skins_it != skins.end() && skins_it->first < skipped_it->first)) {
            out << "skins " << skins_it->first << ' ' << skins_it->second.size();
            for (const Aabb &b : skins_it->second)
                for (const glm::vec3 &corner : {b.min, b.max})
                    out << ' ' << exact_number(corner.x) << ' ' << exact_number(corner.y) << ' '
                        << exact_number(corner.z);
            out << '\n';
            ++skins_it;
        } else {
            // One line, no comment mark: the reason must read back as written.
            std::string reason = skipped_it->second.empty() ? std::string("unknown") : skipped_it->second;
            std::replace_if(reason.begin(), reason.end(), [](char c) { return c == '#' || c == '\n' || c == '\r'; },
                            ' ');
            out << "skipped " << skipped_it->first << ' ' << reason << '\n';
            ++skipped_it;
        }
    }
    writer.finish();
}

OccluderSkinDatabase OccluderSkinDatabase::load(const std::string &path)
{
    DatabaseReader in(path, "occluder-skins", 1, "occluder skin database");
    in.require_algorithm("occluder-skins");
    OccluderSkinDatabase db;
    db.provenance = in.provenance();
    db.meshes = std::uint32_t(in.scene_number("meshes", 0, 0xFFFFFFFFu));
    while (in.next()) {
        const bool skinned = in.record() == "skins";
        if (!skinned && in.record() != "skipped")
            in.fail("unknown record '" + in.record() + "' (a skin database has skins and skipped records)");
        if (db.meshes == 0)
            in.fail("a mesh's record, and the scene has no meshes");
        // A mesh index in range and not yet given a line.
        const auto mesh = std::uint32_t(in.count("the mesh", db.meshes - 1));
        if (db.skins.count(mesh) || db.skipped.count(mesh))
            in.fail("mesh " + std::to_string(mesh) + " repeats");
        if (!skinned) {
            const std::string reason = in.rest();
            if (reason.empty())
                in.fail("skipped wants MESH REASON");
            db.skipped[mesh] = reason;
            continue;
        }
        const std::uint64_t count = in.count("the number of boxes", 1 << 20);
        std::vector<Aabb> &boxes = db.skins[mesh];
        static const char *const names[6] = {"X0", "Y0", "Z0", "X1", "Y1", "Z1"};
        for (std::uint64_t b = 0; b < count; ++b) {
            float v[6];
            for (int i = 0; i < 6; ++i)
                v[i] = in.float_number("box " + std::to_string(b) + " of mesh " + std::to_string(mesh) + ": " +
                                       names[i]);
            const Aabb box{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
            for (int a = 0; a < 3; ++a)
                if (box.min[a] > box.max[a])
                    in.fail("box " + std::to_string(b) + " of mesh " + std::to_string(mesh) +
                            " is empty (min > max along " + "xyz"[a] + ")");
            boxes.push_back(box);
        }
        in.done();
    }
    return db;
}

OccluderSkinDatabase OccluderSkinDatabase::merge(const std::vector<OccluderSkinDatabase> &shards,
                                                 const std::vector<std::string> &names)
{
    if (shards.empty())
        throw std::runtime_error("merge: no shards");
    auto name = [&](std::size_t s) {
        return s < names.size() ? names[s] : "shard " + std::to_string(s + 1);
    };
    OccluderSkinDatabase out = shards.front();
    for (std::size_t s = 1; s < shards.size(); ++s) {
        const OccluderSkinDatabase &d = shards[s];
        if (const std::string diff = d.provenance.difference(out.provenance); !diff.empty())
            throw std::runtime_error("merge: " + name(s) + " was made otherwise than " + name(0) + ": " + diff);
        auto repeat = [&](std::uint32_t mesh) {
            throw std::runtime_error("merge: mesh " + std::to_string(mesh) + " is in " + name(s) +
                                     " and in an earlier shard");
        };
        for (const auto &[mesh, list] : d.skins) {
            if (out.skipped.count(mesh) || !out.skins.emplace(mesh, list).second)
                repeat(mesh);
        }
        for (const auto &[mesh, reason] : d.skipped) {
            if (out.skins.count(mesh) || !out.skipped.emplace(mesh, reason).second)
                repeat(mesh);
        }
    }
    return out;
}

}  // namespace occu
