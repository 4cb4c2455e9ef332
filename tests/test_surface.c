/* test_surface.c: textures and vertex colours, from the files that name
 * them to the shaded picture. Images are written here with libpng and
 * libjpeg; the expected colours come from the sRGB formula (IEC
 * 61966-2-1) written out below and from the geometry of the views, not
 * from the code under test. assimp's test models are Debian's
 * assimp-testmodels (tools/deps.sh installs it). */

#define _DEFAULT_SOURCE

#include <criterion/criterion.h>
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <jpeglib.h>

#include "app.h"
#include "simd.h"
#include "testlib.h"

#define AI_MODELS "/usr/share/assimp/models"

/* ==== helpers ==== */

/* The IEC 61966-2-1 encoding of linear light, in double, as a byte. */
static int iec_byte(double lin)
{
    double c = lin <= 0.0031308 ? lin * 12.92 : 1.055 * pow(lin, 1 / 2.4) - 0.055;
    return (int)floor(c * 255 + 0.5);
}

static char tmpdir[64];

static void make_tmpdir(void)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/zv-surface-XXXXXX");
    cr_assert_not_null(mkdtemp(tmpdir));
}

static void rm_tmpdir(void)
{
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
    cr_expect_eq(system(cmd), 0);
}

static void write_text(const char *name, const char *text)
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", tmpdir, name);
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f, "%s", path);
    fputs(text, f);
    fclose(f);
}

/* A w x h grey image, each texel's value from f, as a PNG file. */
static void write_png_file(const char *name, int w, int h, uint8_t (*f)(int x, int y))
{
    uint8_t *px = malloc((size_t)w * h * 4);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            uint8_t v = f(x, y);
            uint8_t *p = px + 4 * ((size_t)y * w + x);
            p[0] = p[1] = p[2] = v;
            p[3] = 255;
        }
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    img.width = (png_uint_32)w;
    img.height = (png_uint_32)h;
    img.format = PNG_FORMAT_RGBA;
    char path[256];
    snprintf(path, sizeof path, "%s/%s", tmpdir, name);
    cr_assert(png_image_write_to_file(&img, path, 0, px, 0, NULL), "%s", img.message);
    free(px);
}

/* The same as a JPEG (best quality: flat areas come back within a few
 * levels). */
static void write_jpeg_file(const char *name, int w, int h, uint8_t (*f)(int x, int y))
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", tmpdir, name);
    FILE *out = fopen(path, "wb");
    cr_assert_not_null(out);
    struct jpeg_compress_struct c;
    struct jpeg_error_mgr e;
    c.err = jpeg_std_error(&e);
    jpeg_create_compress(&c);
    jpeg_stdio_dest(&c, out);
    c.image_width = (JDIMENSION)w;
    c.image_height = (JDIMENSION)h;
    c.input_components = 3;
    c.in_color_space = JCS_RGB;
    jpeg_set_defaults(&c);
    jpeg_set_quality(&c, 100, TRUE);
    jpeg_start_compress(&c, TRUE);
    uint8_t *row = malloc((size_t)w * 3);
    while (c.next_scanline < c.image_height) {
        for (int x = 0; x < w; x++)
            row[3 * x] = row[3 * x + 1] = row[3 * x + 2] = f(x, (int)c.next_scanline);
        JSAMPROW r = row;
        jpeg_write_scanlines(&c, &r, 1);
    }
    jpeg_finish_compress(&c);
    jpeg_destroy_compress(&c);
    free(row);
    fclose(out);
}

/* A unit quad in the xy plane facing +z, texture coordinates over it
 * whole (v up, as OBJ has it), using material "m" of lib.mtl. */
static const char quad_obj[] = "mtllib lib.mtl\n"
                               "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
                               "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                               "usemtl m\nf 1/1 2/2 3/3 4/4\n";

/* Load the files named into a scene, the light from the viewer at full
 * strength (a texel's colour comes back as it is), seen from the front
 * turned by yaw degrees. */
