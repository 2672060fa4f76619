#include "heavytop/io/map_file.hpp"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <type_traits>

#include <fmt/format.h>

#include "heavytop/io/config.hpp"
#include "heavytop/io/formats.hpp"
#include "heavytop/io/output.hpp"
#include "heavytop/linear_models.hpp"
#include "heavytop/verdicts.hpp"

#ifdef HEAVYTOP_HAVE_HDF5
#include <hdf5.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#if defined(__SANITIZE_ADDRESS__)
#define HEAVYTOP_SANITIZED_CHILD 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define HEAVYTOP_SANITIZED_CHILD 1
#endif
#endif
#ifdef HEAVYTOP_SANITIZED_CHILD
extern "C" void __sanitizer_set_death_callback(void (*callback)(void));
extern "C" void __sanitizer_set_report_path(const char* path);
#endif
#endif

namespace heavytop::io {
namespace {

constexpr LyapunovCertificate kCertificates[] = {
    LyapunovCertificate::EnergyCasimir, LyapunovCertificate::Chetaev,           LyapunovCertificate::CriticalQuartic,
    LyapunovCertificate::OddIndex,      LyapunovCertificate::LinearInstability, LyapunovCertificate::None,
    LyapunovCertificate::Kam,           LyapunovCertificate::KamMarkeev,        LyapunovCertificate::Resonance};
constexpr std::string_view kVerdictColumns[] = {"first-order", "body-fixed", "linearized", "lyapunov"};
constexpr const char* kFormatName = "heavytop stability map 1";
constexpr std::size_t kRowsPerBlock = 1 << 20;  // of a map file, written or read at a time

/// Throws InvalidInput unless `path` is a regular file (a device such as /dev/zero, a FIFO or
/// a folder would be read forever, or not at all); returns its size.
std::uintmax_t map_file_size(const std::string& path, const std::string& key) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) throw InvalidInput(key, fmt::format("cannot read '{}': no such file", printable(path)));
  if (!std::filesystem::is_regular_file(status))
    throw InvalidInput(key, fmt::format("'{}' is not a regular file (a map is a file heavytop sweep wrote)", printable(path)));
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw InvalidInput(key, fmt::format("cannot read '{}'", printable(path)));
  return size;
}

std::string read_whole(const std::string& path, const std::string& key) {
  const std::uintmax_t size = map_file_size(path, key);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidInput(key, fmt::format("cannot read '{}'", printable(path)));
  // A CSV map's size is bounded by its header: at most kMaxSweepPoints rows of at most 32
  // bytes a column (a double's shortest form is at most 24 characters, a certificate 18).
  std::string header(4096, '\0');
  in.read(header.data(), static_cast<std::streamsize>(header.size()));
  header.resize(static_cast<std::size_t>(in.gcount()));
  header = header.substr(0, header.find('\n'));
  in.clear();
  const std::size_t columns = 1 + static_cast<std::size_t>(std::count(header.begin(), header.end(), ','));
  if (size > header.size() + 1 + kMaxSweepPoints * 32 * columns)
    throw InvalidInput(key, fmt::format("'{}' is larger than a map of {} points can be", printable(path), kMaxSweepPoints));
  std::string text(static_cast<std::size_t>(size), '\0');
  in.seekg(0);
  in.read(text.data(), static_cast<std::streamsize>(size));
  text.resize(static_cast<std::size_t>(in.gcount()));
  return text;
}

/// A cell as it goes into a one-line message: control characters shown, at most 40 bytes
/// (fuzz_map: a cell with a carriage return broke the message's line).
std::string cell_shown(std::string_view cell) {
  return printable(cell.size() > 40 ? std::string(cell.substr(0, 40)) + "..." : std::string(cell));
}

/// Throws InvalidInput unless a map's axis key is one a sweep varies: a key becomes the
/// report's axis labels (in gnuplot scripts) and Python's names, so a file's own text must not
/// (issue 46: a key holding a quote and system('...') ran a command in gnuplot); nor one of the
/// `earlier` axes' keys (a sweep varies each key once: two axes of one key name no grid).
void check_axis_key(std::string_view axis_key, const std::vector<std::string>& earlier, const std::string& key) {
  if (!is_sweep_key(axis_key))
    throw InvalidInput(key, fmt::format("the axis key '{}' is not one a sweep varies (a map's keys are among {})",
                                        cell_shown(axis_key), sweep_keys_text()));
  if (std::find(earlier.begin(), earlier.end(), axis_key) != earlier.end())
    throw InvalidInput(key, fmt::format("the axis key '{}' is there twice (a sweep varies each key once)",
                                        cell_shown(axis_key)));
}

