// HDF5 and CSV time-series files (see timeseries_file.h for the layout).
//
// Choices that matter for users:
// - Default (earliest) HDF5 file format: readable by HDF5 1.8 (older MATLAB releases) and, unlike the 1.10 "latest"
//   format, it does not mark the superblock "open for writing", so a file whose writer crashed opens without
//   running h5clear first.
// - The metadata cache is configured never to evict, so HDF5 writes metadata only in H5Fflush/H5Fclose, and the
//   chunks are not compressed, so a chunk rewritten between flushes keeps its address. Together these keep the
//   on-disk file equal to the state of the last flush until the next one, whenever the process dies. (The files
//   are 8 bytes per value: 80,000 rows x 40 channels is 26 MB.)
#include "model/io/timeseries_file.h"
#include "model/io/output_file.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <fstream>
#include <system_error>
#include <utility>

#include <hdf5.h>

namespace turbodyn {
namespace {

constexpr std::size_t kMaxChannelNameLength = 255;
constexpr const char* kProbesGroup = "probes";
constexpr const char* kTimeDataset = "time";
constexpr const char* kCompleteAttribute = "complete";
constexpr const char* kSoftwareAttribute = "software";

std::string quoted(const std::filesystem::path& file) { return "'" + file.string() + "'"; }

// Turns HDF5's automatic error printing off for this thread (the library is built thread-safe, where error state is
// per thread) while our code reports errors itself; restores whatever was installed before.
class QuietHdf5 {
 public:
  QuietHdf5() {
    if (H5Eget_auto2(H5E_DEFAULT, &func_, &data_) < 0) {
      func_ = nullptr;
      data_ = nullptr;
      restore_ = false;
    }
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietHdf5() {
    if (restore_) H5Eset_auto2(H5E_DEFAULT, func_, data_);
  }
  QuietHdf5(const QuietHdf5&) = delete;
  QuietHdf5& operator=(const QuietHdf5&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
  bool restore_ = true;
};

herr_t append_error(unsigned n, const H5E_error2_t* error, void* client_data) {
  auto& text = *static_cast<std::string*>(client_data);
  if (n > 0) text += "; ";
  text += error->func_name != nullptr ? error->func_name : "?";
  text += "(): ";
  // Some descriptions carry a ctime() date with its own line end: keep the message on one line.
  for (const char* c = error->desc != nullptr ? error->desc : ""; *c != '\0'; ++c)
    if (*c != '\n' && *c != '\r') text += *c;
  char minor[160];
  if (H5Eget_msg(error->min_num, nullptr, minor, sizeof minor) > 0) {
    text += " [";
    text += minor;
    text += "]";
  }
  return 0;
}

// The current thread's HDF5 error stack as one line, API call first; clears it.
std::string hdf5_error_stack() {
  std::string text;
  const hid_t stack = H5Eget_current_stack();
  if (stack >= 0) {
    H5Ewalk2(stack, H5E_WALK_DOWNWARD, append_error, &text);
    H5Eclose_stack(stack);
  }
  return text.empty() ? "(HDF5 reported no error stack)" : text;
}

[[noreturn]] void throw_hdf5(const std::string& context, const std::string& what) {
  throw TimeSeriesError(context + ": " + what + " (HDF5: " + hdf5_error_stack() + ")");
}

void check(herr_t status, const std::string& context, const char* what) {
  if (status < 0) throw_hdf5(context, what);
}

// Owns one HDF5 identifier.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(Handle&& other) noexcept
      : id_(std::exchange(other.id_, H5I_INVALID_HID)), closer_(other.closer_) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      close();
      id_ = std::exchange(other.id_, H5I_INVALID_HID);
      closer_ = other.closer_;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { close(); }

  hid_t get() const { return id_; }
  /// Closes now; returns HDF5's status (< 0: the close failed, e.g. a final write).
  herr_t close() noexcept {
    herr_t status = 0;
    if (id_ >= 0 && closer_ != nullptr) status = closer_(id_);
    id_ = H5I_INVALID_HID;
    return status;
  }

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer closer_ = nullptr;
};

Handle checked(hid_t id, Handle::Closer closer, const std::string& context, const char* what) {
  if (id < 0) throw_hdf5(context, what);
  return Handle(id, closer);
}

Handle utf8_string_type(const std::string& context) {
  Handle type = checked(H5Tcopy(H5T_C_S1), H5Tclose, context, "H5Tcopy failed");
  check(H5Tset_size(type.get(), H5T_VARIABLE), context, "H5Tset_size failed");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), context, "H5Tset_cset failed");
  return type;
}

// Creates (replacing any old one) scalar attribute `name` of `location` with file type `file_type`.
Handle create_attribute(hid_t location, const std::string& name, hid_t file_type, const std::string& context) {
  const std::string what = "cannot create attribute '" + name + "'";
  const htri_t exists = H5Aexists(location, name.c_str());
  if (exists < 0) throw_hdf5(context, what);
  if (exists > 0) check(H5Adelete(location, name.c_str()), context, what.c_str());
  Handle space = checked(H5Screate(H5S_SCALAR), H5Sclose, context, what.c_str());
  return checked(H5Acreate2(location, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                 context, what.c_str());
}

void write_string_attribute(hid_t location, const std::string& name, const std::string& value,
                            const std::string& context) {
  Handle type = utf8_string_type(context);
  Handle attribute = create_attribute(location, name, type.get(), context);
  const char* text = value.c_str();
  check(H5Awrite(attribute.get(), type.get(), &text), context, "cannot write a string attribute");
}

void write_number_attribute(hid_t location, const std::string& name, double value, const std::string& context) {
  Handle attribute = create_attribute(location, name, H5T_IEEE_F64LE, context);
  check(H5Awrite(attribute.get(), H5T_NATIVE_DOUBLE, &value), context, "cannot write a number attribute");
}

void write_complete_attribute(hid_t file, bool complete, const std::string& context) {
  Handle attribute = checked(H5Aopen(file, kCompleteAttribute, H5P_DEFAULT), H5Aclose, context,
                             "cannot open attribute 'complete'");
  const int value = complete ? 1 : 0;
  check(H5Awrite(attribute.get(), H5T_NATIVE_INT, &value), context, "cannot write attribute 'complete'");
}

// A friendlier reason than HDF5's stack for the usual cause of a failed create.
std::string missing_directory_reason(const std::filesystem::path& file) {
  const std::filesystem::path parent = file.parent_path();
  std::error_code ec;
  if (!parent.empty() && !std::filesystem::is_directory(parent, ec))
    return "directory " + quoted(parent) + " does not exist";
  return "";
}

bool valid_name_character(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '_' ||
         c == '-';
}

std::string printable(char c) {
  if (static_cast<unsigned char>(c) >= 0x20 && static_cast<unsigned char>(c) < 0x7f) return std::string("'") + c + "'";
  char text[8];
  std::snprintf(text, sizeof text, "0x%02x", static_cast<unsigned>(static_cast<unsigned char>(c)));
  return text;
}

}  // namespace

void validate_channels(const std::vector<Channel>& channels, const std::string& context) {
  std::map<std::string, std::size_t> seen;
  for (std::size_t i = 0; i < channels.size(); ++i) {
    const std::string& name = channels[i].name;
    const std::string where = context + ": channel " + std::to_string(i);
    if (name.empty()) throw TimeSeriesError(where + " has an empty name");
    if (name.size() > kMaxChannelNameLength)
      throw TimeSeriesError(where + " name is longer than " + std::to_string(kMaxChannelNameLength) + " characters");
    for (char c : name)
      if (!valid_name_character(c))
        throw TimeSeriesError(where + " name '" + name + "' contains " + printable(c) +
                              "; allowed are letters, digits, '.', '_' and '-'");
    if (name.front() == '.' || name.front() == '-')
      throw TimeSeriesError(where + " name '" + name + "' must start with a letter, a digit or '_'");
    const auto [it, inserted] = seen.emplace(name, i);
    if (!inserted)
      throw TimeSeriesError(context + ": duplicate channel name '" + name + "' (channels " +
                            std::to_string(it->second) + " and " + std::to_string(i) + ")");
  }
}

// ---------------------------------------------------------------------------------------------------------------
// Writer

struct Hdf5TimeSeriesWriter::Impl {
  std::filesystem::path path;
  std::string context;  // "time-series file '<path>'", starts every message
  std::vector<Channel> channels;
  std::size_t buffer_rows = 0;

