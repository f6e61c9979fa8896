// RockDEM engine: the container of a state file (dem/StateFile.h): the 512-byte RockDEM
// header in the HDF5 user block, its checksum, atomic file writes and the history CSV.
#include "StateFileInternal.h"

#include "dem/StateFile.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <sstream>

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

namespace dem {

namespace test_hooks {
long long failAtomicWriteAfterBytes = -1;
}

const std::vector<std::uint32_t>& supportedStateVersions()
{
  static const std::vector<std::uint32_t> versions = { 1 };
  return versions;
}

std::uint64_t fnv1a64(const void* data, std::size_t size)
{
  return state::fnv1a64Continue(0xcbf29ce484222325ull, data, size);
}

namespace state {

std::uint64_t fnv1a64Continue(std::uint64_t hash, const void* data, std::size_t size)
{
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    hash ^= bytes[i];
    hash *= 0x100000001b3ull;
  }
  return hash;
}

namespace {
void putU32(unsigned char* at, std::uint32_t v)
{
  for (int k = 0; k < 4; ++k) {
    at[k] = static_cast<unsigned char>(v >> (8 * k));
  }
}
void putU64(unsigned char* at, std::uint64_t v)
{
  for (int k = 0; k < 8; ++k) {
    at[k] = static_cast<unsigned char>(v >> (8 * k));
  }
}
std::uint32_t getU32(const unsigned char* at)
{
  std::uint32_t v = 0;
  for (int k = 0; k < 4; ++k) {
    v |= static_cast<std::uint32_t>(at[k]) << (8 * k);
  }
  return v;
}
std::uint64_t getU64(const unsigned char* at)
{
  std::uint64_t v = 0;
  for (int k = 0; k < 8; ++k) {
    v |= static_cast<std::uint64_t>(at[k]) << (8 * k);
  }
  return v;
}

std::string versionList()
{
  std::string s;
  for (std::uint32_t v : supportedStateVersions()) {
    s += (s.empty() ? "" : ", ") + std::to_string(v);
  }
  return s;
}
} // namespace

std::uint64_t imageChecksum(const unsigned char* image, std::size_t size)
{
  // Everything but the checksum field itself: the header (so that a damaged header is
  // caught too) and the HDF5 payload.
  std::uint64_t h = fnv1a64Continue(0xcbf29ce484222325ull, image, std::min<std::size_t>(size, HeaderChecksumOffset));
  if (size > HeaderChecksumOffset + 8) {
    h = fnv1a64Continue(h, image + HeaderChecksumOffset + 8, size - HeaderChecksumOffset - 8);
  }
  return h;
}

void sealImage(std::vector<unsigned char>& image, std::uint32_t version)
{
  if (image.size() < StateHeaderBytes) {
    throw FileError("State file image is " + std::to_string(image.size()) +
                    " bytes: shorter than its " + std::to_string(StateHeaderBytes) + "-byte header.");
  }
  unsigned char* h = image.data();
  std::memset(h, 0, StateHeaderBytes);
  std::memcpy(h, StateMagic, sizeof(StateMagic));
  putU32(h + HeaderVersionOffset, version);
  putU32(h + HeaderSizeOffset, static_cast<std::uint32_t>(StateHeaderBytes));
  putU64(h + HeaderPayloadOffset, image.size() - StateHeaderBytes);
  const char note[] = "RockDEM state file: HDF5 payload from byte 512, checksum FNV-1a 64. "
                      "Schema: Documentation/StateFile.md.\n";
  std::memcpy(h + HeaderNoteOffset, note, sizeof(note));
  putU64(h + HeaderChecksumOffset, imageChecksum(h, image.size()));
}

std::uint32_t checkImage(const unsigned char* image, std::size_t size, const std::string& name,
                         bool verifyChecksum)
{
  const std::string file = "State file '" + name + "'";
  const std::size_t magicSize = sizeof(StateMagic);
  if (size == 0) {
    throw FileError(file + " is empty (0 bytes): not a RockDEM state file.");
  }
  if (size < magicSize || std::memcmp(image, StateMagic, magicSize) != 0) {
    if (size < magicSize && std::memcmp(image, StateMagic, size) == 0) {
      throw FileError(file + " is truncated: " + std::to_string(size) + " bytes, shorter than the " +
                      std::to_string(StateHeaderBytes) + "-byte RockDEM header.");
    }
    const bool hdf5 = size >= 8 && std::memcmp(image, "\x89HDF\r\n\x1a\n", 8) == 0;
    throw FileError(file + " is not a RockDEM state file: it does not start with the magic bytes "
                    "\"RockDEM state\"" + (hdf5 ? " (it is a plain HDF5 file)." : "."));
  }
  if (size < StateHeaderBytes) {
    throw FileError(file + " is truncated: " + std::to_string(size) + " bytes, shorter than the " +
                    std::to_string(StateHeaderBytes) + "-byte RockDEM header.");
  }
  const std::uint32_t headerSize = getU32(image + HeaderSizeOffset);
  if (headerSize != StateHeaderBytes) {
    throw FileError(file + " has a header size of " + std::to_string(headerSize) + " bytes; expected " +
                    std::to_string(StateHeaderBytes) + " (the header is damaged).");
  }
  const std::uint64_t payload = getU64(image + HeaderPayloadOffset);
  const std::uint64_t actual = size - StateHeaderBytes;
  if (payload != actual) {
    if (actual < payload) {
      throw FileError(file + " is truncated: it has " + std::to_string(size) + " bytes; its header says " +
                      std::to_string(StateHeaderBytes + payload) + " (" + std::to_string(payload) +
                      " bytes of data after the " + std::to_string(StateHeaderBytes) + "-byte header).");
    }
    throw FileError(file + " has " + std::to_string(size) + " bytes; its header says " +
                    std::to_string(StateHeaderBytes + payload) + ": " + std::to_string(actual - payload) +
                    " unexpected bytes at the end (damaged or appended to).");
  }
  if (verifyChecksum) {
    const std::uint64_t stored = getU64(image + HeaderChecksumOffset);
    const std::uint64_t computed = imageChecksum(image, size);
    if (stored != computed) {
      std::ostringstream msg;
      msg << file << " is corrupt: its checksum is 0x" << std::hex << std::setw(16) << std::setfill('0')
          << computed << " but the header records 0x" << std::setw(16) << stored
          << " (the file was damaged after it was written).";
      throw FileError(msg.str());
    }
  }
  // The version is read only once the header is known to be intact: a damaged version
  // field is reported as damage (above), not as a file from a newer RockDEM. Bytes 0-39
  // (magic, version, header size, payload length, checksum) keep this layout in every
  // format version, so these checks come first for any version.
  const std::uint32_t version = getU32(image + HeaderVersionOffset);
  const auto& supported = supportedStateVersions();
  if (std::find(supported.begin(), supported.end(), version) == supported.end()) {
    throw FileError(file + " has format version " + std::to_string(version) +
                    ", which this build of RockDEM does not read: supported versions are " + versionList() +
                    (version > StateFormatVersion ? " (the file is from a newer RockDEM)." : "."));
  }
  return version;
}

} // namespace state

