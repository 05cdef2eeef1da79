#include "triage/watch.h"

#include <gtest/gtest.h>

namespace ra::triage {
namespace {

TEST(ChangedNightNote, EveryChangeAttributed) {
  EXPECT_EQ(changed_night_note(40, 40, 2), "40 primitives changed, 2 culprit commit(s)");
  EXPECT_EQ(changed_night_note(1, 1, 1), "1 primitive changed, 1 culprit commit(s)");
}

// A night past --max-primitives attributes a sample: the note must not call the sample the change.
TEST(ChangedNightNote, ASampleIsNotCalledTheWholeChange) {
  EXPECT_EQ(changed_night_note(2005, 2000, 1),
            "2005 primitives changed (2000 of them attributed: a sample, see the bisection's report), "
            "1 culprit commit(s)");
}

}  // namespace
}  // namespace ra::triage
