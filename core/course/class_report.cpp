#include "course/class_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

#include "course/autograder.h"
#include "util/error.h"
#include "util/fs.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace pbrlab {

namespace {

const char* const kClassHeader =
    "student,step,status,score,max_score,mistake,named_by,mistake_group";
const char* const kSummaryHeader = "submission,score,max_score,seconds,error";

// A field as RFC 4180 writes it: quoted when it holds a comma, a quote or a line break.
std::string csvField(const std::string& text) {
    if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
    std::string out = "\"";
    for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

std::string number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", v);
    return text;
}

// The records of a CSV file (quoted fields may hold commas, quotes and line breaks), each with
// the line it starts on.
std::vector<std::pair<int, std::vector<std::string>>> readCsv(const fs::path& file) {
    const std::string text = readFile(file);
    std::vector<std::pair<int, std::vector<std::string>>> records;
    std::vector<std::string> fields(1);
    int line = 1, start = 1;
    bool quoted = false, any = false;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (quoted) {
            if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
                fields.back() += '"';
                ++i;
            } else if (c == '"') {
                quoted = false;
            } else {
                line += c == '\n';
                fields.back() += c;
            }
        } else if (c == '"') {
            quoted = any = true;
        } else if (c == ',') {
            fields.emplace_back();
            any = true;
        } else if (c == '\n' || c == '\r') {
            if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
            if (any || !fields.back().empty()) records.push_back({start, fields});
            fields.assign(1, "");
            any = false;
            start = ++line;
        } else {
            fields.back() += c;
            any = true;
        }
    }
    if (quoted) throw Error(file.string() + ":" + std::to_string(start) + ": unclosed quote");
    if (any || !fields.back().empty()) records.push_back({start, fields});
    return records;
}

// The records after a header that must be `header`, each with as many fields.
std::vector<std::pair<int, std::vector<std::string>>> readTable(const fs::path& file,
                                                                const std::string& header) {
    auto records = readCsv(file);
    std::string first;
    if (!records.empty())
        for (size_t i = 0; i < records[0].second.size(); ++i)
            first += (i ? "," : "") + records[0].second[i];
    if (first != header)
        throw Error(file.string() + ":1: the header is not \"" + header +
                    "\" (not written by pbrlab grade --batch?)");
    records.erase(records.begin());
    const size_t columns = size_t(std::count(header.begin(), header.end(), ',') + 1);
    for (const auto& [line, fields] : records)
        if (fields.size() != columns)
            throw Error(file.string() + ":" + std::to_string(line) + ": " +
                        std::to_string(fields.size()) + " fields, expected " +
                        std::to_string(columns));
    return records;
}

// A status or a named_by as class.csv writes them (nameOf).
template <class E>
E parseName(const std::string& text, const fs::path& file, int line, const char* what) {
    if (const std::optional<E> v = verdictNamed<E>(text)) return *v;
    throw Error(file.string() + ":" + std::to_string(line) + ": " + what + " \"" + text +
                "\" is not one");
}

double parseNumber(const std::string& text, const fs::path& file, int line, const char* what) {
    try {
        size_t used = 0;
        double v = std::stod(text, &used);
        if (used == text.size() && std::isfinite(v)) return v;
    } catch (const std::exception&) {
    }
    throw Error(file.string() + ":" + std::to_string(line) + ": " + what + " \"" + text +
                "\" is not a number");
}

std::string escape(const std::string& s) {
    std::string o;
    for (char c : s)
        o += c == '<'   ? "&lt;"
             : c == '>' ? "&gt;"
             : c == '&' ? "&amp;"
             : c == '"' ? "&quot;"
                        : std::string(1, c);
    return o;
}

const char* statusColour(GradeStatus status) {
    return status == GradeStatus::Passed         ? "#6d6"
           : status == GradeStatus::Failed       ? "#f85"
           : status == GradeStatus::CompileError ? "#e5c07b"
           : status == GradeStatus::Missing      ? "#777"
                                                 : "#c678dd";  // timeout, crashed
}

