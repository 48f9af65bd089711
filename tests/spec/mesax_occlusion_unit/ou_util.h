/* SPDX-License-Identifier: MIT */
/*
 * Helpers shared by the GL_MESAX_occlusion_unit tests.
 *
 * Conventions: ou_init sets a projection in which object coordinates are
 * window coordinates: x and y in pixels (a rectangle from (x0, y0) to
 * (x1, y1) covers exactly the pixels x0..x1-1, y0..y1-1, whose centres it
 * contains) and z in [0, 1] is window depth.
 */
#ifndef OU_UTIL_H
#define OU_UTIL_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <threads.h>
#include <time.h>
#include <unistd.h>

#include "piglit-util-gl.h"
/* piglit's GL header (piglit-dispatch.h) defines APIENTRY but not the
 * APIENTRYP of <GL/glext.h> that the extension's header uses. */
#ifndef APIENTRYP
#define APIENTRYP APIENTRY *
#endif
#include "GL/mesax_occlusion_unit.h"

/* Words of a record (spec section 5.X). */
enum { OU_NOHC, OU_PHC, OU_XMIN, OU_XMAX, OU_YMIN, OU_YMAX, OU_ZMIN, OU_ZMAX, OU_BRIEF_SIZE };

#define OU_EMPTY_MIN 0xffffffffu
#define OU_EMPTY_MAX 0u

/* The test's overall result; subtest() reports one subtest and folds it in. */
static enum piglit_result result = PIGLIT_PASS;

/* Writes all `size` bytes of `data` to `fd`, as a child reporting to its
 * parent through a pipe does; false if the pipe closed or failed. */
static inline bool
ou_write_all(int fd, const void *data, size_t size)
{
    for (const char *p = data; size > 0;) {
        ssize_t n = write(fd, p, size);
        if (n <= 0)
            return false;
        p += n;
        size -= (size_t)n;
    }
    return true;
}

static inline void
subtest(bool ok, const char *name)
{
    piglit_report_subtest_result(ok ? PIGLIT_PASS : PIGLIT_FAIL, "%s", name);
    if (!ok)
        result = PIGLIT_FAIL;
}

static PFNGLSCISSORSMESAXPROC ScissorsMESAX;
static PFNGLOCCLUSIONBUFFERSMESAXPROC OcclusionBuffersMESAX;

/* The drivers occu's patches give the extension. */
static inline bool
ou_driver_is_patched(void)
{
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    return renderer && (strstr(renderer, "softpipe") || strstr(renderer, "llvmpipe"));
}

/* Reports a subtest whose GL feature the context lacks: a failure on
 * softpipe and llvmpipe, which have every feature these tests use, a skip
 * elsewhere. */
static inline void
ou_subtest_unsupported(const char *name, const char *feature)
{
    printf("%s: %s is not supported\n", name, feature);
    if (ou_driver_is_patched())
        subtest(false, name);
    else
        piglit_report_subtest_result(PIGLIT_SKIP, "%s", name);
}

/* Reports a subtest of an interaction with an extension the spec makes
 * optional (a "Dependencies on" section): a failure on llvmpipe, which has
 * it, a skip with the reason elsewhere (softpipe has no
 * ARB_query_buffer_object, for instance). */
static inline void
ou_subtest_dependency_missing(const char *name, const char *extension)
{
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    printf("%s: %s is not supported, so the spec's interaction with it does not apply\n", name, extension);
    if (renderer && strstr(renderer, "llvmpipe"))
        subtest(false, name);
    else
        piglit_report_subtest_result(PIGLIT_SKIP, "%s", name);
}

/* Sets the pixel-exact projection over the window (piglit_width x
 * piglit_height, the test's config). Without the extension the test fails on
 * softpipe and llvmpipe, which must advertise it, and skips elsewhere. */
static inline void
ou_init_context(void)
{
    const int width = piglit_width, height = piglit_height;
    if (!piglit_is_extension_supported("GL_MESAX_occlusion_unit")) {
        if (ou_driver_is_patched()) {
            printf("%s must advertise GL_MESAX_occlusion_unit\n", (const char *)glGetString(GL_RENDERER));
            piglit_report_result(PIGLIT_FAIL);
        }
        piglit_require_extension("GL_MESAX_occlusion_unit");
    }
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(0, width, 0, height, 0, -1); /* window z = object z */
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
}

