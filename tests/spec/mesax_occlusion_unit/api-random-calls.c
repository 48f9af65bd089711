/*
 * GL_MESAX_occlusion_unit and GL_MESAX_occlusion_unit_async under random
 * use: 200,000 calls (OU_RANDOM_CALLS sets another number) of ScissorsMESAX, OcclusionBuffersMESAX, RenderMode,
 * draws, and the pass objects' and conditional rendering's commands (Gen,
 * Delete, Begin, End, GetOcclusionPassiv, Begin/EndConditionalRender on a
 * tile), with arguments drawn from
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
 *   walk-reaches-pass-objects  more than 100 pass objects' records read and
 *                              100 conditional renderings begun
 *   state-matches-the-model    RENDER_MODE, OCCLUSION_TILE_COUNT_MESAX and
 *                              CURRENT_OCCLUSION_PASS_MESAX
 *   records-well-formed        NOHC <= PHC; with NOHC 0 the empty extents,
 *                              else xmin <= xmax, ymin <= ymax, zmin <= zmax
 */
#include "ou_util.h"

#define W 32
#define H 32
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
static unsigned passes_ended, records_checked, pass_objects_read, conditions_begun;

/* The model of GL_MESAX_occlusion_unit_async: a pool of names, what each
 * holds, the pass in progress and conditional rendering. */
