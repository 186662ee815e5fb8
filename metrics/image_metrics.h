// Image metrics other than FLIP: PSNR, relative MSE, ROI luminance, absolute errors, NaN/Inf
// counts, chromaticity shift, banding and flicker. CPU only and free of image I/O, so the
// benchmarks can use them on a GPU machine without an image library.
//
// Conventions shared by every function here:
// - Channels: a FloatImage has 1 to 4 channels. 3 or 4 channels: the first three are linear
//   RGB (Rec.709 / sRGB primaries) and the fourth (alpha) is ignored. 1 or 2 channels: the
//   first is grey (R = G = B = grey) and the second (alpha) is ignored. So "over RGB" on a grey
//   image means over grey, replicated three times, which gives the same mean.
// - Two-image metrics need equal width and height; channel counts may differ (grey against
//   RGB compares the replicated grey).
// - A malformed image (no pixels, 0 or more than 4 channels, pixel array of the wrong size),
//   mismatched sizes, a bad ROI or a result that cannot be computed throw
//   std::invalid_argument with a message that names the function and what was expected.
// - Non-finite input: a NaN in any value a metric reads makes the result NaN (never a silently
//   smaller error); +-Inf follows IEEE arithmetic (PSNR's clamp maps it to 0 or 1).
//   count_non_finite() says how many there are.
// - ROIs are boxes in normalised coordinates: x to the right, y down, (0,0) the top-left corner
//   of the image and (1,1) the bottom-right. A pixel (i, j) belongs to the box when its centre
//   ((i + 0.5) / width, (j + 0.5) / height) lies in [x0, x1) x [y0, y1): half-open, so boxes that
//   share an edge share no pixel, and {0,0,1,1} is the whole image.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "renderer/image/float_image.h"