// The steps in the order they first appear, and each step's rows.
struct StepRows {
    std::string step;
    std::vector<const ClassRow*> rows;
};
std::vector<StepRows> byStep(const std::vector<ClassRow>& rows) {
    std::vector<StepRows> steps;
    for (const ClassRow& r : rows) {
        auto it = std::find_if(steps.begin(), steps.end(),
                               [&](const StepRows& s) { return s.step == r.step; });
        if (it == steps.end()) it = steps.insert(steps.end(), {r.step, {}});
        it->rows.push_back(&r);
    }
    return steps;
}

// A horizontal bar: the share `part / whole` filled.
std::string passBar(size_t part, size_t whole) {
    const double share = whole ? double(part) / double(whole) : 0;
    std::ostringstream s;
    s << "<svg width=180 height=18 role=img><rect width=120 height=14 y=2 fill=#333 />"
      << "<rect width=" << number(120 * share) << " height=14 y=2 fill=#6d6 />"
      << "<text x=128 y=14 fill=#ddd font-size=12>" << std::lround(100 * share) << "%</text></svg>";
    return s.str();
}

// The most common named mistakes of one step: the mistake in words (wrapped by the page),
// and a bar scaled to the number of students.
std::string mistakeChart(const std::vector<const ClassRow*>& rows) {
    std::map<std::string, size_t> counts;
    for (const ClassRow* r : rows)
        if (!r->mistake.empty()) ++counts[r->group.empty() ? r->mistake : r->group];
    if (counts.empty()) return "<span class=muted>none named</span>";
    std::vector<std::pair<std::string, size_t>> top(counts.begin(), counts.end());
    std::stable_sort(top.begin(), top.end(),
                     [](const auto& a, const auto& b) { return a.second > b.second; });
    const size_t shown = std::min<size_t>(top.size(), 5);
    const double barWidth = 160;
    std::ostringstream s;
    s << "<table class=mistakes>";
    for (size_t i = 0; i < shown; ++i) {
        const auto& [mistake, count] = top[i];
        const double share = double(count) / double(rows.size());
        s << "<tr><td class=bar><svg width=" << number(barWidth + 70)
          << " height=16 role=img><rect width=" << number(barWidth)
          << " height=12 y=2 fill=#2a2b30 /><rect width=" << number(std::max(barWidth * share, 1.0))
          << " height=12 y=2 fill=#f85 /><text x=" << number(barWidth + 6)
          << " y=13 fill=#ddd font-size=12>" << count << " (" << std::lround(100 * share)
          << "%)</text></svg></td><td>" << escape(mistake) << "</td></tr>";
    }
    s << "</table>";
    if (top.size() > shown)
        s << "<small class=muted>and " << top.size() - shown << " more named mistakes</small>";
    return s.str();
}

