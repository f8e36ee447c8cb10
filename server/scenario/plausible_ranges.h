// The ranges a material or a forcing must lie in to describe something real. Beyond them a value
// is taken for a mistake (a unit slip, a missing exponent sign) and refused with the key named,
// the same in case files, in UpdateForcing and in a replayed journal: `density: 1e300` ran with a
// kinetic energy of 1e295 J, `sound_speed: 1e-10` "completed" in one step, `saturated_conductivity:
// 1e6` ran at Δt = 8e-11 s for ever (issue 14). The bounds are wide on purpose: they hold every
// fluid and soil a user of this field models, and the accelerated cases of the reference paper.
#pragma once

#include <cmath>
#include <optional>
#include <string>

#include "server/scenario/number_text.h"

namespace cascade {

struct PlausibleRange {
  double min, max;
  const char* unit;
  const char* reason;  // what the bounds hold, for the message
};

// Liquids from liquefied natural gas (about 430 kg/m³) to mercury (13,546 kg/m³).
inline constexpr PlausibleRange kLiquidDensity{100, 2e4, "kg/m^3", "liquids lie between 430 (LNG) and 13,546 (mercury)"};
// A weakly compressible liquid's numerical sound speed (Eq. 24a: 10 times its fastest flow) up
// to the real speed of sound in water (1,480 m/s), with room for stiffer settings.
inline constexpr PlausibleRange kSoundSpeed{0.1, 1e4, "m/s",
                                            "Eq. 24a asks 10 times the fastest flow; water's real one is 1,480"};
// Solid grains from pumice up, and a surcharge modelled as a thin heavy layer of soil
// (cases/terzaghi.yaml: 169,230 kg/m³ gives 10 kPa per 1 cm layer). The lower bound catches g/cm³.
inline constexpr PlausibleRange kGrainDensity{300, 1e7, "kg/m^3",
                                              "mineral grains lie between 300 (pumice) and 8,000; surcharge layers "
                                              "are heavier"};
// From slurries and very soft clay (kPa) to intact rock (about 100 GPa).
inline constexpr PlausibleRange kYoungsModulus{1e2, 1e12, "Pa", "soils and rocks lie between 1e3 (slurry) and 1e11"};
// From intact clay (about 1e-13 m/s) to open gravel (about 1 m/s).
inline constexpr PlausibleRange kSaturatedConductivity{1e-15, 10, "m/s",
                                                       "soils lie between 1e-13 (intact clay) and 1 (open gravel)"};
// The pore water's bulk modulus: the reference paper's numerical 2 MPa up to real water (2.2 GPa).
inline constexpr PlausibleRange kWaterBulkModulus{1e3, 1e10, "Pa", "2e6 (the paper's) to 2.2e9 (real water)"};
// Rain (and evaporation, negative): the heaviest hour ever recorded is about 300 mm (1e-4 m/s);
// the reference paper's accelerated cases rain 0.003–0.01 m/s, and the coarse Fei Tsui Road test
// 1 m/s (K_sat × 100, the rain ten times that). The bound catches unit slips (1e10), not storms.
inline constexpr PlausibleRange kRainfallIntensity{-1, 1, "m/s",
                                                   "the heaviest rain recorded is about 1e-4 m/s, accelerated runs 1"};
// A factor on the case's rain (rainfall.factor, rain_series.h): what-if forecasts from none to a
// hundred times the case's storm; beyond that the intensity itself is the thing to steer.
inline constexpr PlausibleRange kRainFactor{0, 100, "times the case's rain", "a forecast from no rain to a hundred times the case's"};
// The surface's ponding and drying pressures (p_max, p_min of Eq. 39): far beyond any head of
// ponded water or any suction a soil holds (1 GPa).
inline constexpr PlausibleRange kSurfacePressure{-1e8, 1e8, "Pa", "suctions and ponding heads lie well within 1e8"};

// The message for a value outside `range`, or nothing when it lies inside (NaN and ±inf are outside).
inline std::optional<std::string> implausible(const PlausibleRange& range, double value) {
  if (value >= range.min && value <= range.max) return std::nullopt;
  return "must be in [" + number_text(range.min) + ", " + number_text(range.max) + "] " + range.unit + " (is " +
         number_text(value) + "): " + range.reason;
}

}  // namespace cascade
