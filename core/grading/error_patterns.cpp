#include "grading/error_patterns.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <map>
#include <mutex>
#include <numbers>
#include <regex>
#include <sstream>

#include "grading/input_fits.h"
#include "grading/term_fits.h"
#include "shader/code_facts.h"
#include "shader/preprocess.h"

namespace pbrlab {

namespace {

constexpr double kPi = std::numbers::pi;

std::string num(double v, int digits = 3) {
    std::ostringstream o;
    o.precision(digits);
    o << v;
    return o.str();
}

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
    return v[v.size() / 2];
}

// The share of xs within `tolerance` (relative) of `centre`.
double shareNear(const std::vector<double>& xs, double centre, double tolerance) {
    if (xs.empty()) return 0;
    int near = 0;
    for (double x : xs)
        near += std::abs(x - centre) <= tolerance * std::max(std::abs(centre), 1e-9);
    return double(near) / double(xs.size());
}

bool finite(const glm::dvec3& v, int n) {
    for (int c = 0; c < n; ++c)
        if (!std::isfinite(v[c])) return false;
    return true;
}

struct Entry {
    double value, expected, slack;
};

// The generic inputs of a step that declares none (InputAxis): the cosines between its
// directions and the fields of the surface, each settable where that means one thing.
const std::vector<InputAxis>& genericAxes(const std::string& extra) {
    // One list per name of the extra inputs (ModuleDesc::extraName), kept for the program's
    // life: the substitution fits hold on to its elements.
    static std::map<std::string, std::vector<InputAxis>> lists;
    static std::mutex guard;
    const std::lock_guard<std::mutex> lock(guard);
    auto found = lists.find(extra);
    if (found != lists.end()) return found->second;
    return lists[extra] = [&extra] {
        auto field = [](double Surface::*f) -> std::function<void(Surface&, double)> {
            return [f](Surface& s, double v) { s.*f = v; };
        };
        auto get = [](double Surface::*f) -> std::function<double(const Surface&)> {
            return [f](const Surface& s) { return s.*f; };
        };
        return std::vector<InputAxis>{
            {"N.V", [](const Surface& s) { return glm::dot(s.normal, s.view); },
             [](Surface& s, double v) { s.view = atCosine(s.normal, s.view, v); }},
            {"N.L", [](const Surface& s) { return glm::dot(s.normal, s.light); },
             [](Surface& s, double v) {
                 // The light moves with its direction, at the same distance.
                 const double d = glm::length(s.lightPosition - s.position);
                 s.light = atCosine(s.normal, s.light, v);
                 s.lightPosition = s.position + s.light * d;
             }},
            {"V.L", [](const Surface& s) { return glm::dot(s.view, s.light); }, nullptr},
            {"roughness", get(&Surface::roughness), field(&Surface::roughness)},
            {"metallic", get(&Surface::metallic), field(&Surface::metallic)},
            {"ao", get(&Surface::ao), field(&Surface::ao)},
            {"albedo (mean)",
             [](const Surface& s) { return (s.albedo.x + s.albedo.y + s.albedo.z) / 3; }, nullptr},
            {"the light's distance d",
             [](const Surface& s) { return glm::length(s.lightPosition - s.position); },
             [](Surface& s, double v) {
                 s.lightPosition =
                     s.position +
                     ref::safeNormalize(s.lightPosition - s.position, glm::dvec3(0, 0, 1)) * v;
             }},
            {extra + ".x", [](const Surface& s) { return s.extra.x; },
             [](Surface& s, double v) { s.extra.x = v; }},
            {extra + ".y", [](const Surface& s) { return s.extra.y; },
             [](Surface& s, double v) { s.extra.y = v; }},
            {"tangent.w", [](const Surface& s) { return s.tangent.w; },
             [](Surface& s, double v) { s.tangent.w = v; }},
        };
    }();
}

// Every finite (value, expected) component pair.
std::vector<Entry> entries(const FeedbackInputs& in) {
    std::vector<Entry> out;
    const int n = in.module->components;
    for (size_t i = 0; i < in.values.size(); ++i)
        for (int c = 0; c < n; ++c)
            if (std::isfinite(in.values[i][c]) && std::isfinite(in.expected[i][c]))
                out.push_back({in.values[i][c], in.expected[i][c], in.slack[i][c]});
    return out;
}

// The value of each component the same at every one of `points` (within 1e-7, relative).
bool flat(const std::vector<glm::dvec3>& v, const std::vector<size_t>& points, int n) {
    for (int c = 0; c < n; ++c)
        for (size_t i : points)
            if (!(std::abs(v[i][c] - v[points[0]][c]) <=
                  1e-7 * std::max(1.0, std::abs(v[points[0]][c]))))
                return false;
    return true;
}

// Which points are wrong: not finite, or a component outside the band.
std::vector<bool> wrongPoints(const FeedbackInputs& in, int& badCount) {
    const int n = in.module->components;
    std::vector<bool> bad;
    for (size_t i = 0; i < in.values.size(); ++i) {
        bool b = !finite(in.values[i], n);
        for (int c = 0; c < n && !b; ++c)
            b = std::abs(in.values[i][c] - in.expected[i][c]) > in.slack[i][c];
        bad.push_back(b);
        badCount += b;
    }
    return bad;
}

// The threshold `shown` as written, with as many digits as it takes to lie between the
// neighbours a and b: the roughness 0.995 between 0.99 and 1 is not "> 1".
std::string thresholdBetween(double shown, double a, double b) {
    std::string threshold = num(shown, 2);
    for (int digits = 3; digits <= 6 && shown != 0.0; ++digits) {
        const double written = std::stod(threshold);
        if (written > a && written < b) break;
        threshold = num(shown, digits);
    }
    return threshold;
}

// One side of a threshold of one input, the wrong points on it: the points sorted by the
// input, the threshold between xs[k] and xs[k + 1], side 0 below it and 1 above.
struct Split {
    const InputAxis& axis;
    const std::vector<std::pair<double, size_t>>& xs;
    size_t k;
    int side;
    int inBad, sideSize;  // wrong points on that side, and all points there
};

// What region() says of the split that is its best so far: where the wrong points lie, and
// what the two functions do there. Sets *hinted where that names a clamp, a guard or a cut-off.
std::string describeSplit(const FeedbackInputs& in, const std::vector<bool>& bad,
                          const Split& split, bool* hinted) {
    const int n = in.module->components;
    const InputAxis& f = split.axis;
    const std::vector<std::pair<double, size_t>>& xs = split.xs;
    const size_t k = split.k;
    const int side = split.side;
    // A threshold between the two neighbours; 0 when 0 lies between them
    // (where clamps and guards sit).
    const double a = xs[k].first, b = xs[k + 1].first;
    const double shown = a <= 0 && b >= 0 ? 0.0 : 0.5 * (a + b);
    const std::string threshold = thresholdBetween(shown, a, b);
    // "<= 0" where the wrong side holds points at 0 itself (a probe's end).
    const bool atZero = shown == 0 && (side == 0 ? a == 0 : b == 0);
    const std::string where =
        f.name + (side == 0 ? (atZero ? " <= " : " < ") : (atZero ? " >= " : " > ")) + threshold;
    std::string best = "wrong only where " + where + " (" + std::to_string(split.inBad) + " of " +
                       std::to_string(split.sideSize) + " points there), right elsewhere";
    // The wrong points of that side (finite ones: a NaN says nothing of a shape).
    std::vector<size_t> wrongThere;
    for (size_t j = side == 0 ? 0 : k + 1; j < (side == 0 ? k + 1 : xs.size()); ++j)
        if (bad[xs[j].second] && finite(in.values[xs[j].second], n))
            wrongThere.push_back(xs[j].second);
    const bool enough = wrongThere.size() >= 2;
    const bool studentFlat = enough && flat(in.values, wrongThere, n);
    const bool referenceFlat = enough && flat(in.expected, wrongThere, n);
    if (studentFlat && !referenceFlat) {
        std::string value;
        for (int c = 0; c < n; ++c) value += (c ? ", " : "") + num(in.values[wrongThere[0]][c], 4);
        if (n > 1) value = "(" + value + ")";
        best += ": yours is " + value + " where " + where +
                ", the reference is not: a cut-off the contract does not have?";
        if (hinted) *hinted = true;
    } else if (referenceFlat && !studentFlat && shown == 0 && side == 0) {
        best += ": is a max(..., 0.0) or a guard for negative " + f.name + " missing?";
        if (hinted) *hinted = true;
    } else {
        best += ".";
        if (hinted) *hinted = false;
    }
    return best;
}

// Whether the wrong points lie on one side of a threshold of one input while the other side
// is right: "wrong only where N.L < 0". The inputs are the step's own (InputAxis) or the
// generic ones. What is said after it follows what the two functions do on that side: a
// clamp or guard the student's lacks (the reference constant there, the student's not), a
// cut-off the contract does not have (the student's constant there, the reference's not).
std::string region(const FeedbackInputs& in, bool* hinted = nullptr) {
    if (hinted) *hinted = false;
    int badCount = 0;
    const std::vector<bool> bad = wrongPoints(in, badCount);
    const int total = int(bad.size());
    if (badCount == 0 || badCount > 0.8 * total) return "";
    std::string best;
    double bestScore = 0;
    const std::vector<InputAxis>& axes = inputAxes(*in.module);
    for (const InputAxis& f : axes) {
        std::vector<std::pair<double, size_t>> xs;
        for (size_t i = 0; i < bad.size(); ++i) xs.push_back({f.value(in.surfaces[i]), i});
        std::sort(xs.begin(), xs.end());
        if (xs.front().first == xs.back().first) continue;
        // Thresholds between distinct values; the side holding the wrong points.
        int badBelow = 0;
        for (size_t k = 0; k + 1 < xs.size(); ++k) {
            badBelow += bad[xs[k].second];
            if (xs[k].first == xs[k + 1].first) continue;
            const int below = int(k + 1), above = total - below;
            const int badAbove = badCount - badBelow;
            for (int side = 0; side < 2; ++side) {
                const int inBad = side == 0 ? badBelow : badAbove;  // wrong on that side
                const int sideSize = side == 0 ? below : above;
                const int otherBad = badCount - inBad, otherSize = total - sideSize;
                // Nearly all wrong points on the side, nearly all of the other side right, and
                // the other side not a sliver.
                if (inBad < 0.97 * badCount || otherSize < 0.15 * total ||
                    otherBad > 0.02 * otherSize)
                    continue;
                // Purity of the wrong side; among equally pure splits, the one holding more
                // of the wrong points.
                const double score = double(inBad) / sideSize + 1e-6 * inBad;
                if (score <= bestScore) continue;
                bestScore = score;
                best = describeSplit(in, bad, {f, xs, k, side, inBad, sideSize}, hinted);
            }
        }
    }
    if (bestScore < 0.3 && hinted) *hinted = false;
    return bestScore >= 0.3 ? best : "";
}

// Which fields of Surface the sensitivity test varies, with the names people use.
struct Field {
    const char* name;
    void (*copy)(Surface& to, const Surface& from);
};
const Field kFields[] = {
    {"the normal N", [](Surface& a, const Surface& b) { a.normal = b.normal; }},
    {"the view direction V", [](Surface& a, const Surface& b) { a.view = b.view; }},
    {"the light direction L", [](Surface& a, const Surface& b) { a.light = b.light; }},
    {"the light's position",
     [](Surface& a, const Surface& b) { a.lightPosition = b.lightPosition; }},
    {"the light's colour", [](Surface& a, const Surface& b) { a.lightColor = b.lightColor; }},
    {"the position P", [](Surface& a, const Surface& b) { a.position = b.position; }},
    {"albedo", [](Surface& a, const Surface& b) { a.albedo = b.albedo; }},
    {"the albedo texel", [](Surface& a, const Surface& b) { a.albedoTexel = b.albedoTexel; }},
    {"metallic", [](Surface& a, const Surface& b) { a.metallic = b.metallic; }},
    {"roughness", [](Surface& a, const Surface& b) { a.roughness = b.roughness; }},
    {"ao", [](Surface& a, const Surface& b) { a.ao = b.ao; }},
    {"the tangent", [](Surface& a, const Surface& b) { a.tangent = b.tangent; }},
    {"the normal-map texel", [](Surface& a, const Surface& b) { a.normalTexel = b.normalTexel; }},
    {"the first input (extra.x)", [](Surface& a, const Surface& b) { a.extra.x = b.extra.x; }},
    {"the second input (extra.y)", [](Surface& a, const Surface& b) { a.extra.y = b.extra.y; }},
};

// The fields of Surface a module's domain (or, without one, its probe) varies: the inputs
// its function reads. Bit k for kFields[k].
unsigned varyingFields(const ModuleDesc& d) {
    std::vector<Surface> samples;
    if (d.domain) {
        DomainRandom random(3);
        for (int i = 0; i < 32; ++i) samples.push_back(d.domain(random));
    } else if (d.probe.at) {
        for (int i = 0; i < 32; ++i) samples.push_back(d.probe.at((i % 8) / 7.0, (i / 8) / 3.0));
    }
    unsigned mask = 0;
    for (size_t k = 0; k < std::size(kFields); ++k)
        for (size_t i = 1; i < samples.size(); ++i) {
            Surface moved = samples[0];
            kFields[k].copy(moved, samples[i]);
            if (std::memcmp(&moved, &samples[0], sizeof(Surface)) != 0) mask |= 1u << k;
        }
    return mask;
}

// Pairs of domain points that differ in one input only: an input the reference depends on
// and the student's function does not (or the other way round).
std::string sensitivity(const FeedbackInputs& in) {
    if (!in.domain || !in.student || !in.reference) return "";
    DomainRandom random(7);
    const int pairs = 48;
    std::vector<Surface> base, other;
    for (int j = 0; j < pairs; ++j) {
        Surface a = in.domain(random), b = in.domain(random);
        a.covered = b.covered = true;
        base.push_back(a);
        other.push_back(b);
    }
    std::vector<Surface> all = base;
    std::vector<const Field*> fields;
    for (const Field& f : kFields) {
        // Only fields the domain varies.
        bool varies = false;
        for (int j = 0; j < pairs && !varies; ++j) {
            Surface moved = base[size_t(j)];
            f.copy(moved, other[size_t(j)]);
            varies = std::memcmp(&moved, &base[size_t(j)], sizeof(Surface)) != 0;
        }
        if (!varies) continue;
        fields.push_back(&f);
        for (int j = 0; j < pairs; ++j) {
            Surface moved = base[size_t(j)];
            f.copy(moved, other[size_t(j)]);
            all.push_back(moved);
        }
    }
    const std::vector<glm::dvec3> student = in.student(all);
    const int n = in.module->components;
    auto change = [&](const glm::dvec3& a, const glm::dvec3& b) {
        double d = 0, m = 0;
        for (int c = 0; c < n; ++c) {
            d = std::max(d, std::abs(a[c] - b[c]));
            m = std::max({m, std::abs(a[c]), std::abs(b[c])});
        }
        return d / std::max(m, 1e-6);
    };
    std::string ignored, spurious;
    for (size_t k = 0; k < fields.size(); ++k) {
        int refMoves = 0, studentMoves = 0, refStill = 0, studentStillWhereRefMoves = 0;
        for (int j = 0; j < pairs; ++j) {
            const size_t moved = size_t(pairs) * (k + 1) + size_t(j);
            const double dr = change(in.reference(base[size_t(j)]), in.reference(all[moved]));
            const double ds = change(student[size_t(j)], student[moved]);
            if (!std::isfinite(ds)) continue;
            if (dr > 1e-3) {
                ++refMoves;
                studentStillWhereRefMoves += ds < 1e-6;
            } else if (dr < 1e-7) {
                ++refStill;
                studentMoves += ds > 1e-3;
            }
        }
        if (refMoves >= pairs / 2 && studentStillWhereRefMoves == refMoves)
            ignored += std::string(ignored.empty() ? "" : ", ") + fields[k]->name;
        if (refStill == pairs && studentMoves >= pairs / 4)
            spurious += std::string(spurious.empty() ? "" : ", ") + fields[k]->name;
    }
    std::string out;
    if (!ignored.empty())
        out += "Your function does not change with " + ignored +
               ", which the reference depends on: is an argument unused?";
    if (!spurious.empty())
        out += std::string(out.empty() ? "" : " ") + "Your function changes with " + spurious +
               ", which the reference does not depend on.";
    return out;
}

// value - reference = k x feature, exactly (within 0.1% of the error's energy), for one of
// the inputs a term is usually made of.
std::string termFit(const FeedbackInputs& in) {
    struct Feature {
        const char* name;
        double (*of)(const Surface&, int c);
    };
    static const Feature features[] = {
        {"albedo", [](const Surface& s, int c) { return s.albedo[c]; }},
        {"albedo x ao", [](const Surface& s, int c) { return s.albedo[c] * s.ao; }},
        {"ao", [](const Surface& s, int) { return s.ao; }},
        {"metallic", [](const Surface& s, int) { return s.metallic; }},
        {"roughness", [](const Surface& s, int) { return s.roughness; }},
        {"N.L", [](const Surface& s, int) { return std::max(glm::dot(s.normal, s.light), 0.0); }},
        {"N.V", [](const Surface& s, int) { return std::max(glm::dot(s.normal, s.view), 0.0); }},
        {"the light's colour", [](const Surface& s, int c) { return s.lightColor[c]; }},
        {"the emission", [](const Surface& s, int c) { return s.emissive[c]; }},
    };
    const int n = in.module->components;
    for (const Feature& f : features) {
        double ex = 0, xx = 0, ee = 0;
        for (size_t i = 0; i < in.values.size(); ++i)
            for (int c = 0; c < n; ++c) {
                const double e = in.values[i][c] - in.expected[i][c], x = f.of(in.surfaces[i], c);
                if (!std::isfinite(e)) return "";
                ex += e * x, xx += x * x, ee += e * e;
            }
        if (xx <= 0 || ee <= 0) continue;
        const double k = ex / xx, residual = (ee - k * ex) / ee;  // share of the error left
        bool varies = false;  // a feature that is the same everywhere is the offset's case
        for (size_t i = 1; i < in.surfaces.size() && !varies; ++i)
            varies = f.of(in.surfaces[i], 0) != f.of(in.surfaces[0], 0);
        if (varies && residual < 1e-3)
            return "Your value is the reference " + std::string(k < 0 ? "- " : "+ ") +
                   num(std::abs(k), 3) + " x " + f.name + " everywhere: a term with " + f.name +
                   " has a wrong constant, or is extra or "
                   "missing.";
    }
    return "";
}

// One component wrong while the others are right: the patterns above on that component.
std::string componentPattern(const FeedbackInputs& in, bool& exact) {
    const int n = in.module->components;
    if (n < 2) return "";
    static const char* names[] = {"first", "second", "third"};
    int wrongComponent = -1, wrongPoints = 0;
    for (int c = 0; c < n; ++c) {
        int wrong = 0;
        for (size_t i = 0; i < in.values.size(); ++i)
            wrong += !(std::abs(in.values[i][c] - in.expected[i][c]) <= in.slack[i][c]);
        if (wrong > 0.05 * double(in.values.size())) {
            if (wrongComponent >= 0) return "";  // more than one
            wrongComponent = c;
            wrongPoints = wrong;
        }
    }
    if (wrongComponent < 0) return "";
    const int c = wrongComponent;
    std::vector<double> offsets, ratios;
    double lo = 1e300, hi = -1e300;
    for (size_t i = 0; i < in.values.size(); ++i) {
        const double v = in.values[i][c], e = in.expected[i][c];
        offsets.push_back(v - e);
        if (std::abs(e) > 10 * in.slack[i][c]) ratios.push_back(v / e);
        lo = std::min(lo, v), hi = std::max(hi, v);
    }
    const std::string which = std::string("The ") + names[c] + " component of your value";
    if (hi - lo <= 1e-7 * std::max(1.0, std::abs(hi)))
        return which + " is " + num(lo, 4) + " whatever the inputs; the others are right.";
    const double off = median(offsets);
    if (std::abs(off) > 1e-6 && shareNear(offsets, off, 1e-3) >= 0.95)
        return which + " is the reference's " + std::string(off > 0 ? "+ " : "- ") +
               num(std::abs(off), 4) + " everywhere; the others are right.";
    if (ratios.size() >= 8) {
        const double k = median(ratios);
        if (std::abs(k - 1) > 2e-3 && shareNear(ratios, k, 2e-3) >= 0.9) {
            const std::string constant = nameConstant(k);
            return which + " is " + num(k, 4) + " x the reference's" +
                   (constant.empty() ? "" : " (= " + constant + ")") +
                   " everywhere; the others are right.";
        }
    }
    exact = false;
    // The points where it is wrong, of those compared (all of them were said before, which
    // read as if every point were wrong).
    return which + " is wrong at " + std::to_string(wrongPoints) + " of " +
           std::to_string(offsets.size()) + " points; the others are right.";
}

// Where the values are NaN or Inf, and, when the evaluation can tell, the call that made the
// first one there.
std::string nonFiniteMessage(const FeedbackInputs& in, const std::string& where) {
    const int n = in.module->components;
    std::vector<Surface> points;
    int nans = 0, infs = 0;
    for (size_t i = 0; i < in.values.size(); ++i) {
        if (finite(in.values[i], n)) continue;
        bool nan = false;
        for (int c = 0; c < n; ++c) nan = nan || std::isnan(in.values[i][c]);
        ++(nan ? nans : infs);
        points.push_back(in.surfaces[i]);
    }
    const std::string what = infs == 0 ? "NaN" : nans == 0 ? "Inf" : "NaN or Inf";
    std::string s = "Your function returns " + what + " at " + std::to_string(nans + infs) +
                    " of " + std::to_string(in.values.size()) + " points";
    s += where.empty() ? "." : ", " + where;
    if (!where.empty() && s.back() != '.' && s.back() != '?') s += ".";
    // Up to 32 of them, spread, re-rendered by the diagnosis build.
    FeedbackInputs::NonFiniteOrigin origin;
    if (in.traceNonFinite) {
        std::vector<Surface> traced;
        const size_t count = std::min<size_t>(points.size(), 32);
        for (size_t k = 0; k < count; ++k) traced.push_back(points[k * points.size() / count]);
        origin = in.traceNonFinite(traced);
    }
    // A loop that did not end: nothing else is worth saying (the value is the guard's NaN).
    if (origin.cut.line > 0)
        return loopCutMessage(origin.cut, origin.loopBudget, nans + infs, int(in.values.size()));
    // "pow, sqrt, ... or mod": the calls the diagnosis build traces.
    std::string names;
    const std::vector<TracedCall>& calls = tracedCalls();
    for (size_t k = 0; k < calls.size(); ++k)
        names += (k == 0 ? "" : k + 1 == calls.size() ? " or " : ", ") + calls[k].builtin;
    const std::string file = in.module->id + ".glsl";
    // What else makes one from finite values: as the value is NaN, Inf or both.
    const std::string arithmetic = infs == 0   ? "a division 0/0, Inf/Inf or 0 x Inf"
                                   : nans == 0 ? "a division by zero or an overflow"
                                               : "a division by zero, 0/0 or an overflow";
    const auto at = [&](const TraceSite& site) {
        return site.what() + ", at line " + std::to_string(site.line) + " of " + file;
    };
    if (origin.site.traced() && origin.confirmed) {
        s += " The first " + what + " there comes from " + at(origin.site) +
             (origin.points < origin.traced ? " (at " + std::to_string(origin.points) + " of the " +
                                                  std::to_string(origin.traced) + " points traced)"
                                            : "") +
             (origin.other.traced() ? "; " + at(origin.other) + " makes one there too" : "") +
             ": is a guard or a clamp of its argument missing?";
    } else if (origin.site.traced()) {
        // It made one, but the value is not finite without it either: not the cause alone.
        s += " Your " + at(origin.site) +
             ", makes one there, but with its result replaced by 0 the value is still not "
             "finite: " +
             arithmetic + " elsewhere?";
    } else if (origin.traced > 0) {
        s += " No " + names + " in " + file +
             " made it from finite arguments there: " + arithmetic + "?";
    } else {
        s += " (a division by zero or a sqrt/pow of a negative?)";
    }
    // What the other points say, when a pattern accounts for every one of them (an input
    // flipped that makes 0/0 where it cancels the other, normalize(L - V) at L = V).
    FeedbackInputs rest = in;
    rest.surfaces.clear(), rest.values.clear(), rest.expected.clear(), rest.slack.clear();
    rest.traceNonFinite = nullptr;
    for (size_t i = 0; i < in.values.size(); ++i)
        if (finite(in.values[i], n)) {
            rest.surfaces.push_back(in.surfaces[i]);
            rest.values.push_back(in.values[i]);
            rest.expected.push_back(in.expected[i]);
            rest.slack.push_back(in.slack[i]);
        }
    bool exact = false;
    const std::string elsewhere = rest.values.size() >= 8 ? classifyError(rest, &exact) : "";
    if (exact && !elsewhere.empty()) s += " At the other points: " + elsewhere;
    return s;
}

// Where more than one component is wrong: the first wrong component that is the reference's
// to a power at 90% of its points (as the power pattern measures it), or "".
std::string componentPower(const FeedbackInputs& in) {
    const int n = in.module->components;
    static const char* names[] = {"first", "second", "third"};
    for (int c = 0; c < n; ++c) {
        std::vector<double> powers;
        int wrong = 0;
        for (size_t i = 0; i < in.values.size(); ++i) {
            const double v = in.values[i][c], e = in.expected[i][c];
            wrong += !(std::abs(v - e) <= in.slack[i][c]);
            if (e > 0 && v > 0 && std::abs(std::log(e)) > 0.05)
                powers.push_back(std::log(v) / std::log(e));
        }
        if (wrong < 0.05 * double(in.values.size()) || powers.size() < 8) continue;
        const double p = median(powers);
        if (std::abs(p - 1) <= 0.02 || std::abs(p) <= 0.05 || shareNear(powers, p, 0.01) < 0.9)
            continue;
        const double rounded = std::round(p * 2) / 2;
        const std::string power = std::abs(p - rounded) < 0.01 ? num(rounded) : num(p);
        return std::string("The ") + names[c] + " component of your value is the reference's to " +
               "the power " + power + " (x^" + power + " where the reference has x)" +
               (rounded == 2     ? ": is a square root missing, or a square extra?"
                : rounded == 0.5 ? ": is a square missing, or a square root extra?"
                                 : ": is an exponent wrong?") +
               " The other components are wrong too.";
    }
    return "";
}

// A constant output: the message when the student's value is the same at every point and the
// reference's is not, else "".
std::string constantOutput(const FeedbackInputs& in, const std::vector<Entry>& all) {
    double lo = all.front().value, hi = lo, elo = all.front().expected, ehi = elo;
    for (const Entry& e : all) {
        lo = std::min(lo, e.value), hi = std::max(hi, e.value);
        elo = std::min(elo, e.expected), ehi = std::max(ehi, e.expected);
    }
    if (hi - lo <= 1e-7 * std::max(1.0, std::abs(hi)) && ehi - elo > 1e-6) {
        const std::string constant = "Your function returns " + num(lo, 4) +
                                     " whatever the inputs (the reference varies from " + num(elo) +
                                     " to " + num(ehi) + ").";
        // Without the student's code, a constant 0 is most often the stub.
        const std::string why = lo != 0                  ? ""
                                : in.studentCode.empty() ? "Is it still the kit's stub?"
                                                         : whyAlwaysZero(in.studentCode);
        return why.rfind("Your function", 0) == 0 ? why : constant + (why.empty() ? "" : " " + why);
    }
    return "";
}

// Swapped components (multi-component values): where the reference's components differ,
// and at the points the reference does not explain (an estimator's band can be wide enough
// for a sky's red and green to pass for each other where the student is right).
std::string swappedComponents(const FeedbackInputs& in) {
    const int n = in.module->components;
    std::vector<bool> wrong;
    int wrongCount = 0;
    for (size_t i = 0; i < in.values.size(); ++i) {
        bool w = false;
        for (int c = 0; c < n; ++c)
            w = w || !(std::abs(in.values[i][c] - in.expected[i][c]) <= in.slack[i][c]);
        wrong.push_back(w);
        wrongCount += w;
    }
    const int perms[][3] = {{1, 0, 2}, {0, 2, 1}, {2, 1, 0}, {1, 2, 0}, {2, 0, 1}};
    for (const auto& p : perms) {
        if (n == 2 && (p[0] >= 2 || p[1] >= 2)) continue;
        int match = 0, considered = 0, matchWrong = 0;
        for (size_t i = 0; i < in.values.size(); ++i) {
            bool ok = true, differs = false, inBand = true;
            for (int c = 0; c < n; ++c) {
                const double e = in.expected[i][p[c]];
                const double apart = std::abs(in.values[i][c] - e);
                ok = ok && apart <= in.slack[i][p[c]] * 4 + 1e-3 * std::abs(e);
                // Where the reference does not explain the value, the swapped one must, as
                // the reference explains the right ones: within the band.
                inBand = inBand && apart <= in.slack[i][p[c]] + 1e-4 * std::abs(e);
                differs = differs || std::abs(in.expected[i][c] - e) > in.slack[i][c];
            }
            matchWrong += inBand && wrong[i];
            if (!differs) continue;
            ++considered;
            match += ok;
        }
        if (considered > 8 && match >= 0.95 * considered && matchWrong >= 0.9 * wrongCount) {
            const char* names = n == 2 ? "xy" : "xyz";
            std::string s = "Your components are swapped: ";
            for (int c = 0; c < n; ++c)
                if (p[c] != c)
                    s += std::string(c == 0 || p[0] == 0 ? "" : ", ") + names[c] + " holds " +
                         names[p[c]];
            return s + " of the reference.";
        }
    }
    return "";
}

// A constant factor: value / expected the same (`ratios`, where the reference is clearly
// nonzero) at nearly every point, the message naming the constant; else "".
std::string constantFactor(const FeedbackInputs& in, const std::vector<Entry>& all,
                           const std::vector<double>& ratios, double peak) {
    if (ratios.size() >= 8) {
        const double k = median(ratios);
        // The points left out of the ratios (the reference about 0 there) must agree too: a
        // light taken from the wrong side is 0 where the reference is lit (a "factor" of 0)
        // and lit where the reference is 0, which no factor explains.
        size_t unexplained = 0;
        for (const Entry& e : all)
            unexplained += std::abs(e.value - k * e.expected) >
                           4 * e.slack + 2e-3 * std::abs(k * e.expected) + 1e-3 * peak;
        if (std::abs(k - 1) > 2e-3 && shareNear(ratios, k, 2e-3) >= 0.9 &&
            unexplained <= all.size() / 10) {
            const std::string c = nameConstant(k);
            std::string s =
                "Your value is " + num(k, 4) + " x the reference" +
                (c.empty() ? "" : " (= " + c + ")") +
                (shareNear(ratios, k, 2e-3) >= 0.99 ? " everywhere" : " almost everywhere");
            if (c == "pi" || c == "1/pi")
                s += c == "pi" ? ": is a division by PI missing?"
                               : ": is there an extra division by PI?";
            else if (c == "-1")
                s += ": is a sign flipped?";
            else if (!c.empty())
                s += ": is a constant factor wrong?";
            else
                s += ": a constant factor is off.";
            // A term that is the same at every point of this check (the lesson's lights are
            // all of colour 300) explains it as well: said too.
            if (std::string t = nameTerm(in); !t.empty()) s += " " + t;
            return s;
        }
    }
    return "";
}

// A constant offset: value - expected the same at 95% of the points; else "".
std::string constantOffset(const std::vector<double>& offsets) {
    const double c = median(offsets);
    if (std::abs(c) > 1e-6 && shareNear(offsets, c, 1e-3) >= 0.95)
        return "Your value is the reference " + std::string(c > 0 ? "+ " : "- ") +
               num(std::abs(c), 4) + " everywhere: a term is added or missing.";
    return "";
}

// A power: value = expected^p where 0 < expected < 1 (or > 1), away from 1; else "".
std::string referencePower(const std::vector<Entry>& all) {
    std::vector<double> powers;
    for (const Entry& e : all)
        if (e.expected > 0 && e.value > 0 && std::abs(std::log(e.expected)) > 0.05)
            powers.push_back(std::log(e.value) / std::log(e.expected));
    if (powers.size() >= 8) {
        const double p = median(powers);
        if (std::abs(p - 1) > 0.02 && std::abs(p) > 0.05 && shareNear(powers, p, 0.01) >= 0.9)
            return "Your value is the reference to the power " + num(p) + " (x^" + num(p) +
                   " where the reference has x): an exponent is off.";
    }
    return "";
}

}  // namespace