#define NAMES 6
static struct ou_async_functions a;
static GLuint names[NAMES];
static enum { UNUSED, NO_PASS, IN_PROGRESS, ENDED } held[NAMES];
static int pass_tiles[NAMES];
static int current = -1;     /* index of the pass in progress, or -1 */
static int cond = -1;        /* index of conditional rendering's pass, or -1 */

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
    a = ou_init_async(argc, argv, W, H);
    unsigned long calls = 200000;
    const char *calls_env = getenv("OU_RANDOM_CALLS");
    if (calls_env) {
        char *end = NULL;
        calls = strtoul(calls_env, &end, 10);
        if (!*calls_env || *end || calls < 1000) {
            printf("OU_RANDOM_CALLS must be a whole number of at least 1000, not '%s'\n", calls_env);
            piglit_report_result(PIGLIT_FAIL);
        }
    }
    GLint max_tiles = 0;
    glGetIntegerv(GL_MAX_OCCLUSION_TILES_MESAX, &max_tiles);
    if (max_tiles > 64)
        max_tiles = 64;
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);

    for (unsigned i = 0; i < calls; ++i) {
        const bool occlusion = mode == GL_BRIEF_OCCLUSION_MESAX || mode == GL_VERBOSE_OCCLUSION_MESAX;
        switch (next(12)) {
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
            /* RENDER more often than the others: pass objects begin only from it. */
            static const GLenum modes[] = {GL_RENDER, GL_RENDER, GL_RENDER, GL_SELECT, GL_FEEDBACK,
                                           GL_BRIEF_OCCLUSION_MESAX, GL_VERBOSE_OCCLUSION_MESAX,
                                           GL_BRIEF_OCCLUSION_MESAX, 0x1234};
            static GLuint select_buffer[64];
            static GLfloat feedback_buffer[256];
            glSelectBuffer(64, select_buffer);
            glFeedbackBuffer(256, GL_3D, feedback_buffer);
            glGetError();   /* SelectBuffer/FeedbackBuffer inside SELECT/FEEDBACK: not under test */
            const GLenum m = modes[next(9)];
            const int in_effect = tiles > 0 ? tiles : 1;
            glRenderMode(m);
            GLenum e = GL_NO_ERROR;
            if (m == 0x1234)
                e = GL_INVALID_ENUM;
            else if (current >= 0)   /* a pass object's pass ends only with EndOcclusionPassMESAX */
                e = GL_INVALID_OPERATION;
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
        case 3: {   /* GenOcclusionPassesMESAX into a free slot of the pool */
            for (int k = 0; k < NAMES; ++k)
                if (held[k] == UNUSED) {
                    a.GenOcclusionPasses(1, &names[k]);
                    expect(GL_NO_ERROR, "GenOcclusionPassesMESAX", i);
                    held[k] = NO_PASS;
                    /* A deleted name the GL gives out again is this slot's now. */
                    for (int j = 0; j < NAMES; ++j)
                        if (j != k && held[j] == UNUSED && names[j] == names[k])
                            names[j] = 0;
                    break;
                }
            break;
        }
        case 4: {   /* DeleteOcclusionPassesMESAX */
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
            break;
        }
        case 5: {   /* BeginOcclusionPassMESAX */
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
                pass_tiles[k] = in_effect;
            }
            break;
        }
        case 6: {   /* EndOcclusionPassMESAX */
            a.EndOcclusionPass();
            expect(current >= 0 ? GL_NO_ERROR : GL_INVALID_OPERATION, "EndOcclusionPassMESAX", i);
            if (current >= 0) {
                held[current] = ENDED;
                current = -1;
                mode = GL_RENDER;
            }
            break;
        }
        case 7: {   /* GetOcclusionPassivMESAX */
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
            if (e == GL_NO_ERROR && pname == GL_OCCLUSION_PASS_RESULT_MESAX) {
                /* The buffers of the pass are storage[0..] (every buffer set is storage[k]). */
                check_records(pass_tiles[k] < buffers ? pass_tiles[k] : buffers);
                ++pass_objects_read;
            }
            break;
        }
        case 8: {   /* BeginConditionalRenderOcclusionTileMESAX */
            static const GLenum modes[] = {GL_QUERY_WAIT, GL_QUERY_NO_WAIT, GL_QUERY_BY_REGION_WAIT};
            static const float ratios[] = {0.0f, 0.25f, 1.0f, -1.0f, 1e30f};
            const GLenum m = modes[next(3)];
            int k;
            const GLuint name = pick_name(&k);
            const GLuint tile = next(4);
            const float ratio = ratios[next(5)];
            a.BeginConditionalRenderOcclusionTile(name, tile, next(8), ratio, m);
            GLenum e = GL_NO_ERROR;
            if (cond >= 0)
                e = GL_INVALID_OPERATION;
            else if (m == GL_QUERY_BY_REGION_WAIT)
                e = GL_INVALID_ENUM;
            else if (!is_pass(k) || held[k] != ENDED)
                e = GL_INVALID_OPERATION;
            else if ((int)tile >= pass_tiles[k] || ratio < 0.0f)
                e = GL_INVALID_VALUE;
            expect(e, "BeginConditionalRenderOcclusionTileMESAX", i);
            if (e == GL_NO_ERROR) {
                cond = k;
                ++conditions_begun;
            }
            break;
        }
        case 9: {   /* EndConditionalRenderOcclusionTileMESAX */
            a.EndConditionalRenderOcclusionTile();
            expect(cond >= 0 ? GL_NO_ERROR : GL_INVALID_OPERATION, "EndConditionalRenderOcclusionTileMESAX", i);
            cond = -1;
            break;
        }
        default: {   /* a draw */
            const float x0 = (float)next(40) - 4, y0 = (float)next(40) - 4;
            ou_rect(x0, y0, x0 + (float)next(20), y0 + (float)next(20), (float)next(100) / 100.0f);
            expect(GL_NO_ERROR, "draw", i);
            break;
        }
        }
        GLint got_mode = 0, got_tiles = -1, got_current = -1;
        glGetIntegerv(GL_RENDER_MODE, &got_mode);
        glGetIntegerv(GL_OCCLUSION_TILE_COUNT_MESAX, &got_tiles);
        glGetIntegerv(GL_CURRENT_OCCLUSION_PASS_MESAX, &got_current);
        const GLint model_current = current >= 0 ? (GLint)names[current] : 0;
        if (((GLenum)got_mode != mode || got_tiles != tiles || got_current != model_current) && state_ok) {
            printf("call %u: RENDER_MODE 0x%x, tiles %d, current pass %d; the model says 0x%x, %d, %d\n", i, got_mode,
                   got_tiles, got_current, mode, tiles, model_current);
            state_ok = false;
        }
    }
    if (cond >= 0)
        a.EndConditionalRenderOcclusionTile();
    if (current >= 0)
        a.EndOcclusionPass();
    glRenderMode(GL_RENDER);
    printf("%lu calls: %u passes ended, %u records checked, %u pass objects read, %u conditional renderings\n",
           calls, passes_ended, records_checked, pass_objects_read, conditions_begun);
    /* The random walk must have reached the cases it exists for. */
    subtest(passes_ended > 100 && records_checked > 1000, "walk-reaches-occlusion-passes");
    subtest(pass_objects_read > 100 && conditions_begun > 100, "walk-reaches-pass-objects");
    subtest(errors_ok, "errors-match-the-spec");
    subtest(state_ok, "state-matches-the-model");
    subtest(records_ok, "records-well-formed");
    piglit_report_result(result);
}
