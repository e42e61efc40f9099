#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <set>

#include "pbrlab/contract.h"

using namespace pbrlab;

TEST(Contract, TwentyOneStepsInOrderWithUniqueIds) {
    const auto& steps = contractSteps();
    ASSERT_EQ(steps.size(), 21u);
    std::set<std::string> ids;
    for (size_t i = 0; i < steps.size(); ++i) {
        EXPECT_EQ(steps[i].step, int(i + 1));
        EXPECT_TRUE(ids.insert(steps[i].id).second) << steps[i].id;
        EXPECT_EQ(steps[i].lab, i < 14 ? "direct" : "ibl");
        for (const auto& c : steps[i].calls) {
            const ContractStep* callee = findContractStep(c);
            ASSERT_NE(callee, nullptr) << c;
            EXPECT_LT(callee->step, steps[i].step) << "files are concatenated in step order";
        }
    }
    EXPECT_EQ(findContractStep("ndotl")->folder(), "04-ndotl");
}

TEST(Contract, ClosureHoldsEarlierStepsOfTheLabAndWhatTheyCall) {
    std::vector<std::string> ids;
    for (auto* s : contractClosure("ndotl", {})) ids.push_back(s->id);
    EXPECT_EQ(ids, (std::vector<std::string>{"albedo", "radiance", "halfway", "ndotl"}));
    ids.clear();
    for (auto* s : contractClosure("split_sum", {})) ids.push_back(s->id);
    // IBL steps pull in only the direct-lab functions they call.
    EXPECT_EQ(std::count(ids.begin(), ids.end(), "f0"), 1);
    EXPECT_EQ(std::count(ids.begin(), ids.end(), "reflectance"), 0);
}

// docs/design.md carries the contract students write against: each row must say what the
// host's contract says (number, id, signature), so the document cannot drift from the code.
TEST(Contract, TheDesignDocumentsTableIsTheHostsContract) {
    std::ifstream in(std::string(PBRLAB_SOURCE_DIR) + "/docs/design.md");
    ASSERT_TRUE(in) << "docs/design.md is missing";
    std::vector<std::string> rows;
    for (std::string line; std::getline(in, line);)
        if (line.size() > 3 && line[0] == '|' && std::isdigit(static_cast<unsigned char>(line[2])))
            rows.push_back(line);
    const auto& steps = contractSteps();
    ASSERT_EQ(rows.size(), steps.size());
    for (size_t i = 0; i < steps.size(); ++i) {
        const std::string start = "| " + std::to_string(steps[i].step) + " | " + steps[i].id +
                                  " | `" + steps[i].function + "`";
        EXPECT_EQ(rows[i].rfind(start, 0), 0u) << rows[i] << "\nexpected to start with " << start;
    }
}
