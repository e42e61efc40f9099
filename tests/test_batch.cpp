// A class graded at once (grade --batch): the class rows name each student's mistakes, the page
// shows them, a re-run grades only what changed, and two shards merged equal one run.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <set>
#include <tuple>

#include "course/batch.h"
#include "course/class_report.h"
#include "course/kit.h"
#include "grading/error_patterns.h"
#include "test_support.h"
#include "util/error.h"

using namespace pbrlab;
namespace fs = std::filesystem;

namespace {

// A small class from the kit with solutions and the planted mistakes of labs/<id>/mistakes:
// alice correct, bob ndf's typical mistake, carol the ndf and fresnel mistakes, dave a fresnel
// that does not compile, erin no fresnel at all.
struct SmallClass {
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
    test::TempDir dir;
    fs::path batch = dir.path / "class";

    SmallClass() {
        const fs::path kit = dir.path / "kit";
        writeKit(modules, {kit, true, "", false});
        for (const char* student : {"alice", "bob", "carol", "dave", "erin"}) {
            fs::create_directories(batch / student);
            for (const char* step : {"ndf", "fresnel"})
                fs::copy_file(kit / (std::string(step) + ".glsl"),
                              batch / student / (std::string(step) + ".glsl"));
        }
        plant("bob", "ndf", "ndf/mistakes/alpha_is_roughness.glsl");
        plant("carol", "ndf", "ndf/mistakes/alpha_is_roughness.glsl");
        plant("carol", "fresnel", "fresnel/mistakes/pow4.glsl");
        std::ofstream(batch / "dave" / "fresnel.glsl") << "vec3 fresnelSchlick(\n";
        fs::remove(batch / "erin" / "fresnel.glsl");
    }
    void plant(const std::string& student, const std::string& step, const std::string& mistake) {
        fs::copy_file(paths.labs() / mistake, batch / student / (step + ".glsl"),
                      fs::copy_options::overwrite_existing);
    }
    BatchOptions options(const fs::path& out, int shard = 0, int shards = 1) const {
        BatchOptions o;
        o.batch = batch;
        o.out = out;
        o.grade.modules = {"ndf", "fresnel"};
        o.grade.timeoutSeconds = 300;
        o.shard = shard;
        o.shards = shards;
        o.progress = false;
        return o;
    }
};

std::string readText(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

const ClassRow& row(const std::vector<ClassRow>& rows, const std::string& student,
                    const std::string& step) {
    for (const ClassRow& r : rows)
        if (r.student == student && r.step == step) return r;
    throw std::runtime_error("no row for " + student + " " + step);
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

using RowKey = std::tuple<std::string, std::string, GradeStatus, double, std::string>;
std::set<RowKey> rowSet(const std::vector<ClassRow>& rows) {
    std::set<RowKey> set;
    for (const ClassRow& r : rows) set.insert({r.student, r.step, r.status, r.score, r.mistake});
    return set;
}

}  // namespace

TEST(Batch, TheClassRowsNameEachStudentsMistakesAndThePageShowsThem) {
    SmallClass c;
    const fs::path out = c.dir.path / "out";
    BatchSummary s = gradeBatch(c.modules, c.paths, c.options(out));
    EXPECT_EQ(s.students, 5u);
    EXPECT_EQ(s.graded, 5u);
    EXPECT_EQ(s.errors, 0u);
    const auto rows = readClassCsv(out / "class.csv");
    ASSERT_EQ(rows.size(), 10u);
    EXPECT_EQ(row(rows, "alice", "ndf").status, GradeStatus::Passed);
    EXPECT_EQ(row(rows, "alice", "fresnel").status, GradeStatus::Passed);
    EXPECT_EQ(row(rows, "alice", "ndf").mistake, "");
    EXPECT_EQ(row(rows, "bob", "ndf").status, GradeStatus::Failed);
    EXPECT_EQ(row(rows, "bob", "ndf").score, 0);
    EXPECT_TRUE(contains(row(rows, "bob", "ndf").mistake, "alpha = roughness"))
        << row(rows, "bob", "ndf").mistake;
    // The term fit names it first (alpha = roughness^1), exactly; the typical mistake agrees.
    EXPECT_EQ(row(rows, "bob", "ndf").namedBy, NamedBy::Pattern);
    EXPECT_EQ(row(rows, "bob", "fresnel").status, GradeStatus::Passed);
    EXPECT_EQ(row(rows, "bob", "fresnel").score, 1);
    EXPECT_TRUE(contains(row(rows, "carol", "ndf").mistake, "alpha = roughness"));
    EXPECT_TRUE(contains(row(rows, "carol", "fresnel").mistake, "^4 instead of ^5"))
        << row(rows, "carol", "fresnel").mistake;
    EXPECT_EQ(row(rows, "dave", "fresnel").status, GradeStatus::CompileError);
    EXPECT_EQ(row(rows, "erin", "fresnel").status, GradeStatus::Missing);
    EXPECT_EQ(row(rows, "erin", "ndf").status, GradeStatus::Passed);

    const auto totals = readSummaryCsv(out / "summary.csv");
    ASSERT_EQ(totals.size(), 5u);
    EXPECT_EQ(totals[0].student, "alice");
    EXPECT_EQ(totals[0].score, 2);
    EXPECT_EQ(totals[2].student, "carol");
    EXPECT_EQ(totals[2].score, 0);

    const std::string html = readText(out / "class.html");
    // Each step's pass rate (ndf: alice, dave, erin of 5; fresnel: alice, bob of 5), the named
    // mistakes with their counts, and the histogram.
    EXPECT_TRUE(contains(html, "3 of 5")) << html;
    EXPECT_TRUE(contains(html, "2 of 5"));
    EXPECT_TRUE(contains(html, "alpha = roughness (perceptual roughness not squared)"));
    EXPECT_TRUE(contains(html, ">2 (40%)<"));  // bob and carol
    EXPECT_TRUE(contains(html, "(1 - cos)^4 instead of ^5"));
    EXPECT_TRUE(contains(html, "total score (of 2)"));
    EXPECT_FALSE(contains(html, "<script")) << "the page must open offline, without scripts";
    EXPECT_FALSE(contains(html, "http"));
}

TEST(Batch, ARerunGradesOnlyTheStudentsWhoseFilesChanged) {
    SmallClass c;
    const fs::path out = c.dir.path / "out";
    gradeBatch(c.modules, c.paths, c.options(out));
    const auto aliceBefore = fs::last_write_time(out / "alice" / "report.json");

    BatchSummary again = gradeBatch(c.modules, c.paths, c.options(out));
    EXPECT_EQ(again.graded, 0u);
    EXPECT_EQ(again.skipped, 5u);
    EXPECT_EQ(readClassCsv(out / "class.csv").size(), 10u);

    // Bob fixes ndf: only he is graded again, and his row says so.
    fs::copy_file(c.dir.path / "kit" / "ndf.glsl", c.batch / "bob" / "ndf.glsl",
                  fs::copy_options::overwrite_existing);
    BatchSummary fixed = gradeBatch(c.modules, c.paths, c.options(out));
    EXPECT_EQ(fixed.graded, 1u);
    EXPECT_EQ(fixed.skipped, 4u);
    EXPECT_EQ(row(readClassCsv(out / "class.csv"), "bob", "ndf").status, GradeStatus::Passed);
    EXPECT_EQ(fs::last_write_time(out / "alice" / "report.json"), aliceBefore);

    // Other settings (here the seed) are other grades: everyone again.
    BatchOptions seeded = c.options(out);
    seeded.grade.settings.seed = 7;
    EXPECT_EQ(gradeBatch(c.modules, c.paths, seeded).graded, 5u);
}

TEST(Batch, TwoShardsMergedEqualOneRun) {
    SmallClass c;
    gradeBatch(c.modules, c.paths, c.options(c.dir.path / "whole"));
    size_t inShards = 0;
    for (int shard = 0; shard < 2; ++shard) {
        const BatchSummary s =
            gradeBatch(c.modules, c.paths,
                       c.options(c.dir.path / ("shard" + std::to_string(shard)), shard, 2));
        EXPECT_GT(s.students, 0u) << "shard " << shard << " is empty: choose other names";
        inShards += s.students;
    }
    EXPECT_EQ(inShards, 5u);
    mergeBatches({c.dir.path / "shard0", c.dir.path / "shard1"}, c.dir.path / "merged");
    EXPECT_EQ(rowSet(readClassCsv(c.dir.path / "merged" / "class.csv")),
              rowSet(readClassCsv(c.dir.path / "whole" / "class.csv")));
    EXPECT_EQ(readSummaryCsv(c.dir.path / "merged" / "summary.csv").size(), 5u);
    EXPECT_TRUE(fs::exists(c.dir.path / "merged" / "class.html"));

    // The same shard twice, a missing shard, a shard of another split: errors, no report.
    EXPECT_THROW(mergeBatches({c.dir.path / "shard0", c.dir.path / "shard0"}, c.dir.path / "m2"),
                 Error);
    EXPECT_THROW(mergeBatches({c.dir.path / "shard0"}, c.dir.path / "m3"), Error);
    EXPECT_THROW(mergeBatches({c.dir.path / "shard0", c.dir.path / "whole"}, c.dir.path / "m4"),
                 Error);
    EXPECT_FALSE(fs::exists(c.dir.path / "m2" / "class.csv"));
}

TEST(Batch, AShardIsIOfNAndNothingElse) {
    EXPECT_EQ(parseShard("1/4"), std::make_pair(1, 4));
    for (const char* bad : {"4/4", "-1/2", "1", "1/0", "1/2x", "a/b"})
        EXPECT_THROW(parseShard(bad), Error) << bad;
}

// The class chart counts a pattern-named mistake once whatever the student's figures:
// measured numbers become #, names with digits (F0) stay, the full stop after a number stays.
TEST(Feedback, APatternWithoutItsFiguresIsTheSameForEveryStudent) {
    const std::string a =
        "Your function is wrong only where N.V < 0.74 (1536 of 1584 points "
        "there): F0 is 4% too high, 1.5e-3 at worst.";
    const std::string b =
        "Your function is wrong only where N.V < 0.5 (12 of 1584 points "
        "there): F0 is 12% too high, 2e+1 at worst.";
    EXPECT_EQ(withoutFigures(a), withoutFigures(b));
    EXPECT_EQ(withoutFigures(a),
              "Your function is wrong only where N.V < # (# of # points there): "
              "F0 is #% too high, # at worst.");
    EXPECT_NE(withoutFigures("D is off by a factor PI."),
              withoutFigures("G is off by a factor PI."));
    EXPECT_EQ(withoutFigures("k = r^2 / 8 at step 3."), "k = r^# / # at step #.");
}