// The histogram of total scores: whole-point bins when the maximum is small, else 20 bins.
std::string scoreHistogram(const std::vector<StudentTotal>& totals) {
    std::vector<const StudentTotal*> graded;
    double top = 0;
    for (const StudentTotal& t : totals)
        if (t.error.empty()) {
            graded.push_back(&t);
            top = std::max(top, t.maxScore);
        }
    if (graded.empty() || top <= 0) return "<p class=muted>no graded submission</p>";
    const bool whole = top <= 40 && top == std::floor(top);
    const size_t bins = whole ? size_t(top) + 1 : 20;
    const double binWidth = whole ? 1 : top / double(bins);
    std::vector<size_t> count(bins, 0);
    for (const StudentTotal* t : graded)
        ++count[std::min(bins - 1, size_t(std::max(0.0, std::floor(t->score / binWidth + 1e-9))))];
    const size_t most = *std::max_element(count.begin(), count.end());
    // Bars at most 60 px wide, so a short scale does not read as a wall; 20 px above the
    // tallest for its count.
    const double barW = std::min(60.0, 760.0 / double(bins));
    const double plotW = barW * double(bins), plotH = 200, left = 40, bottom = 36, barGap = 2,
                 margin = 20;
    std::ostringstream s;
    s << "<svg width=" << number(left + plotW + 10) << " height=" << number(margin + plotH + bottom)
      << " role=img>";
    // The count axis: a line at the largest count.
    s << "<line x1=" << number(left) << " x2=" << number(left + plotW) << " y1=" << number(margin)
      << " y2=" << number(margin) << " stroke=#333 /><text x=" << number(left - 6)
      << " y=" << number(margin + 4) << " fill=#999 font-size=11 text-anchor=end>" << most
      << "</text><text x=" << number(left - 6) << " y=" << number(margin + plotH)
      << " fill=#999 font-size=11 text-anchor=end>0</text>";
    for (size_t b = 0; b < bins; ++b) {
        const double h = plotH * double(count[b]) / double(std::max<size_t>(most, 1));
        const double x = left + double(b) * barW;
        const std::string range =
            whole ? number(double(b))
                  : number(double(b) * binWidth) + "–" + number(double(b + 1) * binWidth);
        s << "<g><title>score " << range << ": " << count[b]
          << " submissions</title><rect x=" << number(x + barGap / 2)
          << " y=" << number(margin + plotH - h)
          << " width=" << number(std::max(barW - barGap, 1.0)) << " height=" << number(h)
          << " fill=#5b8dd9 />";
        if (count[b])
            s << "<text x=" << number(x + barW / 2) << " y=" << number(margin + plotH - h - 3)
              << " fill=#ddd font-size=11 text-anchor=middle>" << count[b] << "</text>";
        s << "</g>";
        // Labels under every bin when they fit, else every fifth.
        if (bins <= 25 || b % 5 == 0 || b + 1 == bins)
            s << "<text x=" << number(x + (whole ? barW / 2 : 0))
              << " y=" << number(margin + plotH + 14)
              << " fill=#999 font-size=11 text-anchor=" << (whole ? "middle" : "start") << ">"
              << number(whole ? double(b) : double(b) * binWidth) << "</text>";
    }
    s << "<line x1=" << number(left) << " x2=" << number(left + plotW)
      << " y1=" << number(margin + plotH) << " y2=" << number(margin + plotH)
      << " stroke=#777 /><text x=" << number(left + plotW / 2)
      << " y=" << number(margin + plotH + 32)
      << " fill=#999 font-size=12 text-anchor=middle>total score (of " << formatPoints(top)
      << ")</text></svg>";
    return s.str();
}

}  // namespace

std::vector<ClassRow> classRows(const std::string& student, const json& report) {
    std::vector<ClassRow> rows;
    for (const json& m : report.at("modules")) {
        ClassRow r;
        r.student = student;
        r.step = m.at("id").get<std::string>();
        r.status = m.at("status").get<GradeStatus>();
        r.score = m.at("score").get<double>();
        r.maxScore = m.at("max_score").get<double>();
        r.mistake = m.value("mistake", "");
        r.namedBy = m.value("named_by", NamedBy::Nothing);
        r.group = m.value("mistake_group", "");
        rows.push_back(std::move(r));
    }
    return rows;
}

std::string classCsv(const std::vector<ClassRow>& rows) {
    std::string text = std::string(kClassHeader) + "\n";
    for (const ClassRow& r : rows)
        text += csvField(r.student) + "," + csvField(r.step) + "," +
                csvField(std::string(nameOf(r.status))) + "," + formatPoints(r.score) + "," +
                formatPoints(r.maxScore) + "," + csvField(r.mistake) + "," +
                csvField(std::string(nameOf(r.namedBy))) + "," + csvField(r.group) + "\n";
    return text;
}

std::vector<ClassRow> readClassCsv(const fs::path& file) {
    std::vector<ClassRow> rows;
    for (const auto& [line, f] : readTable(file, kClassHeader))
        rows.push_back({f[0], f[1], parseName<GradeStatus>(f[2], file, line, "status"),
                        parseNumber(f[3], file, line, "score"),
                        parseNumber(f[4], file, line, "max_score"), f[5],
                        parseName<NamedBy>(f[6], file, line, "named_by"), f[7]});
    return rows;
}

std::string summaryCsv(const std::vector<StudentTotal>& totals) {
    std::string text = std::string(kSummaryHeader) + "\n";
    for (const StudentTotal& t : totals)
        text += csvField(t.student) + "," + formatPoints(t.score) + "," + formatPoints(t.maxScore) +
                "," + number(t.seconds) + "," + csvField(t.error) + "\n";
    return text;
}

std::vector<StudentTotal> readSummaryCsv(const fs::path& file) {
    std::vector<StudentTotal> totals;
    for (const auto& [line, f] : readTable(file, kSummaryHeader))
        totals.push_back({f[0], parseNumber(f[1], file, line, "score"),
                          parseNumber(f[2], file, line, "max_score"),
                          parseNumber(f[3], file, line, "seconds"), f[4]});
    return totals;
}