const std::vector<InputAxis>& inputAxes(const ModuleDesc& d) {
    return d.inputAxes.empty() ? genericAxes(d.extraName) : d.inputAxes;
}

std::string describeInputs(const ModuleDesc& d, const Surface& s) {
    const unsigned mask = varyingFields(d);
    auto varies = [&](const char* name) {
        for (size_t k = 0; k < std::size(kFields); ++k)
            if (std::string(kFields[k].name) == name) return (mask >> k & 1u) != 0;
        return false;
    };
    std::ostringstream o;
    o.precision(3);
    const char* sep = "";
    auto field = [&](const std::string& name, const std::string& value) {
        o << sep << name << " " << value;
        sep = ", ";
    };
    auto vec = [](const glm::dvec3& v) {
        std::ostringstream t;
        t.precision(3);
        t << "(" << v.x << ", " << v.y << ", " << v.z << ")";
        return t.str();
    };
    const bool N = varies("the normal N"), V = varies("the view direction V"),
               L = varies("the light direction L");
    // A step that names what its function receives is described by those inputs.
    if (!d.inputAxes.empty()) {
        for (const InputAxis& a : d.inputAxes) field(a.name, num(a.value(s)));
        if (N) field("N", vec(s.normal));
        return o.str();
    }
    if (N && V) field("N.V", num(glm::dot(s.normal, s.view)));
    if (N && L) field("N.L", num(glm::dot(s.normal, s.light)));
    if (V && L && glm::length(s.light + s.view) > 1e-6)
        field(N ? "N.H" : "V.L", num(N ? glm::dot(s.normal, glm::normalize(s.light + s.view))
                                       : glm::dot(s.view, s.light)));
    for (size_t k = 0; k < std::size(kFields); ++k) {
        if (!(mask >> k & 1u)) continue;
        const std::string name = kFields[k].name;
        if (name == "roughness")
            field(name, num(s.roughness));
        else if (name == "metallic")
            field(name, num(s.metallic));
        else if (name == "ao")
            field(name, num(s.ao));
        else if (name == "albedo")
            field(name, vec(s.albedo));
        else if (name == "the albedo texel")
            field("texel", vec(s.albedoTexel));
        else if (name == "the light's colour")
            field("light colour", vec(s.lightColor));
        else if (name == "the light's position")
            field("light distance", num(glm::length(s.lightPosition - s.position)));
        else if (name == "the tangent")
            field("tangent", vec(glm::dvec3(s.tangent)) + " w " + num(s.tangent.w));
        else if (name == "the normal-map texel")
            field("texel", vec(s.normalTexel));
        else if (name == "the first input (extra.x)")
            field("extra.x", num(s.extra.x, 4));
        else if (name == "the second input (extra.y)")
            field("extra.y", num(s.extra.y, 4));
    }
    if (N) field("N", vec(s.normal));
    if (V && !N) field("V", vec(s.view));
    if (L && !N) field("L", vec(s.light));
    const std::string out = o.str();
    return out.empty() ? "one point" : out;
}

