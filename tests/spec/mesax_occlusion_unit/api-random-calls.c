/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit and GL_MESAX_occlusion_unit_async under random
 * use: OU_RANDOM_CALLS calls (default 30,000) from a fixed seed, each checked
 * against a model of the GL's state built from the specs (a failure prints
 * the call's number, so it repeats).
 *
 * The calls: ScissorsMESAX, OcclusionBuffersMESAX and RenderMode; the pass
 * objects (Gen, Delete, Begin, End, GetOcclusionPassiv) and conditional
 * rendering on a tile; every primitive type (points, lines, line strips and
 * loops, triangles, strips, fans, quads, quad strips, polygons, and the
 * adjacency types where the context has geometry shaders) through Begin/End
 * and DrawArrays; pixel rectangles (DrawPixels of colour, depth and stencil,
 * Bitmap, CopyPixels of colour, depth and stencil) and Clear; framebuffer
 * objects made, bound for drawing and reading, attached, reallocated and
 * deleted, in and out of passes; display lists compiled (COMPILE and
 * COMPILE_AND_EXECUTE, with draws and the unit's commands between NewList
 * and EndList) and called; ARB_occlusion_query SAMPLES_PASSED queries and
 * NV_conditional_render interleaved with all of it. Arguments come from the
 * valid and the invalid (negative and too large counts, negative tile
 * sizes, NULL arrays, sizes below 8, unknown modes, calls inside an
 * occlusion mode, the pass's framebuffer changed).
 *
 * The oracles (MESAX_occlusion_unit section 5.X unless said otherwise):
 *  - every error is the one the Errors sections give for the call in the
 *    model's state, and an error changes no state (a framebuffer or
 *    renderbuffer the GL refused to delete still exists);
 *  - every record buffer holds a sentinel before every call and is checked
 *    after it: only RenderMode leaving an occlusion mode and
 *    GetOcclusionPassivMESAX reading a pass write, they write the record
 *    of every tile of the pass (a record still holding the sentinel is a
 *    failure), nothing past a record, and no buffer of a tile not in
 *    effect; EndOcclusionPassMESAX, AVAILABLE and errors write nothing;
 *  - each record is well formed: NOHC <= PHC, the empty extents with NOHC
 *    0, else extents inside the tile and the pass's framebuffer; a verbose
 *    list holds min(NOHC, room) pairs inside the extents and a terminator
 *    exactly when it overflows, and RenderMode returns the number of
 *    tiles that overflowed;
 *  - tiles of the same pass agree: a tile inside another (both cut to the
 *    framebuffer) has no larger counts, equal tiles equal records;
 *  - a pass in which no command ran that could produce a fragment (only
 *    Clear, state, lists compiled with COMPILE, draws that conditional
 *    rendering must discard) has NOHC and PHC 0 in every tile;
 *  - a SAMPLES_PASSED query begun and ended in a pass around all of its
 *    drawing commands counts what NOHC counts in a tile that covers the
 *    framebuffer (single-sampled framebuffers: a fragment is a sample; the
 *    section on occlusion queries);
 *  - RENDER_MODE, OCCLUSION_TILE_COUNT_MESAX, CURRENT_OCCLUSION_PASS_MESAX
 *    and both framebuffer bindings are the model's after every call.
 *
 * Subtests:
 *   walk-reaches-occlusion-passes  passes ended, records checked (the walk
 *                                  is not vacuous)
 *   walk-reaches-pass-objects      pass objects read, conditional renderings
 *   walk-reaches-new-commands      framebuffer changes refused in a pass and
 *                                  made outside one, lists compiled and
 *                                  called in passes, queries compared with
 *                                  NOHC, empty passes checked, every
 *                                  primitive type and pixel rectangle drawn
 *   errors-match-the-spec          every call's error as the model predicts
 *   state-matches-the-model        the state above after every call
 *   records-written-as-specified   the sentinel checks
 *   records-well-formed            the form, tile and verbose-list checks
 *   counts-agree                   tiles with each other, empty passes,
 *                                  queries with NOHC
 *
 * With -base-extension-only the walk makes no call of
 * GL_MESAX_occlusion_unit_async (its share goes to primitives) and needs
 * only GL_MESAX_occlusion_unit, so that the series' base part runs it
 * (tools/check-mesa-series.sh); walk-reaches-pass-objects is then not a
 * subtest, and CURRENT_OCCLUSION_PASS_MESAX is not read.
 */
#include "ou_util.h"

#define W 32
#define H 32
#define WORDS 64
/* The walk's tile and buffer counts run from -1 to MAX_TILES, past the
 * spec's minimum of 64: whether 65 and 66 are errors depends on the
 * implementation's limit, which the expectations use (occu's drivers have
 * 4096); counts just past that limit are tried too (limit_probe). */
#define MAX_TILES 66
#define DEFAULT_CALLS 30000ul

static unsigned long long rng = 0x2026112912345ull;

static unsigned
next(unsigned n)
{
    rng = rng * 6364136223846793005ull + 1442695040888963407ull;
    return (unsigned)(rng >> 33) % n;
}

/* GL entry points past OpenGL 1.1. */
static PFNGLGENFRAMEBUFFERSPROC GenFramebuffers;
static PFNGLDELETEFRAMEBUFFERSPROC DeleteFramebuffers;
static PFNGLISFRAMEBUFFERPROC IsFramebuffer;
static PFNGLBINDFRAMEBUFFERPROC BindFramebuffer;
static PFNGLGENRENDERBUFFERSPROC GenRenderbuffers;
static PFNGLDELETERENDERBUFFERSPROC DeleteRenderbuffers;
static PFNGLISRENDERBUFFERPROC IsRenderbuffer;
static PFNGLBINDRENDERBUFFERPROC BindRenderbuffer;
static PFNGLRENDERBUFFERSTORAGEPROC RenderbufferStorage;
static PFNGLFRAMEBUFFERRENDERBUFFERPROC FramebufferRenderbuffer;
static PFNGLCHECKFRAMEBUFFERSTATUSPROC CheckFramebufferStatus;
static PFNGLGENQUERIESPROC GenQueries;
static PFNGLBEGINQUERYPROC BeginQuery;
static PFNGLENDQUERYPROC EndQuery;
static PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv;
static PFNGLBEGINCONDITIONALRENDERPROC BeginConditionalRender;
static PFNGLENDCONDITIONALRENDERPROC EndConditionalRender;
static PFNGLWINDOWPOS3FPROC WindowPos3f;

/* Record buffers: buffer k is always storage[k]; every word holds the
 * sentinel except while a writing call is checked. */
static GLuint storage[MAX_TILES][WORDS];

static void
fill_storage(void)
{
    for (int k = 0; k < MAX_TILES; ++k)
        ou_fill(storage[k], WORDS);
}

/* The model: what the specs say the GL's state is. */
static GLenum mode = GL_RENDER;
static int tiles = 0, buffers = 0;
static GLint tile_set[MAX_TILES][4];
static GLsizei buffer_size[MAX_TILES];

static bool errors_ok = true, state_ok = true, written_ok = true, records_ok = true, counts_ok = true;
static unsigned passes_ended, records_checked, pass_objects_read, conditions_begun;
static unsigned fb_refused, fb_changed, lists_called_in_pass, compiled_in_pass, queries_compared, empty_passes;
static unsigned nv_conditions, pixel_rects, primitives_drawn[14];

/* What one pass took when it began, and what the model knows of it. */
struct pass {
    int n;                     /* tiles in effect */
    GLenum mode;               /* BRIEF or VERBOSE */
    GLsizei sizes[MAX_TILES];
    GLint rect[MAX_TILES][4];
    int fb_w, fb_h;            /* the pass's draw framebuffer */
    unsigned serial;
    unsigned fragment_commands; /* commands run in it that may produce fragments */
    bool query_matches;        /* a query began before its first fragment command */
    unsigned query_end_commands; /* ... and ended after this many */
    GLuint query_samples;
    bool known;                /* records read: nohc and phc below */
    GLuint nohc[MAX_TILES], phc[MAX_TILES];
};
static struct pass active;     /* the pass in progress, either kind */
static unsigned pass_serial;

