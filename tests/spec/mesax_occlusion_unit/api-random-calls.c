/*
 * GL_MESAX_occlusion_unit under random use: 20,000 calls of ScissorsMESAX,
 * OcclusionBuffersMESAX, RenderMode and draws, with arguments drawn from
 * the valid and the invalid (negative and too large counts, negative tile
 * sizes, NULL arrays, sizes below 8, unknown modes, calls inside an
 * occlusion mode), each checked against the spec's Errors section as a
 * model of the GL's state: the error is the one the spec lists for the
 * call in that state (or none), the render mode and the tile count are
 * the model's, and every record written is well formed. A fixed seed
 * makes a failure repeatable; the failing call is printed.
 *
 * Subtests:
 *   walk-reaches-occlusion-passes more than 100 passes ended and 1000
 *                              records checked (the walk is not vacuous)
 *   errors-match-the-spec      every call's error as the model predicts
 *   state-matches-the-model    RENDER_MODE and OCCLUSION_TILE_COUNT_MESAX
 *   records-well-formed        NOHC <= PHC; with NOHC 0 the empty extents,
 *                              else xmin <= xmax, ymin <= ymax, zmin <= zmax
 */
#include "ou_util.h"

#define W 32
#define H 32
#define CALLS 20000
#define WORDS 64

static unsigned long long rng = 0x2026112912345ull;

static unsigned
next(unsigned n)
{
    rng = rng * 6364136223846793005ull + 1442695040888963407ull;
    return (unsigned)(rng >> 33) % n;
}

static GLuint storage[64][WORDS];

/* The model: what the spec says the GL's state is. */
static GLenum mode = GL_RENDER;
static int tiles = 0, buffers = 0;
static GLsizei buffer_size[64];

static bool errors_ok = true, state_ok = true, records_ok = true;
static unsigned passes_ended, records_checked;

static void
expect(GLenum expected, const char *call, unsigned i)
{
    const GLenum got = glGetError();
    if (got != expected && errors_ok) {
        printf("call %u %s: error 0x%x, the spec says 0x%x (mode 0x%x, %d tiles, %d buffers)\n", i, call, got,
               expected, mode, tiles, buffers);
        errors_ok = false;
    }
}

static void
check_records(int n)
{
    for (int k = 0; k < n; ++k) {
        const GLuint *r = storage[k];
        ++records_checked;
        bool ok = r[OU_NOHC] <= r[OU_PHC];
        if (r[OU_NOHC] == 0)
            ok = ok && r[OU_XMIN] == OU_EMPTY_MIN && r[OU_XMAX] == OU_EMPTY_MAX && r[OU_ZMIN] == OU_EMPTY_MIN &&
                 r[OU_ZMAX] == OU_EMPTY_MAX;
        else
            ok = ok && r[OU_XMIN] <= r[OU_XMAX] && r[OU_YMIN] <= r[OU_YMAX] && r[OU_ZMIN] <= r[OU_ZMAX] &&
                 r[OU_XMAX] < W && r[OU_YMAX] < H;
        if (!ok && records_ok) {
            printf("record %d: NOHC %u PHC %u x %u..%u y %u..%u z 0x%x..0x%x\n", k, r[0], r[1], r[2], r[3], r[4],
                   r[5], r[6], r[7]);
            records_ok = false;
        }
    }
}

