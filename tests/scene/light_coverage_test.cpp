// compare --lighting volumes: the mean light volumes covering a pixel, against the geometry of a
// sphere seen from a camera, worked out by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "light_coverage.h"

namespace gbl {
namespace {

Camera axisCamera() {
    Camera c;
    c.position = glm::vec3(0.0f, 0.0f, 10.0f);
    c.target = glm::vec3(0.0f);
    c.up = glm::vec3(0.0f, 1.0f, 0.0f);
    c.yFovRadians = 0.8f;
    return c;
}

TEST(LightCoverage, FullScreenLightsCoverEveryPixel) {
    Light sun;
    sun.type = LightType::Directional;
    Light point;  // range 0: infinite, a full-screen pass
    point.type = LightType::Point;
    EXPECT_DOUBLE_EQ(meanLightVolumesPerPixel({sun, point}, axisCamera(), 1920, 1080), 2.0);
    EXPECT_DOUBLE_EQ(meanLightVolumesPerPixel({}, axisCamera(), 1920, 1080), 0.0);
}

TEST(LightCoverage, ASphereCoversItsProjectedDisc) {
    // A sphere of radius 1 at distance 10 on the view axis: the rays that meet it form a cone of
    // half-angle asin(0.1); on the image plane at distance 1 a disc of radius tan(asin(0.1)). The
    // frame spans 2 tan(0.4) x 2 tan(0.4) * 16/9 there.
    Light l;
    l.type = LightType::Point;
    l.position = glm::vec3(0.0f);
    l.range = 1.0f;
    const double r = std::tan(std::asin(0.1)), t = std::tan(0.4);
    const double expected = M_PI * r * r / (2 * t * 2 * t * 16.0 / 9.0);
    EXPECT_NEAR(meanLightVolumesPerPixel({l}, axisCamera(), 1920, 1080), expected, 0.02 * expected);
    // Behind the camera: nothing.
    l.position = glm::vec3(0.0f, 0.0f, 20.0f);
    EXPECT_DOUBLE_EQ(meanLightVolumesPerPixel({l}, axisCamera(), 1920, 1080), 0.0);
    // The camera inside the volume: every pixel.
    l.position = glm::vec3(0.0f, 0.0f, 9.5f);
    EXPECT_DOUBLE_EQ(meanLightVolumesPerPixel({l}, axisCamera(), 1920, 1080), 1.0);
}

}  // namespace
}  // namespace gbl