  Handle file;
  Handle probes;
  Handle time_dataset;
  std::vector<Handle> probe_datasets;  // in channel order
  Handle block_space;                  // memory dataspace of a full buffer

  std::vector<double> time_buffer;   // dim buffer_rows
  std::vector<double> value_buffer;  // channel c, row i at c * buffer_rows + i
  std::size_t rows_on_disk = 0;
  std::size_t rows_buffered = 0;

  bool open = false;
  bool finished = false;
  std::string failure;  // the message of the write error that stopped the writer

  void create();
  void create_dataset(hid_t location, const char* name, const std::string& unit, const std::string& description,
                      Handle& dataset);
  void write_block();
  void write_and_flush();
  herr_t close_all() noexcept;
  [[noreturn]] void throw_unusable(const char* call) const;
  // Before set_attribute: the file is usable and `name` is not empty and not one the writer keeps for itself.
  void check_attribute_name(const std::string& name) const {
    if (!open || !failure.empty()) throw_unusable("set_attribute()");
    if (name.empty()) throw TimeSeriesError(context + ": attribute names must not be empty");
    if (name == kCompleteAttribute || name == kSoftwareAttribute)
      throw TimeSeriesError(context + ": attribute name '" + name + "' is reserved");
  }
};

void Hdf5TimeSeriesWriter::Impl::create_dataset(hid_t location, const char* name, const std::string& unit,
                                                const std::string& description, Handle& dataset) {
  const std::string what = std::string("cannot create dataset '") + name + "'";
  const hsize_t initial = 0, maximum = H5S_UNLIMITED, chunk = kTimeSeriesChunkRows;
  Handle space = checked(H5Screate_simple(1, &initial, &maximum), H5Sclose, context, what.c_str());
  Handle dcpl = checked(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, context, what.c_str());
  check(H5Pset_chunk(dcpl.get(), 1, &chunk), context, what.c_str());
  dataset = checked(H5Dcreate2(location, name, H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
                    H5Dclose, context, what.c_str());
  write_string_attribute(dataset.get(), "unit", unit, context);
  write_string_attribute(dataset.get(), "description", description, context);
}

void Hdf5TimeSeriesWriter::Impl::create() {
  Handle fapl = checked(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, context, "H5Pcreate failed");
  H5AC_cache_config_t cache{};
  cache.version = H5AC__CURR_CACHE_CONFIG_VERSION;
  check(H5Pget_mdc_config(fapl.get(), &cache), context, "H5Pget_mdc_config failed");
  cache.evictions_enabled = false;  // metadata reaches the file only in H5Fflush / H5Fclose (see top of file)
  cache.incr_mode = H5C_incr__off;
  cache.flash_incr_mode = H5C_flash_incr__off;
  cache.decr_mode = H5C_decr__off;
  check(H5Pset_mdc_config(fapl.get(), &cache), context, "H5Pset_mdc_config failed");

  remove_symlink(path);  // a link at the path is replaced, not written through
  const hid_t id = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get());
  if (id < 0) {
    const std::string reason = missing_directory_reason(path);
    if (!reason.empty()) {
      hdf5_error_stack();  // clears it
      throw TimeSeriesError(context + ": cannot create the file: " + reason);
    }
    throw_hdf5(context, "cannot create the file");
  }
  file = Handle(id, H5Fclose);

  {
    Handle complete = create_attribute(file.get(), kCompleteAttribute, H5T_STD_I32LE, context);
    const int zero = 0;
    check(H5Awrite(complete.get(), H5T_NATIVE_INT, &zero), context, "cannot write attribute 'complete'");
  }
  write_string_attribute(file.get(), kSoftwareAttribute, "turbodyn", context);

  create_dataset(file.get(), kTimeDataset, "s", "simulated time", time_dataset);

  Handle gcpl = checked(H5Pcreate(H5P_GROUP_CREATE), H5Pclose, context, "H5Pcreate failed");
  check(H5Pset_link_creation_order(gcpl.get(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED), context,
        "H5Pset_link_creation_order failed");
  probes = checked(H5Gcreate2(file.get(), kProbesGroup, H5P_DEFAULT, gcpl.get(), H5P_DEFAULT), H5Gclose, context,
                   "cannot create group '/probes'");
  probe_datasets.resize(channels.size());
  for (std::size_t c = 0; c < channels.size(); ++c)
    create_dataset(probes.get(), channels[c].name.c_str(), channels[c].unit, channels[c].description,
                   probe_datasets[c]);

  const hsize_t block = buffer_rows;
  block_space = checked(H5Screate_simple(1, &block, nullptr), H5Sclose, context, "H5Screate_simple failed");
  check(H5Fflush(file.get(), H5F_SCOPE_LOCAL), context, "H5Fflush failed");
}

void Hdf5TimeSeriesWriter::Impl::write_block() {
  if (rows_buffered == 0) return;
  const hsize_t start = rows_on_disk, count = rows_buffered, new_size = rows_on_disk + rows_buffered;
  const hsize_t memory_start = 0;
  check(H5Sselect_hyperslab(block_space.get(), H5S_SELECT_SET, &memory_start, nullptr, &count, nullptr), context,
        "H5Sselect_hyperslab failed");
  auto write = [&](hid_t dataset, const double* data, const std::string* channel_name) {
    auto fail = [&](const char* call) {
      throw_hdf5(context, std::string(call) + " failed on '" +
                              (channel_name != nullptr ? "/probes/" + *channel_name : std::string("/time")) + "'");
    };
    if (H5Dset_extent(dataset, &new_size) < 0) fail("H5Dset_extent");
    Handle file_space(H5Dget_space(dataset), H5Sclose);
    if (file_space.get() < 0) fail("H5Dget_space");
    if (H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, &start, nullptr, &count, nullptr) < 0)
      fail("H5Sselect_hyperslab");
    if (H5Dwrite(dataset, H5T_NATIVE_DOUBLE, block_space.get(), file_space.get(), H5P_DEFAULT, data) < 0)
      fail("H5Dwrite");
  };
  for (std::size_t c = 0; c < channels.size(); ++c)
    write(probe_datasets[c].get(), value_buffer.data() + c * buffer_rows, &channels[c].name);
  // Time last: should the process die inside this loop, the time axis is never longer than any channel.
  write(time_dataset.get(), time_buffer.data(), nullptr);
  rows_on_disk += rows_buffered;
  rows_buffered = 0;
}

void Hdf5TimeSeriesWriter::Impl::write_and_flush() {
  QuietHdf5 quiet;
  try {
    write_block();
    check(H5Fflush(file.get(), H5F_SCOPE_LOCAL), context, "H5Fflush failed");
  } catch (const TimeSeriesError& e) {
    failure = e.what();
    throw;
  }
}

herr_t Hdf5TimeSeriesWriter::Impl::close_all() noexcept {
  herr_t status = 0;
  for (Handle& dataset : probe_datasets) status = std::min(status, dataset.close());
  status = std::min(status, time_dataset.close());
  status = std::min(status, probes.close());
  block_space.close();
  status = std::min(status, file.close());
  open = false;
  return status;
}

void Hdf5TimeSeriesWriter::Impl::throw_unusable(const char* call) const {
  if (finished) throw TimeSeriesError(context + ": " + call + " after finish()");
  throw TimeSeriesError(context + ": " + call + " on a writer stopped by an earlier error: " + failure);
}

Hdf5TimeSeriesWriter::Hdf5TimeSeriesWriter(const std::filesystem::path& file, std::vector<Channel> channels,
                                           std::size_t buffer_rows)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.path = file;
  m.context = "time-series file " + quoted(file);
  validate_channels(channels, m.context);
  if (buffer_rows == 0) throw TimeSeriesError(m.context + ": buffer_rows must be at least 1");
  m.channels = std::move(channels);
  m.buffer_rows = buffer_rows;
  m.time_buffer.assign(buffer_rows, 0.0);
  m.value_buffer.assign(buffer_rows * m.channels.size(), 0.0);
  QuietHdf5 quiet;
  try {
    m.create();
  } catch (...) {
    m.close_all();
    throw;
  }
  m.open = true;
}

