/* SPDX-License-Identifier: MIT */
/*
 * Two contexts of one share group for the tests of what a context shares
 * and what it keeps (MESAX_occlusion_unit section 5.X, issue 23;
 * MESAX_occlusion_unit_async section 5.X.1): A is the test's own context and
 * window from ou_init; B shares A's objects and renders into a window-system
 * buffer of its own of the same size. ou_make_current_on_new_buffer moves the
 * test's context to a new window-system buffer of another size. Include
 * after ou_util.h.
 *
 * The contexts are the window system's: OSMesa's on occu's framework
 * (tests/piglit_util/), EGL's inside piglit (tools/check-in-piglit.sh), where
 * B's buffer is a pbuffer of A's config and a platform without EGL (GLX)
 * skips the test. Under piglit with -fbo, A's window is piglit's FBO, which
 * stays bound in A; B's buffer is B's framebuffer 0 on both.
 */
#ifndef OU_TWO_CONTEXTS_H
#define OU_TWO_CONTEXTS_H

#if defined(PIGLIT_USE_WAFFLE) && defined(PIGLIT_HAS_EGL)
#include <EGL/egl.h>
#include <EGL/eglext.h>

struct ou_two_contexts {
    EGLDisplay display;
    EGLContext a, b;
    EGLSurface a_draw, a_read, b_surface;
    int size;
};

static inline bool
ou_make_current(EGLDisplay display, EGLSurface draw, EGLSurface read, EGLContext context)
{
    if (!eglMakeCurrent(display, draw, read, context)) {
        printf("eglMakeCurrent failed: 0x%x\n", eglGetError());
        return false;
    }
    return true;
}

static inline bool
ou_make_a_current(const struct ou_two_contexts *t)
{
    return ou_make_current(t->display, t->a_draw, t->a_read, t->a);
}

static inline bool
ou_make_b_current(const struct ou_two_contexts *t)
{
    return ou_make_current(t->display, t->b_surface, t->b_surface, t->b);
}