/// The axes (keys and values, exact) of rows whose first columns are a row-major grid.
std::vector<MapAxis> grid_of_rows(const std::vector<std::string>& keys, const std::vector<std::vector<double>>& rows,
                                  const std::string& key) {
  std::vector<MapAxis> axes;
  std::size_t points = 1, inner = rows.size();
  for (std::size_t k = 0; k < keys.size(); ++k) {
    // Axis k takes its next value every `inner / size` rows; its values are those of the
    // first rows of the first stretch of the axes before it.
    MapAxis axis{.key = keys[k], .values = {}};
    std::size_t run = 1;
    while (run < inner && rows[run][k] == rows[0][k]) ++run;
    if (run == 0 || inner % run != 0)
      throw InvalidInput(key, fmt::format("the rows are not a grid of '{}'", cell_shown(keys[k])));
    for (std::size_t i = 0; i < inner; i += run) axis.values.push_back(rows[i][k]);
    points *= axis.values.size();
    inner = run;
    axes.push_back(std::move(axis));
  }
  if (points != rows.size()) throw InvalidInput(key, "the rows are not a grid");
  for (std::size_t r = 0; r < rows.size(); ++r) {  // every row at its grid point, in grid order
    std::size_t index = r;
    for (std::size_t k = axes.size(); k-- > 0;) {
      if (rows[r][k] != axes[k].values[index % axes[k].values.size()])
        throw InvalidInput(key, fmt::format("row {}: '{}' is not the grid's value there", r + 2, cell_shown(keys[k])));
      index /= axes[k].values.size();
    }
  }
  return axes;
}

StabilityMap read_map_csv(const std::string& text, const std::string& key) {
  const std::size_t eol = text.find('\n');
  if (eol == std::string::npos) throw InvalidInput(key, "not a sweep's CSV (no header line)");
  std::vector<std::string> header;
  for (std::string_view line(text.data(), eol); !line.empty();) {
    const std::size_t comma = std::min(line.find(','), line.size());
    header.emplace_back(line.substr(0, comma));
    line.remove_prefix(std::min(line.size(), comma + 1));
  }
  const auto first_verdict = std::find(header.begin(), header.end(), "first-order");
  const std::vector<std::string> keys(header.begin(), first_verdict);
  // `sweep --tolerance-column` adds nonlinear_tolerance after nonlinear (read past: a map
  // holds verdicts).
  const bool tolerance = header.size() > 1 && header.back() == "nonlinear_tolerance";
  const bool nonlinear = header.size() > std::size_t(tolerance) && header[header.size() - 1 - tolerance] == "nonlinear";
  std::vector<SweepAxis> named;
  for (const auto& k : keys) named.push_back(SweepAxis{.key = k, .start = 0, .stop = 0, .count = 1});
  if (keys.empty() || keys.size() > kMaxSweepAxes ||
      text.substr(0, eol + 1) != sweep_csv_header(named, nonlinear, tolerance))
    throw InvalidInput(key, "not a sweep's CSV: the header must be 1 to 3 varied keys, then " +
                                std::string(sweep_csv_header({}, nonlinear).substr(0, sweep_csv_header({}, nonlinear).size() - 1)));
  for (std::size_t k = 0; k < keys.size(); ++k) check_axis_key(keys[k], {keys.begin(), keys.begin() + k}, key);
  std::vector<std::vector<double>> values;
  std::vector<SweepVerdict> verdicts;
  std::size_t row = 1;
  for (std::size_t at = eol + 1; at < text.size(); ++row) {
    const std::size_t end = text.find('\n', at);
    if (end == std::string::npos) throw InvalidInput(key, fmt::format("row {} is torn (no end of line)", row + 1));
    std::string_view line(text.data() + at, end - at);
    at = end + 1;
    std::vector<std::string_view> cells;
    for (std::size_t from = 0;;) {
      const std::size_t comma = line.find(',', from);
      cells.push_back(line.substr(from, comma == std::string_view::npos ? std::string_view::npos : comma - from));
      if (comma == std::string_view::npos) break;
      from = comma + 1;
    }
    if (cells.size() != header.size())
      throw InvalidInput(key, fmt::format("row {} has {} columns, the header {}", row + 1, cells.size(), header.size()));
    auto& point = values.emplace_back(keys.size());
    for (std::size_t k = 0; k < keys.size(); ++k) {
      const auto [p, ec] = std::from_chars(cells[k].data(), cells[k].data() + cells[k].size(), point[k]);
      if (ec != std::errc() || p != cells[k].data() + cells[k].size())
        throw InvalidInput(key, fmt::format("row {}: '{}' is not a number", row + 1, cell_shown(cells[k])));
    }
    auto flag = [&](std::size_t c) {
      if (cells[c] != "0" && cells[c] != "1")
        throw InvalidInput(key, fmt::format("row {}: column '{}' must be 0 or 1", row + 1, header[c]));
      return cells[c] == "1";
    };
    SweepVerdict& v = verdicts.emplace_back();
    const std::size_t c = keys.size();
    for (std::size_t m = 0; m < 3; ++m) v.linear[m] = flag(c + m);
    v.lyapunov = flag(c + 3);
    const auto certificate = std::find_if(std::begin(kCertificates), std::end(kCertificates),
                                          [&](LyapunovCertificate x) { return name(x) == cells[c + 4]; });
    if (certificate == std::end(kCertificates))
      throw InvalidInput(key, fmt::format("row {}: '{}' is not a certificate (SPEC section 7)", row + 1,
                                          cell_shown(cells[c + 4])));
    v.lyapunov_certificate = *certificate;
    if (nonlinear) v.nonlinear = flag(c + 5);
  }
  if (verdicts.empty()) throw InvalidInput(key, "the map has no rows");
  return StabilityMap{.axes = grid_of_rows(keys, values, key), .nonlinear = nonlinear, .verdicts = std::move(verdicts)};
}