Hdf5TimeSeriesWriter::~Hdf5TimeSeriesWriter() {
  if (!impl_ || !impl_->open) return;
  try {
    if (impl_->failure.empty()) impl_->write_and_flush();
  } catch (...) {  // a destructor must not throw; what could be written was written
  }
  QuietHdf5 quiet;
  impl_->close_all();
}

void Hdf5TimeSeriesWriter::append(double time, const double* values) {
  Impl& m = *impl_;
  if (!m.open || !m.failure.empty()) m.throw_unusable("append()");
  const std::size_t row = m.rows_buffered;
  m.time_buffer[row] = time;
  double* column = m.value_buffer.data() + row;
  for (std::size_t c = 0, n = m.channels.size(); c < n; ++c, column += m.buffer_rows) *column = values[c];
  if (++m.rows_buffered == m.buffer_rows) m.write_and_flush();
}

void Hdf5TimeSeriesWriter::flush() {
  Impl& m = *impl_;
  if (!m.open || !m.failure.empty()) m.throw_unusable("flush()");
  m.write_and_flush();
}

void Hdf5TimeSeriesWriter::set_attribute(const std::string& name, const std::string& value) {
  Impl& m = *impl_;
  m.check_attribute_name(name);
  QuietHdf5 quiet;
  write_string_attribute(m.file.get(), name, value, m.context);
}

