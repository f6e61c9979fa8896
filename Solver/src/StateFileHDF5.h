// RockDEM engine: small RAII helpers over the HDF5 C API for the state file (internal).
#pragma once

#include <hdf5.h>

#include <atomic>
#include <string>

namespace dem {
namespace state {

/// Owns an HDF5 identifier and closes it with the matching function.
class Handle {
public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer close) : id_(id), close_(close) {}
  Handle(Handle&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = -1; }
  Handle& operator=(Handle&& o) noexcept
  {
    reset();
    id_ = o.id_;
    close_ = o.close_;
    o.id_ = -1;
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }
  void reset()
  {
    if (id_ >= 0 && close_) {
      close_(id_);
    }
    id_ = -1;
  }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }

private:
  hid_t id_ = -1;
  Closer close_ = nullptr;
};

/// Turns HDF5's automatic error printing off for its lifetime (and restores what was
/// there before: ParaView shares the library). Errors are reported by RockDEM instead.
class QuietHDF5 {
public:
  QuietHDF5()
  {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietHDF5() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  QuietHDF5(const QuietHDF5&) = delete;
  QuietHDF5& operator=(const QuietHDF5&) = delete;

private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

/// A unique name for an in-memory (core driver) HDF5 file.
inline std::string memoryFileName(const char* what)
{
  static std::atomic<unsigned long> counter{ 0 };
  return std::string("rockdem-") + what + "-" + std::to_string(counter++) + ".h5";
}

} // namespace state
} // namespace dem
