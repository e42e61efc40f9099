#include "compare.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace pbrlab {

ErrorStats compareWithReference(const Image& gpu, const std::vector<Surface>& surfaces,
                                const ModuleDesc& module, const ReferenceContext& context,
                                std::vector<glm::dvec3>* referenceOut) {
    ErrorStats s;
    double sumAbs = 0, sumError = 0;
    std::vector<double> pixelErrors;
    const double floor = module.tolerance.floor;
    if (referenceOut) referenceOut->assign(surfaces.size(), glm::dvec3(0));
    for (int y = 0; y < gpu.height; ++y)
        for (int x = 0; x < gpu.width; ++x) {
            const Surface& surface = surfaces[size_t(y) * gpu.width + x];
            if (!surface.covered) continue;
            glm::dvec3 r = module.reference(surface, context);
            if (referenceOut) (*referenceOut)[size_t(y) * gpu.width + x] = r;
            ++s.compared;
            bool nan = false, inf = false, negative = false;
            double pixelError = 0;
            for (int c = 0; c < module.components; ++c) {
                double g = gpu.at(x, y, c);
                nan = nan || std::isnan(g);
                inf = inf || std::isinf(g);
                negative = negative || g < 0;
                if (!std::isfinite(g)) continue;
                double abs = std::abs(g - r[c]);
                double err = abs / std::max(std::abs(r[c]), floor);
                s.maxAbs = std::max(s.maxAbs, abs);
                sumAbs += abs;
                sumError += err;
                pixelError = std::max(pixelError, err);
                if (err > s.maxError || s.worstX < 0) {
                    if (err > s.maxError) s.maxError = err;
                    s.worstX = x;
                    s.worstY = y;
                    s.worstGpu = {gpu.at(x, y, 0), gpu.at(x, y, 1), gpu.at(x, y, 2)};
                    s.worstRef = r;
                }
            }
            pixelErrors.push_back(pixelError);
            s.overCount += pixelError > module.tolerance.maxError;
            s.nanCount += nan;
            s.infCount += inf;
            s.negativeCount += negative;
        }
    if (!pixelErrors.empty()) {
        size_t k = size_t(double(pixelErrors.size() - 1) * (1 - module.tolerance.outlierFraction));
        std::nth_element(pixelErrors.begin(), pixelErrors.begin() + long(k), pixelErrors.end());
        s.quantileError = pixelErrors[k];
    }
    const double n = double(s.compared) * module.components;
    if (n > 0) {
        s.meanAbs = sumAbs / n;
        s.meanError = sumError / n;
    }
    return s;
}

std::string describe(const ErrorStats& s, const Tolerance& t) {
    std::ostringstream o;
    o.precision(3);
    o << s.compared << " px  max err " << s.maxError << " (tol " << t.maxError << ", floor "
      << t.floor << ")  mean err " << s.meanError << "  max abs " << s.maxAbs << "  mean abs "
      << s.meanAbs << "  NaN " << s.nanCount << "  Inf " << s.infCount << "  neg "
      << s.negativeCount << "  over tol " << s.overCount;
    if (t.outlierFraction > 0)
        o << " (allowed " << t.outlierFraction * 100 << "%: quantile err " << s.quantileError
          << ")";
    if (s.worstX >= 0)
        o << "\n    worst at (" << s.worstX << ", " << s.worstY << "): gpu (" << s.worstGpu.x
          << ", " << s.worstGpu.y << ", " << s.worstGpu.z << ") ref (" << s.worstRef.x << ", "
          << s.worstRef.y << ", " << s.worstRef.z << ")";
    return o.str();
}

}  // namespace pbrlab