void Hdf5TimeSeriesWriter::set_attribute(const std::string& name, double value) {
  Impl& m = *impl_;
  m.check_attribute_name(name);
  QuietHdf5 quiet;
  write_number_attribute(m.file.get(), name, value, m.context);
}

void Hdf5TimeSeriesWriter::finish(bool complete) {
  Impl& m = *impl_;
  if (!m.open) m.throw_unusable("finish()");
  std::string error;
  if (!m.failure.empty()) {
    // The data are already incomplete; closing as incomplete is what the caller wants, marking complete is not.
    if (complete) error = m.context + ": finish(true) on a writer stopped by an earlier error: " + m.failure;
  } else {
    try {
      m.write_and_flush();  // data on disk before the flag says complete
      QuietHdf5 quiet;
      write_complete_attribute(m.file.get(), complete, m.context);
    } catch (const TimeSeriesError& e) {
      error = e.what();
    }
  }
  QuietHdf5 quiet;
  const herr_t closed = m.close_all();
  m.finished = true;
  if (!error.empty()) throw TimeSeriesError(error);
  if (closed < 0) throw_hdf5(m.context, "closing the file failed");
}

std::size_t Hdf5TimeSeriesWriter::rows() const { return impl_->rows_on_disk + impl_->rows_buffered; }
const std::vector<Channel>& Hdf5TimeSeriesWriter::channels() const { return impl_->channels; }
const std::filesystem::path& Hdf5TimeSeriesWriter::file() const { return impl_->path; }
bool Hdf5TimeSeriesWriter::is_open() const { return impl_->open && impl_->failure.empty(); }

