// The HDR environment the project makes itself (no downloaded panorama): an outdoor test
// range under a clear sky. Deterministic: integer-hash noise only (no std::rand, no clock), so
// every run gives the same pixels.
#pragma once

#include <glm/glm.hpp>
#include <string>

#include "assets/image_io.h"

namespace pbrlab {

// An equirectangular RGB float image, width x width/2, in the mapping of
// shaders/ibl/cube_face.glsl (row 0 = zenith, column centre = looking down -z, y up), linear
// radiance in arbitrary units (sky about 0.3-1):
//   - a sky gradient (deep blue zenith, pale horizon, brighter towards the sun) with
//     fractal-noise clouds;
//   - a sun: a disc of 1.2 degrees radius with limb darkening and radiance 20000, plus a glow;
//   - two soft rectangular area lights (softbox panels): a warm one low in front (radiance
//     80) and a cool one high on the right (radiance 50);
//   - below the horizon a ground plane of noisy stone tiles lit by sun and sky, fading into
//     haze towards the horizon.
// The brightest texels are over 10^4 times the median. Each texel is the average of 4 x 4
// stratified sub-samples (the sun's edge is antialiased, its energy kept). width must be even
// and in [16, 8192] (512 is the shipped size); throws pbrlab::Error otherwise.
// `soft` ("sky-soft" in scenes): the same range without the sun's disc, its aureole spread ten
// times wider, the panels a tenth as bright with edges five times softer (ground unchanged,
// still lit by the sun). Every feature is then wider than a degree and the brightest is about
// 8, so Monte Carlo and quadrature estimators of any correct kind converge on it: the
// environment the IBL steps are graded on.
Image generateSkyEnvironment(int width = 512, bool soft = false);

// Bump when the generators below change what they make: caches of generated environments
// are keyed by it.
constexpr int kEnvironmentVersion = 4;

// A bright smooth lobe alone ("hdr-lobe" in scenes): 1e4 x 10^((1 + cos g) / 2) at the angle
// g from the sun of generateSkyEnvironment, in the sun's colour: from 1e4 opposite the sun to
// 1e5 towards it, radiance of real dynamic range in a feature every correct estimator still
// converges on. Smooth in its logarithm (a factor 1.4 at most over 30 degrees), so that
// filtered importance sampling, which reads coarse mips for the samples of small pdf (a 1 x 1
// mip averages a whole cube face) and so blurs, stays within its tolerance. Measured: a lobe
// of 1e5 a few degrees wide over the soft sky (e^-1 at 12 degrees) put the filtered
// estimators 100 x their tolerance off at 1024 samples; 1e3 to 1e5 over the sphere (twice
// this slope) still 1.1 to 2 x at 4 and 64 samples (docs/grading.md).
Image generateHdrLobe(int width = 512);

// An environment by the name scenes and grading give it, or nullopt when the name is no
// generated one (a file path): "sky" (512), "sky-soft" (512), "smooth" (256), "hdr-lobe"
// (512), "sky-hdr" (sky-soft plus hdr-lobe, texel by texel: the soft sky with real
// dynamic range), and any of them times a constant, "NAME*K" (K a number: "sky-hdr*1024"),
// for the linearity checks of the estimators (grading/linearity.cpp).
bool isGeneratedEnvironment(const std::string& name);
Image generateEnvironment(const std::string& name);

// A smooth environment ("smooth" in scenes): low-order polynomials of the direction per
// channel, from about 0.3 to 1.6, no feature at all. Any consistent quadrature of the
// irradiance converges on it almost at once, while a wrong one (a gap, a double count, a
// wrong weight) stays off: how `pbrlab mutants` tells another quadrature from a mistake.
Image generateSmoothEnvironment(int width = 256);

// Where the sun of generateSkyEnvironment is (unit vector, y up) and its angular radius in
// radians, for tests and handouts (e.g. where a mirror sphere shows its highlight).
glm::dvec3 skySunDirection();
double skySunAngularRadius();

}  // namespace pbrlab
