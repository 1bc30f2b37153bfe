// The sizes and offsets of the astcenc structures the Rust binding declares, so that the
// binding can refuse to run when its declarations and the compiled header disagree.
#include <cstddef>
#include "astcenc.h"

extern "C" size_t splitsum_astcenc_config_size() { return sizeof(astcenc_config); }
extern "C" size_t splitsum_astcenc_config_callback_offset() { return offsetof(astcenc_config, progress_callback); }
extern "C" size_t splitsum_astcenc_image_size() { return sizeof(astcenc_image); }
extern "C" size_t splitsum_astcenc_swizzle_size() { return sizeof(astcenc_swizzle); }