#ifdef HEAVYTOP_HAVE_HDF5
/// An HDF5 identifier closed when it goes out of scope.
struct Handle {
  hid_t id;
  herr_t (*close)(hid_t);
  Handle(hid_t i, herr_t (*c)(hid_t)) : id(i), close(c) {}
  Handle(const Handle&) = delete;
  ~Handle() {
    if (id >= 0) close(id);
  }
  operator hid_t() const { return id; }
};

hid_t certificate_type() {
  const hid_t type = H5Tenum_create(H5T_NATIVE_UINT8);
  for (LyapunovCertificate c : kCertificates) {
    const std::uint8_t value = static_cast<std::uint8_t>(c);
    H5Tenum_insert(type, std::string(name(c)).c_str(), &value);
  }
  return type;
}

void check(herr_t status, const std::string& what) {
  if (status < 0) throw Failure(what);
}

/// "" when every HDF5 heap in the file fits in it, else what does not. libhdf5 allocates a
/// local heap's data segment ("HEAP", version 0) and a global heap collection ("GCOL",
/// version 1) at the size their header gives before it reads them (fuzz_map, issue 30: a
/// mutated size asked malloc for 2^49 bytes in H5C_protect). libhdf5 only loads a heap whose
/// header starts with its signature, so every heap it could load is among those found here;
/// heavytop's own files (8-byte lengths) have one local heap per group and no global heap.
std::string oversized_heap(const std::string& path, std::uintmax_t file_size) {
  std::ifstream in(path, std::ios::binary);
  constexpr std::size_t kBlock = 1 << 20, kHeader = 24;
  std::string block;
  for (std::uintmax_t at = 0; at < file_size; at += kBlock) {
    block.assign(kBlock + kHeader, '\0');
    in.seekg(static_cast<std::streamoff>(at));
    in.read(block.data(), static_cast<std::streamsize>(block.size()));
    block.resize(static_cast<std::size_t>(in.gcount()));
    in.clear();
    for (const std::string_view signature : {std::string_view("HEAP\0\0\0\0", 8), std::string_view("GCOL\1\0\0\0", 8)}) {
      for (std::size_t i = block.find(signature); i != std::string::npos && i < kBlock; i = block.find(signature, i + 1)) {
        if (i + 16 > block.size()) return fmt::format("a heap at byte {} is torn", at + i);
        std::uint64_t size = 0;  // little-endian, bytes 8-15 of the header
        for (int b = 7; b >= 0; --b) size = size << 8 | static_cast<unsigned char>(block[i + 8 + b]);
        if (size > file_size)
          return fmt::format("a heap at byte {} claims {} bytes, more than the file's {}", at + i, size, file_size);
      }
    }
  }
  return "";
}
#endif

}  // namespace

void pack_verdicts(const std::vector<SweepVerdict>& verdicts, std::string& out) {
  out.reserve(out.size() + verdicts.size() * kPackedVerdictSize);
  for (const auto& v : verdicts) {
    // The tolerance that decided the nonlinear verdict, as a class (map_file.hpp).
    const int tolerance = !v.nonlinear || !v.nonlinear_tolerance     ? 0
                          : *v.nonlinear_tolerance == 0.0             ? 1
                          : *v.nonlinear_tolerance == kLooseTolerance ? 2
                                                                      : 3;
    const char record[kPackedVerdictSize] = {char(v.linear[0]), char(v.linear[1]), char(v.linear[2]), char(v.lyapunov),
                                             char(v.lyapunov_certificate),
                                             char((v.nonlinear ? int(*v.nonlinear) : 2) | tolerance << 2)};
    out.append(record, kPackedVerdictSize);
  }
}

