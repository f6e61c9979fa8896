// RockDEM engine: reading a state file (dem/StateFile.h). The whole file is read into
// memory and its header checked (magic, version, length, checksum) before HDF5 sees it;
// then every dataset of the schema is checked for presence, type, rank and size before
// it is read, and the values are validated as user input is.
#include "StateFileHDF5.h"
#include "StateFileInternal.h"
#include "StateSchema.h"

#include "dem/Simulation.h"
#include "dem/StateFile.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <unordered_set>

#include <sys/stat.h>

namespace dem {
namespace state {
namespace {

enum class Kind { Float, Signed, Unsigned };

const char* kindName(Kind k)
{
  switch (k) {
    case Kind::Float: return "float";
    case Kind::Signed: return "signed integer";
    case Kind::Unsigned: return "unsigned integer";
  }
  return "?";
}

class Reader {
public:
  static constexpr bool Reading = true;

  Reader(hid_t file, const std::string& name, std::size_t imageSize)
    : file_(file), prefix_("State file '" + name + "'"), imageSize_(imageSize)
  {
  }

  void f64(const char* path, double& v, const char*) { scalar(path, Kind::Float, 8, H5T_NATIVE_DOUBLE, &v); }
  void i64(const char* path, std::int64_t& v, const char*) { scalar(path, Kind::Signed, 8, H5T_NATIVE_INT64, &v); }
  void i32(const char* path, int& v, const char*)
  {
    std::int32_t x = 0;
    scalar(path, Kind::Signed, 4, H5T_NATIVE_INT32, &x);
    v = x;
  }
  void u8flag(const char* path, bool& v)
  {
    std::uint8_t x = 0;
    scalar(path, Kind::Unsigned, 1, H5T_NATIVE_UINT8, &x);
    if (x > 1) {
      fail("'/" + std::string(path) + "' = " + std::to_string(x) + " is not a flag: expected 0 or 1");
    }
    v = x != 0;
  }
  template <class E>
  void enumeration(const char* path, E& v, int maxValue)
  {
    std::int32_t x = 0;
    scalar(path, Kind::Signed, 4, H5T_NATIVE_INT32, &x);
    if (x < 0 || x > maxValue) {
      fail("'/" + std::string(path) + "' = " + std::to_string(x) + " is out of range: valid values are 0 to " +
           std::to_string(maxValue));
    }
    v = static_cast<E>(x);
  }
  void vec3(const char* path, Vec3& v, const char*) { fixed(path, Kind::Float, 8, H5T_NATIVE_DOUBLE, 3, v.data()); }
  void doubles3(const char* path, std::array<double, 3>& v, const char*) { fixed(path, Kind::Float, 8, H5T_NATIVE_DOUBLE, 3, v.data()); }
  void flags3(const char* path, std::array<bool, 3>& v)
  {
    std::uint8_t x[3] = { 0, 0, 0 };
    fixed(path, Kind::Unsigned, 1, H5T_NATIVE_UINT8, 3, x);
    for (int k = 0; k < 3; ++k) {
      if (x[k] > 1) {
        fail("'/" + std::string(path) + "' has the value " + std::to_string(x[k]) + ": expected 0 or 1");
      }
      v[static_cast<std::size_t>(k)] = x[k] != 0;
    }
  }
  void u64x4(const char* path, std::array<std::uint64_t, 4>& v) { fixed(path, Kind::Unsigned, 8, H5T_NATIVE_UINT64, 4, v.data()); }

  /// Whether the file has the dataset (for fields added after version 1: see StateSchema.h).
  bool has(const char* path) const
  {
    const std::string full(path);
    for (std::size_t slash = full.find('/');; slash = full.find('/', slash + 1)) {
      if (H5Lexists(file_, full.substr(0, slash).c_str(), H5P_DEFAULT) <= 0) {
        return false;
      }
      if (slash == std::string::npos) {
        return true;
      }
    }
  }

