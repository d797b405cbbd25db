// Finding a model's probe channels by name, and the message for a name that is not there (with the closest name as
// a suggestion), for everything that names probes in a study file: metrics, sensors, spectrograms.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "model/engine/runup.h"

namespace turbodyn::studies {

/// Index of the channel called `name`, or -1.
int find_channel(const std::vector<ProbeChannel>& channels, const std::string& name);

/// Index of the first channel of kind `k` (the rotor speed, the angle), or -1.
int kind_channel(const std::vector<ProbeChannel>& channels, ProbeChannel::Kind k);

/// The x and y channels of a pair stem: "disk.compressor" -> .x/.y, "bearing.turbine" -> .fx/.fy; {-1, -1} if the
/// model has no such pair.
std::pair<int, int> pair_channels(const std::vector<ProbeChannel>& channels, const std::string& stem);

std::vector<std::string> channel_names(const std::vector<ProbeChannel>& channels);

/// "; did you mean 'NAME'?" with the candidate closest to `word`, or `otherwise` when none is close.
std::string did_you_mean(const std::string& word, const std::vector<std::string>& candidates,
                         const std::string& otherwise = "");

/// "the model has no probe 'PROBE'" and the suggestion, or the list of the probes when none is close.
std::string unknown_probe(const std::string& probe, const std::vector<std::string>& names);

}  // namespace turbodyn::studies