std::vector<SweepVerdict> unpack_verdicts(std::string_view bytes, double sweep_rtol) {
  if (bytes.size() % kPackedVerdictSize != 0) throw Failure("packed verdicts: a record is torn");
  std::vector<SweepVerdict> out(bytes.size() / kPackedVerdictSize);
  constexpr auto kLast = static_cast<unsigned char>(kLastLyapunovCertificate);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const auto* r = reinterpret_cast<const unsigned char*>(bytes.data() + i * kPackedVerdictSize);
    const int nonlinear = r[5] & 3, tolerance = r[5] >> 2;
    if (r[0] > 1 || r[1] > 1 || r[2] > 1 || r[3] > 1 || r[4] > kLast || nonlinear > 2 || tolerance > 3 ||
        (nonlinear == 2 && tolerance != 0))
      throw Failure("packed verdicts: a byte is out of range");
    out[i] = SweepVerdict{.linear = {r[0] == 1, r[1] == 1, r[2] == 1}, .lyapunov = r[3] == 1,
                          .lyapunov_certificate = static_cast<LyapunovCertificate>(r[4]),
                          .nonlinear = nonlinear == 2 ? std::nullopt : std::optional<bool>(nonlinear == 1)};
    if (tolerance)
      out[i].nonlinear_tolerance = tolerance == 1 ? 0.0 : tolerance == 2 ? kLooseTolerance : sweep_rtol;
  }
  return out;
}

std::size_t valid_journal_records(std::string_view records, const std::vector<SweepAxis>& axes, bool nonlinear,
                                  bool packed, bool tolerance) {
  tolerance = tolerance && nonlinear;
  const std::size_t total = grid_size(axes);
  std::size_t n = 0;
  if (packed) {
    for (; n < total && (n + 1) * kPackedVerdictSize <= records.size(); ++n) {
      const auto* r = reinterpret_cast<const unsigned char*>(records.data() + n * kPackedVerdictSize);
      if (r[0] > 1 || r[1] > 1 || r[2] > 1 || r[3] > 1 || r[4] > static_cast<unsigned char>(kLastLyapunovCertificate))
        break;
      if ((r[3] == 1) != proves_stability(static_cast<LyapunovCertificate>(r[4]))) break;
      const int verdict = r[5] & 3, class_ = r[5] >> 2;  // class_: the deciding tolerance (pack_verdicts)
      if (nonlinear ? verdict > 1 : verdict != 2) break;
      if (tolerance ? class_ < 1 || class_ > 3 : class_ != 0) break;
    }
    return n;
  }
  const std::size_t cells = axes.size() + 5 + (nonlinear ? 1 : 0) + (tolerance ? 1 : 0);
  std::vector<std::string_view> cell;
  for (std::size_t at = 0; n < total && at < records.size(); ++n) {
    const std::size_t end = records.find('\n', at);
    if (end == std::string_view::npos) break;  // torn
    const std::string_view line = records.substr(at, end - at + 1);
    at = end + 1;
    cell.clear();
    for (std::size_t from = 0;;) {
      const std::size_t comma = line.find(',', from);
      cell.push_back(line.substr(from, comma == std::string_view::npos ? line.size() - 1 - from : comma - from));
      if (comma == std::string_view::npos) break;
      from = comma + 1;
    }
    if (cell.size() != cells) break;
    auto flag = [](std::string_view c) { return c == "0" ? 0 : c == "1" ? 1 : -1; };
    SweepVerdict v;
    bool ok = true;
    const std::size_t c = axes.size();
    for (std::size_t m = 0; m < 3; ++m) {
      const int f = flag(cell[c + m]);
      ok = ok && f >= 0;
      v.linear[m] = f == 1;
    }
    const int lyapunov = flag(cell[c + 3]);
    ok = ok && lyapunov >= 0;
    v.lyapunov = lyapunov == 1;
    const auto certificate = std::find_if(std::begin(kCertificates), std::end(kCertificates),
                                          [&](LyapunovCertificate x) { return name(x) == cell[c + 4]; });
    ok = ok && certificate != std::end(kCertificates) && proves_stability(*certificate) == v.lyapunov;
    if (!ok) break;
    v.lyapunov_certificate = *certificate;
    if (nonlinear) {
      const int f = flag(cell[c + 5]);
      if (f < 0) break;
      v.nonlinear = f == 1;
    }
    if (tolerance) {
      const std::string_view t = cell[c + 6];
      double value = 0.0;
      const auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
      if (ec != std::errc() || p != t.data() + t.size()) break;
      v.nonlinear_tolerance = value;
    }
    if (sweep_csv_rows(axes, n, {v}, tolerance) != line) break;  // the varied values at their grid point, exactly
  }
  return n;
}

#ifndef HEAVYTOP_HAVE_HDF5
bool hdf5_available() { return false; }

void write_map_hdf5(const std::string&, const std::vector<SweepAxis>&, bool, const VerdictSource&, const std::string& key,
                    bool) {
  throw InvalidInput(key, "this heavytop was built without HDF5 (Debian's libhdf5-dev)");
}

StabilityMap read_map(const std::string& path, const std::string& key) {
  const std::string text = read_whole(path, key);
  if (text.starts_with("\x89HDF")) throw InvalidInput(key, fmt::format("'{}' is HDF5: this heavytop was built without HDF5", path));
  return read_map_csv(text, key);
}
#else
bool hdf5_available() { return true; }