/* GL_MESAX_occlusion_unit_async: a pool of names, what each holds, the pass
 * in progress and conditional rendering on a tile. */
#define NAMES 6
static struct ou_async_functions a;
static bool base_extension_only;
static GLuint names[NAMES];
static enum { UNUSED, NO_PASS, IN_PROGRESS, ENDED } held[NAMES];
static struct pass pass_of[NAMES];
static int current = -1;     /* index of the pass object in progress, or -1 */
static int cond = -1;        /* index of conditional rendering's pass, or -1 */
static GLuint cond_tile, cond_min_nohc;
static float cond_ratio;
static GLenum cond_mode;

/* Framebuffer objects: slots of a framebuffer with its own colour and
 * depth renderbuffers. Slot names are 0 when free; a renderbuffer whose
 * name was deleted may still be attached (the object lives on). */
#define FBOS 3
static struct fbo {
    GLuint name;
    GLuint rb[2];          /* colour, depth; 0 once the name is deleted */
    int rb_w[2], rb_h[2];
    bool attached[2];      /* the slot's renderbuffers attached to it */
} fbo[FBOS];
static int draw_fb = -1, read_fb = -1;   /* slot bound, -1 for the default framebuffer */

/* Display lists and queries. */
#define LISTS 4
static GLuint list_base;
static bool list_fragments[LISTS];   /* the list holds a command that may produce fragments */
static int compiling = -1;
static GLenum compile_mode;
static bool compiling_fragments;
#define QUERIES 3
static GLuint query_name[QUERIES];
static bool query_begun[QUERIES], query_known[QUERIES];
static GLuint query_result[QUERIES];
static int query_active = -1, nv_cond = -1;
static GLenum nv_mode;
static unsigned query_begin_serial, query_begin_commands;

static bool adjacency;

static bool
in_occlusion(void)
{
    return mode == GL_BRIEF_OCCLUSION_MESAX || mode == GL_VERBOSE_OCCLUSION_MESAX;
}

/* A name to call with: one of the pool's (possibly deleted), 0 or one never generated. */
static GLuint
pick_name(int *index)
{
    const unsigned r = next(NAMES + 2);
    *index = r < NAMES ? (int)r : -1;
    return r < NAMES ? names[r] : r == NAMES ? 0 : 0x7fff0000u;
}

static bool
is_pass(int index)
{
    return index >= 0 && held[index] != UNUSED && names[index] != 0;
}

static void
fail_errors(unsigned i, const char *call, GLenum got, GLenum expected)
{
    if (errors_ok)
        printf("call %u %s: error 0x%x, the spec says 0x%x (mode 0x%x, %d tiles, %d buffers, draw fb %d, list %d)\n",
               i, call, got, expected, mode, tiles, buffers, draw_fb, compiling);
    errors_ok = false;
}

static void
expect(GLenum expected, const char *call, unsigned i)
{
    const GLenum got = glGetError();
    if (got != expected)
        fail_errors(i, call, got, expected);
}

/* Where the spec gives two errors for the call and says not which comes first. */
static void
expect_either(GLenum one, GLenum other, const char *call, unsigned i)
{
    const GLenum got = glGetError();
    if (got != one && got != other)
        fail_errors(i, call, got, one);
}

/* Any one of the n errors (none when n is 0). */
static void
expect_any(const GLenum *errors, int n, const char *call, unsigned i)
{
    const GLenum got = glGetError();
    bool ok = n == 0 ? got == GL_NO_ERROR : false;
    for (int k = 0; k < n; ++k)
        ok = ok || got == errors[k];
    if (!ok)
        fail_errors(i, call, got, n ? errors[0] : GL_NO_ERROR);
}

static void
count_failure(unsigned i, const char *what)
{
    if (counts_ok)
        printf("call %u: %s\n", i, what);
    counts_ok = false;
}

/* The draw framebuffer's size and completeness, as the model has it. */
static void
framebuffer_size(int slot, int *w, int *h)
{
    *w = W;
    *h = H;
    if (slot < 0)
        return;
    *w = *h = 1 << 30;   /* an object's size is its smallest attachment's */
    for (int r = 0; r < 2; ++r)
        if (fbo[slot].attached[r]) {
            if (fbo[slot].rb_w[r] < *w) *w = fbo[slot].rb_w[r];
            if (fbo[slot].rb_h[r] < *h) *h = fbo[slot].rb_h[r];
        }
}

static bool
has_depth(int slot)
{
    return slot < 0 || fbo[slot].attached[1];
}

/* ---- conditions: does the spec make this conditional command a no-op? ---- */

static bool
tile_condition_known_false(void)
{
    if (cond < 0 || cond_mode != GL_QUERY_WAIT || !pass_of[cond].known)
        return false;
    const double nohc = pass_of[cond].nohc[cond_tile], phc = pass_of[cond].phc[cond_tile];
    return !(nohc > cond_min_nohc && nohc > (double)cond_ratio * phc);
}

static bool
nv_condition_known_false(void)
{
    return nv_cond >= 0 && query_known[nv_cond] && query_result[nv_cond] == 0 &&
           (nv_mode == GL_QUERY_WAIT || nv_mode == GL_QUERY_BY_REGION_WAIT);
}

/* A command that may produce fragments has been issued: executed now unless
 * compiled with COMPILE, counted unless a condition must discard it. */
static void
fragments_issued(bool conditional)
{
    if (compiling >= 0) {
        compiling_fragments = true;
        if (compile_mode == GL_COMPILE) {
            if (in_occlusion())
                ++compiled_in_pass;
            return;
        }
    }
    if (conditional && (tile_condition_known_false() || nv_condition_known_false()))
        return;
    if (in_occlusion())
        ++active.fragment_commands;
}

/* ---- passes ---- */

static void
take_pass(GLenum m)
{
    active.n = tiles > 0 ? tiles : 1;
    active.mode = m;
    for (int k = 0; k < active.n; ++k) {
        active.sizes[k] = buffer_size[k];
        if (tiles > 0)
            memcpy(active.rect[k], tile_set[k], sizeof(active.rect[k]));
        else {   /* the default tile: the viewport, the whole window (the walk never changes it) */
            const GLint whole[4] = {0, 0, W, H};
            memcpy(active.rect[k], whole, sizeof(whole));
        }
    }
    framebuffer_size(draw_fb, &active.fb_w, &active.fb_h);
    active.serial = ++pass_serial;
    active.fragment_commands = 0;
    active.query_matches = false;
    active.known = false;
}

/* A tile cut to the framebuffer: x0, y0, x1, y1 (exclusive), in 64 bits. */
static void
clip_tile(const struct pass *p, int k, long long c[4])
{
    const GLint *r = p->rect[k];
    c[0] = r[0] > 0 ? r[0] : 0;
    c[1] = r[1] > 0 ? r[1] : 0;
    c[2] = (long long)r[0] + r[2] < p->fb_w ? (long long)r[0] + r[2] : p->fb_w;
    c[3] = (long long)r[1] + r[3] < p->fb_h ? (long long)r[1] + r[3] : p->fb_h;
    if (c[2] < c[0]) c[2] = c[0];
    if (c[3] < c[1]) c[3] = c[1];
}

/* Checks the buffers a writing call left: the records of pass p (or none,
 * p NULL) and the sentinel everywhere else; returns the overflow count the
 * records imply, and refills the buffers with the sentinel. */
