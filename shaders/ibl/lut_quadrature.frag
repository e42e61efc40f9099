// Precompute, the host's default method for uBrdfLut (IblSettings::lut = Quadrature): the
// split-sum BRDF LUT (the integrals of the step that provides uBrdfLut, scale A and bias B)
// by deterministic quadrature instead of Monte Carlo; texel centres map to x = N.V and
// y = roughness. The integral over half vectors H of ((1 - Fc), Fc) G_vis pdf(H) becomes,
// with u the GGX distribution function of the half vector's angle theta (as in importance
// sampling, so the lobe's peak is spread evenly over u) and the azimuth phi,
//     (1 / pi) integral du integral_0^phiMax(u) dphi ((1 - Fc), Fc) G_vis,
// where phiMax is the exact azimuth range with N.L > 0: every phi below thetaA = pi/4 - tv/2,
// |phi| < acos(c(theta)) up to thetaB = pi/4 + tv/2, none beyond (tv: the view's angle). u is
// split at thetaA and thetaB, and the range between them is stretched towards both ends
// (u = uA + (uB - uA) (3 t^2 - 2 t^3)), where the inner integral behaves like a power 3/2:
// 8 Gauss-Legendre nodes in u on each side of thetaA, 4 in phi. Accuracy against
// ref::brdfLutExact in docs/ibl.md. Guards and G as in the step `brdf_lut` solution.
uniform vec2 uSize;
layout(location = 0) out vec4 outColor;

const float kNodes8[4] = float[4](0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                  0.9602898564975363);
const float kWeights8[4] = float[4](0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                    0.1012285362903763);
const float kNodes4[2] = float[2](0.3399810435848563, 0.8611363115940526);
const float kWeights4[2] = float[2](0.6521451548625461, 0.3478548451374538);

// GGX's distribution function of the half vector's angle: u = sin^2 / (sin^2 + a2 cos^2).
float pbrlab_ggxCdf(float theta, float a2)
{
    float s = sin(theta), c = cos(theta);
    return s * s / (s * s + a2 * c * c);
}

// The inner integral at u, weighted: adds w / pi * integral over phi of ((1 - Fc), Fc) G_vis.
vec2 pbrlab_lutRing(float u, float w, float NdotV, float roughness, float a2)
{
    float cv = NdotV, sv = sqrt(1.0 - cv * cv);
    float denom = (1.0 - u) + a2 * u;  // cos^2 and sin^2 of theta without 1 - cos^2 (see step `importance`)
    float c2 = (1.0 - u) / denom;
    float ch = sqrt(c2), sh = sqrt(a2 * u / denom);
    float phiMax = 3.14159265358979;
    float across = 2.0 * sv * sh * ch;
    float needed = cv * (1.0 - 2.0 * c2);  // N.L > 0 exactly when across cos(phi) > needed
    if (across > 0.0) phiMax = acos(clamp(needed / across, -1.0, 1.0));
    else if (needed >= 0.0) return vec2(0.0);
    vec2 sum = vec2(0.0);
    for (int j = 0; j < 4; ++j) {
        float x = j < 2 ? -kNodes4[1 - j] : kNodes4[j - 2];
        float wj = kWeights4[j < 2 ? 1 - j : j - 2];
        float phi = 0.5 * phiMax * (1.0 + x);
        float VdotH = clamp(sv * sh * cos(phi) + cv * ch, 0.0, 1.0);
        float NdotL = 2.0 * VdotH * ch - cv;
        if (NdotL > 0.0) {
            float G = pbrlab_lutGeometrySchlickGGX(NdotV, roughness) *
                      pbrlab_lutGeometrySchlickGGX(NdotL, roughness);
            float Gvis = G * VdotH / (max(ch, 1e-4) * NdotV);
            float Fc = pow(1.0 - VdotH, 5.0);
            sum += (0.5 * phiMax * wj) * vec2((1.0 - Fc) * Gvis, Fc * Gvis);
        }
    }
    return sum * (w / 3.14159265358979);
}

vec2 pbrlab_integrateBRDFQuadrature(float NdotV, float roughness)
{
    NdotV = clamp(NdotV, 1e-4, 1.0);
    float a = roughness * roughness;
    float a2 = max(a * a, 1e-7);
    float tv = acos(NdotV);
    float uA = pbrlab_ggxCdf(max(0.25 * PI - 0.5 * tv, 0.0), a2);
    float uB = pbrlab_ggxCdf(0.25 * PI + 0.5 * tv, a2);
    vec2 sum = vec2(0.0);
    for (int i = 0; i < 8; ++i) {
        float x = i < 4 ? -kNodes8[3 - i] : kNodes8[i - 4];
        float w = 0.5 * kWeights8[i < 4 ? 3 - i : i - 4];
        sum += pbrlab_lutRing(0.5 * uA * (1.0 + x), uA * w, NdotV, roughness, a2);
        float t = 0.5 * (1.0 + x);
        sum += pbrlab_lutRing(uA + (uB - uA) * t * t * (3.0 - 2.0 * t),
                              (uB - uA) * 6.0 * t * (1.0 - t) * w, NdotV, roughness, a2);
    }
    return sum;
}

void main()
{
    vec2 xy = gl_FragCoord.xy / uSize;
    outColor = vec4(pbrlab_integrateBRDFQuadrature(xy.x, xy.y), 0.0, 1.0);
}
