// RockDEM engine: writing a state file (dem/StateFile.h). The model goes into an
// in-memory HDF5 file (core driver) with a 512-byte user block; the image is sealed with
// the RockDEM header and written to disk atomically.
#include "StateFileHDF5.h"
#include "StateFileInternal.h"
#include "StateSchema.h"

#include "dem/StateFile.h"

#include <cstring>
#include <string>

namespace dem {
namespace state {
namespace {

[[noreturn]] void hdf5Failure(const std::string& what)
{
  throw FileError("Writing the state file failed in HDF5: " + what + ".");
}

Handle stringType(std::size_t length)
{
  Handle t(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(t.get(), length);
  H5Tset_strpad(t.get(), H5T_STR_NULLTERM);
  return t;
}

void stringAttribute(hid_t object, const char* name, const std::string& value)
{
  Handle type = stringType(value.size() + 1);
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(H5Acreate2(object, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  if (!attr.valid() || H5Awrite(attr.get(), type.get(), value.c_str()) < 0) {
    hdf5Failure(std::string("attribute '") + name + "'");
  }
}

class Writer {
public:
  static constexpr bool Reading = false;

  explicit Writer(hid_t file)
    : file_(file), dcpl_(H5Pcreate(H5P_DATASET_CREATE), H5Pclose), gcpl_(H5Pcreate(H5P_GROUP_CREATE), H5Pclose)
  {
    // No modification times in the object headers: the same model gives the same bytes.
    H5Pset_obj_track_times(dcpl_.get(), 0);
    H5Pset_obj_track_times(gcpl_.get(), 0);
  }

  void f64(const char* path, double& v, const char* unit) { write(path, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 0, 0, 0, &v, unit); }
  void i64(const char* path, std::int64_t& v, const char* unit) { write(path, H5T_STD_I64LE, H5T_NATIVE_INT64, 0, 0, 0, &v, unit); }
  void i32(const char* path, int& v, const char* unit)
  {
    std::int32_t x = v;
    write(path, H5T_STD_I32LE, H5T_NATIVE_INT32, 0, 0, 0, &x, unit);
  }
  void u8flag(const char* path, bool& v)
  {
    std::uint8_t x = v ? 1 : 0;
    write(path, H5T_STD_U8LE, H5T_NATIVE_UINT8, 0, 0, 0, &x, "1");
  }
  template <class E>
  void enumeration(const char* path, E& v, int /*maxValue*/)
  {
    std::int32_t x = static_cast<std::int32_t>(v);
    write(path, H5T_STD_I32LE, H5T_NATIVE_INT32, 0, 0, 0, &x, "1");
  }
  void vec3(const char* path, Vec3& v, const char* unit) { write(path, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 1, 3, 0, v.data(), unit); }
  void doubles3(const char* path, std::array<double, 3>& v, const char* unit) { write(path, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 1, 3, 0, v.data(), unit); }
  void flags3(const char* path, std::array<bool, 3>& v)
  {
    std::uint8_t x[3] = { v[0], v[1], v[2] };
    write(path, H5T_STD_U8LE, H5T_NATIVE_UINT8, 1, 3, 0, x, "1");
  }
  void u64x4(const char* path, std::array<std::uint64_t, 4>& v) { write(path, H5T_STD_U64LE, H5T_NATIVE_UINT64, 1, 4, 0, v.data(), "1"); }

  std::size_t length(const char*, std::size_t n) { return n; }
  bool has(const char*) const { return true; }

  void column(const char* path, std::vector<double>& v, std::size_t n, const char* unit, const char* per) { check(path, v.size(), n, per); write(path, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 1, n, 0, v.data(), unit); }
  void column(const char* path, std::vector<Vec3>& v, std::size_t n, const char* unit, const char* per)
  {
    static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 must be three packed doubles");
    check(path, v.size(), n, per);
    write(path, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 2, n, 3, v.empty() ? nullptr : v.data()->data(), unit);
  }
  void column(const char* path, std::vector<std::int64_t>& v, std::size_t n, const char* unit, const char* per) { check(path, v.size(), n, per); write(path, H5T_STD_I64LE, H5T_NATIVE_INT64, 1, n, 0, v.data(), unit); }
  void column(const char* path, std::vector<std::int32_t>& v, std::size_t n, const char* unit, const char* per) { check(path, v.size(), n, per); write(path, H5T_STD_I32LE, H5T_NATIVE_INT32, 1, n, 0, v.data(), unit); }
  void column(const char* path, std::vector<std::uint32_t>& v, std::size_t n, const char* unit, const char* per) { check(path, v.size(), n, per); write(path, H5T_STD_U32LE, H5T_NATIVE_UINT32, 1, n, 0, v.data(), unit); }
  void column(const char* path, std::vector<std::uint8_t>& v, std::size_t n, const char* unit, const char* per) { check(path, v.size(), n, per); write(path, H5T_STD_U8LE, H5T_NATIVE_UINT8, 1, n, 0, v.data(), unit); }
  void columnZeroOr(const char* path, std::vector<Vec3>& v, std::size_t n, const char* unit, const char* per)
  {
    column(path, v, v.empty() ? 0 : n, unit, per);
  }

  void table(const char* path, std::vector<std::array<double, HistoryColumnCount>>& rows)
  {
    write(path, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 2, rows.size(), HistoryColumnCount,
          rows.empty() ? nullptr : rows.data()->data(), "see columns");
    // The column names (with their units) as an attribute: an array of strings.
    const auto& names = historyColumns();
    std::size_t width = 1;
    for (const auto& s : names) {
      width = std::max(width, s.size() + 1);
    }
    std::vector<char> packed(width * names.size(), '\0');
    for (std::size_t c = 0; c < names.size(); ++c) {
      std::memcpy(packed.data() + c * width, names[c].data(), names[c].size());
    }
    Handle dset(H5Dopen2(file_, path, H5P_DEFAULT), H5Dclose);
    Handle type = stringType(width);
    const hsize_t count = names.size();
    Handle space(H5Screate_simple(1, &count, nullptr), H5Sclose);
    Handle attr(H5Acreate2(dset.get(), "columns", type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
    if (!attr.valid() || H5Awrite(attr.get(), type.get(), packed.data()) < 0) {
      hdf5Failure(std::string("attribute 'columns' of '/") + path + "'");
    }
  }

private:
  static void check(const char* path, std::size_t size, std::size_t n, const char* per)
  {
    if (size != n) {
      throw InputError(std::string("The model is inconsistent: '/") + path + "' would have " +
                       std::to_string(size) + " values; expected " + std::to_string(n) + " (" + per +
                       "). Nothing was written.");
    }
  }

  void write(const char* path, hid_t fileType, hid_t memType, int rank, std::size_t d0, std::size_t d1,
             const void* data, const char* unit)
  {
    const hsize_t dims[2] = { d0, d1 };
    Handle space(rank == 0 ? H5Screate(H5S_SCALAR) : H5Screate_simple(rank, dims, nullptr), H5Sclose);
    makeParents(path);
    Handle dset(H5Dcreate2(file_, path, fileType, space.get(), H5P_DEFAULT, dcpl_.get(), H5P_DEFAULT), H5Dclose);
    if (!dset.valid()) {
      hdf5Failure(std::string("creating '/") + path + "'");
    }
    const bool empty = rank > 0 && (d0 == 0 || (rank == 2 && d1 == 0));
    if (!empty && H5Dwrite(dset.get(), memType, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
      hdf5Failure(std::string("writing '/") + path + "'");
    }
    stringAttribute(dset.get(), "units", unit);
  }

  void makeParents(const std::string& path)
  {
    for (std::size_t slash = path.find('/'); slash != std::string::npos; slash = path.find('/', slash + 1)) {
      const std::string group = path.substr(0, slash);
      if (H5Lexists(file_, group.c_str(), H5P_DEFAULT) > 0) {
        continue;
      }
      Handle g(H5Gcreate2(file_, group.c_str(), H5P_DEFAULT, gcpl_.get(), H5P_DEFAULT), H5Gclose);
      if (!g.valid()) {
        hdf5Failure("creating the group '/" + group + "'");
      }
    }
  }

  hid_t file_;
  Handle dcpl_;
  Handle gcpl_;
};

} // namespace
} // namespace state

std::vector<unsigned char> writeStateToMemory(const Model& model)
{
  using namespace state;
  QuietHDF5 quiet;
  std::vector<unsigned char> image;
  {
    Handle fcpl(H5Pcreate(H5P_FILE_CREATE), H5Pclose);
    H5Pset_userblock(fcpl.get(), StateHeaderBytes);
    Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
    H5Pset_fapl_core(fapl.get(), 1 << 20, 0);
    // The oldest format that holds what we write: files stay readable by HDF5 1.8 tools.
    H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_EARLIEST, H5F_LIBVER_LATEST);
    const std::string name = memoryFileName("write");
    Handle file(H5Fcreate(name.c_str(), H5F_ACC_TRUNC, fcpl.get(), fapl.get()), H5Fclose);
    if (!file.valid()) {
      hdf5Failure("creating the in-memory file");
    }
    Handle root(H5Gopen2(file.get(), "/", H5P_DEFAULT), H5Gclose);
    {
      Handle space(H5Screate(H5S_SCALAR), H5Sclose);
      Handle attr(H5Acreate2(root.get(), "format_version", H5T_STD_U32LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                  H5Aclose);
      const std::uint32_t version = StateFormatVersion;
      if (!attr.valid() || H5Awrite(attr.get(), H5T_NATIVE_UINT32, &version) < 0) {
        hdf5Failure("attribute 'format_version'");
      }
    }
    stringAttribute(root.get(), "creator", "RockDEM");
    stringAttribute(root.get(), "schema", "RockDEM state file, Documentation/StateFile.md");
    Writer writer(file.get());
    // visitModel takes a mutable model for the reader's sake; the writer only reads it.
    visitModel(writer, const_cast<Model&>(model));
    if (H5Fflush(file.get(), H5F_SCOPE_GLOBAL) < 0) {
      hdf5Failure("flushing the in-memory file");
    }
    // The image is the HDF5 file as HDF5 sees it, from its superblock (H5Fget_file_image
    // leaves the user block out): it goes after the 512-byte RockDEM header, where HDF5
    // expects it in a file with a user block.
    const ssize_t size = H5Fget_file_image(file.get(), nullptr, 0);
    if (size <= 0) {
      hdf5Failure("getting the file image");
    }
    image.assign(StateHeaderBytes + static_cast<std::size_t>(size), 0);
    if (H5Fget_file_image(file.get(), image.data() + StateHeaderBytes, static_cast<std::size_t>(size)) != size) {
      hdf5Failure("copying the file image");
    }
  }
  if (std::memcmp(image.data() + StateHeaderBytes, "\x89HDF\r\n\x1a\n", 8) != 0) {
    hdf5Failure("the file image does not start with the HDF5 superblock");
  }
  sealImage(image, StateFormatVersion);
  return image;
}

void writeState(const Model& model, const std::string& path)
{
  const std::vector<unsigned char> image = writeStateToMemory(model);
  writeFileAtomically(path, image.data(), image.size());
}

} // namespace dem