static int
check_written(const struct pass *p, unsigned i, const char *call)
{
    int overflowed = 0;
    const int n = p ? p->n : 0;
    for (int k = 0; k < MAX_TILES; ++k) {
        const GLuint *r = storage[k];
        int end = 0;   /* words of the record */
        if (k < n) {
            ++records_checked;
            end = OU_BRIEF_SIZE;
            for (int w = 0; w < OU_YMAX + 1; ++w)   /* counts and x, y are small: never the sentinel */
                if (r[w] == OU_SENTINEL) {
                    if (written_ok)
                        printf("call %u %s: tile %d's record not written (word %d holds the sentinel)\n", i, call,
                               k, w);
                    written_ok = false;
                }
            long long c[4];
            clip_tile(p, k, c);
            bool ok = r[OU_NOHC] <= r[OU_PHC];
            if (r[OU_NOHC] == 0)
                ok = ok && r[OU_XMIN] == OU_EMPTY_MIN && r[OU_XMAX] == OU_EMPTY_MAX && r[OU_YMIN] == OU_EMPTY_MIN &&
                     r[OU_YMAX] == OU_EMPTY_MAX && r[OU_ZMIN] == OU_EMPTY_MIN && r[OU_ZMAX] == OU_EMPTY_MAX;
            else
                ok = ok && r[OU_XMIN] <= r[OU_XMAX] && r[OU_YMIN] <= r[OU_YMAX] && r[OU_ZMIN] <= r[OU_ZMAX] &&
                     r[OU_XMIN] >= c[0] && r[OU_XMAX] < c[2] && r[OU_YMIN] >= c[1] && r[OU_YMAX] < c[3];
            if (p->mode == GL_VERBOSE_OCCLUSION_MESAX) {
                const long long size = p->sizes[k], nohc = r[OU_NOHC];
                long long pairs;
                if (8 + 2 * nohc <= size) {
                    pairs = nohc;
                    end = 8 + 2 * (int)nohc;
                } else {   /* overflowed: the pairs that fit, then the terminator */
                    ++overflowed;
                    pairs = size > 8 ? (size - 9) / 2 : 0;
                    end = 8 + 2 * (int)pairs + (size > 8 ? 1 : 0);
                    if (size > 8)
                        ok = ok && r[end - 1] == 0xffffffffu;
                }
                for (long long q = 0; q < pairs; ++q) {
                    const GLuint x = r[8 + 2 * q], y = r[9 + 2 * q];
                    ok = ok && x >= r[OU_XMIN] && x <= r[OU_XMAX] && y >= r[OU_YMIN] && y <= r[OU_YMAX];
                }
            }
            if (!ok && records_ok) {
                printf("call %u %s: tile %d (%d,%d %dx%d, framebuffer %dx%d, size %d, mode 0x%x): NOHC %u PHC %u x "
                       "%u..%u y %u..%u z 0x%x..0x%x\n",
                       i, call, k, p->rect[k][0], p->rect[k][1], p->rect[k][2], p->rect[k][3], p->fb_w, p->fb_h,
                       p->sizes[k], p->mode, r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7]);
                records_ok = false;
                if (draw_fb >= 0)
                    printf("draw framebuffer slot %d: colour %dx%d %s, depth %dx%d %s\n", draw_fb,
                           fbo[draw_fb].rb_w[0], fbo[draw_fb].rb_h[0], fbo[draw_fb].attached[0] ? "attached" : "detached",
                           fbo[draw_fb].rb_w[1], fbo[draw_fb].rb_h[1], fbo[draw_fb].attached[1] ? "attached" : "detached");
            }
        }
        for (int w = end; w < WORDS; ++w)
            if (r[w] != OU_SENTINEL) {
                if (written_ok)
                    printf("call %u %s: buffer %d word %d written (0x%x) past the record's %d words (%d tiles of "
                           "the pass)\n",
                           i, call, k, w, r[w], end, n);
                written_ok = false;
                break;
            }
    }
    fill_storage();
    return overflowed;
}

/* The checks between tiles, against the pass's commands and its query,
 * once its records are read (records in storage, before the refill). */
static void
check_counts(struct pass *p, unsigned i)
{
    for (int k = 0; k < p->n; ++k) {
        p->nohc[k] = storage[k][OU_NOHC];
        p->phc[k] = storage[k][OU_PHC];
    }
    p->known = true;
    if (p->fragment_commands == 0) {
        ++empty_passes;
        for (int k = 0; k < p->n; ++k)
            if (p->nohc[k] != 0 || p->phc[k] != 0) {
                printf("tile %d: NOHC %u PHC %u in a pass without a fragment-producing command\n", k, p->nohc[k],
                       p->phc[k]);
                count_failure(i, "an empty pass counted fragments");
                break;
            }
    }
    for (int k = 0; k < p->n; ++k) {
        long long c[4], d[4];
        clip_tile(p, k, c);
        if (p->query_matches && p->query_end_commands == p->fragment_commands && c[0] == 0 && c[1] == 0 && c[2] == p->fb_w && c[3] == p->fb_h) {
            ++queries_compared;
            if (p->nohc[k] != p->query_samples) {
                printf("tile %d covers the %dx%d framebuffer: NOHC %u, SAMPLES_PASSED %u\n", k, p->fb_w, p->fb_h,
                       p->nohc[k], p->query_samples);
                count_failure(i, "NOHC differs from SAMPLES_PASSED over the same draws");
            }
        }
        for (int j = 0; j < p->n; ++j) {
            if (j == k)
                continue;
            clip_tile(p, j, d);
            const bool k_empty = c[0] == c[2] || c[1] == c[3];
            const bool inside = k_empty || (c[0] >= d[0] && c[1] >= d[1] && c[2] <= d[2] && c[3] <= d[3]);
            if (inside && (p->nohc[k] > p->nohc[j] || p->phc[k] > p->phc[j])) {
                printf("tile %d (%lld,%lld..%lld,%lld) lies in tile %d (%lld,%lld..%lld,%lld): NOHC %u > %u or PHC "
                       "%u > %u\n",
                       k, c[0], c[1], c[2], c[3], j, d[0], d[1], d[2], d[3], p->nohc[k], p->nohc[j], p->phc[k],
                       p->phc[j]);
                count_failure(i, "a tile inside another counts more");
            }
            if (!k_empty && c[0] == d[0] && c[1] == d[1] && c[2] == d[2] && c[3] == d[3] &&
                memcmp(storage[k], storage[j], OU_BRIEF_SIZE * sizeof(GLuint)) != 0) {
                printf("tiles %d and %d cover the same pixels, their records differ\n", k, j);
                count_failure(i, "equal tiles, different records");
            }
        }
    }
}

/* ---- the state the walk checks after every call ---- */

static void
check_state(unsigned i)
{
    GLint got_mode = 0, got_tiles = -1, got_current = -1, got_draw = -1, got_read = -1;
    glGetIntegerv(GL_RENDER_MODE, &got_mode);
    glGetIntegerv(GL_OCCLUSION_TILE_COUNT_MESAX, &got_tiles);
    if (base_extension_only)
        got_current = 0;
    else
        glGetIntegerv(GL_CURRENT_OCCLUSION_PASS_MESAX, &got_current);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &got_draw);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &got_read);
    const GLint model_current = current >= 0 ? (GLint)names[current] : 0;
    const GLint model_draw = draw_fb >= 0 ? (GLint)fbo[draw_fb].name : (GLint)piglit_winsys_fbo;
    const GLint model_read = read_fb >= 0 ? (GLint)fbo[read_fb].name : (GLint)piglit_winsys_fbo;
    if (((GLenum)got_mode != mode || got_tiles != tiles || got_current != model_current || got_draw != model_draw ||
         got_read != model_read) &&
        state_ok) {
        printf("call %u: RENDER_MODE 0x%x, tiles %d, current pass %d, draw framebuffer %d, read framebuffer %d; the "
               "model says 0x%x, %d, %d, %d, %d\n",
               i, got_mode, got_tiles, got_current, got_draw, got_read, mode, tiles, model_current, model_draw,
               model_read);
        state_ok = false;
    }
    for (int k = 0; k < MAX_TILES; ++k)
        for (int w = 0; w < WORDS; ++w)
            if (storage[k][w] != OU_SENTINEL) {
                if (written_ok)
                    printf("call %u: buffer %d word %d written (0x%x) by a call that writes no records\n", i, k, w,
                           storage[k][w]);
                written_ok = false;
                fill_storage();
                return;
            }
}