static void load(Scene *s, const char *file, float yaw, int persp)
{
    Options o;
    cli_defaults(&o);
    char path[256];
    snprintf(path, sizeof path, "%s/%s", tmpdir, file);
    o.files[0] = path[0] == '/' && file[0] == '/' ? file : path;
    o.nfiles = 1;
    o.view = "front";
    o.yaw = yaw;
    o.turned = 1;
    o.persp = persp;
    o.fov = 60;
    o.light[0] = o.light[1] = 0;
    o.ambient = 1;
    char err[512];
    cr_assert_eq(app_load_scene(&o, s, err, sizeof err), 0, "%s", err);
}

static void render(Pipeline *p, Scene *s, int w, int h, ShadeMode shade)
{
    cr_assert_eq(pipeline_init(p, s, hsr_find("zbuffer"), 1), 0);
    p->shade = shade;
    cr_assert_eq(pipeline_render(p, w, h, 1.0f, 0, 1), 0);
}

static const uint8_t *px_at(const Pipeline *p, int x, int y)
{
    return p->img.rgb + 3 * ((size_t)y * p->img.w + x);
}

/* ==== perspective-correct ==== */

static uint8_t checker8(int x, int y) { return ((x + y) & 1) ? 255 : 0; }

Test(surface, a_checker_seen_from_the_front_shows_its_texels)
{
    make_tmpdir();
    write_png_file("c.png", 8, 8, checker8);
    write_text("lib.mtl", "newmtl m\nKd 1 1 1\nmap_Kd -clamp on c.png\n");
    write_text("q.obj", quad_obj);
    Scene s;
    load(&s, "q.obj", 0, 0);
    Pipeline p;
    render(&p, &s, 160, 160, SHADE_LAMBERT);
    /* the quad's box on screen, from the lit pixels */
    int x0 = 160, x1 = -1, y0 = 160, y1 = -1;
    for (int y = 0; y < 160; y++)
        for (int x = 0; x < 160; x++)
            if (p.img.lit[y * 160 + x]) {
                x0 = x < x0 ? x : x0;
                x1 = x > x1 ? x : x1;
                y0 = y < y0 ? y : y0;
                y1 = y > y1 ? y : y1;
            }
    cr_assert(x1 > x0 + 80 && y1 > y0 + 80, "the quad covers %d..%d x %d..%d", x0, x1, y0, y1);
    /* the centre of each texel: texel (i, j), j from the image's top,
     * is white when i + j is odd; the top of the picture is the
     * texture's top (OBJ's v = 1) */
    double cw = (x1 - x0 + 1) / 8.0, ch = (y1 - y0 + 1) / 8.0;
    for (int j = 0; j < 8; j++)
        for (int i = 0; i < 8; i++) {
            int x = (int)lround(x0 + (i + 0.5) * cw - 0.5), y = (int)lround(y0 + (j + 0.5) * ch - 0.5);
            const uint8_t *c = px_at(&p, x, y);
            int want = checker8(i, j);
            /* within half a pixel of the texel's centre each way, 18
             * pixels a texel: bilinear blends in at most an eighth of
             * the neighbours, linear */
            int lo = want ? iec_byte(0.88) : 0, hi = want ? 255 : iec_byte(0.12);
            cr_expect(c[0] >= lo && c[0] <= hi && c[0] == c[1] && c[1] == c[2], "texel %d,%d at %d,%d: %d, want %d",
                      i, j, x, y, c[0], want);
        }
    pipeline_free(&p);
    scene_free(&s);
    rm_tmpdir();
}

/* Black and white stripes a quarter of the texture wide: the edges of
 * the stripes at u = 1/4, 1/2, 3/4. */
static uint8_t stripes4(int x, int y)
{
    (void)y;
    return (x & 1) ? 255 : 0;
}

/* Where along row y the picture crosses from below to above (or back)
 * the mid-grey of linear 0.5, to a fraction of a pixel, after x. */
static double crossing(const Pipeline *p, int y, double after, int *found)
{
    int mid = iec_byte(0.5);
    for (int x = (int)after + 1; x + 1 < p->img.w; x++) {
        int a = px_at(p, x, y)[0], b = px_at(p, x + 1, y)[0];
        if (!p->img.lit[y * p->img.w + x] || !p->img.lit[y * p->img.w + x + 1])
            continue;
        if ((a - mid) * (b - mid) <= 0 && a != b) {
            *found = 1;
            return x + (double)(mid - a) / (b - a);
        }
    }
    *found = 0;
    return 0;
}