/* Whether argv holds `flag`, which is taken out of it (piglit's own
 * options are the rest). -tiles-4096 asks the subtests that need occu's
 * part `tiles` (4096 tiles; tests/meson.build registers them in suite
 * 'tiles', which tools/check-mesa-series.sh leaves out before that part). */
static inline bool
ou_take_flag(int *argc, char **argv, const char *flag)
{
    bool found = false;
    int kept = 1;
    for (int k = 1; k < *argc; ++k) {
        if (strcmp(argv[k], flag) == 0)
            found = true;
        else
            argv[kept++] = argv[k];
    }
    *argc = kept;
    return found;
}

/* Resolves the extension's two entry points; false when one is missing. */
static inline bool
ou_resolve_entry_points(void)
{
    ScissorsMESAX = glScissorsMESAX;
    OcclusionBuffersMESAX = glOcclusionBuffersMESAX;
    return ScissorsMESAX && OcclusionBuffersMESAX;
}

/* ou_init_context and ou_resolve_entry_points; fails without the entry points. */
static inline void
ou_init(void)
{
    ou_init_context();
    if (!ou_resolve_entry_points()) {
        printf("extension advertised but its entry points are missing\n");
        piglit_report_result(PIGLIT_FAIL);
    }
}

/* True when every pixel of the rectangle matches `expected` within
 * `tolerance` per channel (0..255 units); prints the first mismatch. */