static void
check_fbo_objects(unsigned i, const char *call)
{
    for (int s = 0; s < FBOS; ++s) {
        bool ok = !fbo[s].name || IsFramebuffer(fbo[s].name);
        for (int r = 0; r < 2; ++r)
            ok = ok && (!fbo[s].rb[r] || IsRenderbuffer(fbo[s].rb[r]));
        if (!ok && state_ok) {
            printf("call %u %s: framebuffer slot %d (%u, renderbuffers %u %u) lost an object the model keeps\n", i,
                   call, s, fbo[s].name, fbo[s].rb[0], fbo[s].rb[1]);
            state_ok = false;
        }
    }
}

/* ---- the calls ---- */

static void call_begin_query(unsigned i);
static void call_end_query(unsigned i);

/* ScissorsMESAX or OcclusionBuffersMESAX with one more than the limit,
 * valid otherwise: INVALID_VALUE (or INVALID_OPERATION in a pass), nothing
 * changed. */
static void
limit_probe(unsigned i, int max_tiles, bool scissors)
{
    static GLint *t;
    static GLuint **p;
    static GLsizei *s;
    const int count = max_tiles + 1;
    if (!t) {
        t = malloc(sizeof(*t) * 4 * count);
        p = malloc(sizeof(*p) * count);
        s = malloc(sizeof(*s) * count);
        if (!t || !p || !s)
            piglit_report_result(PIGLIT_FAIL);
        for (int k = 0; k < count; ++k) {
            const GLint tile[4] = {k % 40, k % 30, 2, 2};
            memcpy(&t[4 * k], tile, sizeof(tile));
            p[k] = storage[k % MAX_TILES];
            s[k] = OU_BRIEF_SIZE;
        }
    }
    if (scissors)
        ScissorsMESAX(count, t);
    else
        OcclusionBuffersMESAX(count, s, p);
    expect(in_occlusion() ? GL_INVALID_OPERATION : GL_INVALID_VALUE,
           scissors ? "ScissorsMESAX(limit + 1)" : "OcclusionBuffersMESAX(limit + 1)", i);
}

static void
call_scissors(unsigned i, int max_tiles)
{
    static GLint t[4 * 70];
    if (next(50) == 0) {
        limit_probe(i, max_tiles, true);
        return;
    }
    const int count = (int)next(MAX_TILES + 2) - 1;   /* -1 .. MAX_TILES */
    bool negative = false;
    for (int k = 0; k < (count > 0 ? count : 0); ++k) {
        const unsigned shape = next(8);
        if (shape == 0 && k > 0) {   /* the tile before it again: equal tiles */
            memcpy(&t[4 * k], &t[4 * (k - 1)], 4 * sizeof(GLint));
        } else if (shape == 1) {     /* covering the framebuffer */
            const GLint cover[4] = {-(GLint)next(4), -(GLint)next(4), 44 + (GLint)next(2000000000), 44 + (GLint)next(100)};
            memcpy(&t[4 * k], cover, sizeof(cover));
        } else {
            t[4 * k] = (GLint)next(48) - 8;
            t[4 * k + 1] = (GLint)next(48) - 8;
            t[4 * k + 2] = next(20) == 0 ? -1 : (GLint)next(40);
            t[4 * k + 3] = (GLint)next(40);
        }
        negative = negative || t[4 * k + 2] < 0;
    }
    const bool null_tiles = count > 0 && next(10) == 0;
    ScissorsMESAX(count, null_tiles ? NULL : t);
    GLenum e = GL_NO_ERROR;
    if (in_occlusion())
        e = GL_INVALID_OPERATION;
    else if (count < 0 || count > max_tiles || null_tiles || negative)
        e = GL_INVALID_VALUE;
    else {
        tiles = count;
        memcpy(tile_set, t, (size_t)count * 4 * sizeof(GLint));
    }
    expect(e, "ScissorsMESAX", i);
}

static void
call_buffers(unsigned i, int max_tiles)
{
    static GLuint *p[70];
    static GLsizei s[70];
    if (next(50) == 0) {
        limit_probe(i, max_tiles, false);
        return;
    }
    const int count = (int)next(MAX_TILES + 2) - 1;
    bool bad = false;
    for (int k = 0; k < (count > 0 ? count : 0); ++k) {
        p[k] = next(30) == 0 ? NULL : storage[k];
        s[k] = next(30) == 0 ? 7 : 8 + (GLsizei)next(WORDS - 8 + 1);
        bad = bad || !p[k] || s[k] < 8;
    }
    const bool null_arrays = count > 0 && next(10) == 0;
    OcclusionBuffersMESAX(count, null_arrays ? NULL : s, null_arrays ? NULL : p);
    GLenum e = GL_NO_ERROR;
    if (in_occlusion())
        e = GL_INVALID_OPERATION;
    else if (count < 0 || count > max_tiles || null_arrays || bad)
        e = GL_INVALID_VALUE;
    else {
        buffers = count;
        for (int k = 0; k < count; ++k)
            buffer_size[k] = s[k];
    }
    expect(e, "OcclusionBuffersMESAX", i);
}

static void
call_render_mode(unsigned i)
{
    /* RENDER more often than the others: pass objects begin only from it. */
    static const GLenum modes[] = {GL_RENDER, GL_RENDER, GL_RENDER, GL_SELECT, GL_FEEDBACK,
                                   GL_BRIEF_OCCLUSION_MESAX, GL_VERBOSE_OCCLUSION_MESAX,
                                   GL_BRIEF_OCCLUSION_MESAX, GL_VERBOSE_OCCLUSION_MESAX, 0x1234};
    static GLuint select_buffer[64];
    static GLfloat feedback_buffer[256];
    if (mode != GL_SELECT)
        glSelectBuffer(64, select_buffer);
    if (mode != GL_FEEDBACK)
        glFeedbackBuffer(256, GL_3D, feedback_buffer);
    expect(GL_NO_ERROR, "SelectBuffer/FeedbackBuffer", i);
    const GLenum m = modes[next(10)];
    const int in_effect = tiles > 0 ? tiles : 1;
    if (in_occlusion() && current < 0 && compiling < 0 && query_active >= 0 && next(2)) {
        call_end_query(i);
        check_state(i);
    }
    const GLint returned = glRenderMode(m);
    GLenum e = GL_NO_ERROR;
    if (m == 0x1234)
        e = GL_INVALID_ENUM;
    else if (current >= 0)   /* a pass object's pass ends only with EndOcclusionPassMESAX */
        e = GL_INVALID_OPERATION;
    else if ((m == GL_BRIEF_OCCLUSION_MESAX || m == GL_VERBOSE_OCCLUSION_MESAX) && buffers < in_effect)
        e = GL_INVALID_OPERATION;
    expect(e, "RenderMode", i);
    if (e != GL_NO_ERROR)
        return;
    if (in_occlusion()) {
        check_counts(&active, i);
        const int overflowed = check_written(&active, i, "RenderMode");
        ++passes_ended;
        if (returned != overflowed && records_ok) {
            printf("call %u: RenderMode returned %d, %d tiles overflowed\n", i, returned, overflowed);
            records_ok = false;
        }
    }
    mode = m;
    if (in_occlusion()) {
        take_pass(m);
        if (compiling < 0 && next(2))   /* a query around the whole pass: NOHC's oracle */
            call_begin_query(i);
    }
}

static void
call_gen_pass(unsigned i)
{
    for (int k = 0; k < NAMES; ++k)
        if (held[k] == UNUSED) {
            a.GenOcclusionPasses(1, &names[k]);
            expect(GL_NO_ERROR, "GenOcclusionPassesMESAX", i);
            held[k] = NO_PASS;
            /* A deleted name the GL gives out again is this slot's now. */
            for (int j = 0; j < NAMES; ++j)
                if (j != k && held[j] == UNUSED && names[j] == names[k])
                    names[j] = 0;
            return;
        }
}

