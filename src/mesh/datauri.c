/* datauri.c: a glTF whose one image is a data: URI that is not base64
 * (a cut or mangled file) is refused whole by assimp ("Invalid base64
 * encoded data"). The model is worth drawing without that image: its
 * JSON is handed to assimp again with each such URI replaced by one of
 * a few known bytes (MESH_BROKEN_IMAGE), which assimp embeds like any
 * image and the texture loader (assimp.c) turns into a warning naming
 * it. Buffers (geometry) are left as they are: without them there is no
 * model. */

#include <stdlib.h>
#include <string.h>

#include "mesh_internal.h"

/* base64 of MESH_BROKEN_IMAGE */
#define BROKEN_URI "data:application/x-zview-broken;base64,enZpZXc6IG5vdCBiYXNlNjQ="

static int b64_char(char c)
{
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '+' || c == '/';
}

/* Whether s[0, n) (a JSON string's contents, after "base64,") is base64:
 * a multiple of 4 characters of its alphabet, at most two '=' at the end
 * ("\/" is JSON's escape of '/'). */
static int is_base64(const char *s, size_t n)
{
    size_t k = 0, pad = 0;
    for (size_t i = 0; i < n; i++, k++) {
        char c = s[i];
        if (c == '\\' && i + 1 < n && s[i + 1] == '/') {
            i++;
            c = '/';
        }
        if (c == '=') {
            pad++;
            continue;
        }
        if (pad || !b64_char(c))
            return 0;
    }
    return k % 4 == 0 && pad <= 2;
}

/* The broken image URI at s (just past its opening quote), its length
 * to the closing quote in *n_out; 0 when it is not one. */
static int broken_image_uri(const char *s, const char *end, size_t *n_out)
{
    static const char head[] = "data:image/";
    size_t hl = sizeof head - 1;
    if ((size_t)(end - s) < hl || memcmp(s, head, hl) != 0)
        return 0;
    const char *q = s;
    while (q < end && *q != '"')
        q += *q == '\\' && q + 1 < end ? 2 : 1;
    if (q >= end)
        return 0;
    *n_out = (size_t)(q - s);
    const char *b = NULL;
    for (const char *p = s; p + 7 <= q; p++)
        if (!memcmp(p, "base64,", 7)) {
            b = p + 7;
            break;
        }
    return b && !is_base64(b, (size_t)(q - b));
}

char *mesh_gltf_mend_images(const char *json, size_t len, size_t *len_out, int *n_out)
{
    const char *end = json + len;
    size_t out_len = 0;
    int n = 0;
    /* first the size; then the copy */
    for (int pass = 0; pass < 2; pass++) {
        char *out = pass ? malloc(out_len + 1) : NULL;
        if (pass && !out)
            return NULL;
        size_t o = 0;
        const char *p = json;
        n = 0;
        while (p < end) {
            const char *q = memchr(p, '"', (size_t)(end - p));
            size_t run = q ? (size_t)(q - p) + 1 : (size_t)(end - p), un;
            if (out)
                memcpy(out + o, p, run);
            o += run;
            p += run;
            if (q && broken_image_uri(p, end, &un)) {
                if (out)
                    memcpy(out + o, BROKEN_URI, sizeof BROKEN_URI - 1);
                o += sizeof BROKEN_URI - 1;
                p += un;
                n++;
            }
        }
        if (!n)
            return NULL;
        if (out) {
            out[o] = 0;
            *len_out = o;
            *n_out = n;
            return out;
        }
        out_len = o;
    }
    return NULL;
}
