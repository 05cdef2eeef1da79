// Sealed JSON (json_seal.h): a document survives its own writing and reading, and one changed
// digit, a lost member or a missing seal is found.
#include "util/json_seal.h"

#include <gtest/gtest.h>

namespace ra::util {
namespace {

TEST(JsonSeal, ADocumentReadBackKeepsItsSealAndAnyChangeBreaksIt) {
  nlohmann::json doc = {{"b", 0.1 + 0.2},      {"a", -0.0},           {"n", 18446744073709551615ull},
                        {"s", "line\n\"é\""}, {"list", {1, -2, 3.5e-300}}, {"o", {{"k", nullptr}}}};
  const nlohmann::json written = sealed(doc);
  const nlohmann::json read = nlohmann::json::parse(written.dump(2));
  EXPECT_EQ(seal_problem(read), "");
  nlohmann::json flipped = read;
  flipped["n"] = 18446744073709551614ull;
  EXPECT_NE(seal_problem(flipped), "");
  nlohmann::json lost = read;
  lost["o"].erase("k");
  EXPECT_NE(seal_problem(lost), "");
  nlohmann::json unsealed = read;
  unsealed.erase("seal");
  EXPECT_EQ(seal_problem(unsealed), "'seal' is missing");
}

}  // namespace
}  // namespace ra::util
