// RockDEM engine: input validation errors.
// Every invalid input raises dem::InputError whose message names the parameter
// (by its GUI label), the offending value with its SI unit, and the valid range.
#pragma once

#include <stdexcept>
#include <string>

namespace dem {

/// Raised for invalid user input. what() is a complete sentence meant for the user.
class InputError : public std::invalid_argument {
public:
  explicit InputError(const std::string& message) : std::invalid_argument(message) {}
};

/// Raised for a file that cannot be read or written, or whose content is not what it
/// should be (a state file that is truncated, corrupt, of an unknown version, ...).
/// what() names the file, what is wrong, the value found and what was expected. A
/// FileError is an InputError, so code that reports input errors reports it too.
class FileError : public InputError {
public:
  explicit FileError(const std::string& message) : InputError(message) {}
};

/// Formats a value the way error messages show it (shortest round-trip-ish, %.6g).
std::string formatValue(double value);

/// Throws InputError unless lo <= value <= hi (closed range) and value is finite.
/// Example message: "Target Porosity = 1.2 is out of range: valid range is (0, 1)."
void requireInRange(const std::string& parameter, double value, double lo, double hi,
                    const std::string& unit = "");
/// Throws InputError unless lo < value < hi (open range) and value is finite.
void requireInOpenRange(const std::string& parameter, double value, double lo, double hi,
                        const std::string& unit = "");
/// Throws InputError unless value > 0 and finite.
void requirePositive(const std::string& parameter, double value, const std::string& unit = "");
/// Throws InputError unless value >= 0 and finite.
void requireNonNegative(const std::string& parameter, double value, const std::string& unit = "");
/// Throws InputError unless value is finite (rejects NaN and infinities).
void requireFinite(const std::string& parameter, double value, const std::string& unit = "");

} // namespace dem