/* Leaves the calling thread without a current context. */
static inline void
ou_release_current(const struct ou_two_contexts *t)
{
    eglMakeCurrent(t->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

/* B, sharing the current context A; A stays current. A failure to make it
 * fails the test: EGL's shared contexts and pbuffers are part of every
 * driver here. */
static inline struct ou_two_contexts
ou_make_second_context(int size)
{
    struct ou_two_contexts t = {eglGetCurrentDisplay(), eglGetCurrentContext(), EGL_NO_CONTEXT,
                                eglGetCurrentSurface(EGL_DRAW), eglGetCurrentSurface(EGL_READ),
                                EGL_NO_SURFACE, size};
    if (t.a == EGL_NO_CONTEXT) {
        printf("the test's context is not EGL's: run it on an EGL platform\n");
        piglit_report_result(PIGLIT_SKIP);
    }
    EGLint id = 0, count = 0;
    EGLConfig config;
    eglQueryContext(t.display, t.a, EGL_CONFIG_ID, &id);
    const EGLint attribs[] = {EGL_CONFIG_ID, id, EGL_NONE};
    const EGLint pbuffer[] = {EGL_WIDTH, size, EGL_HEIGHT, size, EGL_NONE};
    const EGLint compat[] = {EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT,
                             EGL_NONE};
    if (!eglChooseConfig(t.display, attribs, &config, 1, &count) || count != 1 ||
        !eglBindAPI(EGL_OPENGL_API) ||
        (t.b = eglCreateContext(t.display, config, t.a, compat)) == EGL_NO_CONTEXT ||
        (t.b_surface = eglCreatePbufferSurface(t.display, config, pbuffer)) == EGL_NO_SURFACE) {
        printf("could not make a second context sharing the first: EGL error 0x%x\n", eglGetError());
        piglit_report_result(PIGLIT_FAIL);
    }
    return t;
}

/* Makes the current context current on a new window-system buffer of
 * size x size (a pbuffer of its config), its window-system framebuffer from
 * then on; false, with the reason printed, when that fails. */
static inline bool
ou_make_current_on_new_buffer(int size)
{
    const EGLDisplay display = eglGetCurrentDisplay();
    const EGLContext context = eglGetCurrentContext();
    if (context == EGL_NO_CONTEXT) {
        printf("the test's context is not EGL's: run it on an EGL platform\n");
        piglit_report_result(PIGLIT_SKIP);
    }
    EGLint id = 0, count = 0;
    EGLConfig config;
    eglQueryContext(display, context, EGL_CONFIG_ID, &id);
    const EGLint attribs[] = {EGL_CONFIG_ID, id, EGL_NONE};
    const EGLint pbuffer[] = {EGL_WIDTH, size, EGL_HEIGHT, size, EGL_NONE};
    EGLSurface surface = EGL_NO_SURFACE;
    if (!eglChooseConfig(display, attribs, &config, 1, &count) || count != 1 ||
        (surface = eglCreatePbufferSurface(display, config, pbuffer)) == EGL_NO_SURFACE) {
        printf("no pbuffer of %d x %d: EGL error 0x%x\n", size, size, eglGetError());
        return false;
    }
    return ou_make_current(display, surface, surface, context);
}

static inline void
ou_destroy_second_context(struct ou_two_contexts *t)
{
    eglDestroySurface(t->display, t->b_surface);
    eglDestroyContext(t->display, t->b);
    t->b = EGL_NO_CONTEXT;
    t->b_surface = EGL_NO_SURFACE;
}

#else
#include <GL/osmesa.h>

struct ou_two_contexts {
    OSMesaContext a, b;
    void *a_buffer;
    GLubyte *b_pixels;
    int size;
};

/* Makes `context` current on `buffer` (size x size RGBA, y up). */
static inline bool
ou_make_current(const struct ou_two_contexts *t, OSMesaContext context, void *buffer)
{
    if (!OSMesaMakeCurrent(context, buffer, GL_UNSIGNED_BYTE, t->size, t->size)) {
        printf("OSMesaMakeCurrent failed\n");
        return false;
    }
    OSMesaPixelStore(OSMESA_Y_UP, 1);
    return true;
}

static inline bool ou_make_a_current(const struct ou_two_contexts *t) { return ou_make_current(t, t->a, t->a_buffer); }
static inline bool ou_make_b_current(const struct ou_two_contexts *t) { return ou_make_current(t, t->b, t->b_pixels); }

/* Leaves the calling thread without a current context. */
static inline void
ou_release_current(const struct ou_two_contexts *t)
{
    (void)t;
    OSMesaMakeCurrent(NULL, NULL, 0, 0, 0);
}

/* B, sharing the current context A; A stays current. A failure to make it
 * fails the test: OSMesa share lists are part of every driver here. */
static inline struct ou_two_contexts
ou_make_second_context(int size)
{
    struct ou_two_contexts t = {OSMesaGetCurrentContext(), NULL, NULL, NULL, size};
    GLint width, height, format;
    if (!OSMesaGetColorBuffer(t.a, &width, &height, &format, &t.a_buffer)) {
        printf("OSMesaGetColorBuffer failed\n");
        piglit_report_result(PIGLIT_FAIL);
    }
    static const int attribs[] = {
        OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_STENCIL_BITS, 8,
        OSMESA_PROFILE, OSMESA_COMPAT_PROFILE, 0,
    };
    t.b = OSMesaCreateContextAttribs(attribs, t.a);
    t.b_pixels = (GLubyte *)calloc((size_t)size * size, 4);
    if (!t.b || !t.b_pixels) {
        printf("could not make a second context sharing the first\n");
        piglit_report_result(PIGLIT_FAIL);
    }
    return t;
}

/* Makes the current context current on a new window-system buffer of
 * size x size (RGBA, y up; kept to the end of the test), its window-system
 * framebuffer from then on; false, with the reason printed, when that
 * fails. */
static inline bool
ou_make_current_on_new_buffer(int size)
{
    GLubyte *pixels = (GLubyte *)calloc((size_t)size * size, 4);
    if (!pixels || !OSMesaMakeCurrent(OSMesaGetCurrentContext(), pixels, GL_UNSIGNED_BYTE, size, size)) {
        printf("OSMesaMakeCurrent on a buffer of %d x %d failed\n", size, size);
        return false;
    }
    OSMesaPixelStore(OSMESA_Y_UP, 1);
    return true;
}

static inline void
ou_destroy_second_context(struct ou_two_contexts *t)
{
    OSMesaDestroyContext(t->b);
    free(t->b_pixels);
    t->b = NULL;
    t->b_pixels = NULL;
}
#endif

#endif
