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
#include "camera/route.h"
#include "cli/arguments.h"
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
    int brick = 8;
    int list_layers = 4;
    int block_x = 3, block_z = 3;
    double step = 0.5;
    bool verify = true;
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
                 "                    [--size PIXELS] [--driver llvmpipe|softpipe] [--brick CELLS]\n"
                 "                    [--list-layers N] [--block BX,BZ] [--step METRES] [--verify on|off]\n"
                 "                    [--png-every N] [--out DIR]\n"
                 "Ray casts a smoke plume (a density grid of 1 m cells over the courtyard of city block BX,BZ,\n"
                 "default 3,3) into the city's frames along a route, through the pixels named by the verbose\n"
                 "occlusion lists of the plume's bricks (Bartz et al. 1998, section 5): --brick is the bricks'\n"
                 "edge in cells (default 8; 128 makes the whole volume one brick), --list-layers the verbose\n"
                 "lists' room in pairs per pixel (a tile that overflows casts its extents rectangle), --step the\n"
                 "ray marching step. With --verify on (the default) every pixel is cast too and the two images\n"
                 "must be equal (exit status 1 otherwise). Prints rays cast, rays saved and times per part.\n"
                 "Writes DIR/frames.csv and, every --png-every cameras (0: none), DIR/raycast-NNNN.png and\n"
                 "DIR/lists-NNNN.png.\n");
    std::exit(error.empty() ? 0 : 2);
}

Options parse(int argc, char **argv)
{
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "-h" || a == "--help")
            usage("");
        if (i + 1 >= argc)
            usage("unknown argument or missing value: '" + a + "'");
        const std::string v = argv[++i];
        try {
            if (a == "--route") o.route = v;
            else if (a == "--frames") o.frames = int(integer_option(a, v, 1, 1000000));
            else if (a == "--size") o.size = int(integer_option(a, v, 1, 8192));
            else if (a == "--driver") o.driver = v;
            else if (a == "--brick") o.brick = int(integer_option(a, v, 1, 1 << 16));
            else if (a == "--list-layers") o.list_layers = int(integer_option(a, v, 1, 1024));
            else if (a == "--step") o.step = number_option(a, v, 1e-3, 1e3, true);
            else if (a == "--png-every") o.png_every = int(integer_option(a, v, 0, 1000000));
            else if (a == "--out") o.out = v;
            else if (a == "--verify") {
                if (v != "on" && v != "off")
                    usage("--verify wants on or off, got '" + v + "'");
                o.verify = v == "on";
            } else if (a == "--block") {
                const auto comma = v.find(',');
                if (comma == std::string::npos)
                    usage("--block wants BX,BZ, got '" + v + "'");
                const CityOptions city;
                o.block_x = int(integer_option(a, v.substr(0, comma), 0, city.blocks_x - 1));
                o.block_z = int(integer_option(a, v.substr(comma + 1), 0, city.blocks_z - 1));
            } else
                usage("unknown argument '" + a + "'");
        } catch (const std::invalid_argument &e) {
            usage(e.what());
        }
    }
    return o;
}

double ms_since(std::chrono::steady_clock::time_point start)
{
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

struct Totals {
    double pixels = 0, box_rays = 0, listed = 0, contributing = 0;
    double draw_ms = 0, read_ms = 0, pass_ms = 0, mask_ms = 0, cast_lists_ms = 0, cast_all_ms = 0;
    long whole_frames = 0, tiles_overflowed = 0, mismatched_pixels = 0, missed_pixels = 0;
};

}  // namespace