static void
call_delete_pass(unsigned i)
{
    int k;
    const GLuint name = pick_name(&k);
    const bool negative = next(20) == 0;
    a.DeleteOcclusionPasses(negative ? -1 : 1, &name);
    GLenum e = GL_NO_ERROR;
    if (negative)
        e = GL_INVALID_VALUE;
    else if (is_pass(k) && (k == current || k == cond))
        e = GL_INVALID_OPERATION;
    else if (is_pass(k))
        held[k] = UNUSED;
    expect(e, "DeleteOcclusionPassesMESAX", i);
}

static void
call_begin_pass(unsigned i)
{
    static const GLenum modes[] = {GL_BRIEF_OCCLUSION_MESAX, GL_VERBOSE_OCCLUSION_MESAX, GL_RENDER};
    const GLenum m = modes[next(3)];
    int k;
    const GLuint name = pick_name(&k);
    const int in_effect = tiles > 0 ? tiles : 1;
    a.BeginOcclusionPass(m, name);
    GLenum e = GL_NO_ERROR;
    if (m == GL_RENDER)
        e = GL_INVALID_ENUM;
    else if (!is_pass(k) || mode != GL_RENDER || k == cond || buffers < in_effect)
        e = GL_INVALID_OPERATION;
    expect(e, "BeginOcclusionPassMESAX", i);
    if (e == GL_NO_ERROR) {
        mode = m;
        current = k;
        held[k] = IN_PROGRESS;
        take_pass(m);
        if (compiling < 0 && next(2))
            call_begin_query(i);
    }
}

static void
call_end_pass(unsigned i)
{
    if (current >= 0 && compiling < 0 && query_active >= 0 && next(2)) {
        call_end_query(i);
        check_state(i);
    }
    a.EndOcclusionPass();
    expect(current >= 0 ? GL_NO_ERROR : GL_INVALID_OPERATION, "EndOcclusionPassMESAX", i);
    if (current >= 0) {
        held[current] = ENDED;
        pass_of[current] = active;
        current = -1;
        mode = GL_RENDER;
        ++passes_ended;
    }
    /* EndOcclusionPassMESAX writes nothing: check_state sees the sentinel. */
}

static void
call_get_pass(unsigned i)
{
    static const GLenum pnames[] = {GL_OCCLUSION_PASS_RESULT_MESAX, GL_OCCLUSION_PASS_RESULT_AVAILABLE_MESAX,
                                    GL_OCCLUSION_PASS_RESULT_NO_WAIT_MESAX, GL_QUERY_RESULT};
    const GLenum pname = pnames[next(4)];
    int k;
    const GLuint name = pick_name(&k);
    GLint value = -5;
    a.GetOcclusionPassiv(name, pname, &value);
    GLenum e = GL_NO_ERROR;
    if (pname == GL_QUERY_RESULT)
        e = GL_INVALID_ENUM;
    else if (!is_pass(k) || held[k] != ENDED)
        e = GL_INVALID_OPERATION;
    expect(e, "GetOcclusionPassivMESAX", i);
    if (e != GL_NO_ERROR && value != -5 && errors_ok) {
        printf("call %u GetOcclusionPassivMESAX: an error, yet params written (%d)\n", i, value);
        errors_ok = false;
    }
    if (e == GL_NO_ERROR && pname == GL_OCCLUSION_PASS_RESULT_AVAILABLE_MESAX && value != GL_TRUE &&
        value != GL_FALSE && errors_ok) {
        printf("call %u: availability %d\n", i, value);
        errors_ok = false;
    }
    const bool wrote = e == GL_NO_ERROR && (pname == GL_OCCLUSION_PASS_RESULT_MESAX ||
                                            (pname == GL_OCCLUSION_PASS_RESULT_NO_WAIT_MESAX && value != -5));
    if (wrote) {
        check_counts(&pass_of[k], i);
        const int overflowed = check_written(&pass_of[k], i, "GetOcclusionPassivMESAX");
        if (value != overflowed && records_ok) {
            printf("call %u: GetOcclusionPassivMESAX returned %d, %d tiles overflowed\n", i, value, overflowed);
            records_ok = false;
        }
        ++pass_objects_read;
    }
}

static void
call_begin_tile_condition(unsigned i)
{
    static const GLenum modes[] = {GL_QUERY_WAIT, GL_QUERY_WAIT, GL_QUERY_NO_WAIT, GL_QUERY_BY_REGION_WAIT};
    static const float ratios[] = {0.0f, 0.0f, 0.25f, 1.0f, -1.0f, 1e30f};
    const GLenum m = modes[next(4)];
    int k;
    const GLuint name = pick_name(&k);
    const GLuint tile = next(4);
    const GLuint min_nohc = next(3) ? 0 : next(8);
    const float ratio = ratios[next(6)];
    a.BeginConditionalRenderOcclusionTile(name, tile, min_nohc, ratio, m);
    /* Where several errors apply the spec does not say which is generated. */
    GLenum applicable[3];
    int n = 0;
    if (cond >= 0 || nv_cond >= 0 || !is_pass(k) || held[k] != ENDED)
        applicable[n++] = GL_INVALID_OPERATION;
    if (m == GL_QUERY_BY_REGION_WAIT)
        applicable[n++] = GL_INVALID_ENUM;
    if (ratio < 0.0f || (is_pass(k) && held[k] == ENDED && (int)tile >= pass_of[k].n))
        applicable[n++] = GL_INVALID_VALUE;
    const GLenum e = n ? applicable[0] : GL_NO_ERROR;
    expect_any(applicable, n, "BeginConditionalRenderOcclusionTileMESAX", i);
    if (e == GL_NO_ERROR) {
        cond = k;
        cond_tile = tile;
        cond_min_nohc = min_nohc;
        cond_ratio = ratio;
        cond_mode = m;
        ++conditions_begun;
    }
}

static void
call_end_tile_condition(unsigned i)
{
    a.EndConditionalRenderOcclusionTile();
    expect(cond >= 0 ? GL_NO_ERROR : GL_INVALID_OPERATION, "EndConditionalRenderOcclusionTileMESAX", i);
    cond = -1;
}

/* Every primitive type, through Begin/End or DrawArrays, 1 to 9 vertices
 * (too few for a primitive draws nothing). */
static void
call_primitive(unsigned i)
{
    static const GLenum types[] = {GL_POINTS,     GL_LINES,          GL_LINE_STRIP,     GL_LINE_LOOP,
                                   GL_TRIANGLES,  GL_TRIANGLE_STRIP, GL_TRIANGLE_FAN,   GL_QUADS,
                                   GL_QUAD_STRIP, GL_POLYGON,        GL_LINES_ADJACENCY, GL_LINE_STRIP_ADJACENCY,
                                   GL_TRIANGLES_ADJACENCY, GL_TRIANGLE_STRIP_ADJACENCY};
    const unsigned t = next(adjacency ? 14 : 10);
    static GLfloat v[9][3];
    int count = 1 + (int)next(9);
    if (compiling >= 0) {
        /* Whole primitives only in display lists: Mesa 22.3.6 writes past
         * its index buffer compiling some incomplete ones (vbo_save's
         * compile_vertex_list, upstream code; AddressSanitizer reports it,
         * docs/api-walk.md). */
        static const int least[] = {1, 2, 2, 2, 3, 3, 3, 4, 4, 3, 4, 4, 6, 6};
        static const int multiple[] = {1, 2, 1, 1, 3, 1, 1, 4, 2, 1, 4, 1, 6, 2};
        if (count < least[t])
            count = least[t];
        count -= count % multiple[t];
    }
    for (int k = 0; k < count; ++k) {
        v[k][0] = (float)next(48 * 4) / 4.0f - 8.0f;
        v[k][1] = (float)next(48 * 4) / 4.0f - 8.0f;
        v[k][2] = (float)next(101) / 100.0f;
    }
    if (next(2)) {
        glBegin(types[t]);
        for (int k = 0; k < count; ++k)
            glVertex3fv(v[k]);
        glEnd();
    } else {
        glEnableClientState(GL_VERTEX_ARRAY);
        glVertexPointer(3, GL_FLOAT, 0, v);
        glDrawArrays(types[t], 0, count);
        glDisableClientState(GL_VERTEX_ARRAY);
    }
    ++primitives_drawn[t];
    fragments_issued(true);
    expect(GL_NO_ERROR, "draw", i);
}