// ---------------------------------------------------------------------------------------------------------------
// CSV

std::string csv_column_name(const Channel& channel) {
  std::string unit;
  for (char c : channel.unit) {
    switch (c) {
      case '/': unit += "_per_"; break;
      case '*': unit += '_'; break;
      case '^': break;
      case ',': case '"': case ' ': case '\t': case '\r': case '\n': unit += '_'; break;
      default: unit += c;
    }
  }
  return unit.empty() ? channel.name : channel.name + "_" + unit;
}

void write_csv(const std::filesystem::path& file, const std::vector<Channel>& channels,
               const std::vector<double>& time, const std::vector<std::vector<double>>& columns) {
  const std::string context = "CSV file " + quoted(file);
  validate_channels(channels, context);
  if (columns.size() != channels.size())
    throw TimeSeriesError(context + ": " + std::to_string(channels.size()) + " channels but " +
                          std::to_string(columns.size()) + " columns");
  for (std::size_t c = 0; c < columns.size(); ++c)
    if (columns[c].size() != time.size())
      throw TimeSeriesError(context + ": column " + std::to_string(c) + " ('" + channels[c].name + "') has " +
                            std::to_string(columns[c].size()) + " rows, time has " + std::to_string(time.size()));

  remove_symlink(file);
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  if (!out) {
    const int error = errno;
    std::string reason = missing_directory_reason(file);
    if (reason.empty()) reason = std::error_code(error, std::generic_category()).message();
    throw TimeSeriesError(context + ": cannot create the file: " + reason);
  }

  std::string text = "time_s";
  for (const Channel& channel : channels) text += "," + csv_column_name(channel);
  text += '\n';
  constexpr std::size_t kWriteBytes = 1 << 20;
  text.reserve(kWriteBytes + 32 * (channels.size() + 1));
  auto put = [&text](double value) {
    char number[32];
    // Same text as printf("%.17g") in the "C" locale, whatever the current locale: round-trips every double.
    const auto result = std::to_chars(number, number + sizeof number, value, std::chars_format::general, 17);
    text.append(number, result.ptr);
  };
  for (std::size_t row = 0; row < time.size(); ++row) {
    put(time[row]);
    for (const std::vector<double>& column : columns) {
      text += ',';
      put(column[row]);
    }
    text += '\n';
    if (text.size() >= kWriteBytes) {
      out.write(text.data(), static_cast<std::streamsize>(text.size()));
      text.clear();
    }
  }
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.close();
  if (!out) throw TimeSeriesError(context + ": writing failed (disk full?)");
}