int main(int argc, char **argv)
{
    const Options o = parse(argc, argv);
    try {
        gl::select_driver(gl::parse_driver(o.driver));
        const CityOptions city;
        const Scene scene = generate_city(city);
        const Hierarchy hierarchy = Hierarchy::build(scene, HierarchyOptions{});
        const std::vector<Camera> route = make_route(o.route, scene.bounds, city, o.frames, 1.0f);
        const DensityVolume volume = smoke_above_block(o.block_x, o.block_z, city.block_size);

        gl::OffscreenContext ctx(o.size, o.size);
        SceneRenderer renderer(scene, hierarchy);
        OcclusionRayCastingSettings settings;
        settings.brick_cells = o.brick;
        settings.list_layers = o.list_layers;
        OcclusionRayCasting lists(volume, settings);
        RayMarchSettings march;
        march.step = o.step;
        VolumeRayCaster caster(volume, march);

        std::filesystem::create_directories(o.out);
        const std::string csv_path = o.out + "/frames.csv";
        std::ofstream csv(csv_path);
        if (!csv)
            throw std::runtime_error("cannot write '" + csv_path + "'");
        csv << "camera,pixels,box_rays,listed,contributing,whole_frame,tiles_overflowed,pass_ms,mask_ms,"
               "cast_lists_ms,cast_all_ms,mismatched\n";
        std::printf("scene: %zu triangles and a %dx%dx%d-cell volume (block %d,%d); route %s, %zu cameras, %dx%d, %s\n",
                    scene.triangle_count(), volume.cells().x, volume.cells().y, volume.cells().z, o.block_x,
                    o.block_z, o.route.c_str(), route.size(), o.size, o.size, ctx.renderer().c_str());
        const std::vector<Brick> bricks = make_bricks(volume, o.brick);
        std::printf("bricks of %d^3 cells: %zu non-empty of %zu; ray step %g m\n", o.brick,
                    std::size_t(std::count_if(bricks.begin(), bricks.end(), [](const Brick &b) { return !b.empty; })),
                    bricks.size(), o.step);

        const int w = o.size, h = o.size;
        const std::size_t n = std::size_t(w) * std::size_t(h);
        std::vector<std::uint8_t> frame(n * 4), with_lists(n * 4), everywhere(n * 4), contributes;
        Totals t;
        for (std::size_t f = 0; f < route.size(); ++f) {
            const Camera &camera = route[f];
            glViewport(0, 0, w, h);
            auto start = std::chrono::steady_clock::now();
            draw_polygons(renderer, hierarchy, camera);
            glFinish();
            t.draw_ms += ms_since(start);
            start = std::chrono::steady_clock::now();
            const std::vector<double> depth = read_window_depth(w, h);
            std::copy(ctx.pixels(), ctx.pixels() + n * 4, frame.begin());
            t.read_ms += ms_since(start);

            const std::vector<std::uint8_t> &mask = lists.pixels_to_cast(camera, w, h);
            const OcclusionRayCastingStats &s = lists.stats();
            caster.set_view(camera, w, h);
            const CompositeStats cl = composite_volume(caster, w, h, frame.data(), depth, mask.data(), with_lists.data());

            long box_rays = 0;
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x)
                    box_rays += caster.meets_box(x, y, depth[std::size_t(y) * std::size_t(w) + std::size_t(x)]);

            long mismatched = 0, missed = 0;
            double all_ms = 0.0;
            std::size_t contributing = cl.contributing;
            if (o.verify) {
                const CompositeStats ca =
                    composite_volume(caster, w, h, frame.data(), depth, nullptr, everywhere.data(), &contributes);
                all_ms = ca.ms;
                contributing = ca.contributing;
                for (std::size_t i = 0; i < n; ++i) {
                    mismatched += with_lists[4 * i] != everywhere[4 * i] || with_lists[4 * i + 1] != everywhere[4 * i + 1] ||
                                  with_lists[4 * i + 2] != everywhere[4 * i + 2];
                    missed += contributes[i] && !mask[i];
                }
            }
            t.pixels += double(n);
            t.box_rays += double(box_rays);
            t.listed += double(s.listed_pixels);
            t.contributing += double(contributing);
            t.pass_ms += s.pass_ms;
            t.mask_ms += s.mask_ms;
            t.cast_lists_ms += cl.ms;
            t.cast_all_ms += all_ms;
            t.whole_frames += s.whole_frame;
            t.tiles_overflowed += long(s.tiles_overflowed);
            t.mismatched_pixels += mismatched;
            t.missed_pixels += missed;
            csv << f << ',' << n << ',' << box_rays << ',' << s.listed_pixels << ',' << contributing << ','
                << s.whole_frame << ',' << s.tiles_overflowed << ',' << s.pass_ms << ',' << s.mask_ms << ',' << cl.ms
                << ',' << all_ms << ',' << mismatched << '\n';

            if (o.png_every > 0 && f % std::size_t(o.png_every) == 0) {
                char name[64];
                std::snprintf(name, sizeof(name), "/raycast-%04zu.png", f);
                write_png(o.out + name, w, h, with_lists.data());
                std::vector<std::uint8_t> tinted = frame;
                for (std::size_t i = 0; i < n; ++i) {
                    std::uint8_t *p = &tinted[4 * i];
                    if (o.verify && contributes[i])
                        p[0] = p[1] = p[2] = 255;
                    else if (mask[i])
                        p[0] = std::uint8_t(p[0] / 3), p[1] = std::uint8_t(p[1] / 3), p[2] = std::uint8_t(128 + p[2] / 2);
                }
                std::snprintf(name, sizeof(name), "/lists-%04zu.png", f);
                write_png(o.out + name, w, h, tinted.data());
            }
        }

        const double frames = double(route.size());
        std::printf("\nper frame (mean of %zu):\n", route.size());
        std::printf("  pixels %.0f; rays meeting the volume's box %.0f; rays cast through listed pixels %.0f; rays "
                    "that gained something %.0f\n",
                    t.pixels / frames, t.box_rays / frames, t.listed / frames, t.contributing / frames);
        std::printf("  rays saved: %.1f%% of a ray per pixel, %.1f%% of the box-meeting rays\n",
                    100.0 * (1.0 - t.listed / t.pixels), t.box_rays > 0 ? 100.0 * (1.0 - t.listed / t.box_rays) : 0.0);
        std::printf("  ms: polygons %.2f, depth read-back %.2f, verbose pass %.2f, lists to mask %.2f, casting listed "
                    "%.2f",
                    t.draw_ms / frames, t.read_ms / frames, t.pass_ms / frames, t.mask_ms / frames,
                    t.cast_lists_ms / frames);
        if (o.verify)
            std::printf("; casting every pixel %.2f (%.2fx the lists' pass + mask + casting)", t.cast_all_ms / frames,
                        t.cast_all_ms / (t.pass_ms + t.mask_ms + t.cast_lists_ms));
        std::printf("\n  frames cast whole (a brick at the near plane): %ld; tiles overflowed: %ld\n", t.whole_frames,
                    t.tiles_overflowed);
        if (o.verify) {
            std::printf("  verify: %ld pixels differ from casting every pixel, %ld contributing pixels unlisted\n",
                        t.mismatched_pixels, t.missed_pixels);
            if (t.mismatched_pixels || t.missed_pixels) {
                std::fprintf(stderr, "occu-raycast: the lists missed pixels the volume shows\n");
                return 1;
            }
        }
        std::printf("wrote %s\n", csv_path.c_str());
    } catch (const std::exception &e) {
        std::fprintf(stderr, "occu-raycast: %s\n", e.what());
        return 1;
    }
    return 0;
}