  std::size_t length(const char* path, std::size_t)
  {
    Handle d = open(path);
    const std::vector<hsize_t> dims = extent(d.get(), path);
    if (dims.empty()) {
      fail("'/" + std::string(path) + "' is a scalar; expected a one-dimensional array");
    }
    return static_cast<std::size_t>(dims[0]);
  }

  void column(const char* path, std::vector<double>& v, std::size_t n, const char*, const char* per) { array(path, Kind::Float, 8, H5T_NATIVE_DOUBLE, v, n, 1, per); }
  void column(const char* path, std::vector<Vec3>& v, std::size_t n, const char*, const char* per)
  {
    Handle d = check(path, Kind::Float, 8, { n, 3 }, per);
    v.assign(n, Vec3::Zero());
    read(d.get(), path, H5T_NATIVE_DOUBLE, n ? v.data()->data() : nullptr, n * 3);
  }
  void column(const char* path, std::vector<std::int64_t>& v, std::size_t n, const char*, const char* per) { array(path, Kind::Signed, 8, H5T_NATIVE_INT64, v, n, 1, per); }
  void column(const char* path, std::vector<std::int32_t>& v, std::size_t n, const char*, const char* per) { array(path, Kind::Signed, 4, H5T_NATIVE_INT32, v, n, 1, per); }
  void column(const char* path, std::vector<std::uint32_t>& v, std::size_t n, const char*, const char* per) { array(path, Kind::Unsigned, 4, H5T_NATIVE_UINT32, v, n, 1, per); }
  void column(const char* path, std::vector<std::uint8_t>& v, std::size_t n, const char*, const char* per) { array(path, Kind::Unsigned, 1, H5T_NATIVE_UINT8, v, n, 1, per); }
  void columnZeroOr(const char* path, std::vector<Vec3>& v, std::size_t n, const char* unit, const char* per)
  {
    const std::size_t rows = length(path, n);
    column(path, v, rows == 0 ? 0 : n, unit, per);
  }

  void table(const char* path, std::vector<std::array<double, HistoryColumnCount>>& rows)
  {
    const std::size_t r = length(path, 0);
    // Files written before the Gauge Strain column hold the first 27 columns: they read
    // with the gauge strain unknown (NaN). Any other width is refused by check().
    std::size_t columns = HistoryColumnCount;
    {
      Handle probe = open(path);
      const std::vector<hsize_t> dims = extent(probe.get(), path);
      if (dims.size() == 2 && dims[1] == HistoryColumnCountBeforeGaugeStrain) {
        columns = HistoryColumnCountBeforeGaugeStrain;
      }
    }
    Handle d = check(path, Kind::Float, 8, { r, columns }, "one row per sample");
    std::vector<double> flat(r * columns);
    read(d.get(), path, H5T_NATIVE_DOUBLE, flat.empty() ? nullptr : flat.data(), flat.size());
    std::array<double, HistoryColumnCount> unknown{};
    unknown.fill(std::numeric_limits<double>::quiet_NaN());
    rows.assign(r, unknown);
    for (std::size_t i = 0; i < r; ++i) {
      std::copy_n(flat.data() + i * columns, columns, rows[i].data());
    }
  }

  [[noreturn]] void fail(const std::string& what) const { throw FileError(prefix_ + ": " + what + "."); }

private:
  Handle open(const char* path)
  {
    // Every link along the path must exist (H5Lexists needs its parent to).
    std::string sofar;
    const std::string full(path);
    std::size_t start = 0;
    while (true) {
      const std::size_t slash = full.find('/', start);
      sofar = full.substr(0, slash);
      if (H5Lexists(file_, sofar.c_str(), H5P_DEFAULT) <= 0) {
        fail("'/" + sofar + "' is missing (needed for '/" + full + "')");
      }
      if (slash == std::string::npos) {
        break;
      }
      start = slash + 1;
    }
    Handle d(H5Dopen2(file_, path, H5P_DEFAULT), H5Dclose);
    if (!d.valid()) {
      fail("'/" + full + "' is not a readable dataset");
    }
    return d;
  }

