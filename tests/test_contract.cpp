#include <gtest/gtest.h>

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
