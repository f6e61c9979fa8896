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

#include <fcntl.h>
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
  if (size < HeaderVersionOffset + 4) {
    throw FileError(file + " is truncated: " + std::to_string(size) + " bytes, shorter than the " +
                    std::to_string(StateHeaderBytes) + "-byte RockDEM header.");
  }
  const std::uint32_t version = getU32(image + HeaderVersionOffset);
  const auto& supported = supportedStateVersions();
  if (std::find(supported.begin(), supported.end(), version) == supported.end()) {
    throw FileError(file + " has format version " + std::to_string(version) +
                    ", which this build of RockDEM does not read: supported versions are " + versionList() +
                    (version > StateFormatVersion ? " (the file is from a newer RockDEM)." : "."));
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

void writeFileAtomically(const std::string& path, const void* bytes, std::size_t size)
{
  if (path.empty()) {
    throw FileError("File Name is empty: give the path of the file to write.");
  }
  static std::atomic<unsigned> counter{ 0 };
  const std::string temporary =
    path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    throw FileError("Cannot write '" + path + "': creating the temporary file '" + temporary +
                    "' failed (" + std::strerror(errno) + ").");
  }
  auto fail = [&](const std::string& what, int error) {
    ::close(fd);
    ::unlink(temporary.c_str());
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
    ::unlink(temporary.c_str());
    throw FileError("Cannot write '" + path + "': closing the temporary file failed (" +
                    std::strerror(error) + ").");
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    const int error = errno;
    ::unlink(temporary.c_str());
    throw FileError("Cannot write '" + path + "': renaming '" + temporary + "' over it failed (" +
                    std::strerror(error) + "); the previous file, if any, is unchanged.");
  }
  // Make the rename itself durable.
  const std::size_t slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
}

void writeHistoryCSV(const LoadTestState& test, const std::string& path)
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
  const std::string text = out.str();
  writeFileAtomically(path, text.data(), text.size());
}

} // namespace dem