std::string nameConstant(double ratio) {
    struct Named {
        double value;
        const char* name;
    };
    const Named known[] = {
        {kPi, "pi"},
        {1 / kPi, "1/pi"},
        {2, "2"},
        {0.5, "1/2"},
        {4, "4"},
        {0.25, "1/4"},
        {kPi / 4, "pi/4"},
        {4 / kPi, "4/pi"},
        {2 * kPi, "2 pi"},
        {1 / (2 * kPi), "1/(2 pi)"},
        {kPi * kPi, "pi^2"},
        {-1, "-1"},
        {8, "8"},
        {0.125, "1/8"},
        {3, "3"},
        {1.0 / 3, "1/3"},
        {kPi / 2, "pi/2"},
        {2 / kPi, "2/pi"},
        {kPi / 3, "pi/3"},
        {3 / kPi, "3/pi"},
    };
    for (const Named& k : known)
        if (std::abs(ratio - k.value) <= 0.01 * std::abs(k.value)) return k.name;
    return "";
}

std::string loopCutMessage(const LoopSite& loop, int budget, int cut, int points) {
    return loop.file + " line " + std::to_string(loop.line) + ": this loop did not end within " +
           std::to_string(budget) +
           " iterations: a loop that never ends? The loops of your files are stopped after "
           "that many iterations in one evaluation, enough for a correct function, and the value "
           "is then NaN (here at " +
           std::to_string(cut) + " of " + std::to_string(points) + " points).";
}