void resealStateImage(std::vector<unsigned char>& image)
{
  if (image.size() < StateHeaderBytes) {
    throw FileError("State file image is shorter than its header.");
  }
  const std::uint32_t version = state::getU32(image.data() + state::HeaderVersionOffset);
  state::sealImage(image, version);
}

std::string historyPathFor(const std::string& statePath)
{
  const std::size_t slash = statePath.find_last_of('/');
  const std::size_t dot = statePath.find_last_of('.');
  const bool hasExtension = dot != std::string::npos && (slash == std::string::npos || dot > slash + 1);
  return (hasExtension ? statePath.substr(0, dot) : statePath) + ".history.csv";
}

namespace {

std::string directoryOf(const std::string& path)
{
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
}

std::string fileNameOf(const std::string& path)
{
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

/// Whether `text` is one or more decimal digits.
bool allDigits(const std::string& text)
{
  return !text.empty() && std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

/// Removes the temporaries "<name>.tmp-<pid>-<n>" of `path` whose writing process no longer
/// exists (a process killed while writing leaves its temporary behind). Temporaries of a
/// live process, this one included, are left alone: they may be writes in progress.
void removeStaleTemporaries(const std::string& path)
{
  const std::string prefix = fileNameOf(path) + ".tmp-";
  DIR* dir = ::opendir(directoryOf(path).c_str());
  if (!dir) {
    return; // the write itself reports an unusable directory
  }
  std::vector<std::string> stale;
  while (const dirent* entry = ::readdir(dir)) {
    const std::string name = entry->d_name;
    if (name.compare(0, prefix.size(), prefix) != 0) {
      continue;
    }
    const std::string rest = name.substr(prefix.size()); // "<pid>-<n>"
    const std::size_t dash = rest.find('-');
    if (dash == std::string::npos || !allDigits(rest.substr(0, dash)) || !allDigits(rest.substr(dash + 1)) ||
        dash > 9) {
      continue;
    }
    const long pid = std::stol(rest.substr(0, dash));
    if (pid > 0 && pid != static_cast<long>(::getpid()) && ::kill(static_cast<pid_t>(pid), 0) != 0 &&
        errno == ESRCH) {
      stale.push_back(name);
    }
  }
  ::closedir(dir);
  for (const std::string& name : stale) {
    ::unlink((directoryOf(path) + "/" + name).c_str());
  }
}

/// Flushes a directory's entries to disk (makes a rename durable).
void syncDirectory(const std::string& path)
{
  const int dfd = ::open(directoryOf(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
}

/// A file written in full to a temporary beside its target and flushed to disk; commit()
/// renames it over the target. A PendingFile destroyed without commit() removes its
/// temporary, so a failed write leaves neither a half-written target nor a temporary.
class PendingFile {
public:
  PendingFile(const std::string& path, const void* bytes, std::size_t size)
    : path_(path)
  {
    if (path.empty()) {
      throw FileError("File Name is empty: give the path of the file to write.");
    }
    removeStaleTemporaries(path);
    static std::atomic<unsigned> counter{ 0 };
    temporary_ = path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    const int fd = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) {
      const int error = errno;
      temporary_.clear();
      throw FileError("Cannot write '" + path + "': creating a temporary file beside it failed (" +
                      std::strerror(error) + ").");
    }
    // A throwing constructor runs no destructor: every failure below removes the temporary.
    auto fail = [&](const std::string& what, int error) {
      ::close(fd);
      ::unlink(temporary_.c_str());
      throw FileError("Cannot write '" + path + "': " + what + " failed (" + std::strerror(error) +
                      "); the previous file, if any, is unchanged.");
    };
    const auto* p = static_cast<const unsigned char*>(bytes);
    std::size_t done = 0;
    while (done < size) {
      std::size_t chunk = std::min<std::size_t>(size - done, 1u << 24);
      if (test_hooks::failAtomicWriteAfterBytes >= 0) {
        const auto limit = static_cast<std::size_t>(test_hooks::failAtomicWriteAfterBytes);
        if (done >= limit) {
          fail("writing the temporary file (test fault injection)", ENOSPC);
        }
        chunk = std::min(chunk, limit - done);
      }
      const ssize_t written = ::write(fd, p + done, chunk);
      if (written < 0) {
        if (errno == EINTR) {
          continue;
        }
        fail("writing the temporary file", errno);
      }
      done += static_cast<std::size_t>(written);
    }
    if (::fsync(fd) != 0) {
      fail("flushing the temporary file to disk", errno);
    }
    if (::close(fd) != 0) {
      const int error = errno;
      ::unlink(temporary_.c_str());
      throw FileError("Cannot write '" + path + "': closing the temporary file failed (" +
                      std::strerror(error) + "); the previous file, if any, is unchanged.");
    }
  }
  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;
  ~PendingFile()
  {
    if (!temporary_.empty()) {
      ::unlink(temporary_.c_str());
    }
  }

  void commit()
  {
    if (std::rename(temporary_.c_str(), path_.c_str()) != 0) {
      throw FileError("Cannot write '" + path_ + "': renaming '" + temporary_ + "' over it failed (" +
                      std::strerror(errno) + "); the previous file, if any, is unchanged.");
    }
    temporary_.clear();
  }

private:
  std::string path_;
  std::string temporary_;
};

/// Whether a file exists (any kind).
bool exists(const std::string& path)
{
  struct stat info {};
  return ::stat(path.c_str(), &info) == 0;
}

/// The whole content of a file; false when it cannot be read.
bool readWhole(const std::string& path, std::string& text)
{
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    return false;
  }
  std::ostringstream content;
  content << in.rdbuf();
  text = content.str();
  return !in.bad();
}

} // namespace

void writeFileAtomically(const std::string& path, const void* bytes, std::size_t size)
{
  PendingFile file(path, bytes, size);
  file.commit();
  syncDirectory(path);
}

std::string historyCSVText(const LoadTestState& test)
{
  std::ostringstream out;
  const auto& names = historyColumns();
  for (std::size_t c = 0; c < names.size(); ++c) {
    out << (c ? "," : "") << '"' << names[c] << '"';
  }
  out << "\n" << std::setprecision(17);
  for (const auto& row : test.history) {
    for (std::size_t c = 0; c < row.size(); ++c) {
      out << (c ? "," : "") << row[c];
    }
    out << "\n";
  }
  return out.str();
}

void writeHistoryCSV(const LoadTestState& test, const std::string& path)
{
  const std::string text = historyCSVText(test);
  writeFileAtomically(path, text.data(), text.size());
}

void writeStateAndHistory(const Model& model, const std::string& path)
{
  const std::vector<unsigned char> image = writeStateToMemory(model);
  const std::string csvPath = historyPathFor(path);
  // Both files are complete on disk before either is renamed; the state file (the truth)
  // goes first. A crash between the two renames leaves the CSV one write behind, which
  // syncHistoryCSV (DEM State Reader) and the next write repair.
  PendingFile state(path, image.data(), image.size());
  if (model.test.history.empty()) {
    state.commit();
    if (::unlink(csvPath.c_str()) != 0 && errno != ENOENT) {
      throw FileError("Wrote '" + path + "', but the history file '" + csvPath +
                      "' of an earlier write beside it cannot be removed (" + std::strerror(errno) +
                      "): it no longer matches the state file, which has no test history.");
    }
  } else {
    const std::string text = historyCSVText(model.test);
    PendingFile csv(csvPath, text.data(), text.size());
    state.commit();
    csv.commit();
  }
  syncDirectory(path);
}

HistorySyncReport syncHistoryCSV(const LoadTestState& test, const std::string& statePath)
{
  HistorySyncReport report;
  report.path = historyPathFor(statePath);
  report.stateRows = test.history.size();
  std::string found;
  const bool present = exists(report.path);
  if (present && !readWhole(report.path, found)) {
    throw FileError("History file '" + report.path + "' beside '" + statePath + "' cannot be read (" +
                    std::strerror(errno) + ").");
  }
  if (!present) {
    return report; // nothing beside the state file to contradict it
  }
  {
    // Rows = lines after the header.
    const auto lines = static_cast<std::size_t>(std::count(found.begin(), found.end(), '\n'));
    report.fileRows = lines > 0 ? lines - 1 : 0;
  }
  if (test.history.empty()) {
    if (::unlink(report.path.c_str()) != 0) {
      throw FileError("History file '" + report.path + "' does not belong to '" + statePath +
                      "' (the state has no test history) and cannot be removed (" + std::strerror(errno) + ").");
    }
    report.action = HistorySync::Removed;
    return report;
  }
  const std::string expected = historyCSVText(test);
  if (found == expected) {
    return report;
  }
  try {
    writeFileAtomically(report.path, expected.data(), expected.size());
  } catch (const FileError& e) {
    throw FileError("History file '" + report.path + "' is out of step with '" + statePath + "' (" +
                    std::to_string(report.fileRows) + " rows; the state file has " +
                    std::to_string(report.stateRows) + ") and cannot be rewritten from it: " + e.what());
  }
  report.action = HistorySync::Rewritten;
  return report;
}

} // namespace dem
