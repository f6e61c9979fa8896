// Input validation messages: parameter name, value with unit, valid range; NaN rejected.
#include "dem/Errors.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace {

/// The message of the InputError that `f` throws ("" if it throws nothing).
template <class F>
std::string messageOf(F&& f)
{
  try {
    f();
  } catch (const dem::InputError& e) {
    return e.what();
  }
  return "";
}

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

} // namespace

TEST(Errors, FormatValueUsesSixSignificantDigits)
{
  EXPECT_EQ(dem::formatValue(1.2), "1.2");
  EXPECT_EQ(dem::formatValue(0.1 + 0.2), "0.3");
  EXPECT_EQ(dem::formatValue(0.002), "0.002");
  EXPECT_EQ(dem::formatValue(1e15), "1e+15");
  EXPECT_EQ(dem::formatValue(123456789.0), "1.23457e+08");
  EXPECT_EQ(dem::formatValue(kNaN).find("nan") != std::string::npos, true);
}

TEST(Errors, InputErrorIsAnInvalidArgument)
{
  EXPECT_THROW(dem::requirePositive("Density", -1.0), std::invalid_argument);
}

TEST(Errors, OpenRangeMessageMatchesTheDocumentedExample)
{
  const std::string m = messageOf([] { dem::requireInOpenRange("Target Porosity", 1.2, 0.0, 1.0); });
  EXPECT_EQ(m, "Target Porosity = 1.2 is out of range: valid range is (0, 1).");
}

TEST(Errors, OpenRangeRejectsItsEndsAndNonFiniteValues)
{
  EXPECT_NO_THROW(dem::requireInOpenRange("Target Porosity", 0.4, 0.0, 1.0));
  for (double bad : { 0.0, 1.0, -0.1, kNaN, kInf, -kInf }) {
    EXPECT_THROW(dem::requireInOpenRange("Target Porosity", bad, 0.0, 1.0), dem::InputError)
      << bad;
  }
}

TEST(Errors, ClosedRangeAcceptsItsEnds)
{
  EXPECT_NO_THROW(dem::requireInRange("Restitution", 0.0, 0.0, 1.0));
  EXPECT_NO_THROW(dem::requireInRange("Restitution", 1.0, 0.0, 1.0));
  const std::string m = messageOf([] { dem::requireInRange("Restitution", 1.5, 0.0, 1.0); });
  EXPECT_NE(m.find("Restitution = 1.5"), std::string::npos) << m;
  EXPECT_NE(m.find("[0, 1]"), std::string::npos) << m;
  EXPECT_THROW(dem::requireInRange("Restitution", kNaN, 0.0, 1.0), dem::InputError);
}

TEST(Errors, MessagesCarryTheUnit)
{
  const std::string m = messageOf([] { dem::requirePositive("X Dimension", -0.5, "m"); });
  EXPECT_EQ(m, "X Dimension = -0.5 m is out of range: valid range is (0, inf) m.");
}

TEST(Errors, PositiveAndNonNegative)
{
  EXPECT_THROW(dem::requirePositive("Density", 0.0, "kg/m^3"), dem::InputError);
  EXPECT_THROW(dem::requirePositive("Density", kNaN, "kg/m^3"), dem::InputError);
  EXPECT_THROW(dem::requirePositive("Density", kInf, "kg/m^3"), dem::InputError);
  EXPECT_NO_THROW(dem::requirePositive("Density", 2650.0, "kg/m^3"));
  EXPECT_NO_THROW(dem::requireNonNegative("Friction", 0.0));
  EXPECT_THROW(dem::requireNonNegative("Friction", -1e-9), dem::InputError);
  EXPECT_THROW(dem::requireNonNegative("Friction", kNaN), dem::InputError);
  const std::string m = messageOf([] { dem::requireNonNegative("Friction", -2.0); });
  EXPECT_NE(m.find("Friction = -2"), std::string::npos) << m;
  EXPECT_NE(m.find("[0, inf)"), std::string::npos) << m;
}

TEST(Errors, FiniteRejectsNaNAndInfinity)
{
  EXPECT_NO_THROW(dem::requireFinite("Origin X", -1e6, "m"));
  const std::string m = messageOf([] { dem::requireFinite("Origin X", kNaN, "m"); });
  EXPECT_NE(m.find("Origin X = "), std::string::npos) << m;
  EXPECT_NE(m.find("nan"), std::string::npos) << m;
  EXPECT_THROW(dem::requireFinite("Origin X", -kInf, "m"), dem::InputError);
}