Test(surface, a_steeply_tilted_checker_keeps_straight_lines_straight)
{
    make_tmpdir();
    write_png_file("s.png", 4, 1, stripes4);
    write_text("lib.mtl", "newmtl m\nKd 1 1 1\nmap_Kd -clamp on s.png\n");
    write_text("q.obj", quad_obj);
    Scene s;
    load(&s, "q.obj", 65, 1);
    Pipeline p;
    render(&p, &s, 240, 160, SHADE_LAMBERT);
    /* per row crossed by the quad: the three stripe edges */
    double xs[3][160];
    int ys[160], n = 0;
    for (int y = 0; y < 160; y++) {
        double x = -1;
        int ok = 1, f;
        double row[3];
        for (int k = 0; k < 3 && ok; k++) {
            x = crossing(&p, y, x, &f);
            row[k] = x;
            ok = f;
        }
        if (!ok)
            continue;
        for (int k = 0; k < 3; k++)
            xs[k][n] = row[k];
        ys[n++] = y;
    }
    cr_assert(n > 40, "the stripes' edges cross %d rows", n);
    for (int k = 0; k < 3; k++) {
        /* a straight 3D line projects to a straight line: every edge's
         * crossings lie on the line through its first and last, across
         * the quad's diagonal (where its two triangles meet) too */
        double xa = xs[k][0], xb = xs[k][n - 1], ya = ys[0], yb = ys[n - 1], worst = 0;
        for (int i = 0; i < n; i++) {
            double on = xa + (xb - xa) * (ys[i] - ya) / (yb - ya);
            worst = fmax(worst, fabs(xs[k][i] - on));
        }
        cr_expect(worst < 0.75, "stripe edge %d strays %.2f pixels from a straight line", k + 1, worst);
    }
    /* and perspective spaces them unevenly: equal steps in u get
     * smaller towards the far side (the quad turned by 65 degrees, its
     * far side is 2.2x as far as its near one) */
    int mid = n / 2;
    double d1 = xs[1][mid] - xs[0][mid], d2 = xs[2][mid] - xs[1][mid];
    cr_expect(fabs(d1 - d2) > 0.15 * fmax(d1, d2), "stripes %.2f and %.2f pixels wide: affine, not perspective",
              d1, d2);
    pipeline_free(&p);
    scene_free(&s);
    rm_tmpdir();
}

/* ==== filtering ==== */

static uint8_t checker1(int x, int y) { return ((x + y) & 1) ? 255 : 0; }

Test(surface, a_fine_checker_far_away_averages_instead_of_aliasing)
{
    make_tmpdir();
    write_png_file("f.png", 256, 256, checker1);
    write_text("lib.mtl", "newmtl m\nKd 1 1 1\nmap_Kd f.png\n");
    write_text("q.obj", quad_obj);
    Scene s;
    load(&s, "q.obj", 0, 0);
    Pipeline p;
    /* about 8 texels a pixel each way */
    render(&p, &s, 36, 36, SHADE_LAMBERT);
    int want = iec_byte(0.5), n = 0;
    for (int y = 0; y < 36; y++)
        for (int x = 0; x < 36; x++)
            if (p.img.lit[y * 36 + x]) {
                n++;
                cr_expect(abs(px_at(&p, x, y)[0] - want) <= 6, "pixel %d,%d: %d, want about %d (linear 0.5)", x, y,
                          px_at(&p, x, y)[0], want);
            }
    cr_expect(n > 500);
    pipeline_free(&p);
    scene_free(&s);
    rm_tmpdir();
}

/* ==== vertex colours ==== */

static const char rgb_ply[] = "ply\nformat ascii 1.0\nelement vertex 3\n"
                              "property float x\nproperty float y\nproperty float z\n"
                              "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                              "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                              "-1 -1 0 255 0 0\n1 -1 0 0 255 0\n0 1 0 0 0 255\n3 0 1 2\n";

