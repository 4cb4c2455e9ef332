/* glref.c: the reference the z-buffer's frame is held against (issue 35):
 * an OBJ's triangles drawn by OpenGL with a depth test into an offscreen
 * framebuffer (EGL, no window: Mesa's llvmpipe when LIBGL_ALWAYS_SOFTWARE=1),
 * from the views zview --bench --view front draws, and the median time of
 * a frame. A frame is clear, draw, glReadPixels of the colour (zview's
 * frame ends with a picture in memory too) and glFinish; --no-read leaves
 * the read out. Built by make bench-speed only; tools/bench-speed.sh runs it.
 *
 * Usage: glref [--size WxH] [--views N] [--no-read] [--ppm FILE] FILE.obj
 * (--ppm writes the first view's picture, to compare with zview -o's.)
 * Prints one line: renderer, triangles, size, views, frame and CPU medians.
 *
 * The view, as src/oneshot/bench.c and src/scene/transform.c make it for
 * --view front: the camera fitted at no turn (the model's box, centred,
 * its larger half filling 90% of the image, orthographic, depth over
 * [-2r, 2r] with r the box's half diagonal), then view k of n turned by
 * yaw 360k/n + 17 degrees and pitch 25((k mod 3) - 1) degrees. No
 * culling (zview's default). Faces are lit by their own normal (from the
 * derivatives of the view position), the light over the viewer's left.
 *
 * The OBJ reader takes v and f lines only (a/b/c corners, negative
 * indices, polygons as fans); anything else is skipped: it is a tool
 * for the benchmark's models, not a loader. */

#define _DEFAULT_SOURCE    /* mallopt */
#define _POSIX_C_SOURCE 200809L
#define GL_GLEXT_PROTOTYPES 1

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <GL/glext.h>
#include <malloc.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define MAX_VIEWS 1024
#define PI 3.14159265358979323846

typedef struct {
    float    *pos;      /* 3 a vertex */
    uint32_t *idx;      /* 3 a triangle */
    size_t    nv, nt, capv, capt;
} Model;

static int grow(void **p, size_t *cap, size_t need, size_t each)
{
    if (need <= *cap)
        return 0;
    size_t c = *cap ? *cap : 1024;
    while (c < need)
        c *= 2;
    void *q = realloc(*p, c * each);
    if (!q)
        return -1;
    *p = q;
    *cap = c;
    return 0;
}

/* The vertex a face corner names (1-based, or negative from the end). */
static int corner(const char **s, size_t nv, uint32_t *out)
{
    char *end;
    long v = strtol(*s, &end, 10);
    if (end == *s)
        return -1;
    while (*end && *end != ' ' && *end != '\t' && *end != '\r' && *end != '\n')
        end++;          /* /vt/vn */
    *s = end;
    long i = v > 0 ? v - 1 : (long)nv + v;
    if (v == 0 || i < 0 || (size_t)i >= nv)
        return -1;
    *out = (uint32_t)i;
    return 0;
}

static int read_obj(const char *path, Model *m)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        perror(path);
        return -1;
    }
    char line[4096];
    size_t ln = 0;
    int rc = 0;
    while (!rc && fgets(line, sizeof line, f)) {
        ln++;
        if (line[0] == 'v' && (line[1] == ' ' || line[1] == '\t')) {
            if (grow((void **)&m->pos, &m->capv, 3 * (m->nv + 1), sizeof *m->pos)) {
                rc = -1;
                break;
            }
            float *p = m->pos + 3 * m->nv;
            if (sscanf(line + 2, "%f %f %f", &p[0], &p[1], &p[2]) != 3) {
                fprintf(stderr, "glref: %s:%zu: a vertex without three numbers\n", path, ln);
                rc = -1;
            }
            m->nv++;
        } else if (line[0] == 'f' && (line[1] == ' ' || line[1] == '\t')) {
            const char *s = line + 2;
            uint32_t first = 0, prev = 0, v;
            int n = 0;
            for (;;) {
                while (*s == ' ' || *s == '\t')
                    s++;
                if (!*s || *s == '\r' || *s == '\n')
                    break;
                if (corner(&s, m->nv, &v)) {
                    fprintf(stderr, "glref: %s:%zu: a face corner it cannot read\n", path, ln);
                    rc = -1;
                    break;
                }
                if (n == 0)
                    first = v;
                else if (n >= 2) {
                    if (grow((void **)&m->idx, &m->capt, 3 * (m->nt + 1), sizeof *m->idx)) {
                        rc = -1;
                        break;
                    }
                    uint32_t *t = m->idx + 3 * m->nt++;
                    t[0] = first, t[1] = prev, t[2] = v;
                }
                prev = v;
                n++;
            }
        }
    }
    if (ferror(f)) {
        fprintf(stderr, "glref: %s: read error\n", path);
        rc = -1;
    }
    fclose(f);
    if (!rc && !m->nt) {
        fprintf(stderr, "glref: %s: no triangles\n", path);
        rc = -1;
    }
    return rc;
}

