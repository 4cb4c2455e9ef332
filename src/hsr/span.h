#ifndef ZV_SPAN_H
#define ZV_SPAN_H
/* span: private hooks of the interval scanline (src/hsr/span.c), for
 * tests and analysis. */

#include <stdint.h>

/* Samples decided one by one (near-ties, piercing, unsafe planes) over
 * the life of a span state (a pointer from hsr_span.create()). */
uint64_t span_fallback_samples(const void *st);
/* Rows whose next active list was radix-sorted because keeping it
 * sorted by insertion passed its budget (many edges crossing). */
uint64_t span_resorted_rows(const void *st);

#endif