std::string classHtml(const std::vector<ClassRow>& rows, const std::vector<StudentTotal>& totals,
                      const std::string& title) {
    size_t errors = 0;
    double sum = 0, top = 0;
    for (const StudentTotal& t : totals) {
        if (!t.error.empty()) {
            ++errors;
            continue;
        }
        sum = addPoints(sum, t.score);
        top = std::max(top, t.maxScore);
    }
    const size_t graded = totals.size() - errors;
    std::ostringstream h;
    // The look of the student's report (course/autograder.cpp writeHtml): same colours and type.
    h << "<!doctype html><meta charset=utf-8><title>pbrlab class report</title><style>"
         "body{font-family:sans-serif;background:#1c1d21;color:#ddd;max-width:1200px;margin:auto;"
         "padding:0 16px}"
         "table{border-collapse:collapse}td,th{padding:6px;border-bottom:1px solid #333;"
         "vertical-align:top;text-align:left}th{color:#999;font-weight:normal}"
         ".muted{color:#999}.count{display:inline-block;margin-right:10px;white-space:nowrap}"
         ".dot{display:inline-block;width:9px;height:9px;border-radius:2px;margin-right:4px}"
         "table.mistakes td{border:0;padding:1px 6px 1px 0;font-size:13px}td.bar{width:230px}"
         "</style>"
      << "<h1>pbrlab class report: " << escape(title) << "</h1><p>" << graded
      << " submissions graded";
    if (graded)
        h << ", mean score " << formatPoints(sum / double(graded)) << " / " << formatPoints(top);
    h << "; " << byStep(rows).size() << " steps.";
    if (errors) h << " <span style=color:#f85>" << errors << " could not be graded</span> (below).";
    h << "</p><h2>Steps</h2><table><tr><th>step</th><th>passed</th><th>outcomes</th>"
      << "<th>most common named mistakes (share of the class)</th></tr>\n";
    for (const StepRows& s : byStep(rows)) {
        std::map<GradeStatus, size_t> statuses;
        for (const ClassRow* r : s.rows) ++statuses[r->status];
        h << "<tr><td>" << escape(s.step) << "</td><td>"
          << passBar(statuses[GradeStatus::Passed], s.rows.size()) << "<br><small class=muted>"
          << statuses[GradeStatus::Passed] << " of " << s.rows.size() << "</small></td><td>";
        for (const GradeStatus status :
             {GradeStatus::Passed, GradeStatus::Failed, GradeStatus::CompileError,
              GradeStatus::Timeout, GradeStatus::Crashed, GradeStatus::Missing})
            if (statuses.count(status) && statuses[status])
                h << "<span class=count><span class=dot style=background:" << statusColour(status)
                  << "></span>" << status << " " << statuses[status] << "</span> ";
        h << "</td><td>" << mistakeChart(s.rows) << "</td></tr>\n";
    }
    h << "</table><h2>Total scores</h2>" << scoreHistogram(totals);
    if (errors) {
        h << "<h2>Not graded</h2><ul>";
        for (const StudentTotal& t : totals)
            if (!t.error.empty())
                h << "<li>" << escape(t.student) << ": <small>" << escape(t.error)
                  << "</small></li>";
        h << "</ul>";
    }
    h << "<p class=muted><small>Rows: class.csv (one per student and step); totals: "
         "summary.csv.</small></p>";
    return h.str();
}

void writeClassReport(std::vector<ClassRow> rows, std::vector<StudentTotal> totals,
                      const fs::path& folder, const std::string& title) {
    std::stable_sort(rows.begin(), rows.end(),
                     [](const ClassRow& a, const ClassRow& b) { return a.student < b.student; });
    std::sort(totals.begin(), totals.end(),
              [](const StudentTotal& a, const StudentTotal& b) { return a.student < b.student; });
    writeFileAtomically(folder / "class.csv", classCsv(rows));
    writeFileAtomically(folder / "summary.csv", summaryCsv(totals));
    writeFileAtomically(folder / "class.html", classHtml(rows, totals, title));
}

}  // namespace pbrlab