// ---------------------------------------------------------------------------------------------------------------
// Reader

namespace {

struct AttributeValue {
  enum class Kind { Other, String, Number } kind = Kind::Other;
  std::string text;
  double number = 0.0;
};

// Reads a single-valued string or numeric attribute; anything else (arrays, compounds...) gives Kind::Other.
AttributeValue read_attribute(hid_t location, const std::string& name, const std::string& context) {
  const std::string what = "cannot read attribute '" + name + "'";
  Handle attribute = checked(H5Aopen(location, name.c_str(), H5P_DEFAULT), H5Aclose, context, what.c_str());
  Handle type = checked(H5Aget_type(attribute.get()), H5Tclose, context, what.c_str());
  Handle space = checked(H5Aget_space(attribute.get()), H5Sclose, context, what.c_str());
  AttributeValue value;
  if (H5Sget_simple_extent_npoints(space.get()) != 1) return value;
  const H5T_class_t type_class = H5Tget_class(type.get());
  if (type_class == H5T_STRING) {
    Handle memory = checked(H5Tcopy(H5T_C_S1), H5Tclose, context, what.c_str());
    check(H5Tset_cset(memory.get(), H5Tget_cset(type.get())), context, what.c_str());
    const htri_t variable = H5Tis_variable_str(type.get());
    if (variable < 0) throw_hdf5(context, what);
    if (variable > 0) {
      check(H5Tset_size(memory.get(), H5T_VARIABLE), context, what.c_str());
      char* text = nullptr;
      check(H5Aread(attribute.get(), memory.get(), &text), context, what.c_str());
      value.text = text != nullptr ? text : "";
      H5free_memory(text);
    } else {
      const std::size_t size = H5Tget_size(type.get());
      if (size == 0) throw_hdf5(context, what);
      check(H5Tset_size(memory.get(), size), context, what.c_str());
      check(H5Tset_strpad(memory.get(), H5Tget_strpad(type.get())), context, what.c_str());
      std::string text(size, '\0');
      check(H5Aread(attribute.get(), memory.get(), text.data()), context, what.c_str());
      text.resize(std::min(text.find('\0'), text.size()));
      if (H5Tget_strpad(type.get()) == H5T_STR_SPACEPAD) text.erase(text.find_last_not_of(' ') + 1);
      value.text = std::move(text);
    }
    value.kind = AttributeValue::Kind::String;
  } else if (type_class == H5T_INTEGER || type_class == H5T_FLOAT) {
    check(H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, &value.number), context, what.c_str());
    value.kind = AttributeValue::Kind::Number;
  }
  return value;
}

std::string read_string_attribute_or_empty(hid_t location, const char* name, const std::string& context) {
  const htri_t exists = H5Aexists(location, name);
  if (exists < 0) throw_hdf5(context, std::string("cannot look up attribute '") + name + "'");
  if (exists == 0) return "";
  AttributeValue value = read_attribute(location, name, context);
  return value.kind == AttributeValue::Kind::String ? value.text : "";
}

herr_t collect_attribute_name(hid_t, const char* name, const H5A_info_t*, void* names) {
  static_cast<std::vector<std::string>*>(names)->emplace_back(name);
  return 0;
}

std::vector<double> read_dataset(hid_t dataset, const std::string& object, const std::string& context) {
  const std::string what = "cannot read dataset '" + object + "'";
  Handle space = checked(H5Dget_space(dataset), H5Sclose, context, what.c_str());
  Handle type = checked(H5Dget_type(dataset), H5Tclose, context, what.c_str());
  const H5T_class_t type_class = H5Tget_class(type.get());
  if (H5Sget_simple_extent_ndims(space.get()) != 1 || (type_class != H5T_FLOAT && type_class != H5T_INTEGER))
    throw TimeSeriesError(context + ": dataset '" + object + "' is not a 1-D numeric array");
  hsize_t rows = 0;
  if (H5Sget_simple_extent_dims(space.get(), &rows, nullptr) < 0) throw_hdf5(context, what);
  std::vector<double> values(rows);
  if (rows > 0)
    check(H5Dread(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), context, what.c_str());
  return values;
}

}  // namespace

