// Time-series results files: probes (displacements, bearing forces, ring speeds...) sampled at a fixed output rate
// during a run-up, written row by row to HDF5 while the integration runs, and read back for post-processing.
//
// File layout (readable from h5py, MATLAB h5read/h5readatt and HDF5 >= 1.8):
//   /                 attributes: "complete" (int32, 1 only after finish(true)), "software" = "turbodyn",
//                     plus whatever set_attribute() added (scalar UTF-8 strings or scalar float64)
//   /time             float64 [rows], unit "s"
//   /probes/<name>    float64 [rows], one per channel, in channel order (the group tracks creation order)
//   every dataset     attributes "unit" and "description" (scalar UTF-8 strings), chunked 4096 rows, extendible,
//                     uncompressed
// All datasets always have the same length. The run may die at any time: what was flushed (explicitly, or each time
// the buffer of `buffer_rows` rows fills) stays readable, and "complete" then reads 0.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace turbodyn {

/// One recorded quantity.
struct Channel {
  std::string name;         ///< e.g. "disk.compressor.x": letters, digits, '.', '_', '-'; starts with a letter,
                            ///< digit or '_' (so never "." or ".."), at most 255 characters
  std::string unit;         ///< e.g. "m", "N", "Hz", "rad/s"; free text
  std::string description;  ///< free text, e.g. "horizontal displacement of the compressor wheel"
};

/// A problem reading or writing a time-series file. what() names the file and what failed; for HDF5 failures it
/// ends with HDF5's own error stack.
class TimeSeriesError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Rows per HDF5 chunk of every dataset (32 KiB of float64).
inline constexpr std::size_t kTimeSeriesChunkRows = 4096;

/// Throws TimeSeriesError unless every name is valid (see Channel::name) and no name appears twice.
/// `context` starts the message (e.g. the file name).
void validate_channels(const std::vector<Channel>& channels, const std::string& context);

/// Streams rows into an HDF5 file (layout above).
///
/// Rows are collected in a buffer of `buffer_rows` rows; when it is full, or on flush(), the block is appended to
/// every dataset and the file is flushed (H5Fflush) so the file on disk is consistent and readable by another
/// process after the writer's process dies. The metadata cache never writes between flushes and the data are not
/// compressed, so a crash *between* flushes cannot damage what the last flush wrote. Rows still in the buffer when
/// the process is killed are lost; an exception unwinding past the writer is not a crash: the destructor flushes.
///
/// The file is created (truncating an existing one) by the constructor. The writer holds HDF5's file lock until it
/// is closed, so other processes cannot open the file meanwhile (HDF5_USE_FILE_LOCKING=FALSE lifts that, at the
/// reader's risk). Not copyable; one writer must not be used by two threads at once, but writers of different files
/// may run in parallel threads when the HDF5 library is built thread-safe (Debian's is; HDF5 then serialises the
/// calls).
class Hdf5TimeSeriesWriter {
 public:
  /// `channels`: any number (none gives a file with /time only), validated with validate_channels. `buffer_rows` >= 1.
  /// Throws TimeSeriesError if the channels are invalid or the file cannot be created.
  Hdf5TimeSeriesWriter(const std::filesystem::path& file, std::vector<Channel> channels,
                       std::size_t buffer_rows = 4096);
  /// Flushes and closes; never throws. "complete" stays 0 unless finish(true) was called.
  ~Hdf5TimeSeriesWriter();
  Hdf5TimeSeriesWriter(const Hdf5TimeSeriesWriter&) = delete;
  Hdf5TimeSeriesWriter& operator=(const Hdf5TimeSeriesWriter&) = delete;

  /// Appends one row: `time` in s and `values` (dim channels().size()), one per channel in channel order. Values
  /// are stored as given (NaN included). Allocates nothing; writes to the file only when the buffer is full.
  /// Throws TimeSeriesError after finish() or an earlier write failure.
  void append(double time, const double* values);
  /// Writes the buffered rows and flushes the file (H5Fflush): a crash after this loses nothing appended so far.
  void flush();
  /// A file-level attribute (scalar UTF-8 string / float64), replacing any attribute of that name. The names
  /// "complete" and "software" are reserved. Written to disk with the next flush.
  void set_attribute(const std::string& name, const std::string& value);
  void set_attribute(const std::string& name, double value);
  /// Flushes, sets "complete" to 0/1 and closes the file. append(), flush(), set_attribute() and finish() throw
  /// afterwards. If it throws, the file is closed all the same (as far as HDF5 allows).
  void finish(bool complete);

  /// Rows appended so far (on disk or buffered).
  std::size_t rows() const;
  const std::vector<Channel>& channels() const;
  const std::filesystem::path& file() const;
  /// False after finish() or a failed write.
  bool is_open() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Writes a CSV file: header "time_s,<name>_<unit>,..." then one row per sample, every number with 17 significant
/// digits (round-trips exactly), '.' as decimal point whatever the locale, '\n' line ends. In the header the unit is
/// sanitised: '/' -> "_per_", '*' -> "_", '^' dropped, ',', '"' and white space -> "_"; an empty unit gives just
/// "<name>". `columns[c][row]`: dim channels.size() x time.size().
/// Throws TimeSeriesError on invalid channels, mismatched sizes, or when the file cannot be written.
void write_csv(const std::filesystem::path& file, const std::vector<Channel>& channels,
               const std::vector<double>& time, const std::vector<std::vector<double>>& columns);

/// The header field of one channel in write_csv ("rad/s" -> "speed_rad_per_s").
std::string csv_column_name(const Channel& channel);

/// Everything in a time-series file.
struct TimeSeriesData {
  std::vector<Channel> channels;
  std::vector<double> time;                   ///< s, dim rows
  std::vector<std::vector<double>> columns;   ///< columns[c][row], dim channels.size() x rows
  bool complete = false;                      ///< the run finished normally
  std::map<std::string, std::string> string_attributes;  ///< file-level, including "software"
  std::map<std::string, double> number_attributes;       ///< file-level numbers (integers converted), not "complete"
};

/// Reads a file written by Hdf5TimeSeriesWriter (also one that is incomplete because its writer died). Channels come
/// in creation order (name order for files whose /probes group does not track it). Should the datasets differ in
/// length (a crash during a flush), all are cut to the shortest. Throws TimeSeriesError when the file cannot be
/// opened or lacks /time or /probes, or a dataset is not 1-D numeric.
TimeSeriesData read_hdf5_timeseries(const std::filesystem::path& file);

}  // namespace turbodyn
