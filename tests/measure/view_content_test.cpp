// A view with nothing to measure (measure/view_content.h): no geometry in sight, or a reference
// that the exposure tone-maps to nothing but black and white. Each is named with its cause; a
// view with anything between is measured.
#include <gtest/gtest.h>

#include "view_content.h"

namespace gbl {
namespace {

// An RGBA reference: a ramp of radiance, alpha = coverage.
Image reference(float coverage, float scale) {
    Image img(16, 9, 4);
    for (size_t p = 0; p < img.pixelCount(); ++p) {
        for (int c = 0; c < 3; ++c) img.pixels[p * 4 + size_t(c)] = scale * (0.05f + 0.9f * float(p) / float(img.pixelCount()));
        img.pixels[p * 4 + 3] = float(p) < coverage * float(img.pixelCount()) ? 1.0f : 0.0f;
    }
    return img;
}

TEST(ViewContent, AViewWithGradationIsMeasured) {
    EXPECT_EQ(nothingToMeasure(reference(0.5f, 1.0f), 1.0f), "");
    EXPECT_EQ(nothingToMeasure(reference(1.0f, 1.0f), 1.0f), "");
}

TEST(ViewContent, NoGeometryIsCoverageZero) {
    const std::string why = nothingToMeasure(reference(0.0f, 1.0f), 1.0f);
    EXPECT_NE(why.find("sees no geometry (coverage 0)"), std::string::npos) << why;
}

TEST(ViewContent, AReferenceClippedToBlackOrWhiteHasNothingToMeasure) {
    const std::string black = nothingToMeasure(reference(1.0f, 1.0f), 1e-30f);
    EXPECT_NE(black.find("all black at exposure 1e-30"), std::string::npos) << black;
    const std::string white = nothingToMeasure(reference(1.0f, 1.0f), 1e30f);
    EXPECT_NE(white.find("all white at exposure 1e+30"), std::string::npos) << white;
    // An environment of 5e8 everywhere at exposure 1: white.
    EXPECT_NE(nothingToMeasure(reference(1.0f, 5e8f), 1.0f).find("all white"), std::string::npos);
    // Black pixels beside clipped white ones: nothing between either.
    Image both = reference(1.0f, 1.0f);
    for (size_t p = 0; p < both.pixelCount() / 2; ++p)
        for (int c = 0; c < 3; ++c) both.pixels[p * 4 + size_t(c)] = 0.0f;
    EXPECT_NE(nothingToMeasure(both, 1e30f).find("only black and white"), std::string::npos);
    // One value between black and white is enough to measure.
    Image one = reference(1.0f, 0.0f);
    one.pixels[0] = 0.2f;
    EXPECT_EQ(nothingToMeasure(one, 1.0f), "");
}

}  // namespace
}  // namespace gbl
