#ifndef ZV_PIXELS_H
#define ZV_PIXELS_H
/* pixels: a picture as real pixels for terminals that draw them, in the
 * three protocols terminals speak: DEC sixel (xterm -ti vt340, mlterm,
 * foot, WezTerm, Konsole, Windows Terminal), the kitty graphics
 * protocol (kitty, WezTerm, Ghostty, Konsole) and iTerm2's inline images
 * (iTerm2, WezTerm). The encoders turn an Image into the bytes that draw
 * it at the cursor. Asking the terminal which it takes is the
 * terminal's room (tty.h, src/tty/termgfx.c). */

#include <stddef.h>
#include <stdint.h>

#include "image.h"

/* A cell's size in pixels where the terminal does not say. */
#define PIXELS_CELL_W 10
#define PIXELS_CELL_H 20

typedef enum { PIX_CELLS = 0, PIX_SIXEL, PIX_KITTY, PIX_ITERM, PIX_AUTO, PIX_COUNT } PixelProto;

extern const char *const pixel_proto_names[PIX_COUNT];

/* A growing run of bytes; err is set (and stays) when it cannot grow. */
typedef struct {
    uint8_t *b;
    size_t   len, cap;
    int      err;
} ByteBuf;

void bytebuf_put(ByteBuf *o, const void *p, size_t n);
void bytebuf_puts(ByteBuf *o, const char *s);
void bytebuf_free(ByteBuf *o);

/* Standard base64 (RFC 4648, with padding) of n bytes, appended. */
void base64_put(ByteBuf *o, const uint8_t *p, size_t n);

/* The bytes that draw im at the cursor in protocol p (SIXEL, KITTY or
 * ITERM), appended to out. kitty_id: the kitty image's number (a later
 * image of the same number replaces it, and the cursor stays: C=1); 0:
 * unnumbered, the cursor moves below it as after text. Sixel and iTerm2
 * leave the cursor where the terminal puts it. cols x rows > 0: kitty and
 * iTerm2 scale the image to fill that many cells (a smaller image then
 * fills the same place); sixel's pixels are the terminal's, 1:1. Returns
 * 0, or -1 out of memory. */
int  pixels_encode(PixelProto p, const Image *im, uint32_t kitty_id, int cols, int rows, ByteBuf *out);

/* The viewer's link budget: a still image is sent whole only when it
 * takes at most this long at --max-rate (KB/s, default below). */
#define PIXELS_RATE_DEFAULT 1000
#define PIXELS_BUDGET_S     0.5

/* The image as PNG bytes (zlib level 0..9), appended. Returns 0, or -1
 * with the reason in err. */
int  png_encode(const Image *im, int level, ByteBuf *out, char *err, size_t errlen);

#endif