TimeSeriesData read_hdf5_timeseries(const std::filesystem::path& path) {
  const std::string context = "time-series file " + quoted(path);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw TimeSeriesError(context + ": the file does not exist");
  QuietHdf5 quiet;
  Handle fapl = checked(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, context, "H5Pcreate failed");
  check(H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG), context, "H5Pset_fclose_degree failed");
  Handle file = checked(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.get()), H5Fclose, context,
                        "cannot open the file as HDF5");
  TimeSeriesData data;

  std::vector<std::string> names;
  hsize_t index = 0;
  check(H5Aiterate2(file.get(), H5_INDEX_NAME, H5_ITER_INC, &index, collect_attribute_name, &names), context,
        "cannot list the file attributes");
  for (const std::string& name : names) {
    const AttributeValue value = read_attribute(file.get(), name, context);
    if (name == kCompleteAttribute) {
      data.complete = value.kind == AttributeValue::Kind::Number && value.number != 0.0;
    } else if (value.kind == AttributeValue::Kind::String) {
      data.string_attributes[name] = value.text;
    } else if (value.kind == AttributeValue::Kind::Number) {
      data.number_attributes[name] = value.number;
    }
  }

  {
    const htri_t exists = H5Lexists(file.get(), kTimeDataset, H5P_DEFAULT);
    if (exists <= 0) throw TimeSeriesError(context + ": no dataset '/time' (not a turbodyn time-series file?)");
    Handle time = checked(H5Dopen2(file.get(), kTimeDataset, H5P_DEFAULT), H5Dclose, context,
                          "cannot open dataset '/time'");
    data.time = read_dataset(time.get(), "/time", context);
  }

  const htri_t has_probes = H5Lexists(file.get(), kProbesGroup, H5P_DEFAULT);
  if (has_probes <= 0) throw TimeSeriesError(context + ": no group '/probes' (not a turbodyn time-series file?)");
  Handle probes = checked(H5Gopen2(file.get(), kProbesGroup, H5P_DEFAULT), H5Gclose, context,
                          "cannot open group '/probes'");
  H5_index_t order = H5_INDEX_NAME;
  {
    Handle gcpl = checked(H5Gget_create_plist(probes.get()), H5Pclose, context, "H5Gget_create_plist failed");
    unsigned flags = 0;
    check(H5Pget_link_creation_order(gcpl.get(), &flags), context, "H5Pget_link_creation_order failed");
    if ((flags & H5P_CRT_ORDER_TRACKED) != 0) order = H5_INDEX_CRT_ORDER;
  }
  H5G_info_t info;
  check(H5Gget_info(probes.get(), &info), context, "cannot list group '/probes'");
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t length = H5Lget_name_by_idx(probes.get(), ".", order, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (length < 0) throw_hdf5(context, "cannot list group '/probes'");
    std::string name(static_cast<std::size_t>(length) + 1, '\0');
    if (H5Lget_name_by_idx(probes.get(), ".", order, H5_ITER_INC, i, name.data(), name.size(), H5P_DEFAULT) < 0)
      throw_hdf5(context, "cannot list group '/probes'");
    name.resize(static_cast<std::size_t>(length));
    const std::string object = "/probes/" + name;
    Handle item = checked(H5Oopen(probes.get(), name.c_str(), H5P_DEFAULT), H5Oclose, context,
                          ("cannot open '" + object + "'").c_str());
    if (H5Iget_type(item.get()) != H5I_DATASET) continue;  // something a user added; not a channel
    Channel channel;
    channel.name = name;
    channel.unit = read_string_attribute_or_empty(item.get(), "unit", context);
    channel.description = read_string_attribute_or_empty(item.get(), "description", context);
    data.columns.push_back(read_dataset(item.get(), object, context));
    data.channels.push_back(std::move(channel));
  }

  std::size_t rows = data.time.size();
  for (const std::vector<double>& column : data.columns) rows = std::min(rows, column.size());
  data.time.resize(rows);
  for (std::vector<double>& column : data.columns) column.resize(rows);

  probes.close();
  if (file.close() < 0) throw_hdf5(context, "closing the file failed");
  return data;
}

}  // namespace turbodyn
