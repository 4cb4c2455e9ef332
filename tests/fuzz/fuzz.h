#ifndef ZV_FUZZ_H
#define ZV_FUZZ_H
/* fuzz: the libFuzzer entry point every harness defines. The same object
 * links either with libFuzzer (make fuzz, clang) or with replay.c, a
 * plain main() that feeds it the seed and regression corpora (make test,
 * any compiler, no fuzzing engine). */

#include <stddef.h>
#include <stdint.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#endif
