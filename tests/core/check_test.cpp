// LH_DCHECK: on in debug builds (a failed check aborts, naming the condition), compiled out of
// release builds (the condition is not even evaluated).
#include "core/check.h"

#include <gtest/gtest.h>

namespace lh {
namespace {

TEST(DebugCheck, AFailedCheckAbortsWithItsConditionInDebugBuildsOnly) {
    int evaluations = 0;
    LH_DCHECK(++evaluations > 0);
#ifndef NDEBUG
    EXPECT_EQ(evaluations, 1);
    EXPECT_DEATH(LH_DCHECK(evaluations == 2), "internal check failed: evaluations == 2");
#else
    EXPECT_EQ(evaluations, 0);
    LH_DCHECK(evaluations == 2);  // false, but not checked: nothing happens
    GTEST_SUCCEED() << "release build: LH_DCHECK is compiled out";
#endif
}

}  // namespace
}  // namespace lh
