/* budget.c: the memory a sandboxed child may add when --max-memory does
 * not say: proportional to its input, never "what the machine has". A
 * hostile file is small and asks for much (assimp's node DAG, 852 bytes,
 * took 10.3 GB before it failed); a legitimate one is big, or names big
 * files, and asks for a few times their size.
 *
 * The input is the model's file and every file it names (material
 * libraries, glTF buffers, images), each counted once as the child opens
 * it: the child tells its parent, which checks the file is one the
 * model may name (mesh_ref_open, beneath its folder) and raises the
 * child's limits before it reads a byte (sandbox.c). What a byte of
 * input may take (the largest of each kind measured on real files:
 * the smallest --max-memory each loads within, over its size):
 *   - the native loaders: the dragon's 33 MB OBJ needs 2.1 times its
 *     size, as binary STL 1.6, ASCII STL 1.2, binary PLY 2.4, ASCII PLY
 *     1.5; the 31M-triangle OBJ (1.37 GB) 0.9: NATIVE_X;
 *   - assimp: the dragon as GLB 4.3, as glTF and its buffer 4.7, as
 *     COLLADA 36, assimp's own zipped COLLADA sample 38: LIBRARY_X;
 *   - an image: its texels, as many as its bytes can hold (deflate packs
 *     at most 1032 bytes into one, 8256 one-bit pixels; JPEG and TGA
 *     hold fewer), at most TEX_MAX_SIDE squared, each taking what the
 *     decoders ask at most: a progressive CMYK JPEG's coefficients
 *     (8 bytes a pixel) over a PNG's texels and levels (5.3).
 * and never less than SANDBOX_FLOOR, whatever the input: small files
 * with a parser's fixed costs (assimp's own samples need 17 to 40 MB). */

#include "sandbox_internal.h"
#include "sysmem.h"

#define NATIVE_X  4
#define LIBRARY_X 48
#define IMAGE_PX_PER_BYTE 8256
#define IMAGE_BYTES_PER_PX 8
#define IMAGE_SLACK ((uint64_t)64 << 20)    /* a decoder's tables and rows */
/* a thread's room besides the input's: glibc reserves a 64 MB heap
 * arena for a thread that allocates, and its stack is 8 MB (address
 * space, most of it never touched; the stack is writable data) */
#define THREAD_AS   ((uint64_t)80 << 20)
#define THREAD_DATA ((uint64_t)8 << 20)
/* beyond what the machine has available: the hard limits, which the
 * parent may raise the child's to */
#define CEILING_SLACK ((uint64_t)256 << 20)

static uint64_t mul_sat(uint64_t a, uint64_t k)
{
    return a > UINT64_MAX / k ? UINT64_MAX : a * k;
}

static uint64_t add_sat(uint64_t a, uint64_t b)
{
    return a > UINT64_MAX - b ? UINT64_MAX : a + b;
}

uint64_t sandbox_input_allowance(uint64_t bytes, int native)
{
    return mul_sat(bytes, native ? NATIVE_X : LIBRARY_X);
}

uint64_t sandbox_image_allowance(uint64_t bytes)
{
    uint64_t max_px = (uint64_t)TEX_MAX_SIDE * TEX_MAX_SIDE;
    uint64_t px = bytes < max_px / IMAGE_PX_PER_BYTE ? bytes * IMAGE_PX_PER_BYTE : max_px;
    return px * IMAGE_BYTES_PER_PX + IMAGE_SLACK;
}

uint64_t sandbox_budget_of(uint64_t allowance)
{
    return allowance > SANDBOX_FLOOR ? allowance : SANDBOX_FLOOR;
}

uint64_t sandbox_ceiling(void)
{
    return add_sat(sysmem_available(), CEILING_SLACK);
}

void sandbox_thread_room(int threads, uint64_t *as, uint64_t *data)
{
    uint64_t n = threads > 1 ? (uint64_t)threads - 1 : 0;
    *as = n * THREAD_AS;
    *data = n * THREAD_DATA;
}
