// RockDEM engine: the state file (reference guide "Saving and reopening";
// Documentation/StateFile.md has the schema).
//
// A state file (extension .rdem) holds a whole dem::Model: particles, contacts with
// their slip and rolling history, bonds with their state, walls with their servo state,
// the load-test state machine with its history, the clock, the random state, the id
// counter and every model parameter. A model read back steps bit for bit as the saved
// one would have: doubles are stored as native IEEE 754 binary64, integers exactly.
//
// Layout: an HDF5 1.10 file with a 512-byte user block. The user block holds the
// RockDEM header: magic "RockDEM state\0", format version, payload length and an FNV-1a
// 64-bit checksum of the HDF5 part (bytes 512 to the end). The reader checks the header
// before HDF5 sees a byte, so a truncated or damaged file is rejected with a clear
// message instead of reaching HDF5's parser (which is not hardened against damaged
// files). h5dump and h5py read the file as any HDF5 file (user blocks are standard).
//
// Files are written to a temporary name in the target's directory, flushed to disk and
// renamed over the target: a crash never leaves a half-written state file, and a failed
// write leaves the previous file as it was.
//
// SI units throughout.
#pragma once

#include "dem/Errors.h"
#include "dem/LoadTest.h"
#include "dem/Model.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace dem {

/// The format version this build writes. Bump it for any change a reader of the
/// previous version would misread (Documentation/StateFile.md, "Version policy").
constexpr std::uint32_t StateFormatVersion = 1;
/// Versions this build reads.
const std::vector<std::uint32_t>& supportedStateVersions();
/// Size of the RockDEM header (the HDF5 user block), bytes.
constexpr std::size_t StateHeaderBytes = 512;
/// The magic bytes at the start of a state file (14 bytes including the NUL).
constexpr char StateMagic[] = "RockDEM state";
/// The conventional extension, with the dot.
constexpr const char* StateFileExtension = ".rdem";

/// Options of the reader. Tests only: the fuzz target turns the checksum off to reach
/// the HDF5 layer with damaged files.
struct StateReadOptions {
  bool verifyChecksum = true;
};

/// Writes the model to `path` atomically (temporary file in the same directory, fsync,
/// rename). Throws FileError when the file cannot be written (the target is then left
/// as it was) and InputError when the model is inconsistent (vectors of different
/// lengths).
void writeState(const Model& model, const std::string& path);

/// The complete state file (header + HDF5) as bytes, as writeState writes it.
std::vector<unsigned char> writeStateToMemory(const Model& model);

/// Reads a state file. Throws FileError naming the file and what is wrong: missing or
/// unreadable, not a RockDEM state file, an unknown format version, truncated, corrupt
/// (checksum), a missing dataset or one of the wrong type, rank or size, or a value out
/// of range (InputError naming the parameter).
Model readState(const std::string& path, const StateReadOptions& options = {});

/// Reads a state file image in memory (`name` is used in messages). Never crashes on
/// any input; throws FileError / InputError as readState.
Model readStateFromMemory(const void* data, std::size_t size, const StateReadOptions& options = {},
                          const std::string& name = "(memory)");

/// The FNV-1a 64-bit hash of a byte range (the checksum of the state file payload).
std::uint64_t fnv1a64(const void* data, std::size_t size);

/// Recomputes and stores the checksum and payload length of a state file image in
/// memory (tests use it to build files that pass the header checks but are wrong inside).
void resealStateImage(std::vector<unsigned char>& image);

/// The path of the test history CSV beside a state file: "run.rdem" -> "run.history.csv"
/// (the extension, if any, is replaced).
std::string historyPathFor(const std::string& statePath);

/// Writes the test history as CSV (quoted header of historyColumns(), full precision),
/// atomically. Throws FileError.
void writeHistoryCSV(const LoadTestState& test, const std::string& path);

/// The text writeHistoryCSV writes.
std::string historyCSVText(const LoadTestState& test);

/// Writes the state file and the test history CSV beside it (historyPathFor) as a pair.
/// Both are written to temporaries and flushed to disk before either is renamed, the state
/// file first; a model without history removes the CSV an earlier write left beside it (it
/// would contradict the state). The state file is the truth: a crash between the two
/// renames leaves the CSV one write behind, which syncHistoryCSV and the next write repair.
/// Throws FileError (the state file is then as before unless the message says otherwise).
void writeStateAndHistory(const Model& model, const std::string& path);

/// What syncHistoryCSV did to the history CSV beside a state file.
enum class HistorySync {
  InStep,    ///< absent, or already exactly the state's history: nothing done
  Rewritten, ///< it differed (rows of another write): rewritten from the state
  Removed,   ///< the state has no history: the CSV of another write was removed
};
struct HistorySyncReport {
  HistorySync action = HistorySync::InStep;
  std::string path;          ///< the CSV's path
  std::size_t fileRows = 0;  ///< data rows the CSV had before (0 when absent)
  std::size_t stateRows = 0; ///< history rows in the state
};

/// Makes the history CSV beside `statePath` agree with the state's history (the state file
/// is the truth): a CSV that differs is rewritten from it (atomically), one beside a state
/// without history is removed, an absent one is left absent. Throws FileError when the
/// CSV cannot be read, rewritten or removed.
HistorySyncReport syncHistoryCSV(const LoadTestState& test, const std::string& statePath);

/// Writes `bytes` to `path` atomically (temporary file beside it, fsync, rename).
/// Throws FileError; on failure the target is left as it was and no temporary remains.
/// Temporaries of the same target left by a process that no longer exists (killed while
/// writing: "<path>.tmp-<pid>-<n>") are removed first.
void writeFileAtomically(const std::string& path, const void* bytes, std::size_t size);

namespace test_hooks {
/// Tests only: when >= 0, writeFileAtomically fails (as on a full disk) once it has
/// written this many bytes of the temporary file. -1 (the default) = off.
extern long long failAtomicWriteAfterBytes;
} // namespace test_hooks

} // namespace dem
