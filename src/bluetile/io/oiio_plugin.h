// The C interface between the library and its OpenImageIO plugin module (see image_file.h).
// Plain C types only, so the module and the library need not agree on any C++ ABI detail.
#pragma once

#include <stddef.h>

extern "C" {

// Each returns 0 on success, or non-zero with a message in `error` (always terminated, one line:
// what the image libraries would print on stderr while reading goes into it instead).
// Encodes pixels in the format that the extension of `name` names into *bytes (allocated with
// malloc; the caller frees it); the library then streams them to the output (output_file.h),
// checking every write. Nothing is written under `name`; OpenImageIO's messages use it. `bits`
// as for bluetile_oiio_write_fn. Returns 2 when that format cannot be written to memory.
typedef int (*bluetile_oiio_encode_fn)(const char* name, int width, int height, int channels, int bits,
                                       const void* pixels, unsigned char** bytes, size_t* size, char* error,
                                       size_t error_size);
// `bits` names the sample type of `pixels` and of the file: 8 (unsigned char), 16 (unsigned
// short) or 32 (float).
typedef int (*bluetile_oiio_write_fn)(const char* path, int width, int height, int channels, int bits,
                                      const void* pixels, char* error, size_t error_size);
// Allocates *values with malloc; the caller frees it. *is_float tells whether the file stores
// floating-point samples (EXR, HDR, float TIFF): integer samples come scaled to [0, 1].
// Whether OpenImageIO can write a file of the format that the extension of `name` names: 0 when it
// can; nothing is written.
typedef int (*bluetile_oiio_check_fn)(const char* name, char* error, size_t error_size);
typedef int (*bluetile_oiio_read_fn)(const char* path, int* width, int* height, int* channels, int* is_float,
                                     float** values, char* error, size_t error_size);
// The size of the image at `path` from its header alone, nothing decoded: the library refuses an
// image too large for memory before any pixel buffer is allocated.
typedef int (*bluetile_oiio_info_fn)(const char* path, int* width, int* height, int* channels, char* error,
                                     size_t error_size);
}

#define BLUETILE_OIIO_PLUGIN_NAME "libbluetile_oiio.so"
