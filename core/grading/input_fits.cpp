#include "grading/input_fits.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace pbrlab {

namespace {

using glm::dvec3;

std::string num(double v, int digits = 4) {
    std::ostringstream o;
    o.precision(digits);
    o << v;
    return o.str();
}

bool finiteValue(const dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// A candidate's value within twice the band of the student's, plus 1e-4 of it for float
// rounding: as the term fits and the typical mistakes are matched.
double distance(const FeedbackInputs& in, size_t i, const dvec3& candidate) {
    double d = 0;
    for (int c = 0; c < in.module->components; ++c) {
        const double v = in.values[i][c], m = candidate[c];
        if (!std::isfinite(v) || !std::isfinite(m)) return 1e300;
        const double apart = std::abs(v - m);
        d = std::max(d, apart == 0 ? 0 : apart / (2 * in.slack[i][c] + 1e-4 * std::abs(m)));
    }
    return d;
}

// The points a candidate is measured on: up to `budget` of the failed check's, half of them
// among those the reference does not explain (first: a wrong candidate fails there soonest).
struct Points {
    std::vector<size_t> index;
    std::vector<bool> wrong;
    int wrongCount = 0;
};

Points choose(const FeedbackInputs& in, size_t budget) {
    std::vector<size_t> wrong, right;
    for (size_t i = 0; i < in.values.size(); ++i) {
        if (!in.surfaces[i].covered || !finiteValue(in.values[i])) continue;
        (distance(in, i, in.expected[i]) <= 1 ? right : wrong).push_back(i);
    }
    Points p;
    auto spread = [](const std::vector<size_t>& from, size_t count, std::vector<size_t>& to) {
        const size_t n = std::min(count, from.size());
        for (size_t k = 0; k < n; ++k) to.push_back(from[k * from.size() / n]);
    };
    spread(wrong, budget - std::min(right.size(), budget / 2), p.index);
    p.wrongCount = int(p.index.size());
    spread(right, budget - p.index.size(), p.index);
    for (size_t k = 0; k < p.index.size(); ++k) p.wrong.push_back(int(k) < p.wrongCount);
    return p;
}

// How well a candidate explains the student's values on the points: it fails as soon as more
// than 5% of them disagree (most candidates fail at their first point, which matters where
// one evaluation of the reference is an estimate of thousands of samples).
struct Fit {
    bool explains = false;
    std::vector<dvec3> values;  // at the points, when it explains them
    double median = 0;          // distance, in units of the tolerance
    int misses = 0, points = 0;
    // "" when it explains every point, else at how many: a message never says "everywhere"
    // of a candidate that leaves some out.
    std::string where() const {
        return misses == 0 ? ""
                           : " (at " + std::to_string(points - misses) + " of " +
                                 std::to_string(points) + " points)";
    }
};

template <class Value>
Fit measure(const FeedbackInputs& in, const Points& p, Value value) {
    Fit fit;
    const int allowed = int(0.05 * double(p.index.size()));
    int misses = 0, wrongHits = 0;
    std::vector<double> distances;
    for (size_t k = 0; k < p.index.size(); ++k) {
        const dvec3 v = value(p.index[k]);
        const double d = distance(in, p.index[k], v);
        distances.push_back(d);
        fit.values.push_back(v);
        if (d > 1) {
            if (++misses > allowed) return {};
        } else if (p.wrong[k]) {
            ++wrongHits;
        }
    }
    if (p.wrongCount == 0 || wrongHits < 0.9 * p.wrongCount) return {};
    std::nth_element(distances.begin(), distances.begin() + long(distances.size() / 2),
                     distances.end());
    fit.median = distances[distances.size() / 2];
    fit.explains = true;
    fit.misses = misses;
    fit.points = int(p.index.size());
    return fit;
}

// ---- the reference on other inputs ------------------------------------------------------------

// How an input is written in a formula: its name, or the letter that ends it ("the light's
// distance d": d), with what the letter is.
std::pair<std::string, std::string> symbol(const std::string& name) {
    const size_t space = name.rfind(' ');
    if (space == std::string::npos || space + 2 != name.size()) return {name, ""};
    return {name.substr(space + 1),
            " (" + name.substr(space + 1) + ": " + name.substr(0, space) + ")"};
}

struct Substitution {
    std::string said;      // "-L in place of L"
    std::string question;  // "is the light direction flipped ...?"
    std::function<void(Surface&)> change;
    bool mirrorLights = false;  // the scene's lights mirrored through the point as well
};

struct Direction {
    const char* symbol;
    dvec3 Surface::*field;
    const char* flipped;  // the question when it is negated
};
const Direction kDirections[] = {
    {"L", &Surface::light,
     "is the light direction flipped (L pointing from the light to the surface)?"},
    {"V", &Surface::view,
     "is the view direction flipped (V pointing from the camera to the surface)?"},
    {"N", &Surface::normal, "is the normal flipped?"},
};

// Directions negated, two of them swapped: every direction, also one the points share (a
// probe's V = N) or that the reference reads from the scene's lights rather than L.
std::vector<Substitution> directionSubstitutions() {
    std::vector<Substitution> out;
    std::vector<const Direction*> directions;
    for (const Direction& d : kDirections) directions.push_back(&d);
    for (const Direction* d : directions) {
        const std::string x = d->symbol;
        Substitution s{"-" + x + " in place of " + x, d->flipped, nullptr};
        if (d->field == &Surface::light) {
            // The light on the other side of the point, at the same distance.
            s.change = [](Surface& t) {
                t.light = -t.light;
                t.lightPosition = 2.0 * t.position - t.lightPosition;
            };
            s.mirrorLights = true;
        } else {
            s.change = [f = d->field](Surface& t) { t.*f = -(t.*f); };
        }
        out.push_back(std::move(s));
    }
    for (size_t a = 0; a < directions.size(); ++a)
        for (size_t b = a + 1; b < directions.size(); ++b) {
            const std::string x = directions[a]->symbol, y = directions[b]->symbol;
            out.push_back({y + " and " + x + " swapped",
                           "are the two directions passed the wrong way round?",
                           [f = directions[a]->field, g = directions[b]->field](Surface& t) {
                               std::swap(t.*f, t.*g);
                           }});
        }
    return out;
}

// An input of the step's (or a generic one) that can be set, with its range over the points.
struct InputRange {
    const InputAxis* axis;
    double lo, hi;
};

// The step's inputs (or the generic ones) that can be set and vary over the points.
std::vector<InputRange> settableRanges(const FeedbackInputs& in, const Points& p) {
    const std::vector<InputAxis>& axes = inputAxes(*in.module);
    std::vector<InputRange> ranges;
    for (const InputAxis& a : axes) {
        if (!a.set) continue;
        double lo = 1e300, hi = -1e300;
        for (size_t i : p.index) {
            const double x = a.value(in.surfaces[i]);
            lo = std::min(lo, x), hi = std::max(hi, x);
        }
        if (hi - lo > 1e-9) ranges.push_back({&a, lo, hi});
    }
    return ranges;
}

// One input transformed where its range allows: squared, square-rooted, complemented, or its
// sign flipped (appended to `out`).
void addInputTransforms(const FeedbackInputs& in, const Points& p, const InputRange& r,
                        std::vector<Substitution>& out) {
    const InputAxis& a = *r.axis;
    const auto [x, where] = symbol(a.name);
    auto with = [&a](double (*f)(double)) {
        return [&a, f](Surface& t) { a.set(t, f(a.value(t))); };
    };
    if (r.lo >= 0) {
        out.push_back({x + "^2 in place of " + x + where,
                       "is " + x + " squared where it is used, or passed on?",
                       with([](double v) { return v * v; })});
        out.push_back({"sqrt(" + x + ") in place of " + x + where,
                       "is a square missing where " + x + " is used (" + x + " where " + x +
                           "^2 belongs, or alpha where alpha^2 belongs)?",
                       with([](double v) { return std::sqrt(v); })});
    }
    if (r.lo >= 0 && r.hi <= 1) {
        const std::string complement = "1 - " + x;
        out.push_back({complement + " in place of " + x + where,
                       "is " + x + " used where " + complement +
                           " belongs (mix arguments reversed, or " + complement + " missing)?",
                       with([](double v) { return 1 - v; })});
    }
    // A sign: an input that takes two opposite values only (a handedness).
    bool sign = r.lo < 0 && std::abs(r.lo + r.hi) < 1e-9;
    for (size_t i : p.index)
        sign = sign && std::abs(std::abs(a.value(in.surfaces[i])) - r.hi) < 1e-9;
    if (sign)
        out.push_back({"-" + x + " in place of " + x + where,
                       "is what the sign of " + x +
                           " decides (a direction, the order of a cross product) reversed?",
                       with([](double v) { return -v; })});
}

// Two inputs of [0, 1] swapped (appended to `out`).
void addInputSwaps(const std::vector<InputRange>& ranges, std::vector<Substitution>& out) {
    for (size_t a = 0; a < ranges.size(); ++a)
        for (size_t b = a + 1; b < ranges.size(); ++b) {
            const InputRange &r = ranges[a], &s = ranges[b];
            if (r.lo < 0 || r.hi > 1 || s.lo < 0 || s.hi > 1) continue;
            out.push_back(
                {symbol(r.axis->name).first + " and " + symbol(s.axis->name).first + " swapped",
                 "are the two inputs used the wrong way round?",
                 [x = r.axis, y = s.axis](Surface& t) {
                     const double u = x->value(t), v = y->value(t);
                     x->set(t, v);
                     y->set(t, u);
                 }});
        }
}

// Every transformation of the inputs the reference is tried on, for these points.
std::vector<Substitution> substitutions(const FeedbackInputs& in, const Points& p) {
    std::vector<Substitution> out = directionSubstitutions();
    const std::vector<InputRange> ranges = settableRanges(in, p);
    for (const InputRange& r : ranges) addInputTransforms(in, p, r, out);
    addInputSwaps(ranges, out);
    // A texel that stores a vector of [-1, 1] in [0, 1], read as it is stored.
    bool texels = false;
    for (size_t i : p.index)
        texels = texels || in.surfaces[i].normalTexel != in.surfaces[p.index[0]].normalTexel;
    if (texels)
        out.push_back({"(t + 1) / 2 in place of the normal-map texel t",
                       "is the texel used without the [0,1] -> [-1,1] remap (t * 2 - 1)?",
                       [](Surface& t) { t.normalTexel = (t.normalTexel + 1.0) * 0.5; }});
    return out;
}

}  // namespace

std::string nameSubstitution(const FeedbackInputs& in) {
    if (!in.module || in.values.empty()) return "";
    if (!in.reference && !(in.context && in.module->reference)) return "";
    // Values rescaled by their best factor (EstimatorSpec::scaleTolerance) are not the
    // reference's on any inputs.
    if (in.module->estimator && in.module->estimator->scaleTolerance > 0) return "";
    // An estimate of the reference costs its sample count per point.
    const Points p = choose(in, in.module->estimator ? 48 : 128);
    if (p.wrongCount == 0) return "";
    struct Matched {
        const Substitution* s;
        Fit fit;
    };
    const std::vector<Substitution> all = substitutions(in, p);
    std::vector<Matched> matched;
    for (const Substitution& s : all) {
        Fit fit = measure(in, p, [&](size_t i) {
            Surface t = in.surfaces[i];
            s.change(t);
            if (!in.context || !in.module->reference) return in.reference(t);
            if (!s.mirrorLights) return in.module->reference(t, *in.context);
            ReferenceContext c{in.context->params, in.context->lights, in.context->cameraPosition,
                               in.context->ibl};
            for (ref::PointLight& l : c.lights)
                l.position = 2.0 * in.surfaces[i].position - l.position;
            return in.module->reference(t, c);
        });
        if (std::getenv("PBRLAB_TERM_FITS_DEBUG"))
            std::fprintf(stderr, "substitution: %s %s (median %.3g)\n", s.said.c_str(),
                         fit.explains ? "explains" : "no", fit.median);
        if (fit.explains) matched.push_back({&s, std::move(fit)});
    }
    if (matched.empty()) return "";
    // Candidates whose values are the same here (-L and -N under max(N.L, 0)) are said
    // together; of candidates that differ, one is named only when it is 10x closer.
    auto same = [&](const Fit& a, const Fit& b) {
        for (size_t k = 0; k < p.index.size(); ++k)
            if (!(glm::length(a.values[k] - b.values[k]) <=
                  1e-6 * std::max(1.0, glm::length(a.values[k]))))
                return false;
        return true;
    };
    std::sort(matched.begin(), matched.end(),
              [](const Matched& a, const Matched& b) { return a.fit.median < b.fit.median; });
    const Matched& best = matched.front();
    std::vector<const Matched*> alike = {&best};
    for (size_t k = 1; k < matched.size(); ++k) {
        if (same(best.fit, matched[k].fit))
            alike.push_back(&matched[k]);
        else if (matched[k].fit.median < 10 * best.fit.median)
            return "";
    }
    std::string said = alike[0]->s->said;
    for (size_t k = 1; k < alike.size(); ++k)
        said += std::string(k == 1 ? " (the same here as " : ", ") + alike[k]->s->said;
    if (alike.size() > 1) said += ")";
    return "Your value is the reference with " + said + alike[0]->fit.where() + ": " +
           alike[0]->s->question;
}

// ---- a direction at another length --------------------------------------------------------------

std::string nameLength(const FeedbackInputs& in) {
    if (!in.module || in.module->components != 3) return "";
    const Points p = choose(in, 256);
    if (p.wrongCount == 0) return "";
    // The reference's values unit vectors, the student's along them.
    for (size_t i : p.index) {
        const dvec3 &r = in.expected[i], &v = in.values[i];
        if (std::abs(glm::length(r) - 1) > 1e-3) return "";
        if (glm::length(glm::cross(v, r)) > 1e-3 * std::max(glm::length(v), 1e-6) ||
            glm::dot(v, r) <= 0)
            return "";
    }
    struct Sum {
        std::string said;
        dvec3 Surface::*a;
        dvec3 Surface::*b;
        double sign;
    };
    const Sum sums[] = {
        {"L + V", &Surface::light, &Surface::view, 1},
        {"L - V", &Surface::light, &Surface::view, -1},
        {"N + V", &Surface::normal, &Surface::view, 1},
        {"N + L", &Surface::normal, &Surface::light, 1},
    };
    for (const Sum& sum : sums)
        for (const double k : {1.0, 0.5, 2.0}) {
            const Fit fit = measure(in, p, [&](size_t i) {
                const Surface& s = in.surfaces[i];
                return in.expected[i] * (k * glm::length(s.*sum.a + sum.sign * (s.*sum.b)));
            });
            if (!fit.explains) continue;
            const std::string value = k == 1     ? sum.said
                                      : k == 0.5 ? "(" + sum.said + ") / 2"
                                                 : "2 (" + sum.said + ")";
            // Said as the normalised sum when the reference is that sum's direction.
            bool normalised = true;
            for (size_t i : p.index) {
                const Surface& s = in.surfaces[i];
                const dvec3 d = s.*sum.a + sum.sign * (s.*sum.b);
                normalised = normalised && glm::length(d) > 1e-6 &&
                             glm::length(d / glm::length(d) - in.expected[i]) < 1e-4;
            }
            return normalised
                       ? "Your value is " + value + fit.where() +
                             ", where the reference is normalize(" + sum.said +
                             "): is a normalize missing?"
                       : "Your value points the reference's way with length |" + sum.said + "|" +
                             (k == 1     ? ""
                              : k == 0.5 ? " / 2"
                                         : " x 2") +
                             fit.where() + ", where the reference's is 1: is a normalize missing?";
        }
    return "";
}

// ---- curves of one input ------------------------------------------------------------------------

namespace {

// A number as a student would write it: a simple fraction 1/x when it is one (1/2.2, 1/12.92).
std::string constant(double v) {
    if (std::abs(v) < 1e-12) return "0";
    // Two significant digits when they are the number (0.032, 0.5); else 1/x when x has two
    // decimals and is no integer (1/2.2, 1/12.92); else four digits.
    if (const std::string two = num(v, 2); std::abs(std::stod(two) - v) <= 1e-4 * std::abs(v))
        return two;
    const double inverse = 1 / v;
    const double rounded = std::round(inverse * 100) / 100;
    if (std::abs(v) < 1 && std::abs(inverse) < 100 &&
        std::abs(inverse - rounded) < 1e-4 * std::abs(inverse) &&
        std::abs(rounded - std::round(rounded)) > 1e-9)
        return "1/" + num(rounded, 4);
    return num(v, 4);
}

// Least squares of y on the columns of a (up to 3), unweighted; false when singular.
bool solve(const std::vector<std::array<double, 3>>& a, const std::vector<double>& y, int columns,
           std::array<double, 3>& x) {
    double m[3][4] = {};
    for (size_t i = 0; i < y.size(); ++i)
        for (int r = 0; r < columns; ++r) {
            for (int c = 0; c < columns; ++c) m[r][c] += a[i][size_t(r)] * a[i][size_t(c)];
            m[r][3] += a[i][size_t(r)] * y[i];
        }
    for (int c = 0; c < columns; ++c) {
        int pivot = c;
        for (int r = c + 1; r < columns; ++r)
            if (std::abs(m[r][c]) > std::abs(m[pivot][c])) pivot = r;
        if (std::abs(m[pivot][c]) < 1e-300) return false;
        for (int k = 0; k < 4; ++k) std::swap(m[c][k], m[pivot][k]);
        for (int r = 0; r < columns; ++r) {
            if (r == c) continue;
            const double f = m[r][c] / m[c][c];
            for (int k = 0; k < 4; ++k) m[r][k] -= f * m[c][k];
        }
    }
    for (int c = 0; c < columns; ++c) x[size_t(c)] = m[c][3] / m[c][c];
    return true;
}

// An input per component: a scalar (the same for every component) or a colour's channel.
struct CurveInput {
    std::string name;
    std::function<double(const Surface&, int c)> at;
    bool perChannel = false;
};

// The inputs a curve's variable may be: the step's (or the generic ones), then the colours.
std::vector<CurveInput> curveInputs(const ModuleDesc& module) {
    std::vector<CurveInput> inputs;
    for (const InputAxis& a : inputAxes(module))
        inputs.push_back({a.name, [f = a.value](const Surface& s, int) { return f(s); }});
    inputs.push_back(
        {"the albedo texel", [](const Surface& s, int c) { return s.albedoTexel[c]; }, true});
    inputs.push_back({"the albedo", [](const Surface& s, int c) { return s.albedo[c]; }, true});
    inputs.push_back({module.extraName, [](const Surface& s, int c) { return s.extra[c]; }, true});
    inputs.push_back(
        {"the light's colour", [](const Surface& s, int c) { return s.lightColor[c]; }, true});
    return inputs;
}

// An input that takes one value at every point and channel explains nothing. A colour that is
// the same at every point but differs between channels counts as varying: as a factor it
// scales the channels apart (the albedo x a curve of N.L); as a curve's variable it takes
// three values only, which curveSamples refuses.
bool variesOverPoints(const FeedbackInputs& in, const Points& p, const CurveInput& x) {
    const int n = in.module->components;
    for (size_t i : p.index)
        for (int c = 0; c < n; ++c)
            if (x.at(in.surfaces[i], c) != x.at(in.surfaces[p.index[0]], 0)) return true;
    return false;
}

// A factor is one the reference is proportional to, where the points share its value too
// (the lesson's lights are all of colour 300: a factor of radiance, none of N.L): the
// reference with the colour or the albedo doubled, at a few points.
bool proportional(const FeedbackInputs& in, const Points& p, const CurveInput& f) {
    const int n = in.module->components;
    if (f.name.empty()) return true;
    if (!in.reference && !(in.context && in.module->reference)) return variesOverPoints(in, p, f);
    auto reference = [&](const Surface& s) {
        return in.context && in.module->reference ? in.module->reference(s, *in.context)
                                                  : in.reference(s);
    };
    for (size_t k = 0; k < std::min<size_t>(p.index.size(), 4); ++k) {
        Surface s = in.surfaces[p.index[k * p.index.size() / 4]];
        const dvec3 r = reference(s);
        (f.name == "the albedo" ? s.albedo : s.lightColor) *= 2.0;
        const dvec3 twice = reference(s);
        for (int c = 0; c < n; ++c)
            if (std::abs(twice[c] - 2 * r[c]) > 1e-9 * std::max(1.0, std::abs(r[c]))) return false;
    }
    return true;
}

// (x, y = value / factor) at every point and component, in xs and ys; false when they are not
// finite, or the input does not take many values (then any curve fits).
bool curveSamples(const FeedbackInputs& in, const Points& p, const CurveInput& factor,
                  const CurveInput& input, std::vector<double>& xs, std::vector<double>& ys) {
    const int n = in.module->components;
    bool usable = true;
    for (size_t i : p.index)
        for (int c = 0; c < n && usable; ++c) {
            const double f = factor.at(in.surfaces[i], c);
            if (std::abs(f) < 1e-9) continue;
            xs.push_back(input.at(in.surfaces[i], c));
            ys.push_back(in.values[i][c] / f);
            usable = std::isfinite(xs.back()) && std::isfinite(ys.back());
        }
    if (!usable || xs.size() < 16) return false;
    std::vector<double> distinct = xs;
    std::sort(distinct.begin(), distinct.end());
    return std::unique(distinct.begin(), distinct.end()) - distinct.begin() >= 12;
}

// A curve of one input, fitted by least squares, then measured like every candidate.
struct Curve {
    std::string said;
    std::function<double(double)> g;
    bool divides = false;  // said as "factor / (...)"
};

// a + b x (appended to `curves` when it fits and b is not 0).
void fitLine(const std::vector<double>& xs, const std::vector<double>& ys, const std::string& x,
             std::vector<Curve>& curves) {
    std::vector<std::array<double, 3>> a;
    for (double v : xs) a.push_back({1, v, 0});
    std::array<double, 3> c{};
    if (solve(a, ys, 2, c) && std::abs(c[1]) > 1e-9) {
        const double c0 = std::abs(c[0]) < 1e-6 ? 0 : c[0];
        const bool unit = std::abs(c[1] - 1) < 1e-4;
        const std::string scaled = unit ? x : constant(c[1]) + " x " + x;
        curves.push_back({c0 == 0 ? (unit ? x + " itself" : scaled) : constant(c0) + " + " + scaled,
                          [c0, b = c[1]](double v) { return c0 + b * v; }});
    }
}

// a x^p and a clamp(x, 0, 1)^p: a line in log-log, over the points inside (0, 1)
// for the clamped one.
void fitPowers(const std::vector<double>& xs, const std::vector<double>& ys, const std::string& x,
               std::vector<Curve>& curves) {
    for (const bool clamped : {false, true}) {
        std::vector<std::array<double, 3>> a;
        std::vector<double> ly;
        for (size_t k = 0; k < xs.size(); ++k)
            if (xs[k] > 0 && ys[k] > 0 && (!clamped || xs[k] < 1)) {
                a.push_back({1, std::log(xs[k]), 0});
                ly.push_back(std::log(ys[k]));
            }
        std::array<double, 3> c{};
        if (ly.size() < 12 || !solve(a, ly, 2, c)) continue;
        const double scale = std::exp(c[0]), power = c[1];
        if (std::abs(power - 1) < 1e-3 && !clamped) continue;  // the line's case
        if (std::abs(power) < 1e-3) continue;  // a constant: the input plays no part
        const std::string base = clamped ? "clamp(" + x + ", 0, 1)" : x;
        const std::string head = std::abs(scale - 1) < 1e-3 ? "" : constant(scale) + " x ";
        const std::string exponent = constant(power);
        curves.push_back(
            {head + base + "^" +
                 (exponent.find('/') != std::string::npos ? "(" + exponent + ")" : exponent),
             [scale, power, clamped](double v) {
                 return scale * std::pow(clamped ? std::clamp(v, 0.0, 1.0) : v, power);
             }});
    }
}

// 1 / (a + b x + c x^2): a falloff written as a polynomial.
void fitInversePolynomial(const std::vector<double>& xs, const std::vector<double>& ys,
                          const std::string& x, std::vector<Curve>& curves) {
    std::vector<std::array<double, 3>> a;
    std::vector<double> inv;
    for (size_t k = 0; k < xs.size(); ++k)
        if (std::abs(ys[k]) > 1e-12) {
            a.push_back({1, xs[k], xs[k] * xs[k]});
            inv.push_back(1 / ys[k]);
        }
    std::array<double, 3> c{};
    if (inv.size() >= 12 && solve(a, inv, 3, c))
        curves.push_back({"(" + constant(c[0]) + " + " + constant(c[1]) + " " + x + " + " +
                              constant(c[2]) + " " + x + "^2)",
                          [c](double v) { return 1 / (c[0] + c[1] * v + c[2] * v * v); }, true});
}

// The message for the first curve, times the factor, that explains the student's values;
// "" when none does.
std::string explainingCurve(const FeedbackInputs& in, const Points& p, const CurveInput& factor,
                            const CurveInput& input, const std::vector<double>& xs,
                            const std::vector<Curve>& curves, const std::string& where) {
    const int n = in.module->components;
    for (const Curve& curve : curves) {
        // A curve that is flat over the points says the input plays no part.
        double lo = 1e300, hi = -1e300;
        for (double v : xs) lo = std::min(lo, curve.g(v)), hi = std::max(hi, curve.g(v));
        if (!(hi - lo > 1e-6 * std::max(std::abs(hi), std::abs(lo)))) continue;
        const Fit fit = measure(in, p, [&](size_t i) {
            dvec3 v(0);
            for (int c = 0; c < n; ++c)
                v[c] = factor.at(in.surfaces[i], c) * curve.g(input.at(in.surfaces[i], c));
            return v;
        });
        if (!fit.explains) continue;
        const std::string value =
            curve.divides ? (factor.name.empty() ? "1" : factor.name) + " / " + curve.said
                          : (factor.name.empty() ? curve.said : factor.name + " x " + curve.said);
        return "Your value is " + value + where +
               (fit.misses == 0 ? " at every point" : fit.where()) +
               (input.perChannel && n > 1 ? " (channel by channel)" : "") +
               ", where the reference is not.";
    }
    return "";
}

}  // namespace

std::string nameCurve(const FeedbackInputs& in) {
    if (!in.module || in.values.empty()) return "";
    const Points p = choose(in, 256);
    if (p.wrongCount == 0) return "";
    const std::vector<CurveInput> inputs = curveInputs(*in.module);
    // What the value may be a multiple of (the light's colour x a falloff), or 1: the
    // multiples first, which say more where the points have one light's colour only.
    const std::vector<CurveInput> factors = {
        {"the light's colour", [](const Surface& s, int c) { return s.lightColor[c]; }},
        {"the albedo", [](const Surface& s, int c) { return s.albedo[c]; }},
        {"", [](const Surface&, int) { return 1.0; }},
    };
    for (const CurveInput& factor : factors) {
        if (!proportional(in, p, factor)) continue;
        for (const CurveInput& input : inputs) {
            if (input.name == factor.name || !variesOverPoints(in, p, input)) continue;
            std::vector<double> xs, ys;
            if (!curveSamples(in, p, factor, input, xs, ys)) continue;
            const auto [x, where] = symbol(input.name);
            std::vector<Curve> curves;
            fitLine(xs, ys, x, curves);
            fitPowers(xs, ys, x, curves);
            fitInversePolynomial(xs, ys, x, curves);
            const std::string said = explainingCurve(in, p, factor, input, xs, curves, where);
            if (!said.empty()) return said;
        }
    }
    return "";
}

}  // namespace pbrlab