static void vertex_colours(ShadeMode mode)
{
    make_tmpdir();
    write_text("t.ply", rgb_ply);
    Scene s;
    load(&s, "t.ply", 0, 0);
    Pipeline p;
    render(&p, &s, 120, 120, mode);
    /* the centroid: a third of each, in linear light */
    int x0 = 120, x1 = -1, y0 = 120, y1 = -1;
    for (int y = 0; y < 120; y++)
        for (int x = 0; x < 120; x++)
            if (p.img.lit[y * 120 + x]) {
                x0 = x < x0 ? x : x0;
                x1 = x > x1 ? x : x1;
                y0 = y < y0 ? y : y0;
                y1 = y > y1 ? y : y1;
            }
    /* corners: bottom left red, bottom right green, top middle blue */
    int cx = (x0 + x1) / 2, cy = y0 + (y1 - y0) * 2 / 3;
    const uint8_t *c = px_at(&p, cx, cy);
    int third = iec_byte(1.0 / 3);
    for (int a = 0; a < 3; a++)
        cr_expect(abs(c[a] - third) <= 12, "%s: the centre's channel %d is %d, want about %d (a third each)",
                  shade_names[mode], a, c[a], third);
    const int at[3][2] = { { x0 + 3, y1 - 2 }, { x1 - 3, y1 - 2 }, { (x0 + x1) / 2, y0 + 4 } };
    for (int k = 0; k < 3; k++) {
        c = px_at(&p, at[k][0], at[k][1]);
        cr_expect(c[k] > 200 && c[(k + 1) % 3] < 120 && c[(k + 2) % 3] < 120,
                  "%s: near corner %d: %d %d %d, want mostly its own colour", shade_names[mode], k, c[0], c[1], c[2]);
    }
    pipeline_free(&p);
    scene_free(&s);
    rm_tmpdir();
}

/* ==== every SIMD level draws a textured mesh alike ==== */

static uint8_t noise7(int x, int y) { return (uint8_t)((x * 73 + y * 151 + ((x * y) ^ 0x5a)) & 255); }

/* A wavy grid of n x n quads split into triangles, texture coordinates
 * running over [-1.3, 2.7) (repeated or clamped), small faces of a
 * dozen samples at 200x160 as a detailed model has them. */
static void write_wavy_grid(const char *name, int n)
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", tmpdir, name);
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f);
    fprintf(f, "mtllib lib.mtl\nusemtl m\n");
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++)
            fprintf(f, "v %g %g %g\nvt %g %g\n", (double)i / n * 2 - 1, (double)j / n * 2 - 1,
                    0.15 * sin(0.9 * i) * cos(0.7 * j), 4.0 * i / n - 1.3, 4.0 * j / n - 1.3);
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            int a = j * (n + 1) + i + 1, b = a + 1, c = a + n + 2, d = a + n + 1;
            fprintf(f, "f %d/%d %d/%d %d/%d\nf %d/%d %d/%d %d/%d\n", a, a, b, b, c, c, a, a, c, c, d, d);
        }
    cr_assert_eq(fclose(f), 0);
}

/* The picture of file at each SIMD level (ZV_SIMD) against scalar's,
 * byte for byte: the faces seen flat on are looked up several samples
 * at a time at SSE2 and AVX2 (texture_lookup_row), one at a time at
 * scalar, and must come out the same. */
static void expect_levels_alike(const char *file, float yaw, int persp)
{
    Scene s;
    load(&s, file, yaw, persp);
    Pipeline ref;
    cr_assert_eq(setenv("ZV_SIMD", "scalar", 1), 0);
    render(&ref, &s, 200, 160, SHADE_LAMBERT);
    /* the texture shows: not one grey for the whole picture */
    int lit = 0, grey = -1, varied = 0;
    for (int i = 0; i < 200 * 160; i++)
        if (ref.img.lit[i]) {
            lit++;
            varied |= grey >= 0 && ref.img.rgb[3 * i] != grey;
            grey = ref.img.rgb[3 * i];
        }
    cr_assert(lit > 2000 && varied, "%s: %d samples lit", file, lit);
    for (int l = SIMD_SSE2; l <= (int)simd_best(); l++) {
        cr_assert_eq(setenv("ZV_SIMD", simd_name(l), 1), 0);
        Pipeline p;
        render(&p, &s, 200, 160, SHADE_LAMBERT);
        for (int i = 0; i < 200 * 160; i++)
            cr_assert_eq(memcmp(p.img.rgb + 3 * i, ref.img.rgb + 3 * i, 3), 0,
                         "%s yaw %g persp %d at %s: pixel %d,%d is %d %d %d, scalar %d %d %d", file, (double)yaw, persp,
                         simd_name(l), i % 200, i / 200, p.img.rgb[3 * i], p.img.rgb[3 * i + 1], p.img.rgb[3 * i + 2],
                         ref.img.rgb[3 * i], ref.img.rgb[3 * i + 1], ref.img.rgb[3 * i + 2]);
        pipeline_free(&p);
    }
    unsetenv("ZV_SIMD");
    pipeline_free(&ref);
    scene_free(&s);
}