static double now_ms(clockid_t c)
{
    struct timespec ts;
    clock_gettime(c, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static const char *vs_src =
    "#version 330 core\n"
    "layout(location = 0) in vec3 pos;\n"
    "uniform mat4 view;\n"      /* model to view space (x right, y up, z to the viewer) */
    "uniform vec3 ndc;\n"       /* view to clip: x, y scales and the depth scale */
    "out vec3 vpos;\n"
    "void main() {\n"
    "    vec4 v = view * vec4(pos, 1.0);\n"
    "    vpos = v.xyz;\n"
    "    gl_Position = vec4(v.x * ndc.x, v.y * ndc.y, -v.z * ndc.z, 1.0);\n"
    "}\n";
static const char *fs_src =
    "#version 330 core\n"
    "in vec3 vpos;\n"
    "out vec4 colour;\n"
    "void main() {\n"
    "    vec3 n = normalize(cross(dFdx(vpos), dFdy(vpos)));\n"
    "    float d = abs(dot(n, normalize(vec3(-0.45, 0.6, 0.66))));\n"
    "    colour = vec4(vec3(0.22 + 0.78 * d), 1.0);\n"
    "}\n";

static GLuint shader(GLenum kind, const char *src)
{
    GLuint s = glCreateShader(kind);
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024];
        glGetShaderInfoLog(s, sizeof log, NULL, log);
        fprintf(stderr, "glref: shader: %s\n", log);
        return 0;
    }
    return s;
}

/* Column-major yaw-pitch turn (as m4_rotate_ypr, roll 0) after moving c to the origin. */
static void view_matrix(float out[16], float yaw, float pitch, const double c[3])
{
    float cy = cosf(yaw), sy = sinf(yaw), cp = cosf(pitch), sp = sinf(pitch);
    /* rows of rx * ry */
    float r[3][3] = { { cy, 0, sy }, { sp * sy, cp, -sp * cy }, { -cp * sy, sp, cp * cy } };
    memset(out, 0, 16 * sizeof *out);
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++)
            out[j * 4 + i] = r[i][j];
        out[12 + i] = -(float)(r[i][0] * c[0] + r[i][1] * c[1] + r[i][2] * c[2]);
    }
    out[15] = 1;
}

/* The picture, rows from the top (OpenGL's go from the bottom). */
static int write_ppm(const char *path, const unsigned char *rgba, int w, int h)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        perror(path);
        return -1;
    }
    fprintf(f, "P6\n%d %d\n255\n", w, h);
    for (int y = h - 1; y >= 0; y--)
        for (int x = 0; x < w; x++)
            fwrite(rgba + 4 * ((size_t)y * w + x), 1, 3, f);
    if (fclose(f) != 0) {
        fprintf(stderr, "glref: %s: write error\n", path);
        return -1;
    }
    return 0;
}

