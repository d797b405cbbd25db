#include "studies/channels.h"

#include "model/io/model_file.h"

namespace turbodyn::studies {

int find_channel(const std::vector<ProbeChannel>& channels, const std::string& name) {
  for (std::size_t c = 0; c < channels.size(); ++c)
    if (channels[c].name == name) return static_cast<int>(c);
  return -1;
}

int kind_channel(const std::vector<ProbeChannel>& channels, ProbeChannel::Kind k) {
  for (std::size_t c = 0; c < channels.size(); ++c)
    if (channels[c].kind == k) return static_cast<int>(c);
  return -1;
}

std::pair<int, int> pair_channels(const std::vector<ProbeChannel>& channels, const std::string& stem) {
  for (const auto& [sx, sy] : {std::pair<const char*, const char*>{".x", ".y"}, {".fx", ".fy"}}) {
    const int a = find_channel(channels, stem + sx), b = find_channel(channels, stem + sy);
    if (a >= 0 && b >= 0) return {a, b};
  }
  return {-1, -1};
}

std::vector<std::string> channel_names(const std::vector<ProbeChannel>& channels) {
  std::vector<std::string> names;
  for (const ProbeChannel& c : channels) names.push_back(c.name);
  return names;
}

std::string did_you_mean(const std::string& word, const std::vector<std::string>& candidates,
                         const std::string& otherwise) {
  const std::string hint = closest_match(word, candidates);
  return hint.empty() ? otherwise : "; did you mean '" + hint + "'?";
}

std::string unknown_probe(const std::string& probe, const std::vector<std::string>& names) {
  std::string all = " (probes:";
  for (const std::string& n : names) all += " " + n;
  return "the model has no probe '" + probe + "'" + did_you_mean(probe, names, all + ")");
}

}  // namespace turbodyn::studies
