// Measured run-up data as a test bench exports it: a time series (time, rotor speed or tacho pulses, displacement,
// acceleration or force channels) in CSV or HDF5, or already-processed spectra (rotor speed, frequency, amplitude)
// in CSV. Columns are named in the study file together with their units; everything is converted to SI here and
// checked on the way in (docs/identification.md, "Measured data").
//
// The run-up record of the model (identification/evaluation.h) is put into the same Record, so that the feature
// extraction downstream sees model and measurement alike.
#pragma once

#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "model/spec/enum_names.h"
#include "model/spec/units.h"

namespace turbodyn::identification {

/// What a sensor measures; it selects the unit dimension and what is done to the model's displacement.
enum class Quantity { Displacement, Acceleration, Force };

/// The names in study files: "displacement", "acceleration", "force".
extern const EnumName<Quantity> kQuantities[3];
std::string to_string(Quantity q);
/// The dimension of a sensor's values (m, m/s^2, N).
Dimension dimension_of(Quantity q);

/// One column of the measured file.
struct ColumnRef {
  std::string column;  ///< header name in the CSV, dataset name under /probes (or "time") in HDF5
  std::string unit;    ///< unit of the values ("um", "rpm"); "" = the unit in the file's header (CSV "x [um]", HDF5
                       ///< attribute "unit"), else SI
};

/// A sensor: which column holds it and where it sits on the model (a probe: node and direction).
struct SensorSpec {
  std::string name;                         ///< used by the features; default: the column name
  ColumnRef column;                         ///< amplitude column for spectra
  std::string probe;                        ///< model channel, e.g. "disk.compressor.x", "bearing.turbine.fy"
  Quantity quantity = Quantity::Displacement;
};

enum class MeasurementFormat { TimeSeries, Spectra };

struct MeasurementSpec {
  std::filesystem::path file;                       ///< .csv, or .h5/.hdf5 (time series only)
  MeasurementFormat format = MeasurementFormat::TimeSeries;
  ColumnRef time{"time", ""};                       ///< time series
  ColumnRef speed;                                  ///< rotor speed (time series: or tacho / angle; spectra: required)
  ColumnRef angle;                                  ///< rotor angle from an encoder (time series, optional)
  std::string tacho;                                ///< tacho pulse column (time series, optional; no unit)
  double pulses_per_rev = 1.0;                      ///< tacho pulses per revolution
  double tacho_threshold = std::numeric_limits<double>::quiet_NaN();  ///< rising-edge level; NaN = (min + max) / 2
  ColumnRef frequency{"frequency", ""};             ///< spectra
  std::vector<SensorSpec> sensors;

  /// The record carries a phase reference (tacho or angle): 1x phases can be compared.
  bool has_phase_reference() const { return !tacho.empty() || !angle.column.empty(); }
};

/// A uniformly sampled run-up record in SI units: what order tracking and the STFT work on, for the model and for
/// the measurement alike.
struct Record {
  double sample_rate = 0.0;                    ///< Hz
  std::vector<double> time;                    ///< s
  std::vector<double> speed_hz;                ///< rotor speed f_d, Hz
  std::vector<double> angle;                   ///< rotor angle, rad (0 mod 2 pi at a tacho pulse / the model's 0)
  std::vector<std::vector<double>> channels;   ///< per sensor (SensorSpec order), SI
};

/// Processed spectra: one spectrum per rotor speed.
struct SpectraSet {
  std::vector<double> speed_hz;                            ///< per spectrum, ascending
  std::vector<std::vector<double>> frequency_hz;           ///< per spectrum, ascending
  std::vector<std::vector<std::vector<double>>> amplitude; ///< [sensor][spectrum][bin], SI
};

struct MeasuredData {
  MeasurementFormat format = MeasurementFormat::TimeSeries;
  Record record;        ///< time series
  SpectraSet spectra;   ///< spectra
  bool resampled = false;  ///< the time steps were uneven and the record was resampled (linear interpolation)
};

/// Reads and checks the measured file. Throws ModelError with a message that names the file, and where it applies
/// the line, the field position (line:column, 1-based) and the column name: unreadable file, missing column (with
/// the columns present), a field that is not a finite number (NaN, empty, text), time that does not increase, an
/// unknown unit or one of the wrong kind, too few tacho pulses.
MeasuredData read_measurement(const MeasurementSpec& spec);

/// Factor from `unit` to SI for a quantity of dimension `d` ("um" -> 1e-6). Throws UnitError.
double unit_factor(const std::string& unit, const Dimension& d);

}  // namespace turbodyn::identification