void write_map_hdf5(const std::string& path, const std::vector<SweepAxis>& axes, bool nonlinear,
                    const VerdictSource& source, const std::string& key, bool tolerance) {
  tolerance = tolerance && nonlinear;
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // failures are reported as exceptions, not printed
  const std::string failed = fmt::format("{}: cannot write '{}' (HDF5)", key, path);
  const Handle file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
  if (file < 0) throw Failure(failed);
  // No modification times anywhere: the same map is the same bytes.
  const Handle create(H5Pcreate(H5P_OBJECT_CREATE), H5Pclose);
  const Handle group_create(H5Pcreate(H5P_GROUP_CREATE), H5Pclose);
  check(H5Pset_obj_track_times(group_create, false), failed);
  auto attribute = [&](hid_t on, const char* name, hid_t type, const void* value) {
    const Handle space(H5Screate(H5S_SCALAR), H5Sclose);
    const Handle a(H5Acreate2(on, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
    check(a < 0 ? -1 : H5Awrite(a, type, value), failed);
  };
  auto text_attribute = [&](hid_t on, const char* name, const std::string& value) {
    const Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(type, std::max<std::size_t>(1, value.size()));
    attribute(on, name, type, value.c_str());
  };
  const std::size_t points = grid_size(axes);
  const hsize_t size = points;
  auto dataset = [&](hid_t where, const char* name, hid_t type, hsize_t length) {
    const Handle space(H5Screate_simple(1, &length, nullptr), H5Sclose);
    const Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
    const hsize_t chunk = std::min<hsize_t>(length, 1 << 16);
    check(H5Pset_obj_track_times(dcpl, false), failed);
    check(H5Pset_chunk(dcpl, 1, &chunk), failed);
    check(H5Pset_deflate(dcpl, 4), failed);
    const hid_t d = H5Dcreate2(where, name, type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    if (d < 0) throw Failure(failed);
    return d;
  };
  text_attribute(file, "format", kFormatName);
  const std::uint64_t n_axes = axes.size();
  attribute(file, "axes", H5T_NATIVE_UINT64, &n_axes);
  {
    const Handle group(H5Gcreate2(file, "axes", H5P_DEFAULT, group_create, H5P_DEFAULT), H5Gclose);
    for (std::size_t k = 0; k < axes.size(); ++k) {
      std::vector<double> values;
      for (std::size_t i = 0; i < axes[k].count; ++i) values.push_back(axes[k].value(i));
      const Handle d(dataset(group, std::to_string(k).c_str(), H5T_IEEE_F64LE, values.size()), H5Dclose);
      check(H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), failed);
      text_attribute(d, "key", axes[k].key);
      const std::uint64_t count = axes[k].count;
      attribute(d, "start", H5T_NATIVE_DOUBLE, &axes[k].start);
      attribute(d, "stop", H5T_NATIVE_DOUBLE, &axes[k].stop);
      attribute(d, "count", H5T_NATIVE_UINT64, &count);
    }
  }
  const Handle certificates(certificate_type(), H5Tclose);
  std::vector<std::string> names(std::begin(kVerdictColumns), std::end(kVerdictColumns));
  names.emplace_back("lyapunov_certificate");
  if (nonlinear) names.emplace_back("nonlinear");
  std::vector<hid_t> columns;
  struct CloseAll {
    std::vector<hid_t>& ids;
    ~CloseAll() {
      for (hid_t id : ids) H5Dclose(id);
    }
  } close_all{columns};
  std::string shape;
  for (const auto& a : axes) shape += fmt::format("{}{}", shape.empty() ? "" : " ", a.count);
  for (const auto& n : names) {
    columns.push_back(dataset(file, n.c_str(), n == "lyapunov_certificate" ? hid_t(certificates) : H5T_STD_U8LE, size));
    text_attribute(columns.back(), "grid_shape", shape);
  }
  // sweep --tolerance-column: the rtol that decided each nonlinear verdict.
  const Handle tolerances(tolerance ? dataset(file, "nonlinear_tolerance", H5T_IEEE_F64LE, size) : H5I_INVALID_HID,
                          H5Dclose);
  if (tolerance) text_attribute(tolerances, "grid_shape", shape);
  std::vector<double> rtols;
  std::vector<std::uint8_t> buffer;
  for (std::size_t begin = 0; begin < points; begin += kRowsPerBlock) {
    const std::size_t end = std::min(points, begin + kRowsPerBlock);
    const std::vector<SweepVerdict> verdicts = source(begin, end);
    if (verdicts.size() != end - begin) throw Failure(failed);
    const hsize_t start = begin, count = end - begin;
    const Handle memory(H5Screate_simple(1, &count, nullptr), H5Sclose);
    for (std::size_t c = 0; c < columns.size(); ++c) {
      buffer.resize(count);
      for (std::size_t i = 0; i < count; ++i) {
        const SweepVerdict& v = verdicts[i];
        buffer[i] = c < 3 ? v.linear[c] : c == 3 ? v.lyapunov : c == 4 ? std::uint8_t(v.lyapunov_certificate)
                                                                        : std::uint8_t(v.nonlinear.value_or(false));
      }
      const Handle file_space(H5Dget_space(columns[c]), H5Sclose);
      check(H5Sselect_hyperslab(file_space, H5S_SELECT_SET, &start, nullptr, &count, nullptr), failed);
      check(H5Dwrite(columns[c], c == 4 ? hid_t(certificates) : H5T_NATIVE_UINT8, memory, file_space, H5P_DEFAULT,
                     buffer.data()),
            failed);
    }
    if (tolerance) {
      rtols.resize(count);
      for (std::size_t i = 0; i < count; ++i) rtols[i] = verdicts[i].nonlinear_tolerance.value_or(std::nan(""));
      const Handle file_space(H5Dget_space(tolerances), H5Sclose);
      check(H5Sselect_hyperslab(file_space, H5S_SELECT_SET, &start, nullptr, &count, nullptr), failed);
      check(H5Dwrite(tolerances, H5T_NATIVE_DOUBLE, memory, file_space, H5P_DEFAULT, rtols.data()), failed);
    }
  }
  check(H5Fflush(file, H5F_SCOPE_LOCAL), failed);
}

namespace {

/// The HDF5 map read in this process (read_map runs it in a child).
StabilityMap read_map_hdf5(const std::string& path, const std::string& key, std::uintmax_t file_size) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const std::string bad = fmt::format("'{}' is not a heavytop map file", printable(path));
  if (const std::string heap = oversized_heap(path, file_size); !heap.empty())
    throw InvalidInput(key, fmt::format("{} ({})", bad, heap));
  const Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (file < 0) throw InvalidInput(key, bad + " (HDF5 cannot open it)");
  // Every attribute heavytop reads is one value (H5Aread writes the whole dataspace into the
  // buffer given) and its text at most kMaxText bytes (the buffer is sized from the file).
  constexpr std::size_t kMaxText = 256;
  auto open_attribute = [&](hid_t on, const char* name) {
    const hid_t a = H5Aopen(on, name, H5P_DEFAULT);
    if (a < 0) throw InvalidInput(key, fmt::format("{} (attribute '{}')", bad, name));
    const Handle space(H5Aget_space(a), H5Sclose);
    if (space < 0 || H5Sget_simple_extent_npoints(space) != 1) {
      H5Aclose(a);
      throw InvalidInput(key, fmt::format("{} (attribute '{}' is not one value)", bad, name));
    }
    return a;
  };
  auto read_attribute = [&](hid_t on, const char* name, hid_t type, void* value) {
    const Handle a(open_attribute(on, name), H5Aclose);
    if (H5Aread(a, type, value) < 0) throw InvalidInput(key, fmt::format("{} (attribute '{}')", bad, name));
  };
  auto read_text = [&](hid_t on, const char* name) {
    const Handle a(open_attribute(on, name), H5Aclose);
    const Handle type(H5Aget_type(a), H5Tclose);
    if (type < 0 || H5Tget_class(type) != H5T_STRING || H5Tis_variable_str(type) != 0 || H5Tget_size(type) > kMaxText)
      throw InvalidInput(key, fmt::format("{} (attribute '{}')", bad, name));
    std::string value(H5Tget_size(type), '\0');
    if (H5Aread(a, type, value.data()) < 0) throw InvalidInput(key, fmt::format("{} (attribute '{}')", bad, name));
    return value.substr(0, value.find('\0'));
  };
  if (read_text(file, "format") != kFormatName) throw InvalidInput(key, bad + " (its format attribute)");
  std::uint64_t n_axes = 0;
  read_attribute(file, "axes", H5T_NATIVE_UINT64, &n_axes);
  if (n_axes < 1 || n_axes > kMaxSweepAxes) throw InvalidInput(key, bad + " (1 to 3 axes)");
  // What libhdf5 allocates while it reads a dataset is sized by the file's metadata: the
  // chunk (its dimension in the layout), each chunk's stored bytes (the chunk index) and what
  // the filters make of them. A corrupted map asked for gigabytes (fuzz_map, issue 30), so
  // each is checked against what heavytop writes (one dimension, chunks of at most 2^16
  // elements, deflate only) and against the file's size before H5Dread.
  constexpr hsize_t kMaxChunk = 1 << 16;
  constexpr std::uintmax_t kDeflateRatio = 1032;  // zlib's largest expansion, output/input
  auto read_column = [&](const std::string& name, hid_t memory_type, std::size_t expected, auto& out) {
    using Element = typename std::decay_t<decltype(out)>::value_type;
    const auto layout = [&](const std::string& what) {
      return InvalidInput(key, fmt::format("{} (dataset '{}' {})", bad, name, what));
    };
    const Handle d(H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose);
    if (d < 0) throw InvalidInput(key, fmt::format("{} (no dataset '{}')", bad, name));
    const Handle space(H5Dget_space(d), H5Sclose);
    if (H5Sget_simple_extent_ndims(space) != 1 || H5Sget_simple_extent_npoints(space) != hssize_t(expected))
      throw InvalidInput(key, fmt::format("{} (dataset '{}' must have {} elements)", bad, name, expected));
    // Its elements cannot be more than the file's bytes can hold, deflated.
    if (expected * sizeof(Element) > kDeflateRatio * file_size + kMaxChunk)
      throw layout(fmt::format("has more elements than a file of {} bytes can hold", file_size));
    // Only the layout and the element size heavytop writes (chunked, 8-byte axes, 1-byte
    // verdicts) reach H5Dread: a mutated compact layout made HDF5 read past its own buffer
    // (fuzz_map, issue 30), which HDF5 does not check.
    const Handle create(H5Dget_create_plist(d), H5Pclose);
    const Handle type(H5Dget_type(d), H5Tclose);
    if (create < 0 || H5Pget_layout(create) != H5D_CHUNKED || type < 0 || H5Tget_size(type) != sizeof(Element))
      throw layout("is not laid out as heavytop writes it");
    hsize_t chunk = 0;
    if (H5Pget_chunk(create, 1, &chunk) != 1 || chunk < 1 || chunk > std::min<hsize_t>(expected, kMaxChunk))
      throw layout("has a chunk size heavytop does not write");
    const int filters = H5Pget_nfilters(create);
    for (int f = 0; f < filters; ++f) {
      unsigned flags = 0, config = 0;
      std::size_t values = 0;
      if (H5Pget_filter2(create, static_cast<unsigned>(f), &flags, &values, nullptr, 0, nullptr, &config) !=
          H5Z_FILTER_DEFLATE)
        throw layout("has a filter heavytop does not write");
    }
    if (filters < 0 || filters > 1) throw layout("has a filter heavytop does not write");
    // Every chunk written, inside the file, no larger than the file (H5Dread allocates a
    // chunk's stored size before it reads it).
    hsize_t chunks = 0;
    if (H5Dget_num_chunks(d, space, &chunks) < 0 || chunks != (expected + chunk - 1) / chunk)
      throw layout("is not written whole");
    for (hsize_t c = 0; c < chunks; ++c) {
      hsize_t offset = 0, stored = 0;
      haddr_t address = 0;
      unsigned mask = 0;
      if (H5Dget_chunk_info(d, space, c, &offset, &mask, &address, &stored) < 0 || mask != 0 || stored < 1 ||
          address == HADDR_UNDEF || address > file_size || stored > file_size - address)
        throw layout("has a chunk outside the file");
    }
    out.resize(expected);
    if (H5Dread(d, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
      throw InvalidInput(key, fmt::format("{} (dataset '{}' cannot be read)", bad, name));
  };
  StabilityMap map;
  std::size_t points = 1;
  std::vector<std::string> keys;
  for (std::uint64_t k = 0; k < n_axes; ++k) {
    const std::string name = fmt::format("axes/{}", k);
    const Handle d(H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose);
    if (d < 0) throw InvalidInput(key, fmt::format("{} (no dataset '{}')", bad, name));
    std::uint64_t count = 0;
    read_attribute(d, "count", H5T_NATIVE_UINT64, &count);
    if (count < 1 || count > kMaxSweepPoints) throw InvalidInput(key, bad + " (an axis' count)");
    MapAxis axis{.key = read_text(d, "key"), .values = {}};
    check_axis_key(axis.key, keys, key);
    keys.push_back(axis.key);
    read_column(name, H5T_NATIVE_DOUBLE, count, axis.values);
    points *= count;
    if (points > kMaxSweepPoints) throw InvalidInput(key, bad + " (too many points)");
    map.axes.push_back(std::move(axis));
  }
  const Handle nonlinear_set(H5Dopen2(file, "nonlinear", H5P_DEFAULT), H5Dclose);
  map.nonlinear = nonlinear_set >= 0;
  std::vector<std::uint8_t> column;
  map.verdicts.resize(points);
  const Handle certificates(certificate_type(), H5Tclose);
  for (std::size_t c = 0; c < 5u + map.nonlinear; ++c) {
    const std::string name = c < 4 ? std::string(kVerdictColumns[c]) : c == 4 ? "lyapunov_certificate" : "nonlinear";
    read_column(name, c == 4 ? hid_t(certificates) : H5T_NATIVE_UINT8, points, column);
    for (std::size_t i = 0; i < points; ++i) {
      if (column[i] > (c == 4 ? std::uint8_t(kLastLyapunovCertificate) : 1))
        throw InvalidInput(key, fmt::format("{} (dataset '{}': a value out of range)", bad, name));
      SweepVerdict& v = map.verdicts[i];
      if (c < 3) v.linear[c] = column[i];
      else if (c == 3) v.lyapunov = column[i];
      else if (c == 4) v.lyapunov_certificate = static_cast<LyapunovCertificate>(column[i]);
      else v.nonlinear = column[i] == 1;
    }
  }
  return map;
}

/// A map as bytes through the pipe from the child: for each axis its key's length, key, count
/// and values; the nonlinear flag; the packed verdicts (pack_verdicts).
template <class T>
void put(std::string& out, T value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}
template <class T>
T take(std::string_view& in) {
  if (in.size() < sizeof(T)) throw Failure("read_map: the reading process sent a torn map");
  T value;
  std::memcpy(&value, in.data(), sizeof value);
  in.remove_prefix(sizeof value);
  return value;
}

std::string pack_map(const StabilityMap& map) {
  std::string out;
  put<std::uint64_t>(out, map.axes.size());
  for (const MapAxis& axis : map.axes) {
    put<std::uint64_t>(out, axis.key.size());
    out += axis.key;
    put<std::uint64_t>(out, axis.values.size());
    for (double v : axis.values) put(out, v);
  }
  put<std::uint8_t>(out, map.nonlinear);
  pack_verdicts(map.verdicts, out);
  return out;
}

StabilityMap unpack_map(std::string_view in) {
  StabilityMap map;
  map.axes.resize(take<std::uint64_t>(in));
  for (MapAxis& axis : map.axes) {
    const auto length = take<std::uint64_t>(in);
    if (length > in.size()) throw Failure("read_map: the reading process sent a torn map");
    axis.key = std::string(in.substr(0, length));
    in.remove_prefix(length);
    const auto count = take<std::uint64_t>(in);
    if (count > in.size() / sizeof(double)) throw Failure("read_map: the reading process sent a torn map");
    axis.values.resize(count);
    for (double& v : axis.values) v = take<double>(in);
  }
  map.nonlinear = take<std::uint8_t>(in) != 0;
  map.verdicts = unpack_verdicts(in);
  return map;
}

}  // namespace

StabilityMap read_map(const std::string& path, const std::string& key) {
  const std::uintmax_t file_size = map_file_size(path, key);
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) throw InvalidInput(key, fmt::format("cannot read '{}'", printable(path)));
    char magic[4] = {};
    probe.read(magic, 4);
    if (std::string_view(magic, 4) != "\x89HDF") return read_map_csv(read_whole(path, key), key);
  }
  // libhdf5 trusts a file's metadata (fuzz_map, issue 30: an attribute's name without its NUL
  // made it read past its buffer in H5O_attr_shared_decode; a heap's size asked malloc for
  // 2^49 bytes). heavytop checks what it can (oversized_heap, the attributes, the layout and
  // the chunks) and reads the map in a child process, so whatever libhdf5 does on a corrupted
  // file stays there: the parent receives the map or the refusal, or refuses the file the
  // child died on.
  int channel[2];
  if (::pipe(channel) != 0) throw Failure(fmt::format("{}: cannot read '{}' (no pipe)", key, printable(path)));
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(channel[0]);
    ::close(channel[1]);
    throw Failure(fmt::format("{}: cannot read '{}' (no process)", key, printable(path)));
  }
  if (child == 0) {
#ifdef HEAVYTOP_SANITIZED_CHILD
    // A sanitizer's report in the child is the refusal below, not the caller's crash: the death
    // callback the caller set (libFuzzer's, which saves the input as a crash) is not run here.
    __sanitizer_set_death_callback(+[] { ::_exit(6); });
    // Its reports go where scripts/sanitize.sh keeps them apart (they are libhdf5's, on
    // corrupted files the parent refuses; the script checks that each one is inside libhdf5).
    if (const char* path = std::getenv("HEAVYTOP_CHILD_REPORT_PATH")) __sanitizer_set_report_path(path);
#endif
    ::close(channel[0]);
    std::string out;
    int status = 0;
    try {
      out = pack_map(read_map_hdf5(path, key, file_size));
    } catch (const InvalidInput& e) {
      out = e.rule();
      status = 3;
    } catch (...) {
      status = 4;
    }
    for (std::size_t at = 0; at < out.size();) {
      const ssize_t n = ::write(channel[1], out.data() + at, out.size() - at);
      if (n <= 0 && errno != EINTR) ::_exit(5);
      if (n > 0) at += static_cast<std::size_t>(n);
    }
    ::_exit(status);
  }
  ::close(channel[1]);
  std::string received;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(channel[0], buffer, sizeof buffer);
    if (n > 0) received.append(buffer, static_cast<std::size_t>(n));
    else if (n == 0 || errno != EINTR) break;
  }
  ::close(channel[0]);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    try {
      return unpack_map(received);
    } catch (const Failure&) {
    }
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 3 && received.find_first_of("\n\r") == std::string::npos)
    throw InvalidInput(key, received);
  throw InvalidInput(key, fmt::format("'{}' is not a heavytop map file (libhdf5 failed on it)", printable(path)));
}
#endif

}  // namespace heavytop::io