namespace gib::metrics {

// Normalised box; see the conventions above. Requires 0 <= x0 < x1 <= 1 and 0 <= y0 < y1 <= 1.
struct Roi {
  double x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 1.0;
};

// The pixels a Roi covers: columns [x_begin, x_end), rows [y_begin, y_end).
struct PixelRect {
  uint32_t x_begin = 0, y_begin = 0, x_end = 0, y_end = 0;
  uint32_t width() const { return x_end - x_begin; }
  uint32_t height() const { return y_end - y_begin; }
  size_t pixel_count() const { return size_t(width()) * height(); }
};

// Maps a Roi onto a width x height image. Throws std::invalid_argument when the box is not
// finite, not inside [0,1]^2, not ordered (x0 < x1, y0 < y1), or covers no pixel centre.
PixelRect roi_pixels(const Roi& roi, uint32_t width, uint32_t height);

// Rec.709 relative luminance of linear RGB: 0.2126 R + 0.7152 G + 0.0722 B (grey: the value).
// No checks: (x, y) must lie inside a well-formed image.
double luminance(const FloatImage& img, uint32_t x, uint32_t y);

// sRGB OETF (IEC 61966-2-1) of a value in [0,1]: 12.92 x for x <= 0.0031308, otherwise
// 1.055 x^(1/2.4) - 0.055. NaN stays NaN.
double srgb_oetf(double linear);

// Display-referred preview of a linear image, and the first step of psnr(): every colour (or
// grey) value v becomes srgb_oetf(clamp(v, 0, 1)). Exposure 1 and no tone curve: values above 1
// clip to white. Alpha is copied unchanged; width, height and channel count are kept; NaN stays
// NaN.
FloatImage tonemap_srgb(const FloatImage& img);

// PSNR in dB on tone-mapped sRGB: both images go through the mapping of tonemap_srgb() (clamp
// to [0,1] at exposure 1, no tone curve, sRGB OETF; in double, not rounded to float), then MSE = mean over pixels and the three RGB values
// of (test - ref)^2, and PSNR = 10 log10(1 / MSE) (peak 1). Identical tone-mapped images give
// +infinity (std::numeric_limits<double>::infinity(); reports print "inf").
double psnr(const FloatImage& ref, const FloatImage& test);

// One line saying how psnr() is computed, for reports.
std::string psnr_description();

// Relative MSE on linear HDR values: mean over pixels and the three RGB values of
// (t - r)^2 / (r^2 + eps). eps (> 0) keeps dark reference pixels from dominating; the default
// 1e-2 makes an error of 0.1 on black weigh as much as a 100% error on white. Identical -> 0.
double relmse(const FloatImage& ref, const FloatImage& test, double eps = 1e-2);

// Mean Rec.709 luminance (see luminance()) of the pixels whose centres lie in the box.
// Throws std::invalid_argument if the box is malformed or covers no pixel (see roi_pixels()).
double roi_mean_luminance(const FloatImage& img, double x0, double y0, double x1, double y1);
double roi_mean_luminance(const FloatImage& img, const Roi& roi);

// Largest and mean |test - ref| over pixels and the three RGB values, on linear values.
double max_abs_error(const FloatImage& ref, const FloatImage& test);
double mean_abs_error(const FloatImage& ref, const FloatImage& test);

// Counts of values (not pixels) over every channel, alpha included, since a NaN anywhere in a
// resource is a bug: nan = NaN values, inf = +-Inf values, negative = finite values < 0
// (-0.0 is not negative).
struct NonFinite {
  size_t nan = 0, inf = 0, negative = 0;
};
NonFinite count_non_finite(const FloatImage& img);

// Chromaticity shift. Each pixel's linear sRGB goes to CIE XYZ (D65) with the IEC 61966-2-1
// matrix
//   X = 0.4124564 R + 0.3575761 G + 0.1804375 B
//   Y = 0.2126729 R + 0.7151522 G + 0.0721750 B
//   Z = 0.0193339 R + 0.1191920 G + 0.9503041 B
// then to CIE 1976 u' = 4X / (X + 15Y + 3Z), v' = 9Y / (X + 15Y + 3Z). The shift of a pixel is
// the Euclidean distance between the (u', v') of test and of ref. Chromaticity is meaningless
// (noise-dominated) in the dark, so a pixel is skipped when the XYZ Y of ref or of test is below
// luminance_floor (linear units; the default 1e-3 is 0.1% of white at exposure 1, about sRGB
// code 3 of 255) or when X + 15Y + 3Z <= 0. Intensity alone never shifts chromaticity: grey
// against brighter grey is 0.
inline constexpr double kChromaticityLuminanceFloor = 1e-3;
struct ChromaticityShift {
  double max = 0.0;   // largest per-pixel u'v' distance over the counted pixels
  double mean = 0.0;  // mean per-pixel u'v' distance over the counted pixels
  size_t pixels = 0;  // pixels counted
  size_t skipped = 0; // pixels in the ROI skipped for the floor
};
// Throws std::invalid_argument if the ROI is bad or every pixel in it is skipped.
ChromaticityShift chromaticity_shift(const FloatImage& ref, const FloatImage& test, const Roi& roi = {},
                                     double luminance_floor = kChromaticityLuminanceFloor);
// chromaticity_shift(...).max.
double max_chromaticity_shift(const FloatImage& ref, const FloatImage& test, const Roi& roi = {},
                              double luminance_floor = kChromaticityLuminanceFloor);

// Banding index: how much of a gradient's change is concentrated in isolated jumps rather than
// spread over every pixel. One image, no reference needed.
//
// Definition. Let v be the measured signal (one channel, or Rec.709 luminance) inside the ROI.
// Along each line of the ROI (rows, columns or both, see BandingAxis), take the steps
// d_i = v_{i+1} - v_i. For every run of w consecutive steps of a line (w = window; all runs,
// overlapping, of every line measured) let A = (sum |d|)^2 and E = sum d^2 over the run. Then
//   banding = 1 - (sum over runs of A) / (w * sum over runs of E).
// If every E is 0 (a flat ROI has no gradient, hence no bands) the index is 0.
//
// Why this form: A / (w E) is the participation ratio of the steps in a run, the fraction of
// its steps that carry its change (Cauchy-Schwarz puts it in [1/w, 1]). A smooth gradient
// changes a little at every pixel, so its steps are nearly equal and the ratio is near 1.
// Quantisation turns the steps into a spike train: zeros inside a band, a jump at its edge.
// Bands P pixels wide (P dividing w) put exactly w/P equal jumps in every run, so
//   banding = 1 - 1/P exactly, for P <= w, and 1 - 1/w (the ceiling) for bands wider than w:
// 0 with no banding, 0.5 for 2-pixel bands, 0.9375 for 16-pixel bands with w = 16. So for a
// fixed ramp it grows as the number of quantisation levels falls, and 1 / (1 - banding) reads
// as the effective band width in pixels (up to w). The index ignores scale, offset and slope;
// weighting runs by their energy E keeps nearly flat runs (rounding noise) from counting.
// Floor: a linear ramp reads 0; curvature within a run reads a little (about 0.015 for an
// exponential falloff of 40 pixels, about 0.06 for a Gaussian of 21 pixels' standard deviation)
// and noise reads about 0.3. Compare against the reference's index on the same ROI, which is
// the floor for that content. The signal is taken as given (linear, say); pass
// tonemap_srgb(img) to measure display space.
//
// Throws std::invalid_argument for a bad ROI, window < 2, channel outside [-1, channels), or an
// ROI too short (fewer than w + 1 pixels) along every measured axis; lines too short along one
// axis are skipped when the other qualifies.
enum class BandingAxis { rows, columns, both };
struct BandingOptions {
  int channel = -1;        // -1: Rec.709 luminance; otherwise this channel of the image
  uint32_t window = 16;    // w, in steps; the widest band width the index can tell apart
  BandingAxis axis = BandingAxis::both;
};
double banding_index(const FloatImage& img, const Roi& roi = {}, const BandingOptions& options = {});

// Flicker: temporal stability of N >= 2 frames of a static view. For each pixel in the ROI,
// with L_k its Rec.709 luminance in frame k, mean mu = (1/N) sum L_k and population standard
// deviation sigma = sqrt((1/N) sum (L_k - mu)^2); the pixel's relative std is sigma / mu.
// Pixels with mu < mean_floor (> 0; default 1e-3, linear) are skipped: relative noise of black is
// meaningless. The result is the mean relative std over the counted pixels; 0 for identical
// frames, 0.5 for a pixel alternating between 1 and 3. Throws std::invalid_argument for fewer
// than 2 frames, frames of different sizes, a bad ROI, or when every pixel is skipped.
inline constexpr double kFlickerMeanFloor = 1e-3;
double flicker(const std::vector<FloatImage>& frames, const Roi& roi = {},
               double mean_floor = kFlickerMeanFloor);

// Penumbra width along a line across a shadow edge (the contact-shadows case). The ROI's rows
// are averaged into one profile of mean Rec.709 luminance per column, so the line runs along x;
// penumbra_profile() returns it, left to right.
std::vector<double> penumbra_profile(const FloatImage& img, const Roi& roi);
// Width in columns between the points where `profile`, normalised as (p - lo) / (hi - lo),
// first reaches 0.1 and first reaches 0.9, walking from the darkest column of `dark_from`
// (normally the reference's profile, so both images walk the same way: from its umbra) towards
// dark_from's brighter end; linear interpolation between columns. +infinity when the profile is
// not below 0.1 at that column (a leak: it never gets dark) or never reaches 0.9 (a shadow that
// never gets lit). Throws std::invalid_argument for fewer than 2 columns, profiles of different
// lengths, hi <= lo or non-finite levels.
double penumbra_width(const std::vector<double>& profile, const std::vector<double>& dark_from, double lo, double hi);
// |width(test) - width(ref)| / width(ref), both normalised by the reference profile's minimum
// (umbra) and maximum (lit) over the ROI; +infinity where the test's width is. Throws
// std::invalid_argument for a bad ROI, different sizes, or a reference with no edge (width 0
// or not finite).
double penumbra_width_error(const FloatImage& ref, const FloatImage& test, const Roi& roi);

}  // namespace gib::metrics
