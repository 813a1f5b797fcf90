#pragma once
// compare --views: the cameras of the views, the mean over views, and where the sphere grid's
// balls are in the first view (for the IBL figure).
#include <cstdint>
#include <string>
#include <vector>

#include "ibl_figure.h"
#include "report_model.h"
#include "scene.h"

namespace gbl::compare {

// compare --views: the cameras. View 0 is the scene's camera; then orbit views about the scene's
// centre (the point the scene camera looks at; for a camera read from a glTF file, whose target is
// only a direction, the centre of the scene's bounds) at the scene camera's distance from it, 35
// degrees above the horizontal,
// azimuths +40, +160, +280, ... degrees from the scene camera's; with 3 or more views the last is a
// grazing view of the ground: 6 degrees above the plane through the bounds' lowest point, at the
// same distance, azimuth -30 degrees, looking at the centre's foot on that plane. Same field of
// view, near and far planes as the scene camera. Up is the scene camera's up. A framed scene (a
// glTF without a camera, Camera::framed) has no ground: its last view looks at the centre from 6
// degrees up, and each view is fitted to the drawn vertices from its direction (fitPointsInView,
// for `aspect`), so the object fills the frame from every side.
struct CompareView {
    Camera camera;
    std::string description;
};

std::vector<CompareView> compareViews(const Scene& scene, int count, float aspect);

// A suite's cameras (scene_suite.h) as the views, as given, with near and far planes that hug the
// scene's bounding sphere from each position (as frameBounds places them).
std::vector<CompareView> placedViews(const Scene& scene, const std::vector<Camera>& cameras);

// After the last view: a run's metrics become the mean over its views; one view: as before.
// `viewNotMeasured`: per view, why it had nothing to measure ("" measured; record() left such a
// view's metrics empty, so the means leave it out): named in run.notMeasured, and a run with no
// view measured becomes RunStatus::NotMeasured.
void finishViews(RunReport& run, const std::vector<std::string>& viewNotMeasured = {});
// A view's metrics emptied (attributes, image, single frame): a view with nothing to measure.
void clearMeasurements(RunReport& run);

// The material balls of the built-in scene's sphere grid (materials "metal roughness ..." and
// "dielectric roughness ..."), as square crops of a width x height render: metals, then
// dielectrics, each left to right. Empty for other scenes.
std::vector<FigureBall> findFigureBalls(const Scene& scene, uint32_t width, uint32_t height);

}  // namespace gbl::compare