Test(surface, every_simd_level_draws_a_textured_mesh_alike)
{
    make_tmpdir();
    write_png_file("n.png", 61, 37, noise7);
    write_wavy_grid("g.obj", 14);
    write_wavy_grid("c.obj", 14);
    write_text("lib.mtl", "newmtl m\nKd 1 0.8 0.6\nmap_Kd n.png\n");
    /* magnified and minified (the faces turned away), flat on and in
     * perspective */
    for (int k = 0; k < 3; k++)
        expect_levels_alike("g.obj", 50.0f * k, k == 2);
    write_text("lib.mtl", "newmtl m\nKd 1 1 1\nmap_Kd -clamp on n.png\n");
    expect_levels_alike("c.obj", 35, 0);
    rm_tmpdir();
}

Test(surface, vertex_colours_vary_across_a_face_in_flat_shading)
{
    vertex_colours(SHADE_LAMBERT);
}

Test(surface, vertex_colours_vary_across_a_face_in_smooth_shading)
{
    vertex_colours(SHADE_SMOOTH);
}

/* ==== sources ==== */

static uint8_t half_lr(int x, int y)
{
    (void)y;
    return x < 8 ? 30 : 220;
}

/* A textured quad from an OBJ whose texture is `image`: the left half
 * of the picture dark, the right half light, as the image is. */
static void obj_texture(const char *image, int jpeg)
{
    make_tmpdir();
    char mtl[256];
    if (jpeg)
        write_jpeg_file(image, 16, 16, half_lr);
    else
        write_png_file(image, 16, 16, half_lr);
    snprintf(mtl, sizeof mtl, "newmtl m\nKd 1 1 1\nmap_Kd %s\n", image);
    write_text("lib.mtl", mtl);
    write_text("q.obj", quad_obj);
    Scene s;
    load(&s, "q.obj", 0, 0);
    cr_assert_eq(s.meshes[0].ntex, 1);
    cr_expect_eq(s.meshes[0].tex[0].state, MTEX_OK);
    cr_expect_eq(s.meshes[0].info.tex_failed, 0);
    Pipeline p;
    render(&p, &s, 100, 100, SHADE_LAMBERT);
    const uint8_t *l = px_at(&p, 30, 50), *r = px_at(&p, 70, 50);
    cr_expect(abs(l[0] - 30) <= 4 && abs(r[0] - 220) <= 4, "%s: left %d, right %d; want 30 and 220", image, l[0],
              r[0]);
    pipeline_free(&p);
    scene_free(&s);
    rm_tmpdir();
}

Test(surface, obj_textures_in_png_and_jpeg)
{
    obj_texture("a b.png", 0);      /* a name with a space */
    obj_texture("t.jpg", 1);
}

Test(surface, a_missing_texture_warns_once_by_name_and_shows_the_base_colour)
{
    make_tmpdir();
    write_text("lib.mtl", "newmtl m\nKd 1 0 0\nmap_Kd gone.png\nnewmtl n\nKd 1 0 0\nmap_Kd gone.png\n");
    write_text("q.obj", quad_obj);
    Scene s;
    load(&s, "q.obj", 0, 0);
    const MeshInfo *info = &s.meshes[0].info;
    cr_expect_eq(info->tex_failed, 1, "one warning for one missing image, %u", info->tex_failed);
    cr_expect(strstr(info->first_tex_failed, "gone.png") != NULL, "%s", info->first_tex_failed);
    Pipeline p;
    render(&p, &s, 60, 60, SHADE_LAMBERT);
    const uint8_t *c = px_at(&p, 30, 30);
    cr_expect(c[0] == 255 && c[1] == 0 && c[2] == 0, "the base colour: %d %d %d", c[0], c[1], c[2]);
    pipeline_free(&p);
    scene_free(&s);
    rm_tmpdir();
}

