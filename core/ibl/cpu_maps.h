// The maps pbrlab computes on the CPU from the equirectangular environment (IblSettings'
// Bins methods): the environment binned per texel of a small cube, and those bins convolved
// with the prefilter's lobe (the irradiance map is the same convolution at roughness 1).
// equirectToCube and cubeTexelDirection, the other CPU maps, are declared in ibl/precompute.h.
#pragma once

#include <vector>

#include "assets/image_io.h"

namespace pbrlab {

// Four floats processed as one (GCC and Clang vector extensions: SSE on any x86-64).
typedef float Float4 __attribute__((vector_size(16)));

// The environment binned per texel of a cube of n x n texels a face (IrradianceMethod::Bins,
// PrefilterMethod::Bins): every texel of the equirectangular image adds its power, L times its
// exact solid angle, to the bin its centre falls in; per bin, the grey power weighs the mean
// direction m and the mean of d d^T. Stored four bins to a pack, one component per Float4.
// With them the same bins of a constant environment of radiance 1 at the image's own sampling
// (the sphere's solid angle, mean direction and d d^T per bin): what the convolution divides
// by, so that a constant environment gives itself at every roughness.
struct EnvironmentBins {
    struct Pack {
        Float4 power[3], mean[3], second[6];  // second: xx yy zz xy yz xz
    };
    struct SpherePack {
        Float4 solidAngle, mean[3], second[6];
    };
    std::vector<Pack> packs;
    std::vector<SpherePack> sphere;  // as many as packs
};

// The environment in bins of a cube of n x n texels a face.
EnvironmentBins binEnvironment(const Image& equirect, int n);

// One cube map level of `size` texels a side: the environment convolved with the prefilter's
// lobe at `roughness`, from its bins (how and how accurately: ibl/cpu_maps.cpp, docs/ibl.md).
std::vector<Image> convolveBins(const EnvironmentBins& bins, int size, double roughness);

}  // namespace pbrlab
