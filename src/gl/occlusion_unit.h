// SPDX-License-Identifier: MIT
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
//
// Asynchronous passes (GL_MESAX_occlusion_unit_async, issue 14): a pass that
// ends without waiting and is read when its records are ready, so that the
// CPU goes on drawing while the rasterizer answers (the reason every
// occlusion API since NV_occlusion_query has query objects):
//
//   gl::AsyncOcclusionPass pass(unit);          // a pass object, reusable
//   pass.begin(gl::OcclusionMode::brief, tiles);
//   draw_proxies();
//   pass.end();                                 // never waits
//   ... draw other things ...
//   if (pass.available()) use(pass.records()); // records() waits when it must
//
// Where the context lacks the extension the same class runs on the
// synchronous RenderMode path (end() reads the records at once, available()
// is always true): the results are the same, only the wait is not hidden.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "geometry/pixel_rect.h"
#include "gl/gl_headers.h"
#include "GL/mesax_occlusion_unit.h"

namespace occu::gl {

// brief: counts, extents and depth range; verbose: and the pixels that
// passed; conservative: only whether some fragment passed
// (GL_MESAX_occlusion_unit_conservative, spec/MESAX_occlusion_unit_conservative.txt):
// the record's nohc is 1 where some fragment may have passed (the GL may
// say so where none did, never the opposite) and 0 where none did, its
// other fields are those of an empty record. On a context without that
// extension a conservative pass runs as a brief one, which answers the
// same question exactly.
enum class OcclusionMode { brief, verbose, conservative };

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
    // True when the current context advertises GL_MESAX_occlusion_unit_async.
    static bool async_available();
    // True when the current context advertises GL_MESAX_occlusion_unit_conservative.
    static bool conservative_available();
    // Whether asynchronous passes and conditional tile rendering use the
    // extension's entry points (the context advertises it and
    // `allow_native_async` was true) or the emulation on RenderMode.
    // Chosen once, when the unit is made.
    bool native_async() const { return GenPasses_ != nullptr; }

    // `allow_native_async` false forces the emulation even where the
    // extension is present (tests compare the two paths).
    explicit OcclusionUnit(bool allow_native_async);

private:
    friend class OcclusionPass;
    friend class AsyncOcclusionPass;
    friend class ConditionalTileRender;
    friend class RecordBuffers;
    void validate(std::size_t tiles, std::size_t list_sizes) const;
    // The GL's render mode for `mode` on this context.
    GLenum render_mode(OcclusionMode mode) const;
    bool conservative_ = false;
    PFNGLSCISSORSMESAXPROC Scissors_ = nullptr;
    PFNGLOCCLUSIONBUFFERSMESAXPROC OcclusionBuffers_ = nullptr;
    int max_tiles_ = 0;
    // GL_MESAX_occlusion_unit_async, or all null (the emulation).
    PFNGLGENOCCLUSIONPASSESMESAXPROC GenPasses_ = nullptr;
    PFNGLDELETEOCCLUSIONPASSESMESAXPROC DeletePasses_ = nullptr;
    PFNGLBEGINOCCLUSIONPASSMESAXPROC BeginPass_ = nullptr;
    PFNGLENDOCCLUSIONPASSMESAXPROC EndPass_ = nullptr;
    PFNGLGETOCCLUSIONPASSIVMESAXPROC GetPassiv_ = nullptr;
    PFNGLBEGINCONDITIONALRENDEROCCLUSIONTILEMESAXPROC BeginConditionalTile_ = nullptr;
    PFNGLENDCONDITIONALRENDEROCCLUSIONTILEMESAXPROC EndConditionalTile_ = nullptr;
};

