#include "image.h"

namespace gbl {

Image::Image(int w, int h, int c, float fill)
    : width(w), height(h), channels(c), pixels(size_t(w) * size_t(h) * size_t(c), fill) {}

}  // namespace gbl