  std::vector<hsize_t> extent(hid_t d, const char* path)
  {
    Handle space(H5Dget_space(d), H5Sclose);
    if (!space.valid()) {
      fail("'/" + std::string(path) + "' has no readable dataspace");
    }
    const H5S_class_t cls = H5Sget_simple_extent_type(space.get());
    if (cls == H5S_SCALAR) {
      return {};
    }
    if (cls != H5S_SIMPLE) {
      fail("'/" + std::string(path) + "' has an empty or unknown dataspace");
    }
    const int rank = H5Sget_simple_extent_ndims(space.get());
    if (rank < 1 || rank > 8) {
      fail("'/" + std::string(path) + "' has rank " + std::to_string(rank) + "; expected 1 or 2");
    }
    std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
    if (H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr) < 0) {
      fail("'/" + std::string(path) + "' has unreadable dimensions");
    }
    return dims;
  }

  void checkType(hid_t d, const char* path, Kind kind, std::size_t bytes)
  {
    Handle type(H5Dget_type(d), H5Tclose);
    if (!type.valid()) {
      fail("'/" + std::string(path) + "' has an unreadable type");
    }
    const H5T_class_t cls = H5Tget_class(type.get());
    const std::size_t size = H5Tget_size(type.get());
    bool ok = size == bytes;
    std::string found;
    if (cls == H5T_FLOAT) {
      ok = ok && kind == Kind::Float;
      found = std::to_string(8 * size) + "-bit float";
    } else if (cls == H5T_INTEGER) {
      const bool isSigned = H5Tget_sign(type.get()) == H5T_SGN_2;
      ok = ok && kind == (isSigned ? Kind::Signed : Kind::Unsigned);
      found = std::to_string(8 * size) + "-bit " + (isSigned ? "signed" : "unsigned") + " integer";
    } else {
      ok = false;
      found = "a type of class " + std::to_string(static_cast<int>(cls));
    }
    if (!ok) {
      fail("'/" + std::string(path) + "' holds " + found + " values; expected " + std::to_string(8 * bytes) +
           "-bit " + kindName(kind) + " values");
    }
  }

  Handle check(const char* path, Kind kind, std::size_t bytes, const std::vector<std::size_t>& expected,
               const char* per)
  {
    Handle d = open(path);
    checkType(d.get(), path, kind, bytes);
    const std::vector<hsize_t> dims = extent(d.get(), path);
    bool same = dims.size() == expected.size();
    for (std::size_t k = 0; same && k < dims.size(); ++k) {
      same = dims[k] == expected[k];
    }
    if (!same) {
      auto shape = [](const auto& v) {
        if (v.empty()) {
          return std::string("a scalar");
        }
        std::string s;
        for (std::size_t k = 0; k < v.size(); ++k) {
          s += (k ? " x " : "") + std::to_string(v[k]);
        }
        return s + (v.size() == 1 ? " values" : "");
      };
      fail("'/" + std::string(path) + "' has size " + shape(dims) + "; expected " + shape(expected) +
           (per && *per ? std::string(" (") + per + ")" : std::string()));
    }
    // No dataset can hold more data than the whole file (nothing is compressed): a
    // damaged size is caught here rather than by a huge allocation.
    long double total = static_cast<long double>(bytes);
    for (std::size_t e : expected) {
      total *= static_cast<long double>(e);
    }
    if (total > static_cast<long double>(imageSize_)) {
      fail("'/" + std::string(path) + "' claims more data than the whole file holds (" +
           std::to_string(imageSize_) + " bytes)");
    }
    return d;
  }