int main(int argc, char **argv)
{
    ou_init(argc, argv, W, H);
    GLint max_tiles = 0;
    glGetIntegerv(GL_MAX_OCCLUSION_TILES_MESAX, &max_tiles);
    if (max_tiles > 64)
        max_tiles = 64;
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);

    for (unsigned i = 0; i < CALLS; ++i) {
        const bool occlusion = mode == GL_BRIEF_OCCLUSION_MESAX || mode == GL_VERBOSE_OCCLUSION_MESAX;
        switch (next(5)) {
        case 0: {   /* ScissorsMESAX */
            static GLint t[4 * 70];
            const int count = (int)next((unsigned)max_tiles + 3) - 1;   /* -1 .. max + 1 */
            bool negative = false;
            for (int k = 0; k < (count > 0 ? count : 0); ++k) {
                t[4 * k] = (GLint)next(48) - 8;
                t[4 * k + 1] = (GLint)next(48) - 8;
                t[4 * k + 2] = next(20) == 0 ? -1 : (GLint)next(40);
                t[4 * k + 3] = (GLint)next(40);
                negative = negative || t[4 * k + 2] < 0;
            }
            const bool null_tiles = count > 0 && next(10) == 0;
            ScissorsMESAX(count, null_tiles ? NULL : t);
            GLenum e = GL_NO_ERROR;
            if (occlusion)
                e = GL_INVALID_OPERATION;
            else if (count < 0 || count > max_tiles || null_tiles || negative)
                e = GL_INVALID_VALUE;
            else
                tiles = count;
            expect(e, "ScissorsMESAX", i);
            break;
        }
        case 1: {   /* OcclusionBuffersMESAX */
            static GLuint *p[70];
            static GLsizei s[70];
            const int count = (int)next((unsigned)max_tiles + 3) - 1;
            bool bad = false;
            for (int k = 0; k < (count > 0 ? count : 0); ++k) {
                p[k] = next(30) == 0 ? NULL : storage[k];
                s[k] = next(30) == 0 ? 7 : 8 + (GLsizei)next(WORDS - 8 + 1);
                bad = bad || !p[k] || s[k] < 8;
            }
            const bool null_arrays = count > 0 && next(10) == 0;
            OcclusionBuffersMESAX(count, null_arrays ? NULL : s, null_arrays ? NULL : p);
            GLenum e = GL_NO_ERROR;
            if (occlusion)
                e = GL_INVALID_OPERATION;
            else if (count < 0 || count > max_tiles || null_arrays || bad)
                e = GL_INVALID_VALUE;
            else {
                buffers = count;
                for (int k = 0; k < count; ++k)
                    buffer_size[k] = s[k];
            }
            expect(e, "OcclusionBuffersMESAX", i);
            break;
        }
        case 2: {   /* RenderMode */
            static const GLenum modes[] = {GL_RENDER, GL_SELECT, GL_FEEDBACK, GL_BRIEF_OCCLUSION_MESAX,
                                           GL_VERBOSE_OCCLUSION_MESAX, GL_BRIEF_OCCLUSION_MESAX, 0x1234};
            static GLuint select_buffer[64];
            static GLfloat feedback_buffer[256];
            glSelectBuffer(64, select_buffer);
            glFeedbackBuffer(256, GL_3D, feedback_buffer);
            glGetError();   /* SelectBuffer/FeedbackBuffer inside SELECT/FEEDBACK: not under test */
            const GLenum m = modes[next(7)];
            const int in_effect = tiles > 0 ? tiles : 1;
            glRenderMode(m);
            GLenum e = GL_NO_ERROR;
            if (m == 0x1234)
                e = GL_INVALID_ENUM;
            else if ((m == GL_BRIEF_OCCLUSION_MESAX || m == GL_VERBOSE_OCCLUSION_MESAX) && buffers < in_effect)
                e = GL_INVALID_OPERATION;
            expect(e, "RenderMode", i);
            if (e == GL_NO_ERROR) {
                if (occlusion) {
                    check_records(in_effect < buffers ? in_effect : buffers);
                    ++passes_ended;
                }
                mode = m;
            }
            break;
        }
        default: {   /* a draw */
            const float x0 = (float)next(40) - 4, y0 = (float)next(40) - 4;
            ou_rect(x0, y0, x0 + (float)next(20), y0 + (float)next(20), (float)next(100) / 100.0f);
            expect(GL_NO_ERROR, "draw", i);
            break;
        }
        }
        GLint got_mode = 0, got_tiles = -1;
        glGetIntegerv(GL_RENDER_MODE, &got_mode);
        glGetIntegerv(GL_OCCLUSION_TILE_COUNT_MESAX, &got_tiles);
        if (((GLenum)got_mode != mode || got_tiles != tiles) && state_ok) {
            printf("call %u: RENDER_MODE 0x%x, tiles %d; the model says 0x%x, %d\n", i, got_mode, got_tiles, mode,
                   tiles);
            state_ok = false;
        }
    }
    glRenderMode(GL_RENDER);
    printf("%u passes ended, %u records checked\n", passes_ended, records_checked);
    /* The random walk must have reached the cases it exists for. */
    subtest(passes_ended > 100 && records_checked > 1000, "walk-reaches-occlusion-passes");
    subtest(errors_ok, "errors-match-the-spec");
    subtest(state_ok, "state-matches-the-model");
    subtest(records_ok, "records-well-formed");
    piglit_report_result(result);
}
