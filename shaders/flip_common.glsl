// FLIP's colour constants as flip.cpp computes them (double, rounded to float), stored by
// gpu_flip.cpp at the start of the constants buffer's `kernels`: KC_M the linear sRGB -> XYZ
// matrix (row-major), KC_MI its inverse, KC_W the D65 white, KC_IW its reciprocals.
#define KC_M 0
#define KC_MI 9
#define KC_W 18
#define KC_IW 21
vec3 flipM(int row) { return vec3(kernels[KC_M + 3 * row], kernels[KC_M + 3 * row + 1], kernels[KC_M + 3 * row + 2]); }
vec3 flipMi(int row) { return vec3(kernels[KC_MI + 3 * row], kernels[KC_MI + 3 * row + 1], kernels[KC_MI + 3 * row + 2]); }

// HDR-FLIP's tone mapper (flip_hdr.cpp flipToneMap): ACES fit (Narkowicz 2016) of 0.6 x.
float flipToneMap(float x) {
    x = x > 1.0e18 ? 1.0e18 : x;
    float x2 = x * x;
    float num = float(0.6LF * 0.6LF * 2.51LF) * x2 + float(0.6LF * 0.03LF) * x;
    float den = float(0.6LF * 0.6LF * 2.43LF) * x2 + float(0.6LF * 0.59LF) * x + 0.14;
    float t = num / den;
    return t >= 0.0 ? (t <= 1.0 ? t : 1.0) : 0.0;
}
