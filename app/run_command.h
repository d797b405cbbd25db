// `turbodyn run`: the run-up simulation with its outputs (time series, summary, pictures).
#pragma once

#include <filesystem>
#include <vector>

#include "model/io/model_file.h"

namespace turbodyn::app {

struct RunCommandOptions {
  std::filesystem::path model_file;
  std::vector<Override> overrides;
  std::filesystem::path output_dir = "out/run";
  bool plots = true;
  int threads = 1;  ///< threads for the bearings of one right-hand side (RunupOptions::threads)
};

/// Runs the run-up and writes timeseries.h5 (and .csv), summary.json and PNG pictures into the output directory.
/// Returns 0 on success, 3 if the integrator gave up, 130 if interrupted (results up to then are written).
int run_run_command(const RunCommandOptions& options);

struct PlotCommandOptions {
  std::filesystem::path run_dir;    ///< output directory of an earlier `turbodyn run`
  std::vector<Override> overrides;  ///< applied after the run's own, e.g. output.spectrogram_segment=4096
  /// campbell.csv of `turbodyn modal`: its forward and backward natural frequencies are drawn on the spectrograms.
  std::filesystem::path campbell_csv;
  /// modal.json files of `turbodyn modal --amplitudes` measured at a disk: their critical speeds at an amplitude are
  /// drawn on that disk's 1x order track.
  std::vector<std::filesystem::path> backbone_json;
  /// response.json files of `turbodyn response --nonlinear`: their steady states on the disks' 1x order tracks.
  std::vector<std::filesystem::path> response_json;
};

/// Redraws the pictures of an earlier run from its timeseries.h5 (also a partial one), with the model file and
/// overrides recorded in its summary.json plus `overrides`; rewrites the pictures and spectrogram maxima of
/// summary.json. Throws ModelError / TimeSeriesError naming the file on a missing or foreign run directory.
int run_plot_command(const PlotCommandOptions& options);

}  // namespace turbodyn::app