/* ==== images that cannot be had (issue 28) ==== */

static char *base64(const unsigned char *b, size_t n)
{
    static const char a[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    char *o = malloc(4 * (n + 2) / 3 + 4), *q = o;
    for (size_t i = 0; i < n; i += 3) {
        unsigned v = (unsigned)b[i] << 16 | (i + 1 < n ? (unsigned)b[i + 1] << 8 : 0) | (i + 2 < n ? b[i + 2] : 0);
        *q++ = a[v >> 18];
        *q++ = a[(v >> 12) & 63];
        *q++ = i + 1 < n ? a[(v >> 6) & 63] : '=';
        *q++ = i + 2 < n ? a[v & 63] : '=';
    }
    *q = 0;
    return o;
}

/* A 4 x 4 PNG of one colour, as a data: URI. */
static char *png_uri(uint8_t r, uint8_t g, uint8_t b)
{
    uint8_t px[4 * 4 * 4];
    for (int i = 0; i < 16; i++) {
        px[4 * i] = r;
        px[4 * i + 1] = g;
        px[4 * i + 2] = b;
        px[4 * i + 3] = 255;
    }
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    img.width = img.height = 4;
    img.format = PNG_FORMAT_RGBA;
    unsigned char buf[512];
    png_alloc_size_t n = sizeof buf;
    cr_assert(png_image_write_to_memory(&img, buf, &n, 0, px, 0, NULL));
    char *b64 = base64(buf, n), *uri = malloc(strlen(b64) + 32);
    sprintf(uri, "data:image/png;base64,%s", b64);
    free(b64);
    return uri;
}

/* Two triangles side by side (x -1..0 and 0..1, facing the viewer), each
 * with a material of its own whose base-colour image is the URI given. */
static void write_two_image_gltf(const char *name, const char *uri0, const char *uri1)
{
    float geo[18 + 12] = { -1, -1, 0, 0, -1, 0, -1, 1, 0, 0, -1, 0, 1, -1, 0, 0, 1, 0,
                           0, 1, 1, 1, 0, 0, 0, 1, 1, 1, 0, 0 };
    char *buf = base64((const unsigned char *)geo, sizeof geo);
    size_t n = strlen(buf) + strlen(uri0) + strlen(uri1) + 2048;
    char *json = malloc(n);
    snprintf(json, n,
             "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
             "\"buffers\":[{\"byteLength\":%zu,\"uri\":\"data:application/octet-stream;base64,%s\"}],"
             "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":72},"
             "{\"buffer\":0,\"byteOffset\":72,\"byteLength\":48}],"
             "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
             "\"min\":[-1,-1,0],\"max\":[0,1,0]},"
             "{\"bufferView\":0,\"byteOffset\":36,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
             "\"min\":[0,-1,0],\"max\":[1,1,0]},"
             "{\"bufferView\":1,\"componentType\":5126,\"count\":3,\"type\":\"VEC2\"},"
             "{\"bufferView\":1,\"byteOffset\":24,\"componentType\":5126,\"count\":3,\"type\":\"VEC2\"}],"
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"TEXCOORD_0\":2},\"material\":0,\"mode\":4},"
             "{\"attributes\":{\"POSITION\":1,\"TEXCOORD_0\":3},\"material\":1,\"mode\":4}]}],"
             "\"materials\":[{\"name\":\"m0\",\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}},"
             "{\"name\":\"m1\",\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":1}}}],"
             "\"samplers\":[{}],\"textures\":[{\"sampler\":0,\"source\":0},{\"sampler\":0,\"source\":1}],"
             "\"images\":[{\"uri\":\"%s\"},{\"uri\":\"%s\"}]}",
             sizeof geo, buf, uri0, uri1);
    write_text(name, json);
    free(json);
    free(buf);
}

