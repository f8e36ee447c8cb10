#include "render/colour_map.h"

#include <algorithm>
#include <cmath>

namespace cascade::render {

namespace {

std::uint8_t to_byte(double v) { return std::uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); }

// Viridis (van der Walt and Smith, matplotlib 2.0) as the degree-6 least-squares polynomial fit
// per sRGB channel published by M. Zucconi (CC0). It stays within 5/255 of matplotlib's table:
// tests/render/test_colour_map.cpp checks the published end and middle colours.
Rgb8 viridis(double t) {
  static const double c[7][3] = {{0.2777273272234177, 0.005407344544966578, 0.3340998053353061},
                                 {0.1050930431085774, 1.404613529898575, 1.384590162594685},
                                 {-0.3308618287255563, 0.214847559468213, 0.09509516302823659},
                                 {-4.634230498983486, -5.799100973351585, -19.33244095627987},
                                 {6.228269936347081, 14.17993336680509, 56.69055260068105},
                                 {4.776384997670288, -13.74514537774601, -65.35303263337234},
                                 {-5.435455855934631, 4.645852612178535, 26.3124352495832}};
  double rgb[3];
  for (int ch = 0; ch < 3; ++ch) {
    double v = 0;
    for (int k = 6; k >= 0; --k) v = v * t + c[k][ch];  // Horner
    rgb[ch] = v;
  }
  return {to_byte(rgb[0]), to_byte(rgb[1]), to_byte(rgb[2])};
}

// Moreland, "Diverging Color Maps for Scientific Visualization" (ISVC 2009): interpolation in
// the polar form (Msh) of CIELAB between a blue and a red end, through a white of M = 88, with
// the hue of a saturated end turned away from the white (the paper's "adjust hue").
struct Msh {
  double m, s, h;
};

double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }
double linear_to_srgb(double c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055; }

// CIELAB relative to the D65 white point.
constexpr double kWhite[3] = {0.95047, 1.0, 1.08883};
double lab_f(double t) { return t > 216.0 / 24389 ? std::cbrt(t) : (24389.0 / 27 * t + 16) / 116; }
double lab_f_inverse(double t) { return t * t * t > 216.0 / 24389 ? t * t * t : (116 * t - 16) / (24389.0 / 27); }

Msh srgb_to_msh(double r, double g, double b) {
  const double lr = srgb_to_linear(r), lg = srgb_to_linear(g), lb = srgb_to_linear(b);
  const double xyz[3] = {0.4124564 * lr + 0.3575761 * lg + 0.1804375 * lb,
                         0.2126729 * lr + 0.7151522 * lg + 0.0721750 * lb,
                         0.0193339 * lr + 0.1191920 * lg + 0.9503041 * lb};
  const double fx = lab_f(xyz[0] / kWhite[0]), fy = lab_f(xyz[1] / kWhite[1]), fz = lab_f(xyz[2] / kWhite[2]);
  const double l = 116 * fy - 16, a = 500 * (fx - fy), bb = 200 * (fy - fz);
  const double m = std::sqrt(l * l + a * a + bb * bb);
  return {m, m > 0 ? std::acos(l / m) : 0, std::atan2(bb, a)};
}

Rgb8 msh_to_srgb(const Msh& c) {
  const double l = c.m * std::cos(c.s), a = c.m * std::sin(c.s) * std::cos(c.h), bb = c.m * std::sin(c.s) * std::sin(c.h);
  const double fy = (l + 16) / 116, fx = fy + a / 500, fz = fy - bb / 200;
  const double x = kWhite[0] * lab_f_inverse(fx), y = kWhite[1] * lab_f_inverse(fy), z = kWhite[2] * lab_f_inverse(fz);
  const double lr = 3.2404542 * x - 1.5371385 * y - 0.4985314 * z;
  const double lg = -0.9692660 * x + 1.8760108 * y + 0.0415560 * z;
  const double lb = 0.0556434 * x - 0.2040259 * y + 1.0572252 * z;
  return {to_byte(linear_to_srgb(lr)), to_byte(linear_to_srgb(lg)), to_byte(linear_to_srgb(lb))};
}

constexpr double kPi = 3.14159265358979323846;

double adjusted_hue(const Msh& saturated, double unsaturated_m) {
  if (saturated.m >= unsaturated_m) return saturated.h;
  const double spin = saturated.s * std::sqrt(unsaturated_m * unsaturated_m - saturated.m * saturated.m) /
                      (saturated.m * std::sin(saturated.s));
  return saturated.h > -kPi / 3 ? saturated.h + spin : saturated.h - spin;
}

Rgb8 cool_warm(double t) {
  // The paper's end points: sRGB (59, 76, 192) and (180, 4, 38).
  static const Msh blue = srgb_to_msh(59 / 255.0, 76 / 255.0, 192 / 255.0);
  static const Msh red = srgb_to_msh(180 / 255.0, 4 / 255.0, 38 / 255.0);
  Msh a = blue, b = red;
  double u = t;
  if (a.s > 0.05 && b.s > 0.05 && std::fabs(a.h - b.h) > kPi / 3) {
    // Through white: each half runs from a saturated end to the unsaturated midpoint.
    const double mid_m = std::max({a.m, b.m, 88.0});
    if (u < 0.5) {
      b = {mid_m, 0, 0};
      u = 2 * u;
    } else {
      a = {mid_m, 0, 0};
      u = 2 * u - 1;
    }
  }
  if (a.s < 0.05 && b.s > 0.05) a.h = adjusted_hue(b, a.m);
  else if (b.s < 0.05 && a.s > 0.05) b.h = adjusted_hue(a, b.m);
  return msh_to_srgb({(1 - u) * a.m + u * b.m, (1 - u) * a.s + u * b.s, (1 - u) * a.h + u * b.h});
}

}  // namespace

ColourMap::ColourMap(ColourMapKind kind) : kind_(kind) {
  for (int i = 0; i < 256; ++i) {
    const double t = i / 255.0;
    table_[std::size_t(i)] = kind == ColourMapKind::viridis ? viridis(t) : cool_warm(t);
  }
}

const ColourMap& ColourMap::get(ColourMapKind kind) {
  static const ColourMap viridis_map(ColourMapKind::viridis), cool_warm_map(ColourMapKind::cool_warm);
  return kind == ColourMapKind::viridis ? viridis_map : cool_warm_map;
}

Rgb8 ColourMap::at(double t) const {
  if (!(t > 0)) return table_[0];
  return table_[std::size_t(std::lround(std::min(t, 1.0) * 255.0))];
}

std::string colour_map_name(ColourMapKind kind) { return kind == ColourMapKind::viridis ? "viridis" : "cool_warm"; }

Rgb8 phase_colour(std::uint8_t phase) {
  switch (phase) {
    case 0: return {51, 115, 217};   // water: blue
    case 1: return {158, 115, 66};   // soil: brown
    default: return {140, 140, 140};  // boundary: grey
  }
}

}  // namespace cascade::render
