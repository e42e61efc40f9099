// IblSettings: what the precomputed maps depend on, as cache keys and as one line for people,
// and LearnOpenGL's settings (the baseline of `pbrlab precompute --bench`). Apart from the
// passes so that a new setting is one edit here and one where the pass reads it.
#include <sstream>

#include "ibl/precompute.h"

namespace pbrlab {

namespace {

std::string number(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

}  // namespace

std::string IblSettings::irradianceBy() const {
    switch (irradiance) {
        case IrradianceMethod::Bins:
            return "bins " + std::to_string(bins);
        case IrradianceMethod::StepPass:
            return "the step's pass";
        case IrradianceMethod::Riemann:
            return "Riemann " + number(riemannStep);
    }
    return "";
}

std::string IblSettings::prefilterBy() const {
    switch (prefilter) {
        case PrefilterMethod::Bins:
            return "bins " + std::to_string(bins);
        case PrefilterMethod::Filtered:
            return std::to_string(prefilterSamples) + " filtered samples (bias " +
                   number(filteredLodBias) + ")";
        case PrefilterMethod::StepPass:
            return std::to_string(prefilterSamples) + " samples";
    }
    return "";
}

std::string IblSettings::key() const {
    // The environment cube's size too: steps 17-19 read it (textureSize, LOD from the texel
    // angle), so maps of one size must never stand in for another's.
    return "env" + std::to_string(environmentSize) + "_src" + std::to_string(source()) + "_irr" +
           std::to_string(irradianceSize) + " " + irradianceBy() + "_pre" +
           std::to_string(prefilterSize) + "x" + std::to_string(prefilterMips) +
           (prefilterMirrorExact ? "m" : "") + std::to_string(mirrorSupersample) + " " +
           prefilterBy();
}

std::string IblSettings::lutKey() const {
    return std::string(lut == LutMethod::Quadrature ? "quad" : "mc" + std::to_string(lutSamples)) +
           "_" + std::to_string(lutWidth) + "x" + std::to_string(lutHeight);
}

std::string IblSettings::describe() const {
    return "irradiance " + std::to_string(irradianceSize) + "^2 by " + irradianceBy() +
           "; prefilter " + std::to_string(prefilterSize) + "^2 x " +
           std::to_string(prefilterMips) + " by " + prefilterBy() +
           (prefilterMirrorExact ? ", mip 0 resampled" : "") + " (source " +
           std::to_string(source()) + "^2); LUT " + std::to_string(lutWidth) + " x " +
           std::to_string(lutHeight) + " by " +
           (lut == LutMethod::Quadrature ? std::string("quadrature")
                                         : std::to_string(lutSamples) + " samples");
}

IblSettings IblSettings::learnOpenGl() {
    IblSettings s;
    s.environmentSize = 512;
    s.sourceSize = 512;
    s.irradiance = IrradianceMethod::Riemann;
    s.irradianceSize = 32;
    s.riemannStep = 0.025;
    s.prefilterSize = 128;
    s.prefilterMips = 5;
    s.prefilterMirrorExact = false;
    s.prefilter = PrefilterMethod::StepPass;
    s.prefilterSamples = 1024;
    s.lut = LutMethod::StepPass;
    s.lutWidth = s.lutHeight = 512;
    s.lutSamples = 1024;
    return s;
}

}  // namespace pbrlab