int main(int argc, char **argv)
{
    int w = 1920, h = 1080, views = 8, readback = 1;
    const char *file = NULL, *ppm = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--size") && i + 1 < argc) {
            if (sscanf(argv[++i], "%dx%d", &w, &h) != 2 || w < 1 || h < 1 || w > 16384 || h > 16384) {
                fprintf(stderr, "glref: --size WxH\n");
                return 2;
            }
        } else if (!strcmp(argv[i], "--views") && i + 1 < argc) {
            views = atoi(argv[++i]);
            if (views < 1 || views > MAX_VIEWS) {
                fprintf(stderr, "glref: --views 1..%d\n", MAX_VIEWS);
                return 2;
            }
        } else if (!strcmp(argv[i], "--ppm") && i + 1 < argc) {
            ppm = argv[++i];
        } else if (!strcmp(argv[i], "--no-read")) {
            readback = 0;
        } else if (argv[i][0] != '-' && !file) {
            file = argv[i];
        } else {
            fprintf(stderr, "usage: glref [--size WxH] [--views N] [--no-read] [--ppm FILE] FILE.obj\n");
            return 2;
        }
    }
    if (!file) {
        fprintf(stderr, "usage: glref [--size WxH] [--views N] [--no-read] [--ppm FILE] FILE.obj\n");
        return 2;
    }
    /* llvmpipe allocates and frees its bins and vertex buffers every
     * frame; glibc would hand the memory back to the kernel each time and
     * fault it in again (two thirds of the bunny's frame): kept here, so
     * that llvmpipe is measured at its best */
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
    mallopt(M_TOP_PAD, 256 << 20);
    mallopt(M_MMAP_THRESHOLD, 1 << 30);
    Model m = { 0 };
    if (read_obj(file, &m))
        return 1;

    /* the fit at no turn: the box of the vertices */
    double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (size_t v = 0; v < m.nv; v++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], m.pos[3 * v + k]);
            hi[k] = fmax(hi[k], m.pos[3 * v + k]);
        }
    double c[3], half[3], r2 = 0;
    for (int k = 0; k < 3; k++) {
        c[k] = 0.5 * (lo[k] + hi[k]);
        half[k] = 0.5 * (hi[k] - lo[k]);
        r2 += half[k] * half[k];
    }
    double big = fmax(half[0], fmax(half[1], half[2])), tiny = big > 0 ? big * 1e-3 : 1;
    double hx = fmax(half[0], tiny), hy = fmax(half[1], tiny), r = r2 > 0 ? sqrt(r2) : 1;
    double fx = 0.9 * fmin(0.5 * w / hx, 0.5 * h / hy);    /* pixels a unit */

    /* EGL with no window: the surfaceless platform, else the default display */
    EGLDisplay dpy = EGL_NO_DISPLAY;
    PFNEGLGETPLATFORMDISPLAYEXTPROC getdpy =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    if (getdpy)
        dpy = getdpy(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    if (dpy == EGL_NO_DISPLAY)
        dpy = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    EGLint major, minor;
    if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, &major, &minor)) {
        fprintf(stderr, "glref: no EGL display (error 0x%x)\n", eglGetError());
        return 1;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        fprintf(stderr, "glref: EGL has no desktop OpenGL\n");
        return 1;
    }
    const EGLint cfg_attr[] = { EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE };
    EGLConfig cfg = NULL;
    EGLint ncfg = 0;
    eglChooseConfig(dpy, cfg_attr, &cfg, 1, &ncfg);     /* surfaceless: none may match, and none is needed */
    const EGLint ctx_attr[] = { EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE };
    EGLContext ctx = eglCreateContext(dpy, ncfg ? cfg : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, ctx_attr);
    if (ctx == EGL_NO_CONTEXT || !eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
        fprintf(stderr, "glref: no OpenGL 3.3 context without a surface (error 0x%x)\n", eglGetError());
        return 1;
    }

    GLuint fbo, rb[2];
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glGenRenderbuffers(2, rb);
    glBindRenderbuffer(GL_RENDERBUFFER, rb[0]);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
    glBindRenderbuffer(GL_RENDERBUFFER, rb[1]);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb[1]);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        fprintf(stderr, "glref: the %dx%d framebuffer is incomplete\n", w, h);
        return 1;
    }
    GLuint vs = shader(GL_VERTEX_SHADER, vs_src), fs = shader(GL_FRAGMENT_SHADER, fs_src);
    if (!vs || !fs)
        return 1;
    GLuint prog = glCreateProgram();
    glAttachShader(prog, vs);
    glAttachShader(prog, fs);
    glLinkProgram(prog);
    glUseProgram(prog);
    GLuint vao, buf[2];
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(2, buf);
    glBindBuffer(GL_ARRAY_BUFFER, buf[0]);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(m.nv * 3 * sizeof(float)), m.pos, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, NULL);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buf[1]);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(m.nt * 3 * sizeof(uint32_t)), m.idx, GL_STATIC_DRAW);
    glViewport(0, 0, w, h);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClearColor(0, 0, 0, 0);
    GLint u_view = glGetUniformLocation(prog, "view"), u_ndc = glGetUniformLocation(prog, "ndc");
    glUniform3f(u_ndc, (float)(fx / (0.5 * w)), (float)(fx / (0.5 * h)), (float)(0.5 / r));
    unsigned char *pixels = malloc((size_t)w * h * 4);
    double *wall = malloc(sizeof(double) * views * 2), *cpu = wall + views;
    if (!pixels || !wall) {
        fprintf(stderr, "glref: out of memory\n");
        return 1;
    }

    /* a pass over every view first: llvmpipe compiles its code on first use */
    uint64_t covered = 0;
    for (int pass = 0; pass < 2; pass++)
        for (int k = 0; k < views; k++) {
            float mv[16];
            view_matrix(mv, (float)((360.0 * k / views + 17) * PI / 180), (float)(25.0 * (k % 3 - 1) * PI / 180), c);
            double t0 = now_ms(CLOCK_MONOTONIC), c0 = now_ms(CLOCK_PROCESS_CPUTIME_ID);
            glUniformMatrix4fv(u_view, 1, GL_FALSE, mv);
            glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            glDrawElements(GL_TRIANGLES, (GLsizei)(m.nt * 3), GL_UNSIGNED_INT, NULL);
            if (readback)
                glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
            glFinish();
            wall[k] = now_ms(CLOCK_MONOTONIC) - t0;
            cpu[k] = now_ms(CLOCK_PROCESS_CPUTIME_ID) - c0;
            if (pass == 1 && k == 0 && readback) {
                for (size_t i = 0; i < (size_t)w * h; i++)
                    covered += pixels[4 * i + 3] != 0;
                if (ppm && write_ppm(ppm, pixels, w, h))
                    return 1;
            }
        }
    GLenum err = glGetError();
    if (err != GL_NO_ERROR) {
        fprintf(stderr, "glref: OpenGL error 0x%x\n", err);
        return 1;
    }
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    printf("renderer \"%s\" triangles %zu size %dx%d views %d read %s frame_ms %.3f cpu_ms %.3f covered_pct %.1f\n",
           renderer ? renderer : "?", m.nt, w, h, views, readback ? "colour" : "none", median(wall, views),
           median(cpu, views), 100.0 * covered / ((double)w * h));
    free(pixels);
    free(wall);
    free(m.pos);
    free(m.idx);
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, ctx);
    eglTerminate(dpy);
    return fflush(stdout) == 0 && !ferror(stdout) ? 0 : 1;
}