#ifdef ZV_ASSIMP
Test(surface, a_gltf_with_one_broken_base64_image_draws_untextured_there_with_one_warning)
{
    make_tmpdir();
    char *red = png_uri(230, 20, 20), *green = png_uri(20, 230, 20);
    /* the second image cut: its base64 no longer a multiple of 4 characters */
    green[strlen(green) - 7] = 0;
    write_two_image_gltf("two.gltf", red, green);
    Scene s;
    load(&s, "two.gltf", 0, 0);
    const Mesh *m = &s.meshes[0];
    cr_assert_eq(m->ntex, 2);
    cr_expect_eq(m->tex[0].state, MTEX_OK);
    cr_expect_eq(m->tex[1].state, MTEX_FAILED);
    cr_expect_eq(m->info.tex_failed, 1);
    cr_expect_str_eq(m->info.first_tex_failed,
                     "texture two.gltf *1: its data: URI is not base64; its faces show their base colour");
    /* left: the red image; right: the base colour (glTF's default white) */
    Pipeline p;
    render(&p, &s, 100, 100, SHADE_LAMBERT);
    const uint8_t *l = px_at(&p, 25, 70), *r = px_at(&p, 62, 70);
    cr_expect(l[0] > 200 && l[1] < 60, "left %d %d %d", l[0], l[1], l[2]);
    cr_expect(r[0] > 200 && r[1] > 200 && r[2] > 200, "right %d %d %d", r[0], r[1], r[2]);
    pipeline_free(&p);
    scene_free(&s);
    /* an empty data: URI: the model loads, the material's image is named */
    write_two_image_gltf("empty.gltf", red, "data:");
    load(&s, "empty.gltf", 0, 0);
    cr_expect_eq(s.meshes[0].info.tex_failed, 1);
    cr_expect_str_eq(s.meshes[0].info.first_tex_failed,
                     "texture empty.gltf material 'm1': its image is empty (a data: URI without data?); its faces "
                     "show their base colour");
    scene_free(&s);
    free(red);
    free(green);
    rm_tmpdir();
}
#endif

Test(surface, map_kd_dot_says_it_names_a_folder)
{
    make_tmpdir();
    write_text("lib.mtl", "newmtl m\nKd 1 0 0\nmap_Kd .\n");
    write_text("q.obj", quad_obj);
    Scene s;
    load(&s, "q.obj", 0, 0);
    const MeshInfo *info = &s.meshes[0].info;
    cr_expect_eq(info->tex_failed, 1);
    cr_expect(strstr(info->first_tex_failed, "/.: a folder, not an image; its faces show their base colour") != NULL,
              "%s", info->first_tex_failed);
    cr_expect_null(strchr(info->first_tex_failed, '\n'));
    scene_free(&s);
    rm_tmpdir();
}

/* A model of assimp's test corpus: its textures decoded, and the
 * picture with them differs from the one without. */
static void assimp_model(const char *rel, uint32_t ntex)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", AI_MODELS, rel);
    cr_assert(access(path, R_OK) == 0, "%s: install assimp-testmodels (tools/deps.sh)", path);
    Scene s;
    load(&s, path, 30, 0);
    uint32_t n = 0, ok = 0;
    for (int i = 0; i < s.nmeshes; i++)
        for (uint32_t k = 0; k < s.meshes[i].ntex; k++, n++)
            ok += s.meshes[i].tex[k].state == MTEX_OK;
    cr_expect(n >= ntex && ok == n, "%s: %u textures, %u decoded", rel, n, ok);
    Pipeline p;
    render(&p, &s, 120, 90, SHADE_LAMBERT);
    Image with = { 0 };
    image_resize(&with, p.img.w, p.img.h);
    memcpy(with.rgb, p.img.rgb, (size_t)p.img.w * p.img.h * 3);
    p.no_textures = 1;
    cr_assert_eq(pipeline_render(&p, 120, 90, 1.0f, 0, 1), 0);
    long differ = 0;
    for (size_t i = 0; i < (size_t)p.img.w * p.img.h * 3; i++)
        differ += with.rgb[i] != p.img.rgb[i];
    cr_expect(differ > 300, "%s: the texture changes %ld channel values", rel, differ);
    image_free(&with);
    pipeline_free(&p);
    scene_free(&s);
}