static inline bool
ou_probe_rect_rgba_ub(int x, int y, int w, int h, const unsigned char expected[4], int tolerance)
{
    unsigned char *pixels = malloc((size_t)w * (size_t)h * 4);
    glReadPixels(x, y, w, h, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
    for (int j = 0; j < h; ++j) {
        for (int i = 0; i < w; ++i) {
            const unsigned char *p = pixels + ((size_t)j * (size_t)w + (size_t)i) * 4;
            for (int c = 0; c < 4; ++c) {
                if (abs(p[c] - expected[c]) > tolerance) {
                    printf("Probe at (%d, %d): expected %u %u %u %u, observed %u %u %u %u (tolerance %d)\n",
                           x + i, y + j, expected[0], expected[1], expected[2], expected[3],
                           p[0], p[1], p[2], p[3], tolerance);
                    free(pixels);
                    return false;
                }
            }
        }
    }
    free(pixels);
    return true;
}

static inline void
ou_rect(float x0, float y0, float x1, float y1, float z)
{
    glBegin(GL_QUADS);
    glVertex3f(x0, y0, z);
    glVertex3f(x1, y0, z);
    glVertex3f(x1, y1, z);
    glVertex3f(x0, y1, z);
    glEnd();
}

/* One buffer per tile, each of `size` words, filled with a sentinel so that
 * tests see which words the GL wrote. */
#define OU_SENTINEL 0xdeadbeefu

static inline void
ou_fill(GLuint *buffer, int size)
{
    for (int i = 0; i < size; ++i)
        buffer[i] = OU_SENTINEL;
}

/* Record depth of window z, as the spec maps it. */
static inline GLuint
ou_depth(double z)
{
    if (z < 0) z = 0;
    if (z > 1) z = 1;
    return (GLuint)(z * 4294967295.0 + 0.5);
}

/* The brief record a draw at window depth z should give, from the colour
 * buffer (0, 0, width, height) read back after drawing it onto black: the
 * pixels with non-zero red are its non-occluded fragments (NOHC = PHC), their
 * box, and z as both depths, or the empty record. */
static inline void
ou_record_of_drawn_pixels(int width, int height, double z, GLuint record[OU_BRIEF_SIZE])
{
    GLubyte *pixels = malloc((size_t)width * (size_t)height * 4);
    GLuint n = 0, x0 = OU_EMPTY_MIN, x1 = OU_EMPTY_MAX, y0 = OU_EMPTY_MIN, y1 = OU_EMPTY_MAX;
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
    for (GLuint y = 0; y < (GLuint)height; ++y) {
        for (GLuint x = 0; x < (GLuint)width; ++x) {
            if (!pixels[((size_t)y * (size_t)width + x) * 4])
                continue;
            ++n;
            x0 = x < x0 ? x : x0;
            x1 = x > x1 ? x : x1;
            y0 = y < y0 ? y : y0;
            y1 = y > y1 ? y : y1;
        }
    }
    free(pixels);
    const GLuint depth = ou_depth(z);
    const GLuint r[OU_BRIEF_SIZE] = {n, n, x0, x1, y0, y1, n ? depth : OU_EMPTY_MIN, n ? depth : OU_EMPTY_MAX};
    memcpy(record, r, sizeof(r));
}

/* Tolerance, in record units, between a record's z and the same fragment's
 * depth read back from a 24-bit depth buffer as GL_UNSIGNED_INT. One step
 * of the buffer is (2^32 - 1) / (2^24 - 1) = 257.00002 record units; the
 * buffer holds z rounded or truncated to a step (implementations do
 * either), so within one step of z, and the read-back scales it to 32 bits
 * by bit replication, within 1 unit of (2^32 - 1) / (2^24 - 1) times the
 * stored value. A record of the buffer's value also passes this tolerance:
 * tests that must tell the two apart compare with a float depth buffer or
 * with a z that float32 represents exactly. */
#define OU_Z24_READBACK_TOLERANCE 258u

static int
ou_compare_pairs(const void *a, const void *b)
{
    const GLuint *p = a, *q = b;
    if (p[1] != q[1])
        return p[1] < q[1] ? -1 : 1;
    return p[0] < q[0] ? -1 : p[0] > q[0];
}

/* Sorts n (x, y) pairs by y, then x: verbose lists are sets, in no order. */
static inline void
ou_sort_pairs(GLuint *pairs, size_t n)
{
    qsort(pairs, n, 2 * sizeof(GLuint), ou_compare_pairs);
}

/* Compares a record's 8 words with expectations; prints the differences. */
static inline bool
ou_check_record(const char *what, const GLuint *got, const GLuint expected[OU_BRIEF_SIZE], GLuint z_tolerance)
{
    static const char *names[] = {"NOHC", "PHC", "xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
    bool ok = true;
    for (int i = 0; i < OU_BRIEF_SIZE; ++i) {
        const GLuint tol = i >= OU_ZMIN ? z_tolerance : 0;
        const GLuint diff = got[i] > expected[i] ? got[i] - expected[i] : expected[i] - got[i];
        if (diff > tol) {
            printf("%s: %s is %u (0x%08x), expected %u (0x%08x), tolerance %u\n", what, names[i], got[i], got[i],
                   expected[i], expected[i], tol);
            ok = false;
        }
    }
    return ok;
}

/* Brief pass over `draw` with one buffer per tile; returns RenderMode's value. */
static inline GLint
ou_brief_pass(int num_tiles, const GLint *tiles, GLuint (*records)[OU_BRIEF_SIZE], void (*draw)(void))
{
    GLuint *buffers[64];
    GLsizei sizes[64];
    int n = num_tiles > 0 ? num_tiles : 1;
    for (int i = 0; i < n; ++i) {
        ou_fill(records[i], OU_BRIEF_SIZE);
        buffers[i] = records[i];
        sizes[i] = OU_BRIEF_SIZE;
    }
    OcclusionBuffersMESAX(n, sizes, buffers);
    ScissorsMESAX(num_tiles, tiles);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    draw();
    GLint r = glRenderMode(GL_RENDER);
    ScissorsMESAX(0, NULL);
    return r;
}

/* The first error glGetError reports, and the others cleared. */
static inline GLenum
ou_first_error(void)
{
    GLenum e = glGetError();
    while (glGetError() != GL_NO_ERROR)
        ;
    return e;
}

/* An integer state; -1 if the query wrote nothing. */
static inline GLint
ou_get_integer(GLenum pname)
{
    GLint v = -1;
    glGetIntegerv(pname, &v);
    return v;
}

/* Subtest `name`: the brief record counts no fragment (NOHC 0, PHC 0) and
 * the GL raised no error; `counted` says what a nonzero count would mean. */
static inline void
ou_expect_no_fragments(const GLuint *record, const char *name, const char *counted)
{
    const bool ok = record[OU_NOHC] == 0 && record[OU_PHC] == 0;
    if (!ok)
        printf("%s: NOHC %u PHC %u, expected 0 0 (%s)\n", name, record[OU_NOHC], record[OU_PHC], counted);
    subtest(ok && piglit_check_gl_error(GL_NO_ERROR), name);
}

/* GL_MESAX_occlusion_unit_async's entry points (ou_init_async). */
struct ou_async_functions {
    PFNGLGENOCCLUSIONPASSESMESAXPROC GenOcclusionPasses;
    PFNGLDELETEOCCLUSIONPASSESMESAXPROC DeleteOcclusionPasses;
    PFNGLISOCCLUSIONPASSMESAXPROC IsOcclusionPass;
    PFNGLBEGINOCCLUSIONPASSMESAXPROC BeginOcclusionPass;
    PFNGLENDOCCLUSIONPASSMESAXPROC EndOcclusionPass;
    PFNGLGETOCCLUSIONPASSIVMESAXPROC GetOcclusionPassiv;
    PFNGLBEGINCONDITIONALRENDEROCCLUSIONTILEMESAXPROC BeginConditionalRenderOcclusionTile;
    PFNGLENDCONDITIONALRENDEROCCLUSIONTILEMESAXPROC EndConditionalRenderOcclusionTile;
};

/* ou_init, then GL_MESAX_occlusion_unit_async, which softpipe and llvmpipe
 * must advertise beside GL_MESAX_occlusion_unit (a failure there, a skip
 * elsewhere), and its entry points (a failure when one is missing). */
static inline struct ou_async_functions
ou_init_async(void)
{
    ou_init();
    if (!piglit_is_extension_supported("GL_MESAX_occlusion_unit_async")) {
        if (ou_driver_is_patched()) {
            printf("%s must advertise GL_MESAX_occlusion_unit_async\n", (const char *)glGetString(GL_RENDERER));
            piglit_report_result(PIGLIT_FAIL);
        }
        piglit_require_extension("GL_MESAX_occlusion_unit_async");
    }
    struct ou_async_functions a;
/* Through the GL's dispatch (piglit's, or occu's for the functions OSMesa
 * does not export): a missing entry point is NULL here, or fails the test
 * at its first call under piglit. */
#define OU_RESOLVE(member, function)                                \
    a.member = function;                                            \
    if (!a.member) {                                                \
        printf("extension advertised but %s is missing\n", #function); \
        piglit_report_result(PIGLIT_FAIL);                          \
    }
    OU_RESOLVE(GenOcclusionPasses, glGenOcclusionPassesMESAX);
    OU_RESOLVE(DeleteOcclusionPasses, glDeleteOcclusionPassesMESAX);
    OU_RESOLVE(IsOcclusionPass, glIsOcclusionPassMESAX);
    OU_RESOLVE(BeginOcclusionPass, glBeginOcclusionPassMESAX);
    OU_RESOLVE(EndOcclusionPass, glEndOcclusionPassMESAX);
    OU_RESOLVE(GetOcclusionPassiv, glGetOcclusionPassivMESAX);
    OU_RESOLVE(BeginConditionalRenderOcclusionTile, glBeginConditionalRenderOcclusionTileMESAX);
    OU_RESOLVE(EndConditionalRenderOcclusionTile, glEndConditionalRenderOcclusionTileMESAX);
#undef OU_RESOLVE
    return a;
}

/* GL_MESAX_occlusion_unit_conservative, which softpipe and llvmpipe must
 * advertise wherever they have the unit (a failure there, a skip
 * elsewhere); it adds no entry points. */
static inline void
ou_require_conservative(void)
{
    if (piglit_is_extension_supported("GL_MESAX_occlusion_unit_conservative"))
        return;
    if (ou_driver_is_patched()) {
        printf("%s must advertise GL_MESAX_occlusion_unit_conservative\n", (const char *)glGetString(GL_RENDERER));
        piglit_report_result(PIGLIT_FAIL);
    }
    piglit_require_extension("GL_MESAX_occlusion_unit_conservative");
}

/* Polls OCCLUSION_PASS_RESULT_AVAILABLE_MESAX until it is TRUE, for at most
 * about ten seconds (the spec: repeated calls eventually return TRUE). */
static inline bool
ou_wait_available(const struct ou_async_functions *a, GLuint pass)
{
    for (long i = 0; i < 10000000; ++i) {
        GLint available = -1;
        a->GetOcclusionPassiv(pass, GL_OCCLUSION_PASS_RESULT_AVAILABLE_MESAX, &available);
        if (available == GL_TRUE)
            return true;
        if (available != GL_FALSE) {
            printf("availability %d is neither TRUE nor FALSE\n", available);
            return false;
        }
        if (i % 1000 == 999) {
            const struct timespec ms = {0, 1000000};
            thrd_sleep(&ms, NULL);
        }
    }
    printf("pass %u never became available\n", pass);
    return false;
}

/* Framebuffer-object entry points (OpenGL 3.0, ARB_framebuffer_object). */
struct ou_fbo_functions {
    PFNGLGENFRAMEBUFFERSPROC GenFramebuffers;
    PFNGLBINDFRAMEBUFFERPROC BindFramebuffer;
    PFNGLGENRENDERBUFFERSPROC GenRenderbuffers;
    PFNGLBINDRENDERBUFFERPROC BindRenderbuffer;
    PFNGLRENDERBUFFERSTORAGEPROC RenderbufferStorage;
    PFNGLRENDERBUFFERSTORAGEMULTISAMPLEPROC RenderbufferStorageMultisample;
    PFNGLFRAMEBUFFERRENDERBUFFERPROC FramebufferRenderbuffer;
    PFNGLFRAMEBUFFERTEXTURE2DPROC FramebufferTexture2D;
    PFNGLCHECKFRAMEBUFFERSTATUSPROC CheckFramebufferStatus;
    PFNGLBLITFRAMEBUFFERPROC BlitFramebuffer;
};

static inline struct ou_fbo_functions
ou_fbo_functions(void)
{
    struct ou_fbo_functions f;
    f.GenFramebuffers = glGenFramebuffers;
    f.BindFramebuffer = glBindFramebuffer;
    f.GenRenderbuffers = glGenRenderbuffers;
    f.BindRenderbuffer = glBindRenderbuffer;
    f.RenderbufferStorage = glRenderbufferStorage;
    f.RenderbufferStorageMultisample =
        glRenderbufferStorageMultisample;
    f.FramebufferRenderbuffer =
        glFramebufferRenderbuffer;
    f.FramebufferTexture2D = glFramebufferTexture2D;
    f.CheckFramebufferStatus = glCheckFramebufferStatus;
    f.BlitFramebuffer = glBlitFramebuffer;
    return f;
}

/* Makes and binds a framebuffer object of width x height: an RGBA8 colour
 * renderbuffer and, with `depth`, a 24-bit depth one, of `samples` samples
 * (0: single-sampled); their names go to renderbuffers[0] and [1]. Fails
 * the test when the object is incomplete. */
static inline GLuint
ou_make_fbo(const struct ou_fbo_functions *f, int width, int height, int samples, bool depth,
            GLuint renderbuffers[2])
{
    GLuint fbo;
    f->GenFramebuffers(1, &fbo);
    f->GenRenderbuffers(depth ? 2 : 1, renderbuffers);
    const GLenum formats[2] = {GL_RGBA8, GL_DEPTH_COMPONENT24};
    for (int i = 0; i < (depth ? 2 : 1); ++i) {
        f->BindRenderbuffer(GL_RENDERBUFFER, renderbuffers[i]);
        if (samples > 0)
            f->RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, formats[i], width, height);
        else
            f->RenderbufferStorage(GL_RENDERBUFFER, formats[i], width, height);
    }
    f->BindFramebuffer(GL_FRAMEBUFFER, fbo);
    f->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, renderbuffers[0]);
    if (depth)
        f->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, renderbuffers[1]);
    if (f->CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        printf("a %dx%d framebuffer object of %d samples is incomplete\n", width, height, samples);
        piglit_report_result(PIGLIT_FAIL);
    }
    return fbo;
}

#endif
