// RockDEM engine: internals of the state file shared by its source files.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace dem {
namespace state {

// Byte offsets of the RockDEM header fields (little-endian integers).
constexpr std::size_t HeaderVersionOffset = 16; ///< uint32 format version
constexpr std::size_t HeaderSizeOffset = 20;    ///< uint32 header size (512)
constexpr std::size_t HeaderPayloadOffset = 24; ///< uint64 bytes after the header
constexpr std::size_t HeaderChecksumOffset = 32; ///< uint64 FNV-1a 64 of all other bytes
constexpr std::size_t HeaderNoteOffset = 40;    ///< a human-readable line (NUL-terminated)

std::uint64_t fnv1a64Continue(std::uint64_t hash, const void* data, std::size_t size);
/// The checksum of a whole image: every byte except the checksum field.
std::uint64_t imageChecksum(const unsigned char* image, std::size_t size);
/// Fills the header of an image whose HDF5 part starts at StateHeaderBytes.
void sealImage(std::vector<unsigned char>& image, std::uint32_t version);
/// Checks magic, version, length and (optionally) checksum; returns the version.
std::uint32_t checkImage(const unsigned char* image, std::size_t size, const std::string& name,
                         bool verifyChecksum);

} // namespace state
} // namespace dem
