// GL_MESAX_occlusion_unit as the library uses it (spec/MESAX_occlusion_unit.txt):
// the one owner of its entry points, tiles, buffers and records. Every user
// (strategies, preprocessing, benchmarks) runs passes through it.
//
//   gl::OcclusionUnit unit;                     // throws without the extension
//   gl::OcclusionPass pass(unit, gl::OcclusionMode::brief, tiles);
//   draw_proxies();                             // depth tested, nothing written
//   for (const gl::OcclusionRecord &r : pass.end())
//       r.nohc ... r.phc ... r.pixels ...
//
// Tiles are in window pixels of the framebuffer bound when the pass begins
// (geometry/pixel_rect.h conventions); no tiles means one tile over the
// scissor box or the viewport. A pass draws nothing and leaves the
// framebuffer as it was (the spec's "the framebuffer is not modified").
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "geometry/pixel_rect.h"
#include "gl/gl_headers.h"
#include "GL/mesax_occlusion_unit.h"

namespace occu::gl {

enum class OcclusionMode { brief, verbose };

// One tile's record (spec, section 5.X: words 0..7, then the pixel list).
struct OcclusionRecord {
    std::uint32_t nohc = 0;   // non-occlusion hit count: fragments that passed the depth test
    std::uint32_t phc = 0;    // projection hit count: fragments that entered the tests
    // Extents of the fragments that passed: window x, y and depth mapped to
    // [0, 2^32 - 1]. When nohc is 0 the minima are 0xFFFFFFFF and the maxima 0.
    std::uint32_t x_min = 0, x_max = 0, y_min = 0, y_max = 0, z_min = 0, z_max = 0;
    // Verbose passes: the window positions of the fragments that passed,
    // one per fragment; `overflowed` when the tile's buffer held only the first.
    struct Pixel {
        std::uint32_t x, y;
    };
    std::vector<Pixel> pixels;
    bool overflowed = false;
};

class OcclusionUnit {
public:
    // Needs a current context that advertises GL_MESAX_occlusion_unit;
    // throws std::runtime_error naming what is missing otherwise.
    OcclusionUnit();
    // True when the current context advertises the extension.
    static bool available();
    // GL_MAX_OCCLUSION_TILES_MESAX.
    int max_tiles() const { return max_tiles_; }

private:
    friend class OcclusionPass;
    PFNGLSCISSORSMESAXPROC Scissors_ = nullptr;
    PFNGLOCCLUSIONBUFFERSMESAXPROC OcclusionBuffers_ = nullptr;
    int max_tiles_ = 0;
};

// One pass: begins on construction, ends with end() (or, unread, when it
// goes out of scope). `list_pixels` sizes the verbose lists: one count
// for every tile, or one per tile.
class OcclusionPass {
public:
    OcclusionPass(const OcclusionUnit &unit, OcclusionMode mode, const std::vector<PixelRect> &tiles,
                  const std::vector<std::size_t> &list_pixels = {});
    ~OcclusionPass();
    OcclusionPass(const OcclusionPass &) = delete;
    OcclusionPass &operator=(const OcclusionPass &) = delete;

    // Leaves the occlusion mode and returns one record per tile (one in all
    // without tiles).
    const std::vector<OcclusionRecord> &end();

private:
    const OcclusionUnit &unit_;
    OcclusionMode mode_;
    std::size_t tiles_;
    bool ended_ = false;
    std::unique_ptr<GLuint[]> words_;   // every tile's record; the GL writes what is read, no need to clear
    std::vector<std::size_t> offsets_;  // tile i's record is words_[offsets_[i], offsets_[i + 1])
    std::vector<OcclusionRecord> records_;
};

}  // namespace occu::gl
