#pragma once
// Image file I/O, loaded at run time from libmanylight_imageio.so beside the executable
// (the reasons are in scene/image_io_module.h).
#include "scene/image_io_module.h"

namespace manylight {

// The module's functions, loading it on first use. Throws Error naming the module when it
// cannot be loaded.
const ImageIoApi& imageIo();

// Links the module now, on this thread, so that a later imageIo() finds it linked; a module
// that will not load is left for that call to report.
void preloadImageIo();

}  // namespace manylight
