// SPDX-License-Identifier: MIT
// occu-raycast: ray casting in a mixed polygon/volume scene accelerated by
// verbose occlusion lists (Bartz, Meissner and Huettner 1998, section 5,
// "Support for Ray Casting"; applications/ray_casting.h). The scene is the
// city with a smoke plume rising from a block's courtyard (a density
// field on a grid of 1 m cells). At every camera of a route it draws the
// polygons, draws the plume's non-empty bricks in one
// GL_VERBOSE_OCCLUSION_MESAX pass against their depth, and casts rays only
// through the pixels the lists name, each stopping at the polygons' depth;
// with --verify on it also casts a ray through every pixel and checks that
// the two images are equal pixel for pixel. Reports rays cast, rays saved
// and the time of each part, per frame (DIR/frames.csv) and in total.
//
// Writes DIR/raycast-NNNN.png (the composited image) and DIR/lists-NNNN.png
// (the polygon frame with the listed pixels tinted blue, the pixels whose
// rays gained something from the volume white) every --png-every cameras.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "applications/ray_casting.h"
#include "camera/footprint.h"
#include "cli/arguments.h"
#include "evaluation/scene_setup.h"
#include "gl/offscreen_context.h"
#include "image/png.h"
#include "scene/city.h"

namespace {

using namespace occu;

struct Options {
    std::string route = "dense";
    int frames = 12;
    int size = 512;
    std::string driver = "llvmpipe";
    std::vector<int> bricks{8};
    int list_layers = 4;
    int block_x = 3, block_z = 3;
    double step = 0.5;
    int png_every = 6;
    std::string out = "raycast-out";
};

[[noreturn]] void usage(const std::string &error)
{
    std::FILE *to = error.empty() ? stdout : stderr;
    if (!error.empty())
        std::fprintf(to, "occu-raycast: %s\n", error.c_str());
    std::fprintf(to,
                 "usage: occu-raycast [--route dense|street|medium|open|orbit|random:N:SEED|FILE] [--frames N]\n"
                 "                    [--size PIXELS] [--driver llvmpipe|softpipe] [--brick CELLS,...]\n"
                 "                    [--list-layers N] [--block BX,BZ] [--step METRES]\n"
                 "                    [--png-every N] [--out DIR]\n"
                 "Ray casts a smoke plume (a density grid of 1 m cells over the courtyard of city block BX,BZ,\n"
                 "default 3,3) into the city's frames along a route, through the pixels named by the verbose\n"
                 "occlusion lists of the plume's bricks (Bartz et al. 1998, section 5): --brick is the bricks'\n"
                 "edge in cells (default 8; 128 makes the whole volume one brick; a list runs each size on every\n"
                 "frame, interleaved), --list-layers the verbose\n"
                 "lists' room in pairs per pixel (a tile that overflows casts its extents rectangle), --step the\n"
                 "ray marching step. Every frame is also cast through every pixel (the reference: each lists'\n"
                 "image must equal it, exit status 1 otherwise), through the pixels whose ray meets the volume's\n"
                 "box (what a caster without occlusion information does) and, the floor, through the pixels\n"
                 "whose ray gains something (known only from the reference). Prints per variant rays cast,\n"
                 "rays saved and ms per frame.\n"
                 "Writes DIR/frames.csv and, every --png-every cameras (0: none), DIR/raycast-NNNN.png and\n"
                 "DIR/lists-NNNN.png.\n");
    std::exit(error.empty() ? 0 : 2);
}

std::vector<int> brick_sizes(const std::string &option, const std::string &text)
{
    std::vector<int> sizes;
    std::size_t from = 0;
    while (from <= text.size()) {
        const std::size_t comma = std::min(text.find(',', from), text.size());
        sizes.push_back(int(integer_option(option, text.substr(from, comma - from), 1, 1 << 16)));
        from = comma + 1;
    }
    return sizes;
}

Options parse(int argc, char **argv)
{
    Options o;
    for_each_option(argc, argv, usage, [&](const std::string &a, const std::string &v) {
        if (a == "--route") o.route = v;
        else if (a == "--frames") o.frames = int(integer_option(a, v, 1, 1000000));
        else if (a == "--size") o.size = int(integer_option(a, v, 1, 8192));
        else if (a == "--driver") o.driver = v;
        else if (a == "--brick") o.bricks = brick_sizes(a, v);
        else if (a == "--list-layers") o.list_layers = int(integer_option(a, v, 1, 1024));
        else if (a == "--step") o.step = number_option(a, v, 1e-3, 1e3, true);
        else if (a == "--png-every") o.png_every = int(integer_option(a, v, 0, 1000000));
        else if (a == "--out") o.out = v;
        else if (a == "--block") {
            const auto comma = v.find(',');
            if (comma == std::string::npos)
                usage("--block wants BX,BZ, got '" + v + "'");
            const CityOptions city;
            o.block_x = int(integer_option(a, v.substr(0, comma), 0, city.blocks_x - 1));
            o.block_z = int(integer_option(a, v.substr(comma + 1), 0, city.blocks_z - 1));
        } else {
            return false;
        }
        return true;
    });
    return o;
}

double ms_since(std::chrono::steady_clock::time_point start)
{
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// One way of choosing the pixels to cast, summed over the route.
struct Variant {
    std::string name;
    double rays = 0, pass_ms = 0, mask_ms = 0, cast_ms = 0;
    long whole_frames = 0, tiles_overflowed = 0, mismatched = 0, missed = 0;
    double total_ms() const { return pass_ms + mask_ms + cast_ms; }
};

bool same_rgb(const std::vector<std::uint8_t> &a, const std::vector<std::uint8_t> &b, std::size_t i)
{
    return a[4 * i] == b[4 * i] && a[4 * i + 1] == b[4 * i + 1] && a[4 * i + 2] == b[4 * i + 2];
}


}  // namespace

int main(int argc, char **argv)
{
    const Options o = parse(argc, argv);
    try {
        gl::select_driver(gl::parse_driver(o.driver));
        const SceneSetup setup{SceneChoice{}};
        const Scene &scene = setup.scene();
        const Hierarchy &hierarchy = setup.hierarchy();
        const CityOptions city;
        const std::vector<Camera> route = setup.route(o.route, o.frames);
        const DensityVolume volume = smoke_above_block(o.block_x, o.block_z, city.block_size);

        gl::OffscreenContext ctx(o.size, o.size);
        SceneRenderer renderer(scene, hierarchy);
        std::vector<OcclusionRayCasting> lists;
        for (int cells : o.bricks) {
            OcclusionRayCastingSettings settings;
            settings.brick_cells = cells;
            settings.list_layers = o.list_layers;
            lists.emplace_back(volume, settings);
        }
        RayMarchSettings march;
        march.step = o.step;
        VolumeRayCaster caster(volume, march);

        std::filesystem::create_directories(o.out);
        const std::string csv_path = o.out + "/frames.csv";
        std::ofstream csv(csv_path);
        if (!csv)
            throw std::runtime_error("cannot write '" + csv_path + "'");
        csv << "camera,variant,rays,pass_ms,mask_ms,cast_ms,whole_frame,tiles_overflowed,mismatched\n";
        std::printf("scene: %zu triangles and a %dx%dx%d-cell volume (block %d,%d); route %s, %zu cameras, %dx%d, %s; "
                    "ray step %g m\n",
                    scene.triangle_count(), volume.cells().x, volume.cells().y, volume.cells().z, o.block_x,
                    o.block_z, o.route.c_str(), route.size(), o.size, o.size, ctx.renderer().c_str(), o.step);
        for (const OcclusionRayCasting &l : lists) {
            const std::vector<Brick> bricks = make_bricks(volume, l.settings().brick_cells);
            std::printf("bricks of %d^3 cells: %zu non-empty of %zu\n", l.settings().brick_cells,
                        std::size_t(std::count_if(bricks.begin(), bricks.end(), [](const Brick &b) { return !b.empty; })),
                        bricks.size());
        }

        const int w = o.size, h = o.size;
        const std::size_t n = std::size_t(w) * std::size_t(h);
        std::vector<std::uint8_t> frame(n * 4), reference(n * 4), image(n * 4), contributes, box_mask(n);
        Variant every{"every pixel"}, box{"volume box"}, floor{"floor (rays that gain)"};
        std::vector<Variant> by_lists;
        for (int cells : o.bricks)
            by_lists.push_back({"lists, " + std::to_string(cells) + "^3-cell bricks"});
        double draw_ms = 0, read_ms = 0;
        auto row = [&](std::size_t f, const Variant &v, double rays, double pass, double mask, double cast, bool whole,
                       std::size_t overflowed, long mismatched) {
            csv << f << ",\"" << v.name << "\"," << rays << ',' << pass << ',' << mask << ',' << cast << ',' << whole
                << ',' << overflowed << ',' << mismatched << '\n';
        };
        for (std::size_t f = 0; f < route.size(); ++f) {
            const Camera &camera = route[f];
            glViewport(0, 0, w, h);
            auto start = std::chrono::steady_clock::now();
            draw_polygons(renderer, hierarchy, camera);
            glFinish();
            draw_ms += ms_since(start);
            start = std::chrono::steady_clock::now();
            const std::vector<double> depth = read_window_depth(w, h);
            std::copy(ctx.pixels(), ctx.pixels() + n * 4, frame.begin());
            read_ms += ms_since(start);
            caster.set_view(camera, w, h);

            // The reference: a ray through every pixel.
            const CompositeStats all = composite_volume(caster, w, h, frame.data(), depth, nullptr, reference.data(), &contributes);
            every.rays += double(all.rays), every.cast_ms += all.ms;
            row(f, every, double(all.rays), 0, 0, all.ms, false, 0, 0);

            // Rays through the pixels whose ray meets the volume's box in front of the polygons.
            // Only the pixels of the box's footprint can meet it (all of
            // them when it has none: it holds the eye or crosses the near plane).
            start = std::chrono::steady_clock::now();
            std::fill(box_mask.begin(), box_mask.end(), std::uint8_t(0));
            PixelRect near_box{0, 0, w, h};
            if (const auto f = box_footprint(camera.view_projection(), camera.position, volume.box(), w, h))
                near_box = f->rect;
            for (int y = near_box.y0; y < near_box.y1; ++y)
                for (int x = near_box.x0; x < near_box.x1; ++x) {
                    const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
                    box_mask[i] = caster.meets_box(x, y, depth[i]);
                }
            const double box_mask_ms = ms_since(start);
            const CompositeStats boxed = composite_volume(caster, w, h, frame.data(), depth, box_mask.data(), image.data());
            box.rays += double(boxed.rays), box.mask_ms += box_mask_ms, box.cast_ms += boxed.ms;
            row(f, box, double(boxed.rays), 0, box_mask_ms, boxed.ms, false, 0, 0);

            // The floor: rays through the pixels that gain something, known from the reference alone.
            const CompositeStats least = composite_volume(caster, w, h, frame.data(), depth, contributes.data(), image.data());
            floor.rays += double(least.rays), floor.cast_ms += least.ms;
            row(f, floor, double(least.rays), 0, 0, least.ms, false, 0, 0);

            for (std::size_t k = 0; k < lists.size(); ++k) {
                const std::vector<std::uint8_t> &mask = lists[k].pixels_to_cast(camera, w, h);
                const OcclusionRayCastingStats &s = lists[k].stats();
                const CompositeStats cast = composite_volume(caster, w, h, frame.data(), depth, mask.data(), image.data());
                Variant &v = by_lists[k];
                long mismatched = 0, missed = 0;
                for (std::size_t i = 0; i < n; ++i) {
                    mismatched += !same_rgb(image, reference, i);
                    missed += contributes[i] && !mask[i];
                }
                v.rays += double(cast.rays), v.pass_ms += s.pass_ms, v.mask_ms += s.mask_ms, v.cast_ms += cast.ms;
                v.whole_frames += s.whole_frame, v.tiles_overflowed += long(s.tiles_overflowed);
                v.mismatched += mismatched, v.missed += missed;
                row(f, v, double(cast.rays), s.pass_ms, s.mask_ms, cast.ms, s.whole_frame, s.tiles_overflowed, mismatched);

                if (k == 0 && o.png_every > 0 && f % std::size_t(o.png_every) == 0) {
                    char name[64];
                    std::snprintf(name, sizeof(name), "/raycast-%04zu.png", f);
                    write_png(o.out + name, w, h, image.data());
                    std::vector<std::uint8_t> tinted = frame;
                    for (std::size_t i = 0; i < n; ++i) {
                        std::uint8_t *p = &tinted[4 * i];
                        if (contributes[i])
                            p[0] = p[1] = p[2] = 255;
                        else if (mask[i])
                            p[0] = std::uint8_t(p[0] / 3), p[1] = std::uint8_t(p[1] / 3), p[2] = std::uint8_t(128 + p[2] / 2);
                    }
                    std::snprintf(name, sizeof(name), "/lists-%04zu.png", f);
                    write_png(o.out + name, w, h, tinted.data());
                }
            }
        }

        const double frames = double(route.size());
        std::printf("per frame, mean of %zu (polygons %.2f ms, depth read-back %.2f ms, the same for every variant):\n",
                    route.size(), draw_ms / frames, read_ms / frames);
        std::printf("%-28s %10s %9s %9s %9s %9s %9s %8s %8s %s\n", "variant", "rays", "saved %", "pass ms",
                    "mask ms", "cast ms", "total ms", "x floor", "x every", "whole frames / tiles overflowed");
        auto print = [&](const Variant &v, bool lists_row) {
            std::printf("%-28s %10.0f %9.2f %9.2f %9.2f %9.2f %9.2f %8.2f %8.2f", v.name.c_str(), v.rays / frames,
                        100.0 * (1.0 - v.rays / every.rays), v.pass_ms / frames, v.mask_ms / frames, v.cast_ms / frames,
                        v.total_ms() / frames, floor.total_ms() > 0 ? v.total_ms() / floor.total_ms() : 0.0,
                        every.total_ms() > 0 ? v.total_ms() / every.total_ms() : 0.0);
            if (lists_row)
                std::printf(" %ld / %ld", v.whole_frames, v.tiles_overflowed);
            std::printf("\n");
        };
        print(every, false);
        print(box, false);
        for (const Variant &v : by_lists)
            print(v, true);
        print(floor, false);
        bool wrong = false;
        for (const Variant &v : by_lists) {
            std::printf("%s: %ld pixels differ from casting every pixel, %ld pixels the volume shows in unlisted\n",
                        v.name.c_str(), v.mismatched, v.missed);
            wrong |= v.mismatched || v.missed;
        }
        std::printf("wrote %s\n", csv_path.c_str());
        if (wrong) {
            std::fprintf(stderr, "occu-raycast: the lists missed pixels the volume shows in\n");
            return 1;
        }
    } catch (const std::exception &e) {
        std::fprintf(stderr, "occu-raycast: %s\n", e.what());
        return 1;
    }
    return 0;
}