  void read(hid_t d, const char* path, hid_t memType, void* data, std::size_t count)
  {
    if (count == 0) {
      return;
    }
    if (H5Dread(d, memType, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
      fail("'/" + std::string(path) + "' could not be read (damaged data)");
    }
  }

  void scalar(const char* path, Kind kind, std::size_t bytes, hid_t memType, void* data)
  {
    Handle d = check(path, kind, bytes, {}, "");
    read(d.get(), path, memType, data, 1);
  }

  void fixed(const char* path, Kind kind, std::size_t bytes, hid_t memType, std::size_t count, void* data)
  {
    Handle d = check(path, kind, bytes, { count }, "");
    read(d.get(), path, memType, data, count);
  }

  template <class T>
  void array(const char* path, Kind kind, std::size_t bytes, hid_t memType, std::vector<T>& v, std::size_t n,
             std::size_t, const char* per)
  {
    Handle d = check(path, kind, bytes, { n }, per);
    v.assign(n, T{});
    read(d.get(), path, memType, v.data(), n);
  }

  hid_t file_;
  std::string prefix_;
  std::size_t imageSize_;
};

/// What the engine relies on beyond the per-value checks of validate().
void validateModel(const Model& m, const Reader& r)
{
  try {
    validate(m.domain);
    validate(m.material);
    validate(m.solver);
    validate(m.particles);
    validate(m.test.settings);
    requireFinite("Settle Tolerance", m.test.settings.settleTolerance);
  } catch (const InputError& e) {
    r.fail(std::string("it holds an invalid value: ") + e.what());
  }
  const Particles& p = m.particles;
  std::unordered_set<std::int64_t> ids;
  ids.reserve(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!(p.mass[i] > 0.0 && std::isfinite(p.mass[i])) || !(p.inertia[i] > 0.0 && std::isfinite(p.inertia[i]))) {
      r.fail("particle " + std::to_string(p.id[i]) + " has mass " + formatValue(p.mass[i]) + " kg and inertia " +
             formatValue(p.inertia[i]) + " kg m^2; both must be positive and finite");
    }
    if (!ids.insert(p.id[i]).second) {
      r.fail("two particles have the id " + std::to_string(p.id[i]) + "; ids must be unique");
    }
  }
  if (!m.walls.empty() && m.walls.size() != 6) {
    r.fail("'/walls' has " + std::to_string(m.walls.size()) + " walls; expected 0 or 6");
  }
  for (std::size_t w = 0; w < m.walls.size(); ++w) {
    const Wall& wall = m.walls[w];
    if (wall.axis != static_cast<int>(w / 2) || wall.side != static_cast<int>(w % 2)) {
      r.fail("wall " + std::to_string(w) + " has axis " + std::to_string(wall.axis) + " and side " +
             std::to_string(wall.side) + "; expected axis " + std::to_string(w / 2) + " and side " +
             std::to_string(w % 2) + " (walls are stored as X-, X+, Y-, Y+, Z-, Z+)");
    }
    if (!std::isfinite(wall.position) || !std::isfinite(wall.velocity)) {
      r.fail("wall " + std::to_string(w) + " has a non-finite position or velocity");
    }
  }
  const Bonds& b = m.bonds;
  for (std::size_t k = 0; k < b.size(); ++k) {
    const std::int64_t a = b.idA[k];
    const std::int64_t c = b.idB[k];
    if (!(a < c) || (k > 0 && !(b.idA[k - 1] < a || (b.idA[k - 1] == a && b.idB[k - 1] < c)))) {
      r.fail("bond " + std::to_string(k) + " (" + std::to_string(a) + ", " + std::to_string(c) +
             ") breaks the order of '/bonds' (sorted by (id_a, id_b) with id_a < id_b)");
    }
    if (!ids.count(a) || !ids.count(c)) {
      r.fail("bond " + std::to_string(k) + " joins " + std::to_string(a) + " and " + std::to_string(c) +
             ", but there is no particle with id " + std::to_string(ids.count(a) ? c : a));
    }
    if (b.failure[k] > static_cast<std::uint8_t>(BondFailure::Inherited)) {
      r.fail("bond " + std::to_string(k) + " has failure mode " + std::to_string(b.failure[k]) +
             "; valid values are 0 to " + std::to_string(static_cast<int>(BondFailure::Inherited)));
    }
  }
  if (!std::isfinite(m.clock.time) || m.clock.step < 0 || !(m.clock.timestep >= 0.0) ||
      !std::isfinite(m.clock.timestep)) {
    r.fail("the clock (time " + formatValue(m.clock.time) + " s, step " + std::to_string(m.clock.step) +
           ", timestep " + formatValue(m.clock.timestep) + " s) is invalid");
  }
}

Model readImage(const unsigned char* image, std::size_t size, const StateReadOptions& options,
                const std::string& name)
{
  const std::uint32_t version = checkImage(image, size, name, options.verifyChecksum);
  QuietHDF5 quiet;
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  H5Pset_fapl_core(fapl.get(), 1 << 20, 0);
  // HDF5 gets the part after the RockDEM header (the user block): a plain HDF5 file.
  if (H5Pset_file_image(fapl.get(), const_cast<unsigned char*>(image) + StateHeaderBytes,
                        size - StateHeaderBytes) < 0) {
    throw FileError("State file '" + name + "': HDF5 could not take the file image.");
  }
  const std::string memName = memoryFileName("read");
  Handle file(H5Fopen(memName.c_str(), H5F_ACC_RDONLY, fapl.get()), H5Fclose);
  if (!file.valid()) {
    throw FileError("State file '" + name + "': its HDF5 part cannot be opened (damaged file).");
  }
  Reader reader(file.get(), name, size);
  {
    Handle root(H5Gopen2(file.get(), "/", H5P_DEFAULT), H5Gclose);
    if (!root.valid() || H5Aexists(root.get(), "format_version") <= 0) {
      reader.fail("the attribute '/format_version' is missing");
    }
    Handle attr(H5Aopen(root.get(), "format_version", H5P_DEFAULT), H5Aclose);
    Handle space(attr.valid() ? H5Aget_space(attr.get()) : -1, H5Sclose);
    Handle type(attr.valid() ? H5Aget_type(attr.get()) : -1, H5Tclose);
    std::uint32_t stored = 0;
    if (!space.valid() || !type.valid() || H5Sget_simple_extent_npoints(space.get()) != 1 ||
        H5Tget_class(type.get()) != H5T_INTEGER || H5Tget_size(type.get()) != 4 ||
        H5Aread(attr.get(), H5T_NATIVE_UINT32, &stored) < 0) {
      reader.fail("the attribute '/format_version' is not a single 32-bit integer");
    }
    if (stored != version) {
      reader.fail("the attribute '/format_version' = " + std::to_string(stored) +
                  " disagrees with the header's format version " + std::to_string(version));
    }
  }
  Model model;
  state::visitModel(reader, model);
  validateModel(model, reader);
  return model;
}

} // namespace
} // namespace state

Model readStateFromMemory(const void* data, std::size_t size, const StateReadOptions& options,
                          const std::string& name)
{
  static const unsigned char none = 0;
  return state::readImage(data ? static_cast<const unsigned char*>(data) : &none, data ? size : 0, options, name);
}

Model readState(const std::string& path, const StateReadOptions& options)
{
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) {
    throw FileError("State file '" + path + "' cannot be opened: " + std::strerror(errno) + ".");
  }
  if (!S_ISREG(info.st_mode)) {
    throw FileError("State file '" + path + "' is not a regular file" +
                    (S_ISDIR(info.st_mode) ? std::string(" (it is a directory).") : std::string(".")));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw FileError("State file '" + path + "' cannot be opened: " + std::strerror(errno) + ".");
  }
  std::vector<unsigned char> image(static_cast<std::size_t>(info.st_size));
  if (!image.empty() && !in.read(reinterpret_cast<char*>(image.data()), static_cast<std::streamsize>(image.size()))) {
    throw FileError("State file '" + path + "' cannot be read: reading " + std::to_string(image.size()) +
                    " bytes failed.");
  }
  return state::readImage(image.data(), image.size(), options, path);
}

} // namespace dem
