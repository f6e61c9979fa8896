#include "dem/SizeClass.h"

#include <algorithm>
#include <cmath>

namespace dem {

int sizeClassOf(double radius, double smallestRadius)
{
  if (!(radius > smallestRadius)) {
    return 0;
  }
  // floor(log2(ratio)) via frexp: exact at the powers of two that bound the classes.
  int exponent = 0;
  std::frexp(radius / smallestRadius, &exponent); // ratio = m * 2^exponent, m in [0.5, 1)
  return std::min(exponent - 1, MaxSizeClasses - 1);
}

std::vector<std::uint8_t> sizeClasses(const std::vector<double>& radius)
{
  std::vector<std::uint8_t> cls(radius.size(), 0);
  if (radius.empty()) {
    return cls;
  }
  const double smallest = *std::min_element(radius.begin(), radius.end());
  for (std::size_t i = 0; i < radius.size(); ++i) {
    cls[i] = static_cast<std::uint8_t>(sizeClassOf(radius[i], smallest));
  }
  return cls;
}

} // namespace dem