/* DrawPixels (colour, depth, stencil), Bitmap and CopyPixels (colour,
 * depth, stencil) at a random raster position. */
static void
call_pixel_rectangle(unsigned i)
{
    static GLubyte pixels[8 * 8 * 4];
    static GLfloat depths[8 * 8];
    static const GLubyte bitmap[8] = {0xff, 0x81, 0xa5, 0x18, 0x18, 0xa5, 0x81, 0xff};
    const int x = (int)next(40) - 4, y = (int)next(40) - 4;
    const int w = 1 + (int)next(8), h = 1 + (int)next(8);
    for (int k = 0; k < 64; ++k)
        depths[k] = (float)next(101) / 100.0f;
    /* WindowPos, not a Bitmap of 0 x 0 after RasterPos, reaches positions
     * left of and below the window: Mesa 22.3.6 compiles no such Bitmap
     * into a display list (OUT_OF_MEMORY, upstream code; docs/api-walk.md). */
    WindowPos3f((float)x, (float)y, (float)next(101) / 100.0f);
    GLenum e = GL_NO_ERROR;
    bool fragments = true;
    switch (next(7)) {
    case 0:
    case 1:
        glDrawPixels(w, h, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
        break;
    case 2:
        glDrawPixels(w, h, GL_DEPTH_COMPONENT, GL_FLOAT, depths);
        if (!has_depth(draw_fb))
            e = GL_INVALID_OPERATION;
        break;
    case 3:   /* stencil: only the default framebuffer has one */
        glDrawPixels(w, h, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, pixels);
        if (draw_fb >= 0)
            e = GL_INVALID_OPERATION;
        break;
    case 4:
        glBitmap(8, 8, 0, 0, 0, 0, bitmap);
        break;
    case 5: {
        static const GLenum types[] = {GL_COLOR, GL_COLOR, GL_DEPTH, GL_STENCIL};
        const GLenum type = types[next(4)];
        glCopyPixels((GLint)next(24), (GLint)next(24), w, h, type);
        if (type == GL_DEPTH && !(has_depth(draw_fb) && has_depth(read_fb)))
            e = GL_INVALID_OPERATION;
        if (type == GL_STENCIL && !(draw_fb < 0 && read_fb < 0))
            e = GL_INVALID_OPERATION;
        break;
    }
    default:   /* Clear: no fragments, and no effect in a pass */
        glClearDepth((float)next(101) / 100.0f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        fragments = false;
        break;
    }
    if (fragments) {
        ++pixel_rects;
        if (e == GL_NO_ERROR || compiling >= 0)
            fragments_issued(true);
    }
    /* Compiled, the command's error is the list's when it is called. */
    expect(compiling >= 0 && compile_mode == GL_COMPILE ? GL_NO_ERROR : e, "pixel rectangle", i);
    if (compiling >= 0 && e != GL_NO_ERROR)
        compiling_fragments = true;
}

static void
call_depth_mask(unsigned i)
{
    /* Depth writes in RENDER mode make later passes see different depths. */
    glDepthMask(next(2) ? GL_TRUE : GL_FALSE);
    expect(GL_NO_ERROR, "DepthMask", i);
}

/* ---- framebuffer objects ---- */

static bool
fb_fixed(int slot)
{
    /* In an occlusion mode the pass's draw framebuffer may not change. */
    return in_occlusion() && slot == draw_fb && slot >= 0;
}

static void
rb_storage(GLuint rb, GLenum format, int *w, int *h)
{
    static const int sizes[][2] = {{32, 32}, {16, 24}, {24, 16}, {40, 40}, {8, 8}};
    const unsigned s = next(5);
    BindRenderbuffer(GL_RENDERBUFFER, rb);
    RenderbufferStorage(GL_RENDERBUFFER, format, sizes[s][0], sizes[s][1]);
    *w = sizes[s][0];
    *h = sizes[s][1];
}

static const GLenum rb_format[2] = {GL_RGBA8, GL_DEPTH_COMPONENT24};
static const GLenum rb_attachment[2] = {GL_COLOR_ATTACHMENT0, GL_DEPTH_ATTACHMENT};

/* A new framebuffer object, made through the read binding: allowed in a
 * pass, as it changes no framebuffer bound for drawing. */
static void
call_make_fbo(unsigned i)
{
    int s = -1;
    for (int k = 0; k < FBOS; ++k)
        if (!fbo[k].name)
            s = k;
    if (s < 0)
        return;
    struct fbo *f = &fbo[s];
    GenFramebuffers(1, &f->name);
    GenRenderbuffers(2, f->rb);
    for (int r = 0; r < 2; ++r)
        rb_storage(f->rb[r], rb_format[r], &f->rb_w[r], &f->rb_h[r]);
    BindFramebuffer(GL_READ_FRAMEBUFFER, f->name);
    read_fb = s;
    for (int r = 0; r < 2; ++r) {
        FramebufferRenderbuffer(GL_READ_FRAMEBUFFER, rb_attachment[r], GL_RENDERBUFFER, f->rb[r]);
        f->attached[r] = true;
    }
    expect(GL_NO_ERROR, "making a framebuffer object", i);
    if (CheckFramebufferStatus(GL_READ_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE && state_ok) {
        printf("call %u: a new framebuffer object of RGBA8 and DEPTH_COMPONENT24 is incomplete\n", i);
        state_ok = false;
    }
    ++fb_changed;
}

static int
pick_fb(void)
{
    const int s = (int)next(FBOS + 1) - 1;
    return s >= 0 && !fbo[s].name ? -1 : s;
}

static void
call_bind_fbo(unsigned i)
{
    static const GLenum targets[] = {GL_FRAMEBUFFER, GL_DRAW_FRAMEBUFFER, GL_READ_FRAMEBUFFER};
    const GLenum target = targets[next(3)];
    const int s = pick_fb();
    BindFramebuffer(target, s >= 0 ? fbo[s].name : piglit_winsys_fbo);
    GLenum e = GL_NO_ERROR;
    if (target != GL_READ_FRAMEBUFFER && in_occlusion() && s != draw_fb)
        e = GL_INVALID_OPERATION;
    expect(e, "BindFramebuffer", i);
    if (e != GL_NO_ERROR) {
        ++fb_refused;
        return;
    }
    if (target != GL_READ_FRAMEBUFFER)
        draw_fb = s;
    if (target != GL_DRAW_FRAMEBUFFER)
        read_fb = s;
    ++fb_changed;
}

static void
call_delete_fbo(unsigned i)
{
    const int s = pick_fb();
    if (s < 0)
        return;
    DeleteFramebuffers(1, &fbo[s].name);
    if (fb_fixed(s)) {
        expect(GL_INVALID_OPERATION, "DeleteFramebuffers of the pass's framebuffer", i);
        ++fb_refused;
        check_fbo_objects(i, "DeleteFramebuffers");
        return;
    }
    expect(GL_NO_ERROR, "DeleteFramebuffers", i);
    /* The GL binds framebuffer 0 in place of a deleted bound one; the
     * window's is piglit_winsys_fbo (piglit's FBO under -fbo), bound back
     * here. The draw framebuffer of a pass cannot be deleted (above), and
     * the read framebuffer may change in a pass. */
    if (draw_fb == s) {
        draw_fb = -1;
        if (piglit_winsys_fbo)
            BindFramebuffer(GL_DRAW_FRAMEBUFFER, piglit_winsys_fbo);
    }
    if (read_fb == s) {
        read_fb = -1;
        if (piglit_winsys_fbo)
            BindFramebuffer(GL_READ_FRAMEBUFFER, piglit_winsys_fbo);
    }
    expect(GL_NO_ERROR, "BindFramebuffer of the window's in place of a deleted one", i);
    /* Its renderbuffers go too: the walk's slots own them. */
    for (int r = 0; r < 2; ++r)
        if (fbo[s].rb[r])
            DeleteRenderbuffers(1, &fbo[s].rb[r]);
    expect(GL_NO_ERROR, "DeleteRenderbuffers of a deleted framebuffer's", i);
    memset(&fbo[s], 0, sizeof(fbo[s]));
    ++fb_changed;
}

static void
call_delete_renderbuffer(unsigned i)
{
    const int s = pick_fb();
    const int r = (int)next(2);
    if (s < 0 || !fbo[s].rb[r])
        return;
    /* A colour attachment removed from a bound framebuffer would make it
     * incomplete (drawing errors the walk does not model): colour
     * renderbuffers are deleted only where that cannot happen. */
    const bool bound = s == draw_fb || s == read_fb;
    const bool refused = fb_fixed(s) && fbo[s].attached[r];
    if (r == 0 && bound && !refused)
        return;
    DeleteRenderbuffers(1, &fbo[s].rb[r]);
    if (refused) {
        expect(GL_INVALID_OPERATION, "DeleteRenderbuffers of an image of the pass's framebuffer", i);
        ++fb_refused;
        check_fbo_objects(i, "DeleteRenderbuffers");
        return;
    }
    expect(GL_NO_ERROR, "DeleteRenderbuffers", i);
    if (bound)   /* detached from the bound framebuffers only; elsewhere the object lives on */
        fbo[s].attached[r] = false;
    fbo[s].rb[r] = 0;
    ++fb_changed;
}

static void
call_renderbuffer_storage(unsigned i)
{
    const int s = pick_fb();
    const int r = (int)next(2);
    if (s < 0 || !fbo[s].rb[r])
        return;
    int w, h;
    rb_storage(fbo[s].rb[r], rb_format[r], &w, &h);
    if (fb_fixed(s) && fbo[s].attached[r]) {
        expect(GL_INVALID_OPERATION, "RenderbufferStorage of an image of the pass's framebuffer", i);
        ++fb_refused;
        return;
    }
    expect(GL_NO_ERROR, "RenderbufferStorage", i);
    fbo[s].rb_w[r] = w;
    fbo[s].rb_h[r] = h;
    ++fb_changed;
}

/* Attaches or detaches the depth renderbuffer, or attaches the colour one
 * again, of the framebuffer bound to a target. */
static void
call_attach(unsigned i)
{
    static const GLenum targets[] = {GL_FRAMEBUFFER, GL_DRAW_FRAMEBUFFER, GL_READ_FRAMEBUFFER};
    const GLenum target = targets[next(3)];
    const int s = target == GL_READ_FRAMEBUFFER ? read_fb : draw_fb;
    const int r = (int)next(2);
    const bool detach = r == 1 && next(2);
    GLuint rb = 0;
    /* Under piglit with -fbo the window's framebuffer is piglit's FBO, whose
     * attachments can change: only a window-system framebuffer refuses. */
    if (s < 0 && piglit_winsys_fbo)
        return;
    if (s >= 0 && !detach) {
        rb = fbo[s].rb[r];
        if (!rb)
            return;
    }
    FramebufferRenderbuffer(target, rb_attachment[r], GL_RENDERBUFFER, rb);
    GLenum e = GL_NO_ERROR;
    if (s < 0)
        e = GL_INVALID_OPERATION;   /* the default framebuffer has no attachments to change */
    else if (fb_fixed(s))
        e = GL_INVALID_OPERATION;
    expect(e, "FramebufferRenderbuffer", i);
    if (e != GL_NO_ERROR) {
        if (s >= 0)
            ++fb_refused;
        return;
    }
    fbo[s].attached[r] = !detach;
    ++fb_changed;
}

/* ---- display lists ---- */

static void
call_new_list(unsigned i)
{
    const int k = (int)next(LISTS + 1) - 1;   /* -1: list 0 */
    const GLenum m = next(2) ? GL_COMPILE : GL_COMPILE_AND_EXECUTE;
    glNewList(k >= 0 ? list_base + (GLuint)k : 0, m);
    GLenum e = GL_NO_ERROR;
    if (compiling >= 0)
        e = GL_INVALID_OPERATION;
    else if (k < 0)
        e = GL_INVALID_VALUE;
    if (compiling >= 0 && k < 0)
        expect_either(GL_INVALID_OPERATION, GL_INVALID_VALUE, "NewList", i);
    else
        expect(e, "NewList", i);
    if (e == GL_NO_ERROR) {
        compiling = k;
        compile_mode = m;
        compiling_fragments = false;
    }
}

static void
call_end_list(unsigned i)
{
    glEndList();
    expect(compiling >= 0 ? GL_NO_ERROR : GL_INVALID_OPERATION, "EndList", i);
    if (compiling >= 0)
        list_fragments[compiling] = compiling_fragments;
    compiling = -1;
}

static void
call_call_list(unsigned i)
{
    const int k = (int)next(LISTS);
    /* No list calls another: lists calling lists that are recompiled later
     * would nest to Mesa's depth limit, their draws multiplying. */
    if (compiling >= 0)
        return;
    /* Mesa 22.3.6 crashes calling a list of three or more primitive modes in
     * SELECT or FEEDBACK mode (st_feedback_draw_vbo_multi_mode, upstream
     * code; docs/api-walk.md): the walk calls lists in the other modes. */
    if (mode == GL_SELECT || mode == GL_FEEDBACK)
        return;
    glCallList(list_base + (GLuint)k);
    if (list_fragments[k]) {
        if (in_occlusion())
            ++lists_called_in_pass;
        /* What the list holds is counted as if issued directly (section 5.4 edit). */
        fragments_issued(true);
    }
    /* A list's pixel rectangles give the errors of the state it is called
     * in (a depth rectangle where no depth buffer is attached), which the
     * model does not follow: cleared here, checked nowhere. */
    (void)i;
    glGetError();
}

/* ---- occlusion queries and NV_conditional_render ---- */

static void
call_begin_query(unsigned i)
{
    const int k = (int)next(QUERIES);
    if (k == nv_cond)   /* a query conditional rendering uses is not begun again under it */
        return;
    BeginQuery(GL_SAMPLES_PASSED, query_name[k]);
    expect(query_active >= 0 ? GL_INVALID_OPERATION : GL_NO_ERROR, "BeginQuery", i);
    if (query_active >= 0)
        return;
    query_active = k;
    query_begun[k] = true;
    query_known[k] = false;
    query_begin_serial = in_occlusion() ? active.serial : 0;
    query_begin_commands = in_occlusion() ? active.fragment_commands : 1;
}

static void
call_end_query(unsigned i)
{
    EndQuery(GL_SAMPLES_PASSED);
    expect(query_active >= 0 ? GL_NO_ERROR : GL_INVALID_OPERATION, "EndQuery", i);
    if (query_active < 0)
        return;
    const int k = query_active;
    query_active = -1;
    GetQueryObjectuiv(query_name[k], GL_QUERY_RESULT, &query_result[k]);
    expect(GL_NO_ERROR, "GetQueryObjectuiv", i);
    query_known[k] = true;
    /* Begun in this pass before any of its fragment commands: it counts what
     * the pass counts if none follow before the pass ends. */
    if (in_occlusion() && query_begin_serial == active.serial && query_begin_commands == 0) {
        active.query_matches = true;
        active.query_samples = query_result[k];
        active.query_end_commands = active.fragment_commands;
    } else if (in_occlusion()) {
        active.query_matches = false;
    }
}

static void
call_begin_nv_condition(unsigned i)
{
    static const GLenum modes[] = {GL_QUERY_WAIT, GL_QUERY_NO_WAIT, GL_QUERY_BY_REGION_WAIT,
                                   GL_QUERY_BY_REGION_NO_WAIT, 0x1234};
    const int k = (int)next(QUERIES);
    const GLenum m = modes[next(5)];
    BeginConditionalRender(query_name[k], m);
    /* A query of no target yet, or in progress, is INVALID_OPERATION
     * (NV_conditional_render); so is either kind of conditional rendering
     * in progress (MESAX_occlusion_unit_async). */
    GLenum applicable[2];
    int n = 0;
    if (nv_cond >= 0 || cond >= 0 || !query_begun[k] || k == query_active)
        applicable[n++] = GL_INVALID_OPERATION;
    if (m == 0x1234)
        applicable[n++] = GL_INVALID_ENUM;
    const GLenum e = n ? applicable[0] : GL_NO_ERROR;
    expect_any(applicable, n, "BeginConditionalRender", i);
    if (e == GL_NO_ERROR) {
        nv_cond = k;
        nv_mode = m;
        ++nv_conditions;
    }
}

static void
call_end_nv_condition(unsigned i)
{
    EndConditionalRender();
    expect(nv_cond >= 0 ? GL_NO_ERROR : GL_INVALID_OPERATION, "EndConditionalRender", i);
    nv_cond = -1;
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 10;
    config.window_width = W;
    config.window_height = H;
    config.window_visual = PIGLIT_GL_VISUAL_RGBA | PIGLIT_GL_VISUAL_DEPTH | PIGLIT_GL_VISUAL_STENCIL;
    config.khr_no_error_support = PIGLIT_HAS_ERRORS;

PIGLIT_GL_TEST_CONFIG_END

enum piglit_result
piglit_display(void)
{
    /* piglit_init reports the result. */
    return PIGLIT_FAIL;
}

void
piglit_init(int argc, char **argv)
{
    /* Taken out of argv: piglit's own options are the rest. */
    int kept = 1;
    for (int k = 1; k < argc; ++k) {
        if (strcmp(argv[k], "-base-extension-only") == 0)
            base_extension_only = true;
        else
            argv[kept++] = argv[k];
    }
    argc = kept;
    if (base_extension_only)
        ou_init();
    else
        a = ou_init_async();
    unsigned long calls = DEFAULT_CALLS;
    const char *calls_env = getenv("OU_RANDOM_CALLS");
    if (calls_env) {
        char *end = NULL;
        calls = strtoul(calls_env, &end, 10);
        if (!*calls_env || *end || calls < 1000) {
            printf("OU_RANDOM_CALLS must be a whole number of at least 1000, not '%s'\n", calls_env);
            piglit_report_result(PIGLIT_FAIL);
        }
    }
    GenFramebuffers = glGenFramebuffers;
    DeleteFramebuffers = glDeleteFramebuffers;
    IsFramebuffer = glIsFramebuffer;
    BindFramebuffer = glBindFramebuffer;
    GenRenderbuffers = glGenRenderbuffers;
    DeleteRenderbuffers = glDeleteRenderbuffers;
    IsRenderbuffer = glIsRenderbuffer;
    BindRenderbuffer = glBindRenderbuffer;
    RenderbufferStorage = glRenderbufferStorage;
    FramebufferRenderbuffer = glFramebufferRenderbuffer;
    CheckFramebufferStatus = glCheckFramebufferStatus;
    GenQueries = glGenQueries;
    BeginQuery = glBeginQuery;
    EndQuery = glEndQuery;
    GetQueryObjectuiv = glGetQueryObjectuiv;
    BeginConditionalRender = glBeginConditionalRender;
    EndConditionalRender = glEndConditionalRender;
    WindowPos3f = glWindowPos3f;
    /* Adjacency primitives need geometry shaders: OpenGL 3.2. */
    const char *version = (const char *)glGetString(GL_VERSION);
    int major = 0, minor = 0;
    sscanf(version ? version : "", "%d.%d", &major, &minor);
    adjacency = major > 3 || (major == 3 && minor >= 2);
    printf("GL_VERSION %s: adjacency primitives %s\n", version ? version : "?", adjacency ? "drawn" : "not drawn");

    GLint max_tiles = 0;
    glGetIntegerv(GL_MAX_OCCLUSION_TILES_MESAX, &max_tiles);
    list_base = glGenLists(LISTS);
    GenQueries(QUERIES, query_name);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glPointSize(3.0f);
    glLineWidth(2.0f);
    fill_storage();
    if (!piglit_check_gl_error(GL_NO_ERROR))
        piglit_report_result(PIGLIT_FAIL);

    for (unsigned i = 0; i < calls; ++i) {
        unsigned r = next(100);
        if (base_extension_only && r >= 17 && r < 38)
            r = 38 + (r - 17);   /* pass objects and tile conditions: primitives instead */
        if (r < 5) call_scissors(i, max_tiles);
        else if (r < 10) call_buffers(i, max_tiles);
        else if (r < 17) call_render_mode(i);
        else if (r < 19) call_gen_pass(i);
        else if (r < 21) call_delete_pass(i);
        else if (r < 25) call_begin_pass(i);
        else if (r < 28) call_end_pass(i);
        else if (r < 32) call_get_pass(i);
        else if (r < 35) call_begin_tile_condition(i);
        else if (r < 38) call_end_tile_condition(i);
        else if (r < 58) call_primitive(i);
        else if (r < 64) call_pixel_rectangle(i);
        else if (r < 65) call_depth_mask(i);
        else if (r < 66) call_make_fbo(i);
        else if (r < 69) call_bind_fbo(i);
        else if (r < 70) call_delete_fbo(i);
        else if (r < 71) call_delete_renderbuffer(i);
        else if (r < 72) call_renderbuffer_storage(i);
        else if (r < 74) call_attach(i);
        else if (r < 77) call_new_list(i);
        else if (r < 80) call_end_list(i);
        else if (r < 84) call_call_list(i);
        else if (r < 88) { if (compiling < 0) call_begin_query(i); }   /* queries are compiled: not while compiling */
        else if (r < 92) { if (compiling < 0) call_end_query(i); }
        else if (r < 95) { if (compiling < 0) call_begin_nv_condition(i); }
        else if (r < 98) { if (compiling < 0) call_end_nv_condition(i); }
        else call_primitive(i);
        check_state(i);
    }
    if (compiling >= 0)
        glEndList();
    if (cond >= 0)
        a.EndConditionalRenderOcclusionTile();
    if (nv_cond >= 0)
        EndConditionalRender();
    if (query_active >= 0)
        EndQuery(GL_SAMPLES_PASSED);
    if (current >= 0)
        a.EndOcclusionPass();
    glRenderMode(GL_RENDER);
    unsigned primitive_types = 0;
    for (int t = 0; t < 14; ++t)
        primitive_types += primitives_drawn[t] > 0;
    printf("%lu calls: %u passes ended, %u records checked, %u pass objects read, %u conditional renderings\n",
           calls, passes_ended, records_checked, pass_objects_read, conditions_begun);
    printf("framebuffer changes: %u refused in a pass, %u made; lists: %u called in a pass, %u commands compiled "
           "in a pass; %u queries compared with NOHC, %u empty passes, %u NV conditions; %u primitive types, %u "
           "pixel rectangles\n",
           fb_refused, fb_changed, lists_called_in_pass, compiled_in_pass, queries_compared, empty_passes,
           nv_conditions, primitive_types, pixel_rects);
    /* The random walk must have reached the cases it exists for. */
    const unsigned scale = (unsigned)(calls / 1000);
    subtest(passes_ended > scale && records_checked > 10 * scale, "walk-reaches-occlusion-passes");
    if (!base_extension_only)
        subtest(pass_objects_read > scale / 4 && conditions_begun > scale / 4, "walk-reaches-pass-objects");
    subtest(fb_refused > scale / 10 && fb_changed > scale && lists_called_in_pass > scale / 10 &&
                compiled_in_pass > scale / 10 && queries_compared > scale / 10 && empty_passes > scale / 10 &&
                nv_conditions > scale / 10 && primitive_types == (adjacency ? 14u : 10u) && pixel_rects > scale,
            "walk-reaches-new-commands");
    subtest(errors_ok, "errors-match-the-spec");
    subtest(state_ok, "state-matches-the-model");
    subtest(written_ok, "records-written-as-specified");
    subtest(records_ok, "records-well-formed");
    subtest(counts_ok, "counts-agree");
    piglit_report_result(result);
}
