#pragma once
// What a comparison is asked to do: the scenes, layouts, IBL modes, size, views, output folder and
// the rest, each field's default the one of `gbufferlab compare` without its flag, but for the
// scenes (below, kDefaultSuiteWidth) (the command line reads its flags into it: cli/compare_flags.h;
// app/compare_api.h runs it).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "ibl_precompute.h"
#include "effective_bandwidth.h"
#include "image_io.h"
#include "layout.h"
#include "renderer.h"
#include "scene.h"
#include "temporal_resolve.h"

namespace gbl::compare {

inline constexpr const char* kReferenceLayout = "reference";
inline constexpr const char* kGroundTruth = "ground-truth";  // the IBL mode's name
// compare --temporal N: at most this many frames (a frame costs a full G-buffer and lighting pass).
inline constexpr int kMaxTemporalFrames = 256;

// `gbufferlab compare` without --scene runs the bundled scenes as a suite (scene_suite.h
// defaultSuitePath(): the built-in scene, FlightHelmet and WaterBottle) at this size and view count
// unless --size / --views are given: chosen so that it takes no longer than the built-in scene
// alone at 1920x1080, the default before it (bench/RESULTS.md). A CompareOptions without sceneArgs
// is the built-in scene alone, at its own width, height and viewCount.
inline constexpr uint32_t kDefaultSuiteWidth = 480, kDefaultSuiteHeight = 270;
inline constexpr int kDefaultSuiteViews = 3;

struct CompareOptions {
    std::string scenePath;  // empty: the built-in scene
    // Every --scene as given (glTF files, builtin, suite .toml files; scene_suite.h): more than
    // one, or a suite, is a comparison over several scenes (compare_suite.h).
    std::vector<std::string> sceneArgs;
    // A suite scene's cameras (scene_suite.h): its views instead of --views' placement.
    std::vector<Camera> cameras;
    std::string envPath;    // empty: the built-in sky
    bool allowOutsideScene = false;
    std::optional<std::string> layoutsSpec;  // --layouts as given; unset: all
    std::vector<IblMode> modes = {IblMode::SplitSum};  // --ibl, in the order given
    std::vector<std::string> modeNames = {"split-sum"};  // their names, as given
    int splitSumShaderSamples = 1024;
    int gtBatchSamples = 64;
    int gtMaxBatches = 256;
    double gtNoise = 0.002f;  // as --gt-noise reads it: a float
    IblSettings iblSettings;
    uint32_t width = 1920, height = 1080;
    int viewCount = 3;
    std::filesystem::path outDir;
    bool force = false;
    std::string device;  // --device; empty: lavapipe
    bool validation = false;
    float exposure = 1.0f;      // --exposure X (or a suite scene's `exposure`)
    bool autoExposure = true;   // no --exposure: each view's exposure metered from its reference (auto_exposure.h)
    bool nativeFormats = false;
    bool hdrFlip = false;
    ExrPixelType exrType = ExrPixelType::Half;
    bool errorExr = false;  // --error-exr: each run's errors.exr (CPU evaluation only)
    std::string evalWhere = "auto";  // auto, gpu or cpu
    bool groundTruthAsked = false;   // ground-truth among the modes
    std::optional<uint32_t> bandRowsGiven;  // unset: --band-rows auto
    // --temporal N (temporal_resolve.h): frames per view, jittered, resolved by `resolve`; 1: one
    // frame, no jitter (the code path of a comparison without the flag).
    int temporalFrames = 1;
    ResolveMethod resolve = ResolveMethod::Mean;
    std::string commandLine;  // "gbufferlab compare" and the arguments, for the report ("": none)
    // --lighting (measure/effective_bandwidth.h): how the lighting pass reads the G-buffer in every
    // traffic figure; volumes without L: counted from the scene's lights at view 0's camera.
    LightingModel lighting;
    // The framebuffer-compression model on view 0's words (report_bandwidth.h); --no-compression: off.
    bool compressionModel = true;

    // Several modes with ground-truth among them: each mode's reference is also compared with the
    // ground truth's (the error of the lighting approximation).
    bool compareLighting() const;
};

// --layouts: names in layouts/ or .toml paths, or all (unset: all), loaded and validated; two of
// one name (requireDistinctRunNames) are a UserError.
std::vector<Layout> resolveLayouts(const std::optional<std::string>& spec);
// Throws a UserError naming both files when two layouts share a name (their runs' folder).
void requireDistinctRunNames(const std::vector<Layout>& layouts);

std::string joinList(const std::vector<std::string>& items);

}  // namespace gbl::compare