std::string classifyError(const FeedbackInputs& in, bool* exactOut) {
    bool unused = false;
    bool& exact = exactOut ? *exactOut : unused;
    exact = true;  // every pattern below explains every point, but the last ones
    const int n = in.module->components;
    const std::vector<Entry> all = entries(in);
    // Not finite.
    int nonFinite = 0;
    for (const glm::dvec3& v : in.values) nonFinite += !finite(v, n);
    bool hinted = false;
    std::string where = region(in, &hinted);
    if (nonFinite > 0) {
        exact = false;
        return nonFiniteMessage(in, where);
    }
    if (all.empty()) return exact = false, "";
    if (std::string c = constantOutput(in, all); !c.empty()) return c;
    if (n >= 2)
        if (std::string s = swappedComponents(in); !s.empty()) return s;
    // A constant factor: value / expected the same wherever the reference is clearly nonzero.
    double peak = 0;
    for (const Entry& e : all) peak = std::max(peak, std::abs(e.expected));
    std::vector<double> ratios, offsets;
    for (const Entry& e : all) {
        offsets.push_back(e.value - e.expected);
        if (std::abs(e.expected) > std::max(1e-3 * peak, 10 * e.slack))
            ratios.push_back(e.value / e.expected);
    }
    if (std::string f = constantFactor(in, all, ratios, peak); !f.empty()) return f;
    if (std::string o = constantOffset(offsets); !o.empty()) return o;
    // A term of the step missing, applied twice or extra, or an input at another power
    // (term_fits.h): before the power of the reference, which gamma 3 also is.
    if (std::string t = nameTerm(in); !t.empty()) return t;
    if (std::string p = referencePower(all); !p.empty()) return p;
    // The error explained by one input: value = reference + k x (albedo x ao, N.L, ...).
    if (std::string f = termFit(in); !f.empty()) return f;
    // The reference on other inputs, a direction at another length, a curve of one input
    // (input_fits.h).
    if (std::string f = nameSubstitution(in); !f.empty()) return f;
    if (std::string f = nameLength(in); !f.empty()) return f;
    // A curve says less than a clamp or a cut-off on one side of an input (N.L unclamped is
    // N.L itself, and wrong only where N.L < 0 with the reference 0 there).
    if (std::string f = hinted ? "" : nameCurve(in); !f.empty()) return f;
    // One component wrong, the others right.
    if (std::string c = componentPattern(in, exact); !c.empty()) return c;
    exact = false;
    // Several wrong: one of them the reference's to a power (a square root missing in what
    // makes it), said for that one.
    if (std::string c = componentPower(in); !c.empty()) return c;
    std::string s = where.empty() ? "" : "Your function is " + where;
    const std::string sens = sensitivity(in);
    if (!sens.empty()) s += (s.empty() ? "" : " ") + sens;
    return s;
}

std::string withoutFigures(const std::string& mistake) {
    auto isName = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    auto isDigit = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; };
    std::string out;
    for (size_t i = 0; i < mistake.size();) {
        const bool afterName = i > 0 && (isName(mistake[i - 1]) || mistake[i - 1] == '.');
        const bool startsNumber =
            isDigit(mistake[i]) ||
            (mistake[i] == '.' && i + 1 < mistake.size() && isDigit(mistake[i + 1]) && !afterName);
        if (!startsNumber || afterName) {
            out += mistake[i++];
            continue;
        }
        // A number: digits, a decimal part, an exponent, a trailing % or x.
        size_t j = i;
        while (j < mistake.size() && (isDigit(mistake[j]) || mistake[j] == '.')) ++j;
        if (j + 1 < mistake.size() && (mistake[j] == 'e' || mistake[j] == 'E') &&
            (isDigit(mistake[j + 1]) || mistake[j + 1] == '-' || mistake[j + 1] == '+')) {
            j += 2;
            while (j < mistake.size() && isDigit(mistake[j])) ++j;
        }
        if (mistake[j - 1] == '.' && j - 1 > i) --j;  // a full stop after the number
        out += '#';
        i = j;
    }
    return out;
}

}  // namespace pbrlab
