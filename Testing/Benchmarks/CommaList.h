// The benchmarks' comma-separated command-line lists ("--sizes 1000,10000,100000").
#pragma once

#include <sstream>
#include <string>
#include <vector>

namespace rockdem_bench {

/// The items of a comma-separated list, each read as a T (empty items are skipped).
template <class T>
std::vector<T> parseList(const std::string& text)
{
  std::vector<T> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (!item.empty()) {
      std::stringstream is(item);
      T value{};
      is >> value;
      out.push_back(value);
    }
  }
  return out;
}

} // namespace rockdem_bench
