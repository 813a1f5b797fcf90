#pragma once
// Colour spaces and the CIEDE2000 colour difference.
//
// Conversions (all double precision, no clamping):
//   linear sRGB (Rec. 709 primaries, D65) -> CIE XYZ with the sRGB matrix (IEC 61966-2-1 values as
//   tabulated to 7 digits), Y of RGB (1,1,1) = 1;
//   XYZ -> CIELAB (CIE 15:2004) with the D65 white of that matrix (its rows summed:
//   Xn = 0.9504700, Yn = 1.0000001, Zn = 1.0888300), so linear RGB (1,1,1) -> L* = 100,
//   a* = b* = 0 up to rounding. The inverse matrix is the exact inverse of that matrix.
// CIEDE2000 follows Sharma, Wu & Dalal, "The CIEDE2000 Color-Difference Formula: Implementation
// Notes, Supplementary Test Data, and Mathematical Observations", Color Res. Appl. 30(1), 2005,
// equations (1)-(22) there, including their hue conventions (h' = 0 when a' = b = 0; mean hue is
// the plain sum when one chroma is zero).

namespace gbl {

struct Lab {
    double L = 0.0;
    double a = 0.0;
    double b = 0.0;
};

struct Xyz {
    double X = 0.0;
    double Y = 0.0;
    double Z = 0.0;
};

// The D65 white used by every conversion here: the XYZ of linear RGB (1,1,1).
Xyz d65White();

Xyz linearSrgbToXyz(double r, double g, double b);
void xyzToLinearSrgb(const Xyz& xyz, double& r, double& g, double& b);
Lab xyzToLab(const Xyz& xyz);
Xyz labToXyz(const Lab& lab);
Lab linearSrgbToLab(double r, double g, double b);

// The exact piecewise sRGB transfer functions (IEC 61966-2-1).
double srgbEncode(double linear);
double srgbDecode(double encoded);

// CIEDE2000 (Sharma et al. 2005), parametric factors kL = kC = kH = 1 unless given. Symmetric.
double deltaE2000(const Lab& lab1, const Lab& lab2, double kL = 1.0, double kC = 1.0, double kH = 1.0);

}  // namespace gbl