// Client memory for a pass's records (spec, section 5.X): one allocation,
// tile i's buffer at its own offset, and the records read from it.
class RecordBuffers {
public:
    RecordBuffers() = default;
    RecordBuffers(OcclusionMode mode, std::size_t tiles, const std::vector<std::size_t> &list_pixels);
    // glOcclusionBuffersMESAX with these buffers.
    void bind(const OcclusionUnit &unit) const;
    // Reads every tile's record from the words the GL wrote.
    void parse(std::vector<OcclusionRecord> &records) const;
    std::size_t tiles() const { return tiles_; }

private:
    OcclusionMode mode_ = OcclusionMode::brief;
    std::size_t tiles_ = 0;
    std::unique_ptr<GLuint[]> words_;   // every tile's record; the GL writes what is read, no need to clear
    std::vector<std::size_t> offsets_;  // tile i's record is words_[offsets_[i], offsets_[i + 1])
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
    bool ended_ = false;
    RecordBuffers buffers_;
    std::vector<OcclusionRecord> records_;
};

// A named pass (GL_MESAX_occlusion_unit_async), begun and ended without
// waiting, its records read when they are ready; one object serves pass
// after pass. With the extension: glBeginOcclusionPassMESAX captures the
// tiles and this object's buffers, glEndOcclusionPassMESAX returns at once,
// glGetOcclusionPassivMESAX asks (RESULT_AVAILABLE, never waits) and reads
// (RESULT, waits). Emulated: begin() is glRenderMode(mode), end() is
// glRenderMode(GL_RENDER), which waits and writes the records, and
// available() is then always true. Only one pass (named or not) is open at
// a time, as the spec has it: RENDER_MODE is the pass's mode until end().
class AsyncOcclusionPass {
public:
    explicit AsyncOcclusionPass(const OcclusionUnit &unit);
    ~AsyncOcclusionPass();
    AsyncOcclusionPass(const AsyncOcclusionPass &) = delete;
    AsyncOcclusionPass &operator=(const AsyncOcclusionPass &) = delete;

    void begin(OcclusionMode mode, const std::vector<PixelRect> &tiles, const std::vector<std::size_t> &list_pixels = {});
    // Leaves the occlusion mode without waiting for the records.
    void end();
    // The records of the last pass are ready (never waits). False before
    // the first end().
    bool available();
    // The last pass's records, one per tile (one in all without tiles);
    // waits for them when they are not ready.
    const std::vector<OcclusionRecord> &records();
    // The pass object's GL name; 0 when emulated.
    GLuint name() const { return name_; }
    bool native() const { return name_ != 0; }

private:
    friend class ConditionalTileRender;
    const OcclusionUnit &unit_;
    GLuint name_ = 0;
    enum class State { idle, open, ended, read } state_ = State::idle;
    RecordBuffers buffers_;
    std::vector<OcclusionRecord> records_;
};

// Conditional rendering on one tile (glBeginConditionalRenderOcclusionTileMESAX):
// the draws issued while it lives execute only when tile `tile` of `pass`
// had NOHC > min_nohc and NOHC > min_ratio * PHC; with wait false an
// unavailable result draws (GL_QUERY_NO_WAIT). With the extension the GL
// decides, where the result is, and draws() is true; emulated, the CPU
// reads the record (the emulated pass's records are always ready) and
// draws() says whether to issue the draws at all. Callers write
//   { ConditionalTileRender c(pass, i, 0, 0.0f, false); if (c.draws()) draw(); }
class ConditionalTileRender {
public:
    ConditionalTileRender(AsyncOcclusionPass &pass, std::size_t tile, std::uint32_t min_nohc, float min_ratio,
                          bool wait);
    ~ConditionalTileRender();
    ConditionalTileRender(const ConditionalTileRender &) = delete;
    ConditionalTileRender &operator=(const ConditionalTileRender &) = delete;
    bool draws() const { return draws_; }

    // The condition on a record, as the spec states it (the emulation's decision).
    static bool passes(const OcclusionRecord &r, std::uint32_t min_nohc, float min_ratio)
    {
        return r.nohc > min_nohc && double(r.nohc) > double(min_ratio) * double(r.phc);
    }

private:
    const OcclusionUnit &unit_;
    bool native_ = false, draws_ = true;
};

}  // namespace occu::gl
