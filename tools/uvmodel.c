/* uvmodel: a textured copy of a model, for the texture benchmarks.
 *
 *   uvmodel IN OUT.obj IMAGE SIDE [TILES]
 *
 * reads IN (any format zview reads), writes OUT.obj with a texture
 * coordinate per vertex (the model projected onto the plane of its two
 * longest sides, TILES times across, default 4: the image repeats), an
 * MTL beside it (OUT with .mtl) naming IMAGE, and IMAGE itself: SIDE x
 * SIDE texels of a pattern with fine detail (a checker of 8-texel
 * squares over colour gradients), PNG or JPEG by its name. */

#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <jpeglib.h>

#include "mesh.h"

static void texel(int x, int y, int side, unsigned char *rgb)
{
    int check = ((x >> 3) + (y >> 3)) & 1;
    rgb[0] = (unsigned char)(40 + 200 * x / side);
    rgb[1] = (unsigned char)(40 + 200 * y / side);
    rgb[2] = (unsigned char)(check ? 220 : 60);
}

static int write_png(const char *path, int side)
{
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    img.width = img.height = (png_uint_32)side;
    img.format = PNG_FORMAT_RGB;
    unsigned char *px = malloc((size_t)side * side * 3);
    if (!px)
        return -1;
    for (int y = 0; y < side; y++)
        for (int x = 0; x < side; x++)
            texel(x, y, side, px + 3 * ((size_t)y * side + x));
    int ok = png_image_write_to_file(&img, path, 0, px, 0, NULL);
    free(px);
    return ok ? 0 : -1;
}

static int write_jpeg(const char *path, int side)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return -1;
    struct jpeg_compress_struct c;
    struct jpeg_error_mgr e;
    c.err = jpeg_std_error(&e);
    jpeg_create_compress(&c);
    jpeg_stdio_dest(&c, f);
    c.image_width = c.image_height = (JDIMENSION)side;
    c.input_components = 3;
    c.in_color_space = JCS_RGB;
    jpeg_set_defaults(&c);
    jpeg_set_quality(&c, 90, TRUE);
    jpeg_start_compress(&c, TRUE);
    unsigned char *row = malloc((size_t)side * 3);
    while (c.next_scanline < c.image_height) {
        for (int x = 0; x < side; x++)
            texel(x, (int)c.next_scanline, side, row + 3 * x);
        JSAMPROW r = row;
        jpeg_write_scanlines(&c, &r, 1);
    }
    jpeg_finish_compress(&c);
    jpeg_destroy_compress(&c);
    free(row);
    return fclose(f) ? -1 : 0;
}

int main(int argc, char **argv)
{
    if (argc < 5) {
        fprintf(stderr, "usage: uvmodel IN OUT.obj IMAGE SIDE [TILES]\n");
        return 2;
    }
    int side = atoi(argv[4]);
    float tiles = argc > 5 ? (float)atof(argv[5]) : 4;
    Mesh m;
    char err[512];
    if (mesh_load(&m, argv[1], err, sizeof err)) {
        fprintf(stderr, "uvmodel: %s\n", err);
        return 1;
    }
    float lo[3] = { 1e30f, 1e30f, 1e30f }, hi[3] = { -1e30f, -1e30f, -1e30f };
    for (uint32_t v = 0; v < m.nverts; v++)
        for (int k = 0; k < 3; k++) {
            float c = m.pos[3 * (size_t)v + k];
            lo[k] = c < lo[k] ? c : lo[k];
            hi[k] = c > hi[k] ? c : hi[k];
        }
    /* the two longest sides span the texture */
    int a = 0, b = 1, thin = 2;
    for (int k = 0; k < 3; k++)
        if (hi[k] - lo[k] < hi[thin] - lo[thin])
            thin = k;
    a = thin == 0 ? 1 : 0;
    b = thin == 2 ? 1 : 2;
    char mtl[4096];
    snprintf(mtl, sizeof mtl, "%s", argv[2]);
    char *dot = strrchr(mtl, '.');
    if (dot)
        strcpy(dot, ".mtl");
    const char *mtl_base = strrchr(mtl, '/') ? strrchr(mtl, '/') + 1 : mtl;
    const char *img_base = strrchr(argv[3], '/') ? strrchr(argv[3], '/') + 1 : argv[3];
    FILE *f = fopen(mtl, "w");
    if (!f || fprintf(f, "newmtl tex\nKd 1 1 1\nmap_Kd %s\n", img_base) < 0 || fclose(f)) {
        perror(mtl);
        return 1;
    }
    f = fopen(argv[2], "w");
    if (!f) {
        perror(argv[2]);
        return 1;
    }
    fprintf(f, "mtllib %s\nusemtl tex\n", mtl_base);
    for (uint32_t v = 0; v < m.nverts; v++)
        fprintf(f, "v %.9g %.9g %.9g\n", m.pos[3 * (size_t)v], m.pos[3 * (size_t)v + 1], m.pos[3 * (size_t)v + 2]);
    for (uint32_t v = 0; v < m.nverts; v++) {
        const float *p = &m.pos[3 * (size_t)v];
        fprintf(f, "vt %.6f %.6f\n", tiles * (p[a] - lo[a]) / (hi[a] - lo[a]), tiles * (p[b] - lo[b]) / (hi[b] - lo[b]));
    }
    for (uint32_t i = 0; i < m.nfaces; i++) {
        fputc('f', f);
        for (uint32_t c = m.face_start[i]; c < m.face_start[i + 1]; c++)
            fprintf(f, " %u/%u", m.corner[c] + 1, m.corner[c] + 1);
        fputc('\n', f);
    }
    if (fclose(f)) {
        perror(argv[2]);
        return 1;
    }
    mesh_free(&m);
    size_t n = strlen(argv[3]);
    int jpeg = n > 4 && (strcmp(argv[3] + n - 4, ".jpg") == 0 || strcmp(argv[3] + n - 5, ".jpeg") == 0);
    if ((jpeg ? write_jpeg(argv[3], side) : write_png(argv[3], side)) != 0) {
        fprintf(stderr, "uvmodel: cannot write %s\n", argv[3]);
        return 1;
    }
    return 0;
}