#ifdef ZV_ASSIMP
Test(surface, assimp_textures_external_embedded_glb_data_uri)
{
    assimp_model("glTF2/BoxTextured-glTF/BoxTextured.gltf", 1);           /* a PNG beside it */
    assimp_model("glTF2/BoxTextured-glTF-Binary/BoxTextured.glb", 1);     /* in the GLB */
    assimp_model("glTF2/BoxTextured-glTF-Embedded/BoxTextured.gltf", 1);  /* a data: URI */
}

Test(surface, assimp_textures_collada_tga)
{
    assimp_model("Collada/duck.dae", 1);        /* a TGA beside it */
}
#endif

Test(surface, obj_jpeg_textures_of_the_spider)
{
    assimp_model("OBJ/spider.obj", 4);          /* map_Kd JPEG images, read natively */
}

/* ==== the exact step is untouched ==== */

Test(surface, every_algorithm_draws_the_same_ids_on_a_textured_scene)
{
    char path[512];
    snprintf(path, sizeof path, "%s/OBJ/spider.obj", AI_MODELS);
    cr_assert(access(path, R_OK) == 0, "%s: install assimp-testmodels (tools/deps.sh)", path);
    Scene s;
    cr_assert_eq(tl_scene_from_file(&s, path), 0);
    cr_assert_not_null(s.face_surf, "the spider is textured");
    TlAgree a = { 0 };
    for (uint32_t seed = 1; seed <= 6; seed++) {
        tl_random_view(&s, seed, seed & 1);
        Viewport vp = { 160, 120, 1.0f, 0 };
        char msg[256];
        cr_expect_eq(tl_agree(&a, &s, &vp, 1, msg, sizeof msg), 0, "seed %u: %s", seed, msg);
    }
    tl_agree_free(&a);
    scene_free(&s);
}

/* ==== big images after the first picture ==== */

#include "../src/viewer/viewer_app.h"

Test(surface, a_big_texture_waits_for_its_thread_and_then_shows)
{
    make_tmpdir();
    write_png_file("big.png", 16, 16, half_lr);
    write_text("lib.mtl", "newmtl m\nKd 1 1 1\nmap_Kd big.png\n");
    write_text("q.obj", quad_obj);
    Scene s;
    Options o;
    cli_defaults(&o);
    char path[256], err[512];
    snprintf(path, sizeof path, "%s/q.obj", tmpdir);
    o.files[0] = path;
    o.nfiles = 1;
    o.view = "front";
    o.light[0] = o.light[1] = 0;
    o.ambient = 1;
    o.tex_defer = 8;                /* "big": longer than 8 texels a side */
    cr_assert_eq(app_load_scene(&o, &s, err, sizeof err), 0, "%s", err);
    cr_assert_eq(s.meshes[0].ntex, 1);
    cr_expect_eq(s.meshes[0].tex[0].state, MTEX_PENDING, "left for later");
    /* the first picture: the base colour, white */
    Pipeline p;
    render(&p, &s, 100, 100, SHADE_LAMBERT);
    cr_expect(px_at(&p, 30, 50)[0] == 255 && px_at(&p, 70, 50)[0] == 255, "before: %d %d", px_at(&p, 30, 50)[0],
              px_at(&p, 70, 50)[0]);
    TexJob *job = texjob_start(&s, &o);
    cr_assert_not_null(job);
    char note[256] = "";
    int put = 0;
    for (int i = 0; i < 30000 && job; i++) {      /* 30 s at least: a loaded machine's */
        put |= texjob_poll(&job, &s, note, sizeof note);
        usleep(1000);
    }
    cr_assert_null(job, "the job ends");
    cr_expect(put && s.meshes[0].tex[0].state == MTEX_OK, "installed: %s", note);
    cr_assert_eq(pipeline_render(&p, 100, 100, 1.0f, 0, 1), 0);
    const uint8_t *l = px_at(&p, 30, 50), *r = px_at(&p, 70, 50);
    cr_expect(abs(l[0] - 30) <= 4 && abs(r[0] - 220) <= 4, "after: left %d, right %d", l[0], r[0]);
    pipeline_free(&p);
    scene_free(&s);
    rm_tmpdir();
}
