// SPDX-License-Identifier: MIT
// What a Quake III level holds and what loading it costs: for each level
// named (a .bsp file or PAK.pk3:maps/NAME.bsp), the time from the pk3 to
// the scene (load_scene: the member inflated, the BSP read, patches
// tessellated) and on to the hierarchy the strategies traverse
// (spatial/hierarchy.h), the best of --repeat runs, and the level's
// statistics: triangles, drawn patches, see-through faces and their
// triangles, billboards and hidden faces, leaves (open and solid),
// clusters, spawn points. One CSV row a level on standard output.
//
// Usage: occu-bench-level-load [--patch-segments N] [--repeat N] [--look] LEVEL...
//        (--look: with the textures' pictures and the lightmaps, scene/quake3_look.h)
//        occu-bench-level-load --all-debian   (every level of Debian's openarena-data
//                                              and openarena-088-data pk3s)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <zip.h>

#include "evaluation/allocator.h"
#include "level_statistics.h"
#include "scene/quake3_bsp.h"
#include "scene/scene_file.h"
#include "spatial/hierarchy.h"

using namespace occu;

namespace {

[[noreturn]] void usage(const std::string &error)
{
    std::fprintf(stderr, "occu-bench-level-load: %s\n", error.c_str());
    std::fprintf(stderr, "usage: occu-bench-level-load [--patch-segments N] [--repeat N] [--look] (LEVEL... | --all-debian)\n"
                         "LEVEL: a .bsp file or PAK.pk3:maps/NAME.bsp\n");
    std::exit(2);
}

// Every maps/*.bsp of the pk3s of Debian's OpenArena packages.
std::vector<std::string> debian_levels()
{
    const std::string dir = "/usr/share/games/openarena/baseoa/";
    std::vector<std::string> out;
    for (const char *pak : {"pak1-maps.pk3", "pak6-patch085.pk3", "pak6-patch088.pk3"}) {
        int error = 0;
        zip_t *z = zip_open((dir + pak).c_str(), ZIP_RDONLY, &error);
        if (!z) {
            std::fprintf(stderr, "occu-bench-level-load: cannot open %s%s (tools/deps.sh test installs it)\n",
                         dir.c_str(), pak);
            std::exit(1);
        }
        for (zip_int64_t i = 0; i < zip_get_num_entries(z, 0); ++i) {
            const std::string name = zip_get_name(z, zip_uint64_t(i), 0);
            if (name.rfind("maps/", 0) == 0 && name.size() > 4 && name.compare(name.size() - 4, 4, ".bsp") == 0)
                out.push_back(dir + pak + ":" + name);
        }
        zip_discard(z);
    }
    return out;
}

double ms_since(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char **argv)
{
    control_allocator(AllocatorPolicy::keep_freed);   // as every benchmark (evaluation/allocator.h)
    Quake3Options options;
    int repeat = 3;
    std::vector<std::string> levels;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if ((a == "--patch-segments" || a == "--repeat") && i + 1 < argc) {
            char *end = nullptr;
            const long v = std::strtol(argv[++i], &end, 10);
            if (*end || v < 1 || v > 1000)
                usage(a + " takes a whole number of 1 to 1000");
            (a == "--repeat" ? repeat : options.patch_segments) = int(v);
        } else if (a == "--look") {
            // With what the look needs: texture coordinates, lightmaps,
            // and the textures' pictures found and decoded (scene/quake3_look.h).
            options.look = true;
        } else if (a == "--all-debian") {
            const std::vector<std::string> all = debian_levels();
            levels.insert(levels.end(), all.begin(), all.end());
        } else if (!a.empty() && a[0] == '-') {
            usage("unknown option " + a);
        } else {
            levels.push_back(a);
        }
    }
    if (levels.empty())
        usage("no level named");
    std::printf("level,load_ms,hierarchy_ms,%s\n", LevelStatistics::columns());
    int failures = 0;
    for (const std::string &level_name : levels) {
        double load = 1e30, build = 1e30;
        try {
            Scene scene;
            for (int r = 0; r < repeat; ++r) {
                auto t0 = std::chrono::steady_clock::now();
                scene = load_scene(level_name, nullptr, options);
                load = std::min(load, ms_since(t0));
                t0 = std::chrono::steady_clock::now();
                const Hierarchy h = Hierarchy::build(scene);
                build = std::min(build, ms_since(t0));
            }
            std::printf("%s,%.1f,%.1f,%s\n", level_name.c_str(), load, build, level_statistics(scene).row().c_str());
        } catch (const std::exception &e) {
            std::fprintf(stderr, "occu-bench-level-load: %s\n", e.what());
            ++failures;
        }
    }
    return failures ? 1 : 0;
}
