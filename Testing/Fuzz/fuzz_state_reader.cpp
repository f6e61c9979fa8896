// libFuzzer target for the state file reader (Documentation/StateFile.md, "Robustness").
// Any input must end in a model or a dem::InputError / dem::FileError: a crash, a sanitizer
// report, a hang or any other exception (std::bad_alloc from a huge size, ...) is a bug.
//
// ROCKDEM_FUZZ_NO_CHECKSUM=1 turns the checksum check off (StateReadOptions), so that
// mutated files reach the HDF5 layer instead of stopping at the checksum; see
// scripts/fuzz_state_reader.sh.
#include "dem/Errors.h"
#include "dem/StateFile.h"

#include <cstddef>
#include <cstdint>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  static const bool noChecksum = std::getenv("ROCKDEM_FUZZ_NO_CHECKSUM") != nullptr;
  dem::StateReadOptions options;
  options.verifyChecksum = !noChecksum;
  try {
    const dem::Model model = dem::readStateFromMemory(data, size, options, "fuzz input");
    (void)model;
  } catch (const dem::InputError&) {
    // A rejected file: the expected outcome for almost every input.
  }
  return 0;
}
