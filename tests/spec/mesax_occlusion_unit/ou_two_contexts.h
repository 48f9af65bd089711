/*
 * Two OSMesa contexts of one share group for the tests of what a context
 * shares and what it keeps (MESAX_occlusion_unit section 5.X, issue 23;
 * MESAX_occlusion_unit_async section 5.X.1): A is the test's own context and
 * window-system buffer from ou_init; B shares A's objects and renders into a
 * client buffer of the same size. Include after ou_util.h.
 */
#ifndef OU_TWO_CONTEXTS_H
#define OU_TWO_CONTEXTS_H

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

static inline void
ou_destroy_second_context(struct ou_two_contexts *t)
{
    OSMesaDestroyContext(t->b);
    free(t->b_pixels);
    t->b = NULL;
    t->b_pixels = NULL;
}

#endif
