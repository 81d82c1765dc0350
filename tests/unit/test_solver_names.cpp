// Names the scene uses for solver options, translated by one table each.
#include <gtest/gtest.h>

#include <string>

#include "structure/integrate/FictitiousMass.hpp"
#include "structure/model/Error.hpp"

using namespace fsi::structure;

TEST(FictitiousMassRuleNames, EveryNameRoundTripsAndAnUnknownOneListsThem) {
  ASSERT_EQ(fictitiousMassRuleNames().size(), 3u);
  for (const std::string& name : fictitiousMassRuleNames())
    EXPECT_EQ(toString(fictitiousMassRuleFromName(name)), name);
  EXPECT_EQ(fictitiousMassRuleFromName("stress"), FictitiousMassRule::StressBound);
  try {
    fictitiousMassRuleFromName("gershgorin");
    FAIL() << "no error for an unknown rule";
  } catch (const fsi::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("valid: gerschgorin, stress, rezaiee_pajand"), std::string::npos)
        << e.what();
  }
}
